// make_default_skirt: writes the embedded default garment of mrcloth, a
// knee-length skirt around a standing 1.65 m woman, as an all-quad OBJ.
//
//   make_default_skirt <output.obj>
//
// The committed resources/garments/default_skirt.obj is this program's output
// with the default options (CMake target `regenerate_default_skirt`); a test
// regenerates it and requires the bytes to match, so change the options here,
// regenerate, and commit both together.
//
// Standard library only, on purpose: the default garment must not depend on
// the code it is used to test (OpenMesh readers, mrcloth's loader).
//
// Frame: metres, Y up, the mannequin faces +Z, ground at y = 0, the body's
// vertical axis is x = z = 0.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

/// Shape and resolution of the skirt. Circumferences are the garment's own
/// (it rests on the body at waist and hips, so they equal the mannequin's
/// measurements there); "aspect" is the width (side to side, along x) over
/// the depth (front to back, along z) of the elliptical cross-section.
struct SkirtOptions {
  int segments = 40;                  ///< vertices around each ring (>= 3); 40 x 20 = 800 vertices
  int rings = 20;                     ///< rings from waist to hem (>= 2); rings - 1 rows of quads
  double waist_height = 1.02;         ///< y of the top boundary loop (natural waist of a 1.65 m woman), m
  double waist_circumference = 0.70;  ///< m
  double waist_aspect = 1.40;         ///< the waist is much wider than deep
  double hip_height = 0.90;           ///< y of the widest part of the hips, m
  double hip_circumference = 0.96;    ///< m
  double hip_aspect = 1.30;           ///< hips are a little rounder than the waist
  double hem_height = 0.55;           ///< y of the bottom boundary loop, above the knees, m
  double hem_circumference = 1.50;    ///< m; the A-line flare leaves room for a walking stride (knees ~0.35 m apart)
  double hem_aspect = 1.15;           ///< a flared hem hangs rounder than the body
};

/// One cross-section: the ellipse at height y.
struct Ring {
  double y = 0.0;
  double circumference = 0.0;
  double aspect = 1.0;
};

void check_options(const SkirtOptions& o) {
  if (o.segments < 3) throw std::invalid_argument("segments must be >= 3");
  if (o.rings < 2) throw std::invalid_argument("rings must be >= 2");
  if (!(o.waist_height > o.hip_height && o.hip_height > o.hem_height))
    throw std::invalid_argument("heights must decrease: waist > hip > hem");
  for (double c : {o.waist_circumference, o.hip_circumference, o.hem_circumference})
    if (!(c > 0.0)) throw std::invalid_argument("circumferences must be positive");
  for (double a : {o.waist_aspect, o.hip_aspect, o.hem_aspect})
    if (!(a >= 1.0)) throw std::invalid_argument("aspects must be >= 1 (wider than deep)");
}

/// Cross-section at height y. Waist to hips follows a quarter sine so the
/// side reaches the hips with a vertical tangent (the widest point); hips to
/// hem starts vertical too and flares quadratically, as cloth falling from
/// the hips does, so there is no crease at the hip line.
Ring profile(const SkirtOptions& o, double y) {
  Ring ring;
  ring.y = y;
  if (y >= o.hip_height) {
    const double t = (o.waist_height - y) / (o.waist_height - o.hip_height);
    const double s = std::sin(0.5 * kPi * t);
    ring.circumference = o.waist_circumference + s * (o.hip_circumference - o.waist_circumference);
    ring.aspect = o.waist_aspect + s * (o.hip_aspect - o.waist_aspect);
  } else {
    const double t = (o.hip_height - y) / (o.hip_height - o.hem_height);
    const double s = t * t;
    ring.circumference = o.hip_circumference + s * (o.hem_circumference - o.hip_circumference);
    ring.aspect = o.hip_aspect + s * (o.hem_aspect - o.hip_aspect);
  }
  return ring;
}


struct Vertex {
  double x, y, z;
};

/// Ring r's vertices. Vertex 0 of every ring is at the front centre (+z);
/// the index grows towards +x (the mannequin's left), which with rings
/// stored top to bottom makes the faces below counter-clockwise from outside.
std::vector<Vertex> ring_vertices(const Ring& ring, int segments) {
  const double b = ring.circumference / ellipse_perimeter(ring.aspect, 1.0);  // depth semi-axis
  const double a = ring.aspect * b;                                            // width semi-axis
  std::vector<Vertex> out;
  for (double t : equal_arc_angles(a, b, segments)) out.push_back({a * std::sin(t), ring.y, b * std::cos(t)});
  return out;
}

std::vector<Vertex> skirt_vertices(const SkirtOptions& o) {
  std::vector<Vertex> vertices;
  for (int r = 0; r < o.rings; ++r) {
    // Equal steps in height: the profile is steep nowhere, so rows stay close to square.
    const double y = o.waist_height + (o.hem_height - o.waist_height) * r / (o.rings - 1);
    for (const Vertex& v : ring_vertices(profile(o, y), o.segments)) vertices.push_back(v);
  }
  return vertices;
}

/// Quads as 0-based vertex indices. Face (r, s) joins rings r (above) and
/// r+1 (below) between segments s and s+1; the last segment wraps to 0, so
/// the tube has no seam vertices. Order top-left, bottom-left, bottom-right,
/// top-right: (down) x (along +x at the front) = +z, i.e. outward.
std::vector<std::array<int, 4>> skirt_quads(const SkirtOptions& o) {
  std::vector<std::array<int, 4>> quads;
  for (int r = 0; r + 1 < o.rings; ++r) {
    for (int s = 0; s < o.segments; ++s) {
      const int s1 = (s + 1) % o.segments;
      const int top = r * o.segments, bottom = (r + 1) * o.segments;
      quads.push_back({top + s, bottom + s, bottom + s1, top + s1});
    }
  }
  return quads;
}

/// Fixed-point text, with -0 printed as 0 so the output never depends on
/// the sign of a rounding residue.
std::string obj_text(const SkirtOptions& o) {
  const std::vector<Vertex> vertices = skirt_vertices(o);
  const auto quads = skirt_quads(o);
  std::ostringstream out;
  out << "# mrcloth default garment: above-knee A-line skirt, " << vertices.size() << " vertices, " << quads.size()
      << " quads\n"
      << "# Generated by resources/generators/make_default_skirt.cpp -- do not edit by hand;\n"
      << "# rebuild with: cmake --build <build-dir> --target regenerate_default_skirt\n"
      << "# Units: metres. Y up, facing +Z, ground at y = 0. Open tube: waist and hem loops.\n"
      << "# waist y " << format_coordinate(o.waist_height) << " circumference " << format_coordinate(o.waist_circumference)
      << "; hips y " << format_coordinate(o.hip_height) << " circumference " << format_coordinate(o.hip_circumference)
      << "; hem y " << format_coordinate(o.hem_height) << " circumference " << format_coordinate(o.hem_circumference)
      << "\n"
      << "o default_skirt\n";
  write_obj_elements(out, vertices, quads);
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  return generator_main(argc, argv, "make_default_skirt", "Writes mrcloth's default above-knee A-line skirt (all quads, metres, Y up, facing +Z).", [] {
    const SkirtOptions options;
    check_options(options);
    return obj_text(options);
  });
}
