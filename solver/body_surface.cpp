#include "body_surface.h"

#include "mesh_ops/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

namespace mrcloth {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Two unit vectors completing `axis` (unit) to an orthonormal frame.
void frame_around(const Eigen::Vector3d& axis, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d helper = std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  u = axis.cross(helper).normalized();
  v = axis.cross(u);
}

/// One capsule: a lathe around a->b. A profile point at polar angle alpha
/// (0 = along +axis) lies on sphere B when alpha <= the tangent angle, on
/// sphere A otherwise; the tangent cone's points are where both meet.
void add_capsule(const CapsuleCollider& given, int segments, int rings, BodySurface& out) {
  CapsuleCollider capsule = given;
  Eigen::Vector3d axis = capsule.b - capsule.a;
  double length = axis.norm();
  axis = length > 0.0 ? Eigen::Vector3d(axis / length) : Eigen::Vector3d::UnitY();
  // One sphere inside the other: the capsule is the larger sphere.
  if (length + capsule.radius_b <= capsule.radius_a) {
    capsule.b = capsule.a;
    capsule.radius_b = capsule.radius_a;
    length = 0.0;
  } else if (length + capsule.radius_a <= capsule.radius_b) {
    capsule.a = capsule.b;
    capsule.radius_a = capsule.radius_b;
    length = 0.0;
  }
  // sin(phi) = (ra - rb) / L: the cone touches both spheres at polar angle pi/2 - phi.
  const double sin_phi = length > 0.0 ? (capsule.radius_a - capsule.radius_b) / length : 0.0;
  const double tangent = 0.5 * kPi - std::asin(sin_phi);
  Eigen::Vector3d u, v;
  frame_around(axis, u, v);

  // Profile from the pole at B (alpha = 0) to the pole at A (alpha = pi):
  // `rings` steps over B's cap, then `rings` over A's; the shared tangent
  // angle appears once per sphere so the cone between them is one band.
  struct ProfilePoint { Eigen::Vector3d centre; double radius; double alpha; };
  std::vector<ProfilePoint> profile;
  for (int k = 0; k <= rings; ++k)
    profile.push_back({capsule.b, capsule.radius_b, tangent * k / rings});
  for (int k = 0; k <= rings; ++k)
    profile.push_back({capsule.a, capsule.radius_a, tangent + (kPi - tangent) * k / rings});

  const int base = static_cast<int>(out.vertices.rows());
  const int profile_count = static_cast<int>(profile.size());
  // Poles are single vertices; the other profile points are rings.
  const int ring_count = profile_count - 2;
  out.vertices.conservativeResize(base + 2 + ring_count * segments, 3);
  const int pole_b = base, pole_a = base + 1;
  out.vertices.row(pole_b) = (capsule.b + capsule.radius_b * axis).transpose();
  out.vertices.row(pole_a) = (capsule.a - capsule.radius_a * axis).transpose();
  const auto ring_vertex = [&](int ring, int s) { return base + 2 + ring * segments + (s % segments); };
  for (int ring = 0; ring < ring_count; ++ring) {
    const ProfilePoint& point = profile[static_cast<std::size_t>(ring + 1)];
    for (int s = 0; s < segments; ++s) {
      const double theta = 2.0 * kPi * s / segments;
      const Eigen::Vector3d radial = std::cos(theta) * u + std::sin(theta) * v;
      const Eigen::Vector3d direction = std::cos(point.alpha) * axis + std::sin(point.alpha) * radial;
      out.vertices.row(ring_vertex(ring, s)) = (point.centre + point.radius * direction).transpose();
    }
  }
  // Outward: seen from outside, counter-clockwise. Around +axis, theta grows
  // counter-clockwise, and rings go from B (+axis) towards A.
  for (int s = 0; s < segments; ++s) {
    out.faces.push_back({pole_b, ring_vertex(0, s), ring_vertex(0, s + 1)});
    for (int ring = 0; ring + 1 < ring_count; ++ring)
      out.faces.push_back({ring_vertex(ring, s), ring_vertex(ring + 1, s), ring_vertex(ring + 1, s + 1),
                           ring_vertex(ring, s + 1)});
    out.faces.push_back({ring_vertex(ring_count - 1, s), pole_a, ring_vertex(ring_count - 1, s + 1)});
  }
}

}  // namespace

BodySurface capsule_surface(const std::vector<Collider>& colliders, int segments, int rings) {
  if (segments < 3 || rings < 1)
    throw ArgumentError("capsule_surface: expected segments >= 3 and rings >= 1, got " + std::to_string(segments) +
                        " and " + std::to_string(rings));
  BodySurface surface;
  surface.vertices.resize(0, 3);
  for (const Collider& collider : colliders)
    if (const auto* capsule = std::get_if<CapsuleCollider>(&collider.shape))
      add_capsule(*capsule, segments, rings, surface);
  return surface;
}

void append_surface(BodySurface& surface, const BodySurface& more) {
  const int base = static_cast<int>(surface.vertices.rows());
  surface.vertices.conservativeResize(base + more.vertices.rows(), 3);
  surface.vertices.bottomRows(more.vertices.rows()) = more.vertices;
  const bool textured = !surface.uvs.empty();
  for (std::size_t f = 0; f < more.faces.size(); ++f) {
    std::vector<int> face = more.faces[f];
    for (int& v : face) v += base;
    // A textured surface stays textured: what is appended without UVs (the
    // bridges' capsules) gets the texture's corner.
    if (textured)
      surface.uvs.push_back(more.uvs.empty() ? std::vector<Eigen::Vector2d>(face.size(), Eigen::Vector2d::Zero())
                                             : more.uvs[f]);
    surface.faces.push_back(std::move(face));
  }
}

std::vector<int> used_vertices(const BodySurface& surface) {
  std::vector<char> used(static_cast<std::size_t>(surface.vertices.rows()), 0);
  for (const std::vector<int>& face : surface.faces)
    for (const int v : face) used[static_cast<std::size_t>(v)] = 1;
  std::vector<int> kept;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (used[v]) kept.push_back(static_cast<int>(v));
  return kept;
}

BodySurface keep_vertices(const BodySurface& surface, const std::vector<int>& kept) {
  BodySurface out;
  out.vertices.resize(static_cast<Eigen::Index>(kept.size()), 3);
  std::vector<int> renumbered(static_cast<std::size_t>(surface.vertices.rows()), -1);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    out.vertices.row(static_cast<Eigen::Index>(k)) = surface.vertices.row(kept[k]);
    renumbered[static_cast<std::size_t>(kept[k])] = static_cast<int>(k);
  }
  out.faces = surface.faces;
  for (std::vector<int>& face : out.faces)
    for (int& v : face) v = renumbered[static_cast<std::size_t>(v)];
  out.uvs = surface.uvs;
  return out;
}

}  // namespace mrcloth
