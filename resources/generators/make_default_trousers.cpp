// make_default_trousers: writes mrcloth's default trousers, full length,
// around the default mannequin (a standing 1.65 m woman, see
// make_default_character.cpp), as an all-quad OBJ.
//
//   make_default_trousers <output.obj>
//
// The committed resources/garments/default_trousers.obj is this program's
// output with the default options (CMake target
// `regenerate_default_trousers`); a test regenerates it and requires the
// bytes to match, so change the options here, regenerate, and commit both.
//
// Standard library only, on purpose: the garment must not depend on the
// code it is used to test (OpenMesh readers, mrcloth's loader).
//
// Frame: metres, Y up, the mannequin faces +Z, its left is +X, ground at
// y = 0; the body's vertical axis is x = z = 0, the legs' axes x = +-0.09 at
// the hips converging to +-0.075 at the ankles.
//
// Topology: one manifold piece, a sphere with three holes (waist, two
// ankles; Euler characteristic -1), every face a quad, no seam vertices.
//  - The seat: a tube of `waist_segments` (24) vertices around, index 0 at
//    the front centre growing towards +x, from the waist down to the seat
//    ring where the legs split.
//  - The crotch: a path of 5 vertices in the plane x = 0 from the seat
//    ring's front centre (vertex 0) down through the crotch point and up to
//    its back centre (vertex 12), equally spaced along a half ellipse.
//  - Each leg starts with a ring of 18 = 13 + 5: its half of the seat ring
//    (front centre, its side, back centre) closed by the crotch path; the
//    two legs share the crotch path, each of its 6 edges bordering one quad
//    of each leg. Below, rings of 18 go down to the ankle, blending in four
//    rings from the shape of the split to circles around the leg's axis.
//    (13 + 5 spaces the split ring's vertices evenly around the leg: the
//    seat half spans about 250 degrees of it, the crotch the other 110.)
// Every quad is ordered so that its normal points out of the body.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ellipse.h"
#include "generated_file.h"

namespace {

using mrcloth::generators::equal_arc_angles;
using mrcloth::generators::ellipse_perimeter;
using mrcloth::generators::generator_main;
using mrcloth::generators::write_obj_elements;
using mrcloth::generators::format_coordinate;

constexpr double kPi = 3.14159265358979323846;

/// Shape and resolution. Circumferences are the garment's own; "aspect" is
/// width (x) over depth (z) of an elliptical cross-section.
struct TrouserOptions {
  int waist_segments = 24;            ///< vertices around the seat tube; must be even
  int seat_rings = 6;                 ///< rings from the waist to the split (>= 2)
  int crotch_vertices = 5;            ///< on the crotch path, >= 1
  int leg_rings = 13;                 ///< rings of each leg below its split ring (>= blend_rings)
  double waist_height = 1.00;         ///< y of the waist boundary loop, m
  double waist_circumference = 0.78;  ///< m
  double waist_aspect = 1.25;
  double hip_height = 0.87;           ///< widest part, m
  double hip_circumference = 1.00;    ///< m; around the mannequin's pelvis and thighs with ease
  double hip_aspect = 1.30;
  double seat_height = 0.84;          ///< the seat ring, where the legs split, m
  double crotch_height = 0.77;        ///< lowest point of the crotch path (x = z = 0), m
  double ankle_height = 0.10;         ///< y of the two ankle boundary loops (clear of the feet), m
  double leg_axis_top = 0.09;         ///< |x| of a leg's axis at the split (the hip joints')
  double leg_axis_ankle = 0.075;      ///< |x| of a leg's axis at the ankle (the ankle joints')
  double thigh_radius = 0.082;        ///< leg tube radius at the top, m
  double knee_height = 0.47;          ///< m
  double knee_radius = 0.072;         ///< m
  double ankle_radius = 0.064;        ///< m
  int blend_rings = 4;                ///< rings over which a leg goes from the split's shape to circles

  int leg_segments() const { return waist_segments / 2 + 1 + crotch_vertices; }
};

void check_options(const TrouserOptions& o) {
  if (o.waist_segments < 8 || o.waist_segments % 4 != 0)
    throw std::invalid_argument("waist_segments must be a multiple of 4, >= 8 (front, sides and back on vertices)");
  if (o.seat_rings < 2) throw std::invalid_argument("seat_rings must be >= 2");
  if (o.crotch_vertices < 1) throw std::invalid_argument("crotch_vertices must be >= 1");
  if (o.leg_rings < o.blend_rings || o.blend_rings < 1) throw std::invalid_argument("leg_rings must be >= blend_rings >= 1");
  if (!(o.waist_height > o.hip_height && o.hip_height >= o.seat_height && o.seat_height > o.crotch_height &&
        o.crotch_height > o.knee_height && o.knee_height > o.ankle_height))
    throw std::invalid_argument("heights must decrease: waist > hip >= seat > crotch > knee > ankle");
  for (double v : {o.waist_circumference, o.hip_circumference, o.thigh_radius, o.knee_radius, o.ankle_radius})
    if (!(v > 0.0)) throw std::invalid_argument("sizes must be positive");
  for (double a : {o.waist_aspect, o.hip_aspect})
    if (!(a >= 1.0)) throw std::invalid_argument("aspects must be >= 1 (wider than deep)");
  if (!(o.thigh_radius < o.leg_axis_top)) throw std::invalid_argument("the legs must not overlap at the crotch");
}


double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

double lerp(double a, double b, double t) { return a + (b - a) * t; }

struct Vertex {
  double x, y, z;
};

/// Semi-axes (width, depth) of the seat tube at height y: a quarter sine
/// from the waist to the hips (vertical at the hips), then constant.
std::pair<double, double> seat_semi_axes(const TrouserOptions& o, double y) {
  const double t = std::clamp((o.waist_height - y) / (o.waist_height - o.hip_height), 0.0, 1.0);
  const double s = std::sin(0.5 * kPi * t);
  const double circumference = lerp(o.waist_circumference, o.hip_circumference, s);
  const double aspect = lerp(o.waist_aspect, o.hip_aspect, s);
  const double depth = circumference / ellipse_perimeter(aspect, 1.0);
  return {aspect * depth, depth};
}

/// A seat ring: vertex 0 at the front centre (+z), growing towards +x.
std::vector<Vertex> seat_ring(const TrouserOptions& o, double y) {
  const auto [a, b] = seat_semi_axes(o, y);
  std::vector<Vertex> ring;
  for (double t : equal_arc_angles(a, b, o.waist_segments)) ring.push_back({a * std::sin(t), y, b * std::cos(t)});
  return ring;
}

/// Leg tube radius at height y: thigh -> knee -> ankle, linear in pieces.
double leg_radius(const TrouserOptions& o, double y) {
  if (y >= o.knee_height)
    return lerp(o.knee_radius, o.thigh_radius, std::min(1.0, (y - o.knee_height) / (o.seat_height - o.knee_height)));
  return lerp(o.ankle_radius, o.knee_radius, std::max(0.0, (y - o.ankle_height) / (o.knee_height - o.ankle_height)));
}

/// |x| of a leg's axis at height y.
double leg_axis(const TrouserOptions& o, double y) {
  const double t = std::clamp((y - o.ankle_height) / (o.seat_height - o.ankle_height), 0.0, 1.0);
  return lerp(o.leg_axis_ankle, o.leg_axis_top, t);
}

struct Trousers {
  std::vector<Vertex> vertices;
  std::vector<std::array<int, 4>> quads;
};

/// The seat tube, waist first: o.seat_rings rings of o.waist_segments
/// vertices and the quads between them.
void add_seat_tube(const TrouserOptions& o, Trousers& out) {
  const int n = o.waist_segments;
  for (int r = 0; r < o.seat_rings; ++r) {
    const double y = lerp(o.waist_height, o.seat_height, static_cast<double>(r) / (o.seat_rings - 1));
    for (const Vertex& v : seat_ring(o, y)) out.vertices.push_back(v);
  }
  for (int r = 0; r + 1 < o.seat_rings; ++r)
    for (int s = 0; s < n; ++s) {
      const int top = r * n, bottom = (r + 1) * n, s1 = (s + 1) % n;
      out.quads.push_back({top + s, bottom + s, bottom + s1, top + s1});
    }
}

/// The crotch path, front to back, equally spaced on a half ellipse in the
/// plane x = 0 (half of the full ellipse's equal-arc points); returns its
/// first vertex's id.
int add_crotch_path(const TrouserOptions& o, Trousers& out) {
  const double depth = seat_semi_axes(o, o.seat_height).second, drop = o.seat_height - o.crotch_height;
  const int crotch = static_cast<int>(out.vertices.size());
  const std::vector<double> crotch_angles = equal_arc_angles(drop, depth, 2 * (o.crotch_vertices + 1));
  for (int c = 1; c <= o.crotch_vertices; ++c) {
    const double angle = crotch_angles[c];
    out.vertices.push_back({0.0, o.seat_height - drop * std::sin(angle), depth * std::cos(angle)});
  }
  return crotch;
}

/// The left leg's rings, the split ring (vertex ids `split`) first. Lower
/// rings: heights step evenly from the split ring's mean height to the
/// ankle, the split's slant fading out; each vertex keeps its angle around
/// the leg's axis at first and moves to an even spacing, from the split's
/// shape to a circle, over blend_rings rings.
std::vector<std::vector<Vertex>> left_leg_rings(const TrouserOptions& o, const Trousers& out,
                                                const std::vector<int>& split) {
  const int m = o.leg_segments();
  double mean_y = 0.0;
  for (int id : split) mean_y += out.vertices[id].y / m;
  const double axis_top = leg_axis(o, o.seat_height);
  std::vector<double> split_angle(m);
  for (int i = 0; i < m; ++i) {
    const Vertex& v = out.vertices[split[i]];
    split_angle[i] = std::atan2(v.x - axis_top, v.z);  // 0 at the front, growing towards +x
    if (i > 0)
      while (split_angle[i] < split_angle[i - 1]) split_angle[i] += 2.0 * kPi;
  }
  double start = 0.0;  // even angles rotated to fit the split's best
  for (int i = 0; i < m; ++i) start += (split_angle[i] - 2.0 * kPi * i / m) / m;

  std::vector<std::vector<Vertex>> left(o.leg_rings + 1);
  for (int i = 0; i < m; ++i) left[0].push_back(out.vertices[split[i]]);
  for (int k = 1; k <= o.leg_rings; ++k) {
    const double w = smoothstep(static_cast<double>(k) / o.blend_rings);
    const double level = lerp(mean_y, o.ankle_height, static_cast<double>(k) / o.leg_rings);
    const double axis = leg_axis(o, level), radius = leg_radius(o, level);
    for (int i = 0; i < m; ++i) {
      const Vertex& s = left[0][i];
      const double angle = start + 2.0 * kPi * i / m;
      const double x = lerp(s.x - axis_top, radius * std::sin(angle), w) + axis;
      const double z = lerp(s.z, radius * std::cos(angle), w);
      const double y = level + (s.y - mean_y) * (1.0 - w);
      left[k].push_back({x, y, z});
    }
  }
  return left;
}

Trousers make_trousers(const TrouserOptions& o) {
  Trousers out;
  const int n = o.waist_segments, half = n / 2, m = o.leg_segments();
  add_seat_tube(o, out);
  const int seat = (o.seat_rings - 1) * n;  // first vertex of the seat ring
  const int crotch = add_crotch_path(o, out);

  // The left leg's split ring: its half of the seat ring, front centre to
  // back centre over its side, then the crotch path from back to front.
  std::vector<int> split;
  for (int s = 0; s <= half; ++s) split.push_back(seat + s);
  for (int c = o.crotch_vertices - 1; c >= 0; --c) split.push_back(crotch + c);
  const std::vector<std::vector<Vertex>> left = left_leg_rings(o, out, split);

  // Leg rings as vertex ids; the right leg is the left one mirrored (x ->
  // -x) with its ring order reversed, which keeps every face outward and
  // maps the split ring onto the right half of the seat ring and the same
  // crotch path: right index j <-> left index (m - j) % m.
  std::vector<std::vector<int>> left_ids(o.leg_rings + 1), right_ids(o.leg_rings + 1);
  left_ids[0] = split;
  for (int j = 0; j < m; ++j) {
    const int i = (m - j) % m;
    const int id = split[i];
    right_ids[0].push_back(id < crotch && id != seat && id != seat + half ? seat + (n - (id - seat)) : id);
  }
  for (int k = 1; k <= o.leg_rings; ++k)
    for (int i = 0; i < m; ++i) {
      left_ids[k].push_back(static_cast<int>(out.vertices.size()));
      out.vertices.push_back(left[k][i]);
    }
  for (int k = 1; k <= o.leg_rings; ++k)
    for (int j = 0; j < m; ++j) {
      const Vertex& v = left[k][(m - j) % m];
      right_ids[k].push_back(static_cast<int>(out.vertices.size()));
      out.vertices.push_back({-v.x, v.y, v.z});
    }
  for (const auto* leg : {&left_ids, &right_ids})
    for (int k = 0; k < o.leg_rings; ++k)
      for (int i = 0; i < m; ++i) {
        const int i1 = (i + 1) % m;
        out.quads.push_back({(*leg)[k][i], (*leg)[k + 1][i], (*leg)[k + 1][i1], (*leg)[k][i1]});
      }
  return out;
}

std::string obj_text(const TrouserOptions& o) {
  const Trousers trousers = make_trousers(o);
  std::ostringstream out;
  out << "# mrcloth default trousers: full length, " << trousers.vertices.size() << " vertices, "
      << trousers.quads.size() << " quads\n"
      << "# Generated by resources/generators/make_default_trousers.cpp -- do not edit by hand;\n"
      << "# rebuild with: cmake --build <build-dir> --target regenerate_default_trousers\n"
      << "# Units: metres. Y up, facing +Z, ground at y = 0. One piece: waist loop and two ankle loops.\n"
      << "# waist y " << format_coordinate(o.waist_height) << " circumference "
      << format_coordinate(o.waist_circumference) << "; hips y " << format_coordinate(o.hip_height)
      << " circumference " << format_coordinate(o.hip_circumference) << "; crotch y "
      << format_coordinate(o.crotch_height) << "; ankles y " << format_coordinate(o.ankle_height) << "\n"
      << "o default_trousers\n";
  write_obj_elements(out, trousers.vertices, trousers.quads);
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  return generator_main(argc, argv, "make_default_trousers", "Writes mrcloth's default full-length trousers (all quads, metres, Y up, facing +Z).", [] {
    const TrouserOptions options;
    check_options(options);
    return obj_text(options);
  });
}
