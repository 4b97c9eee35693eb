#include "colliders.h"

#include "mesh_ops/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

namespace mrcloth {
namespace {

using Eigen::Vector3d;

// Halving the step's path 40 times locates the entry point to 1e-12 of it.
constexpr int kEntryBisections = 40;
// Nearest-surface and entry normals more than 60 degrees apart mean the
// nearest surface is not the one the point came through.
constexpr double kSameSide = 0.5;

/// A unit vector perpendicular to unit `u`, the same every time for the same
/// `u`: crossing with the coordinate axis least aligned with `u` keeps it
/// well conditioned.
Vector3d any_perpendicular(const Vector3d& u) {
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(u(k)) < std::abs(u(least))) least = k;
  return u.cross(Vector3d::Unit(least)).normalized();
}

/// Distance to a ball; at the centre every direction is closest, so +y.
SurfaceQuery ball_query(const Vector3d& center, double radius, const Vector3d& p) {
  const Vector3d offset = p - center;
  const double length = offset.norm();
  SurfaceQuery query;
  query.distance = length - radius;
  query.normal = length > 0.0 ? Vector3d(offset / length) : Vector3d::UnitY();
  return query;
}

SurfaceQuery query_plane(const PlaneCollider& plane, const Vector3d& p) {
  assert(plane.normal.squaredNorm() > 0.0 && "validate_colliders refuses a zero plane normal");
  SurfaceQuery query;
  query.normal = plane.normal.normalized();
  query.distance = query.normal.dot(p - plane.point);
  return query;
}

/// The exact signed distance to the convex hull of two balls (a, ra), (b, rb).
/// By rotational symmetry it is a 2D problem in the half-plane spanned by the
/// axis and p, with coordinates t (along the axis from a) and h >= 0 (from
/// the axis). There the boundary is an arc of circle a, the slant line
/// tangent to both circles, and an arc of circle b. The slant line has
/// outward normal n = (s, c) with s = (ra - rb) / L (L = |b - a|) and
/// touches circle a at ra * n and circle b at (L, 0) + rb * n; the signed
/// position of q = (t, h) along the line, sigma = c t - s h, tells which of
/// the three pieces is closest, for points inside as well as outside.
SurfaceQuery query_capsule(const CapsuleCollider& capsule, const Vector3d& p) {
  const Vector3d axis = capsule.b - capsule.a;
  const double length = axis.norm();
  const double dr = capsule.radius_a - capsule.radius_b;
  // One ball inside the other (or equal centres): the hull is the larger ball.
  if (length <= std::abs(dr)) {
    return capsule.radius_a >= capsule.radius_b ? ball_query(capsule.a, capsule.radius_a, p)
                                                : ball_query(capsule.b, capsule.radius_b, p);
  }
  const Vector3d u = axis / length;
  const Vector3d offset = p - capsule.a;
  const double t = offset.dot(u);
  const Vector3d radial = offset - t * u;
  const double h = radial.norm();
  // On the axis every radial direction is closest; any fixed one will do.
  const Vector3d e = h > 0.0 ? Vector3d(radial / h) : any_perpendicular(u);

  const double s = dr / length;
  const double c = std::sqrt(std::max(0.0, (1.0 - s) * (1.0 + s)));
  const double sigma = c * t - s * h;
  if (sigma < 0.0) return ball_query(capsule.a, capsule.radius_a, p);
  if (sigma > length * c) return ball_query(capsule.b, capsule.radius_b, p);
  SurfaceQuery query;
  query.distance = s * t + c * h - capsule.radius_a;
  query.normal = (s * u + c * e).normalized();
  return query;
}

/// max over the collider of n . x: its tangent plane with outward normal n
/// is n . x = support(n) (n unit; for a plane, n must be its normal).
double support(const Collider& collider, const Vector3d& n) {
  if (const auto* plane = std::get_if<PlaneCollider>(&collider.shape)) return n.dot(plane->point);
  if (const auto* sphere = std::get_if<SphereCollider>(&collider.shape)) return n.dot(sphere->center) + sphere->radius;
  const auto& capsule = std::get<CapsuleCollider>(collider.shape);
  return std::max(n.dot(capsule.a) + capsule.radius_a, n.dot(capsule.b) + capsule.radius_b);
}

/// Reports "collider 3 (sphere): radius must be > 0 (got -0.1)".
[[noreturn]] void refuse(std::size_t index, const char* kind, const std::string& problem) {
  throw ArgumentError("collider " + std::to_string(index) + " (" + kind + "): " + problem);
}

std::string text(double value) { return number_text(value); }

std::string text(const Vector3d& v) { return "(" + text(v.x()) + ", " + text(v.y()) + ", " + text(v.z()) + ")"; }

void require_finite(std::size_t index, const char* kind, const char* field, const Vector3d& v) {
  if (!v.allFinite()) refuse(index, kind, std::string(field) + " must be finite (got " + text(v) + ")");
}

void require_finite_at_least(std::size_t index, const char* kind, const char* field, double value, double minimum,
                             bool strict) {
  const bool ok = std::isfinite(value) && (strict ? value > minimum : value >= minimum);
  if (!ok) {
    refuse(index, kind,
           std::string(field) + " must be a finite number " + (strict ? "> " : ">= ") + text(minimum) + " (got " +
               text(value) + ")");
  }
}

void validate_shape(std::size_t index, const PlaneCollider& plane) {
  require_finite(index, "plane", "point", plane.point);
  require_finite(index, "plane", "normal", plane.normal);
  if (!(plane.normal.squaredNorm() > 0.0)) refuse(index, "plane", "normal must not be zero");
}

void validate_shape(std::size_t index, const SphereCollider& sphere) {
  require_finite(index, "sphere", "center", sphere.center);
  require_finite_at_least(index, "sphere", "radius", sphere.radius, 0.0, true);
}

void validate_shape(std::size_t index, const CapsuleCollider& capsule) {
  require_finite(index, "capsule", "a", capsule.a);
  require_finite(index, "capsule", "b", capsule.b);
  require_finite_at_least(index, "capsule", "radius_a", capsule.radius_a, 0.0, false);
  require_finite_at_least(index, "capsule", "radius_b", capsule.radius_b, 0.0, false);
  if (capsule.radius_a == 0.0 && capsule.radius_b == 0.0)
    refuse(index, "capsule", "radius_a and radius_b are both 0 (at least one must be > 0)");
}

const char* kind_of(const Collider& collider) {
  switch (collider.shape.index()) {
    case 0: return "plane";
    case 1: return "sphere";
    default: return "capsule";
  }
}

/// Pushes `position` out to `thickness` from one collider that moved from
/// `before` to `after`, through the surface the point entered by, and
/// applies Coulomb friction to the step's tangential motion relative to the
/// collider; returns the normal correction (0 when the point is clear).
double resolve_against(const Collider& before, const Collider& after, const Vector3d& start, Vector3d& position,
                       bool friction) {
  if (surely_clear(after, position)) return 0.0;  // most of a body's capsules are far from any one point
  const SurfaceQuery query = query_surface(after, position);
  const double gap = query.distance - after.thickness;
  if (!(gap < 0.0)) return 0.0;
  const Vector3d carried = carry_with(before, after, start);
  Vector3d normal = query.normal;
  double correction = -gap;
  const SurfaceQuery start_query = query_surface(after, carried);
  const double start_gap = start_query.distance - after.thickness;
  // A start whose nearest surface faces the way the end's does entered by
  // that surface (cloth resting on a limb, every step): no entry to find.
  if (start_gap > 0.0 && start_query.normal.dot(query.normal) < kSameSide) {
    // The thickened collider is convex, so along the segment from the
    // carried start (outside) to the end (inside) its distance crosses the
    // thickness once: bisect for the entry point. When the nearest surface
    // faces away from the entry (the collider moved past the point), push
    // to the tangent plane at the entry instead, which the whole thickened
    // collider lies behind; otherwise the nearest surface is the entry side.
    double outside = 0.0, inside = 1.0;
    const Vector3d path = position - carried;
    for (int k = 0; k < kEntryBisections; ++k) {
      const double middle = 0.5 * (outside + inside);
      if (query_surface(after, carried + middle * path).distance - after.thickness > 0.0) outside = middle;
      else inside = middle;
    }
    const Vector3d entry_normal = query_surface(after, carried + outside * path).normal;
    if (entry_normal.dot(query.normal) < kSameSide) {
      normal = entry_normal;
      correction = std::max(0.0, support(after, normal) + after.thickness - normal.dot(position));
    }
  }
  position += correction * normal;
  if (!friction) return correction;
  const Vector3d step = position - carried;
  const Vector3d tangential = step - normal * normal.dot(step);
  const double slide = tangential.norm();
  const double grip = after.friction * correction;
  // Inside the friction cone the point sticks; outside it slides, slowed by
  // mu times the normal impulse (here expressed as displacements).
  if (slide <= grip) position -= tangential;
  else position -= tangential * (grip / slide);
  return correction;
}

}  // namespace

SurfaceQuery query_surface(const Collider& collider, const Eigen::Vector3d& p) {
  return std::visit(
      [&](const auto& shape) -> SurfaceQuery {
        using Shape = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<Shape, PlaneCollider>) return query_plane(shape, p);
        else if constexpr (std::is_same_v<Shape, SphereCollider>) return ball_query(shape.center, shape.radius, p);
        else return query_capsule(shape, p);
      },
      collider.shape);
}

namespace {

/// Squared distance from p to the capsule's axis segment a-b.
double axis_distance2(const CapsuleCollider& capsule, const Vector3d& p) {
  const Vector3d axis = capsule.b - capsule.a, offset = p - capsule.a;
  const double axis2 = axis.squaredNorm();
  const double t = axis2 > 0.0 ? std::clamp(offset.dot(axis) / axis2, 0.0, 1.0) : 0.0;
  return (offset - t * axis).squaredNorm();
}

}  // namespace

bool surely_clear(const Collider& collider, const Eigen::Vector3d& p) {
  const auto* capsule = std::get_if<CapsuleCollider>(&collider.shape);
  if (!capsule) return false;
  // A tapered capsule lies inside the round one of its larger radius, so a
  // point farther than that radius plus thickness from the axis segment is
  // clear: no square root, and tighter than a bounding ball. A micrometre
  // more leaves the points a push put exactly at the thickness (resting
  // cloth) to the exact query, whose rounding may still push them.
  constexpr double kRoundingMargin = 1e-6;  // metres
  const double reach = std::max(capsule->radius_a, capsule->radius_b) + collider.thickness + kRoundingMargin;
  return axis_distance2(*capsule, p) > reach * reach;
}

void validate_colliders(const std::vector<Collider>& colliders) {
  for (std::size_t i = 0; i < colliders.size(); ++i) {
    const Collider& collider = colliders[i];
    std::visit([&](const auto& shape) { validate_shape(i, shape); }, collider.shape);
    require_finite_at_least(i, kind_of(collider), "thickness", collider.thickness, 0.0, false);
    if (collider.thickness > kMostContactThickness)
      refuse(i, kind_of(collider),
             "thickness must be at most " + text(kMostContactThickness) + " m (got " + text(collider.thickness) + ")");
    require_finite_at_least(i, kind_of(collider), "friction", collider.friction, 0.0, false);
  }
}

constexpr int kMaxCollisionSweeps = 8;

Eigen::Vector3d carry_with(const Collider& before, const Collider& after, const Eigen::Vector3d& p) {
  if (const auto* from = std::get_if<SphereCollider>(&before.shape)) {
    if (const auto* to = std::get_if<SphereCollider>(&after.shape)) return p + (to->center - from->center);
  }
  if (const auto* from = std::get_if<CapsuleCollider>(&before.shape)) {
    if (const auto* to = std::get_if<CapsuleCollider>(&after.shape)) {
      const Vector3d axis_from = from->b - from->a, axis_to = to->b - to->a;
      const double length_from = axis_from.norm(), length_to = axis_to.norm();
      if (!(length_from > 0.0) || !(length_to > 0.0)) return p + (to->a - from->a);
      const Vector3d u = axis_from / length_from;
      const Vector3d offset = p - from->a;
      const double along = offset.dot(u);
      const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(axis_from, axis_to);
      return to->a + turn * (offset - along * u) + (along * length_to / length_from) * (axis_to / length_to);
    }
  }
  return p;
}

double resolve_point(const std::vector<Collider>& colliders, const Eigen::Vector3d& previous,
                     Eigen::Vector3d& position) {
  return resolve_point(colliders, colliders, previous, position, true);
}

namespace {

/// resolve_point's sweeps over `count` colliders, the k-th being index(k).
/// The sweeps end as they would over all of them (a single collider,
/// after.size() == 1, needs one sweep), so where the others are clear of
/// every position the sweeps pass through, the result is the same to the
/// bit. Callers check only where the point ends (CapsuleBody: within its
/// memo's trusted ball); a push out of that ball and back within one call
/// is the case this does not cover.
template <typename Index>
double resolve_sweeps(const std::vector<Collider>& before, const std::vector<Collider>& after, std::size_t count,
                      Index index, const Vector3d& start, Vector3d& position, bool friction) {
  assert(before.size() == after.size());
  double largest = 0.0;
  // Overlapping colliders (a body of capsules) can push a point from one
  // into another; sweep until a sweep changes nothing. Eight sweeps settle
  // every configuration the tests and the bodies we build produce; the cap
  // keeps a point wedged between two shapes from costing more.
  for (int sweep = 0; sweep < kMaxCollisionSweeps; ++sweep) {
    double this_sweep = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = index(k);
      this_sweep = std::max(this_sweep, resolve_against(before[i], after[i], start, position, friction));
    }
    largest = std::max(largest, this_sweep);
    if (this_sweep == 0.0 || after.size() == 1) break;
  }
  return largest;
}

}  // namespace

double resolve_point(const std::vector<Collider>& before, const std::vector<Collider>& after,
                     const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction) {
  return resolve_sweeps(before, after, after.size(), [](std::size_t k) { return k; }, start, position, friction);
}

double resolve_point_among(const std::vector<Collider>& before, const std::vector<Collider>& after,
                           const std::vector<int>& among, const Eigen::Vector3d& start, Eigen::Vector3d& position,
                           bool friction) {
  return resolve_sweeps(before, after, among.size(), [&](std::size_t k) { return static_cast<std::size_t>(among[k]); },
                        start, position, friction);
}

void colliders_near(const std::vector<Collider>& colliders, const Eigen::Vector3d& p, double margin,
                    std::vector<int>& out) {
  for (std::size_t i = 0; i < colliders.size(); ++i) {
    const Collider& collider = colliders[i];
    // Far when the distance to the axis (or centre) is at least its radius
    // plus thickness plus margin, compared squared.
    double distance2 = 0.0, reach = 0.0;
    if (const auto* capsule = std::get_if<CapsuleCollider>(&collider.shape)) {
      distance2 = axis_distance2(*capsule, p);
      reach = std::max(capsule->radius_a, capsule->radius_b);
    } else if (const auto* sphere = std::get_if<SphereCollider>(&collider.shape)) {
      distance2 = (p - sphere->center).squaredNorm();
      reach = sphere->radius;
    } else {
      out.push_back(static_cast<int>(i));  // a plane is everywhere
      continue;
    }
    reach += collider.thickness + margin;
    if (!(distance2 >= reach * reach)) out.push_back(static_cast<int>(i));
  }
}

SurfaceNearby nearest_surface(const std::vector<Collider>& colliders, const Eigen::Vector3d& p, double reach) {
  SurfaceNearby nearby;
  nearby.clearance = std::numeric_limits<double>::infinity();
  double planed = nearby.clearance;  // the clearance of the surface nearby.point lies on
  for (const Collider& collider : colliders) {
    // A capsule or sphere is at least its axis' distance less its larger
    // radius away: beyond reach that bound is all the clearance needs.
    double bound = -std::numeric_limits<double>::infinity();
    if (const auto* capsule = std::get_if<CapsuleCollider>(&collider.shape))
      bound = std::sqrt(axis_distance2(*capsule, p)) - std::max(capsule->radius_a, capsule->radius_b) - collider.thickness;
    else if (const auto* sphere = std::get_if<SphereCollider>(&collider.shape))
      bound = (p - sphere->center).norm() - sphere->radius - collider.thickness;
    if (bound >= reach) {
      nearby.clearance = std::min(nearby.clearance, bound);
      continue;
    }
    const SurfaceQuery q = query_surface(collider, p);
    const double clearance = q.distance - collider.thickness;
    nearby.clearance = std::min(nearby.clearance, clearance);
    if (clearance < planed) {
      planed = clearance;
      nearby.has_plane = true;
      nearby.normal = q.normal;
      nearby.point = p - clearance * q.normal;
    }
  }
  // The plane is the nearest surface's, or none (one only bounded is nearer).
  if (planed > nearby.clearance) nearby.has_plane = false;
  // A point resolve_point left a hair inside (its sweeps are capped in
  // sharp corners) counts as on the surface.
  nearby.clearance = std::max(0.0, nearby.clearance);
  return nearby;
}

double penetration(const std::vector<Collider>& colliders, const Eigen::Vector3d& p) {
  double deepest = 0.0;
  for (const Collider& collider : colliders) {
    if (surely_clear(collider, p)) continue;  // beyond thickness: adds nothing
    deepest = std::max(deepest, collider.thickness - query_surface(collider, p).distance);
  }
  return deepest;
}

double depth(const std::vector<Collider>& colliders, const Eigen::Vector3d& p) {
  double deepest = 0.0;
  for (const Collider& collider : colliders) {
    if (surely_clear(collider, p)) continue;  // beyond thickness, so outside
    deepest = std::max(deepest, -query_surface(collider, p).distance);
  }
  return deepest;
}

}  // namespace mrcloth
