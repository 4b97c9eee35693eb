#include "solver/colliders.h"

#include "mesh_ops/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

Collider make(PlaneCollider plane, double thickness = 0.0, double friction = 0.0) {
  return Collider{plane, thickness, friction};
}
Collider make(SphereCollider sphere, double thickness = 0.0, double friction = 0.0) {
  return Collider{sphere, thickness, friction};
}
Collider make(CapsuleCollider capsule, double thickness = 0.0, double friction = 0.0) {
  return Collider{capsule, thickness, friction};
}

Vector3d random_point(std::mt19937& rng, const Vector3d& low, const Vector3d& high) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  return Vector3d(low.x() + unit(rng) * (high.x() - low.x()), low.y() + unit(rng) * (high.y() - low.y()),
                  low.z() + unit(rng) * (high.z() - low.z()));
}

Vector3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  for (;;) {
    const Vector3d v(gauss(rng), gauss(rng), gauss(rng));
    if (v.norm() > 1e-3) return v.normalized();
  }
}

double segment_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

/// Brute-force signed distance to the convex hull of the discs (0, ra) and
/// (L, rb) at q = (t, h >= 0), by numerically maximising over directions n
/// the signed distance to the supporting line: for a convex body K,
/// sd(q) = max_n (n . q - support_K(n)), inside and outside alike, and the
/// support of a hull of discs is the larger of the discs' supports. A dense
/// angular grid finds the best candidates, golden-section search refines them.
double hull_distance_oracle(double t, double h, double length, double ra, double rb) {
  const auto f = [&](double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return std::min(c * t + s * h - ra, c * (t - length) + s * h - rb);
  };
  constexpr int kSteps = 4000;
  const double step = kPi / kSteps;
  std::vector<std::pair<double, int>> grid;
  for (int i = 0; i <= kSteps; ++i) grid.emplace_back(-f(i * step), i);
  std::partial_sort(grid.begin(), grid.begin() + 4, grid.end());
  double best = -grid[0].first;
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int candidate = 0; candidate < 4; ++candidate) {
    const int i = grid[candidate].second;
    double lo = std::max(0.0, (i - 1) * step), hi = std::min(kPi, (i + 1) * step);
    double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
    double f1 = f(x1), f2 = f(x2);
    for (int iteration = 0; iteration < 90; ++iteration) {
      if (f1 < f2) {
        lo = x1;
        x1 = x2;
        f1 = f2;
        x2 = lo + golden * (hi - lo);
        f2 = f(x2);
      } else {
        hi = x2;
        x2 = x1;
        f2 = f1;
        x1 = hi - golden * (hi - lo);
        f1 = f(x1);
      }
    }
    best = std::max({best, f1, f2, f(lo), f(hi)});
  }
  return best;
}

double oracle_distance(const CapsuleCollider& capsule, const Vector3d& p) {
  const Vector3d axis = capsule.b - capsule.a;
  const double length = axis.norm();
  if (length == 0.0) return (p - capsule.a).norm() - std::max(capsule.radius_a, capsule.radius_b);
  const Vector3d u = axis / length;
  const double t = (p - capsule.a).dot(u);
  const double h = ((p - capsule.a) - t * u).norm();
  return hull_distance_oracle(t, h, length, capsule.radius_a, capsule.radius_b);
}

Vector3d gradient_by_central_differences(const Collider& collider, const Vector3d& p, double step = 1e-6) {
  Vector3d gradient;
  for (int k = 0; k < 3; ++k) {
    Vector3d forward = p, backward = p;
    forward(k) += step;
    backward(k) -= step;
    gradient(k) = (query_surface(collider, forward).distance - query_surface(collider, backward).distance) / (2 * step);
  }
  return gradient;
}

/// A radius-0 end of a capsule: the sharp tip of a cone, where the surface
/// has no normal.
bool is_cone_tip(const Collider& collider, const Vector3d& x) {
  const auto* capsule = std::get_if<CapsuleCollider>(&collider.shape);
  return capsule && ((capsule->radius_a == 0 && (x - capsule->a).norm() < 1e-9) ||
                     (capsule->radius_b == 0 && (x - capsule->b).norm() < 1e-9));
}

/// The closest surface point p - d n lies on the surface and has the same
/// normal (except at a cone tip, where the surface has none).
void expect_closest_point_consistent(const Collider& collider, const Vector3d& p, const std::string& where) {
  const SurfaceQuery query = query_surface(collider, p);
  const Vector3d foot = p - query.distance * query.normal;
  const SurfaceQuery at_foot = query_surface(collider, foot);
  EXPECT_NEAR(at_foot.distance, 0.0, 1e-12) << where;
  if (std::abs(query.distance) > 1e-6 && !is_cone_tip(collider, foot)) {
    EXPECT_LT((at_foot.normal - query.normal).norm(), 1e-9) << where;
  }
}

std::vector<CapsuleCollider> random_tapered_capsules(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> radius(0.0, 0.6);
  std::vector<CapsuleCollider> capsules;
  for (int i = 0; i < count; ++i) {
    CapsuleCollider capsule;
    capsule.a = random_point(rng, Vector3d::Constant(-1), Vector3d::Constant(1));
    capsule.b = random_point(rng, Vector3d::Constant(-1), Vector3d::Constant(1));
    capsule.radius_a = radius(rng);
    capsule.radius_b = radius(rng);
    if (i % 7 == 3) capsule.radius_b = 0.0;  // a pointed cone end
    if (i % 7 == 5) capsule.b = capsule.a + 0.5 * (capsule.b - capsule.a).normalized() *
                                                std::abs(capsule.radius_a - capsule.radius_b);  // one ball inside the other
    capsules.push_back(capsule);
  }
  return capsules;
}

// ---------------------------------------------------------------------------
// query_surface against closed forms

TEST(SurelyClear, NeverSkipsAPointWithinTheThickness) {
  // The cull may only skip points the exact query finds farther than the
  // thickness, and must skip points well away from the axis.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  Collider capsule{CapsuleCollider{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.3, 0.1, 0), 0.12, 0.05}, 0.01, 0.3};
  int skipped = 0;
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (!surely_clear(capsule, p)) continue;
    ++skipped;
    EXPECT_GT(query_surface(capsule, p).distance, capsule.thickness) << p.transpose();
  }
  EXPECT_GT(skipped, 2500);
  EXPECT_TRUE(surely_clear(capsule, Eigen::Vector3d(2, 0, 0)));
  EXPECT_FALSE(surely_clear(capsule, Eigen::Vector3d(0.15, 0.05, 0.12 + 0.005)));
  EXPECT_FALSE(surely_clear(Collider{SphereCollider{Eigen::Vector3d::Zero(), 0.1}, 0.0, 0.0}, Eigen::Vector3d(5, 0, 0)))
      << "only capsules are culled";
  // Tighter than a bounding ball: beside the middle of a long capsule,
  // 2 cm beyond its thickness, well inside the ball round it.
  const Collider rod{CapsuleCollider{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.05, 0.05}, 0.01, 0.3};
  EXPECT_TRUE(surely_clear(rod, Eigen::Vector3d(0.5, 0.08, 0)));
  // A point a push left exactly at the thickness (resting cloth) goes to the
  // exact query, whatever the rounding of the cull: points pushed out of
  // the rod and of the tapered capsule are never culled.
  EXPECT_FALSE(surely_clear(rod, Eigen::Vector3d(0.5, 0.06, 0)));
  int pushed = 0;
  for (const Collider& c : {rod, capsule}) {
    const std::vector<Collider> one{c};
    for (int i = 0; i < 20000; ++i) {
      Eigen::Vector3d p(u(rng), u(rng), u(rng));
      p *= 0.3;
      p.x() += 0.3;
      if (resolve_point(one, one, p, p, false) <= 0.0) continue;
      ++pushed;
      EXPECT_FALSE(surely_clear(c, p)) << "a point pushed to the thickness was culled: " << p.transpose();
    }
  }
  EXPECT_GT(pushed, 1000);
}

TEST(QuerySurface, PlaneIsTheSignedDistanceAlongTheNormalisedNormal) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    PlaneCollider plane{random_point(rng, Vector3d::Constant(-1), Vector3d::Constant(1)),
                        3.0 * random_unit(rng)};
    const Vector3d n = plane.normal.normalized();
    for (int i = 0; i < 40; ++i) {
      const Vector3d p = random_point(rng, Vector3d::Constant(-3), Vector3d::Constant(3));
      const SurfaceQuery query = query_surface(make(plane), p);
      EXPECT_NEAR(query.distance, n.dot(p - plane.point), 1e-12);
      EXPECT_LT((query.normal - n).norm(), 1e-15);
    }
  }
}

TEST(QuerySurface, SphereIsDistanceToCentreLessRadius) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 50; ++trial) {
    SphereCollider sphere{random_point(rng, Vector3d::Constant(-1), Vector3d::Constant(1)), 0.05 + trial * 0.02};
    for (int i = 0; i < 40; ++i) {
      const Vector3d p = random_point(rng, Vector3d::Constant(-3), Vector3d::Constant(3));
      const SurfaceQuery query = query_surface(make(sphere), p);
      EXPECT_NEAR(query.distance, (p - sphere.center).norm() - sphere.radius, 1e-12);
      EXPECT_LT((query.normal - (p - sphere.center).normalized()).norm(), 1e-12);
    }
  }
  const SurfaceQuery centre = query_surface(make(SphereCollider{{1, 2, 3}, 0.5}), {1, 2, 3});
  EXPECT_EQ(centre.distance, -0.5);
  EXPECT_EQ(centre.normal, Vector3d::UnitY()) << "at the centre the normal is +y by convention";
}

TEST(QuerySurface, EqualRadiiCapsuleIsDistanceToSegmentLessRadius) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 60; ++trial) {
    CapsuleCollider capsule;
    capsule.a = random_point(rng, Vector3d::Constant(-1), Vector3d::Constant(1));
    capsule.b = random_point(rng, Vector3d::Constant(-1), Vector3d::Constant(1));
    capsule.radius_a = capsule.radius_b = 0.02 + 0.01 * trial;
    for (int i = 0; i < 60; ++i) {
      const Vector3d p = random_point(rng, Vector3d::Constant(-2), Vector3d::Constant(2));
      const SurfaceQuery query = query_surface(make(capsule), p);
      EXPECT_NEAR(query.distance, segment_distance(p, capsule.a, capsule.b) - capsule.radius_a, 1e-12)
          << "capsule " << trial << " point " << i;
      EXPECT_NEAR(query.normal.norm(), 1.0, 1e-12);
    }
  }
}

TEST(QuerySurface, TaperedCapsuleMatchesBruteForceHullDistance) {
  std::mt19937 rng(4);
  int inside = 0, outside = 0;
  for (const CapsuleCollider& capsule : random_tapered_capsules(rng, 70)) {
    const Vector3d low = capsule.a.cwiseMin(capsule.b).array() - 1.0;
    const Vector3d high = capsule.a.cwiseMax(capsule.b).array() + 1.0;
    for (int i = 0; i < 60; ++i) {
      // Every fifth point lies exactly on the axis line, where the radial
      // direction is undefined.
      std::uniform_real_distribution<double> along(-0.5, 1.5);
      const Vector3d p = i % 5 == 0 ? Vector3d(capsule.a + along(rng) * (capsule.b - capsule.a))
                                    : random_point(rng, low, high);
      const SurfaceQuery query = query_surface(make(capsule), p);
      EXPECT_NEAR(query.distance, oracle_distance(capsule, p), 1e-9)
          << "a " << capsule.a.transpose() << " b " << capsule.b.transpose() << " ra " << capsule.radius_a << " rb "
          << capsule.radius_b << " p " << p.transpose();
      EXPECT_NEAR(query.normal.norm(), 1.0, 1e-12);
      (query.distance < 0 ? inside : outside)++;
    }
  }
  EXPECT_GT(inside, 200) << "the sample should probe the inside too";
  EXPECT_GT(outside, 200);
}

/// Where the slant meets the end caps the pieces of the formula switch;
/// sample densely within a millimetre of those two circles, inside and out.
TEST(QuerySurface, TaperedCapsuleMatchesBruteForceWhereTheSlantMeetsTheCaps) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> across(-1e-3, 1e-3), off(-0.05, 0.3);
  int checked = 0;
  for (const CapsuleCollider& capsule : random_tapered_capsules(rng, 70)) {
    const Vector3d axis = capsule.b - capsule.a;
    const double length = axis.norm(), dr = capsule.radius_a - capsule.radius_b;
    if (length <= std::abs(dr)) continue;  // a ball: no slant
    const Vector3d u = axis / length;
    const double s = dr / length, c = std::sqrt(1 - s * s);
    for (int i = 0; i < 40; ++i) {
      Vector3d radial = random_unit(rng);
      radial = (radial - u * u.dot(radial)).normalized();
      const Vector3d n = s * u + c * radial, along_slant = c * u - s * radial;
      const bool at_a = i % 2 == 0;
      const Vector3d touch = at_a ? Vector3d(capsule.a + capsule.radius_a * n) : Vector3d(capsule.b + capsule.radius_b * n);
      const Vector3d p = touch + off(rng) * n + across(rng) * along_slant;
      EXPECT_NEAR(query_surface(make(capsule), p).distance, oracle_distance(capsule, p), 1e-9)
          << "a " << capsule.a.transpose() << " b " << capsule.b.transpose() << " ra " << capsule.radius_a << " rb "
          << capsule.radius_b << " p " << p.transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(QuerySurface, TaperedCapsuleWithEqualRadiiIsAnOrdinaryCapsule) {
  std::mt19937 rng(5);
  const CapsuleCollider capsule{{0.1, -0.2, 0.3}, {0.7, 0.4, -0.1}, 0.25, 0.25};
  for (int i = 0; i < 500; ++i) {
    const Vector3d p = random_point(rng, Vector3d::Constant(-1), Vector3d::Constant(1.5));
    const SurfaceQuery query = query_surface(make(capsule), p);
    EXPECT_NEAR(query.distance, segment_distance(p, capsule.a, capsule.b) - 0.25, 1e-12);
    // Outside the end caps the normal is radial from the end point.
    const double t = (p - capsule.a).dot(capsule.b - capsule.a) / (capsule.b - capsule.a).squaredNorm();
    if (t < 0) {
      EXPECT_LT((query.normal - (p - capsule.a).normalized()).norm(), 1e-12);
    } else if (t > 1) {
      EXPECT_LT((query.normal - (p - capsule.b).normalized()).norm(), 1e-12);
    } else {
      EXPECT_NEAR(query.normal.dot(capsule.b - capsule.a), 0.0, 1e-12);
    }
  }
}

TEST(QuerySurface, OneBallInsideTheOtherIsTheLargerBall) {
  const CapsuleCollider big_a{{0, 0, 0}, {0.3, 0, 0}, 1.0, 0.5};
  const CapsuleCollider big_b{{0, 0, 0}, {0, 0.2, 0}, 0.1, 0.4};
  const CapsuleCollider same{{1, 1, 1}, {1, 1, 1}, 0.3, 0.3};
  std::mt19937 rng(6);
  for (int i = 0; i < 200; ++i) {
    const Vector3d p = random_point(rng, Vector3d::Constant(-2), Vector3d::Constant(2));
    EXPECT_NEAR(query_surface(make(big_a), p).distance, p.norm() - 1.0, 1e-12);
    EXPECT_NEAR(query_surface(make(big_b), p).distance, (p - big_b.b).norm() - 0.4, 1e-12);
    EXPECT_NEAR(query_surface(make(same), p).distance, (p - same.a).norm() - 0.3, 1e-12);
  }
}

TEST(QuerySurface, OnTheAxisTheNormalIsAFixedPerpendicular) {
  const CapsuleCollider capsule{{0, 0, 0}, {0, 2, 0}, 0.3, 0.3};
  const SurfaceQuery first = query_surface(make(capsule), {0, 1, 0});
  const SurfaceQuery again = query_surface(make(capsule), {0, 1, 0});
  EXPECT_DOUBLE_EQ(first.distance, -0.3);
  EXPECT_NEAR(first.normal.norm(), 1.0, 1e-15);
  EXPECT_NEAR(first.normal.y(), 0.0, 1e-15) << "perpendicular to the axis";
  EXPECT_EQ(first.normal, again.normal) << "deterministic";

  const CapsuleCollider cone{{0, 0, 0}, {0, 0, 1}, 0.4, 0.1};
  const SurfaceQuery tapered = query_surface(make(cone), {0, 0, 0.5});
  EXPECT_NEAR(tapered.normal.norm(), 1.0, 1e-15);
  // The slant normal leans away from the thicker end: n . axis = (ra - rb) / L.
  EXPECT_NEAR(tapered.normal.z(), 0.3, 1e-15);
}

// ---------------------------------------------------------------------------
// Normals are gradients

TEST(QuerySurface, NormalIsTheFiniteDifferenceGradient) {
  std::mt19937 rng(7);
  std::vector<Collider> colliders = {make(PlaneCollider{{0.1, 0.2, 0.3}, {1, 2, -0.5}}),
                                     make(SphereCollider{{0.2, -0.1, 0.4}, 0.35})};
  for (const CapsuleCollider& capsule : random_tapered_capsules(rng, 30)) colliders.push_back(make(capsule));
  int checked = 0;
  for (std::size_t c = 0; c < colliders.size(); ++c) {
    for (int i = 0; i < 60; ++i) {
      const Vector3d p = random_point(rng, Vector3d::Constant(-2), Vector3d::Constant(2));
      const SurfaceQuery query = query_surface(colliders[c], p);
      // The distance is smooth everywhere outside a convex body, and inside a
      // plane or a ball away from its centre; elsewhere inside it has ridges.
      const bool smooth = query.distance > 1e-2 || c == 0 ||
                          (c == 1 && (p - Vector3d(0.2, -0.1, 0.4)).norm() > 1e-3);
      if (!smooth) continue;
      const Vector3d gradient = gradient_by_central_differences(colliders[c], p);
      EXPECT_LT((gradient - query.normal).norm(), 1e-6) << "collider " << c << " p " << p.transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(QuerySurface, ClosestPointLiesOnTheSurfaceWithTheSameNormal) {
  std::mt19937 rng(8);
  std::vector<Collider> colliders = {make(PlaneCollider{{0.1, 0.2, 0.3}, {1, 2, -0.5}}),
                                     make(SphereCollider{{0.2, -0.1, 0.4}, 0.35})};
  for (const CapsuleCollider& capsule : random_tapered_capsules(rng, 30)) colliders.push_back(make(capsule));
  for (std::size_t c = 0; c < colliders.size(); ++c) {
    for (int i = 0; i < 60; ++i) {
      const Vector3d p = random_point(rng, Vector3d::Constant(-2), Vector3d::Constant(2));
      expect_closest_point_consistent(colliders[c], p, "collider " + std::to_string(c));
    }
  }
}

// ---------------------------------------------------------------------------
// resolve_point and penetration

TEST(ResolvePoint, LeavesAClearPointAlone) {
  const std::vector<Collider> colliders = {make(PlaneCollider{}, 0.01, 0.5)};
  Vector3d position(0.3, 0.02, 0.1);
  EXPECT_EQ(resolve_point(colliders, {0, 0.5, 0}, position), 0.0);
  EXPECT_EQ(position, Vector3d(0.3, 0.02, 0.1));
}

TEST(ResolvePoint, ProjectsToThicknessAndReturnsTheCorrection) {
  const std::vector<Collider> colliders = {make(PlaneCollider{{0, 1, 0}, {0, 1, 0}}, 0.01, 0.0)};
  Vector3d position(0.3, 0.95, 0.1);
  EXPECT_NEAR(resolve_point(colliders, {0.3, 1.5, 0.1}, position), 0.06, 1e-15);
  EXPECT_NEAR(position.y(), 1.01, 1e-15);
  EXPECT_NEAR(penetration(colliders, position), 0.0, 1e-15);
}

/// Previous positions at least `thickness` clear of every collider, steps up
/// to 0.2: after resolution nothing is left inside the thickness band.
TEST(ResolvePoint, NoPointIsLeftInsideAnyCollider) {
  const std::vector<Collider> colliders = {
      make(PlaneCollider{{0, 0, 0}, {0, 1, 0}}, 0.002, 0.3),          // floor
      make(PlaneCollider{{-1, 0, 0}, {1, 0, 0}}, 0.003, 0.6),         // wall: a right-angle corner with the floor
      make(SphereCollider{{0, 1, 0}, 0.3}, 0.002, 0.3),               //
      make(CapsuleCollider{{2, 0.8, 0}, {2, 1.6, 0.5}, 0.3, 0.1}, 0.004, 0.2),
      make(CapsuleCollider{{0.3, 1.8, -0.6}, {1.2, 1.8, -0.6}, 0.15, 0.15}, 0.0, 1.5)};
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> step(-0.2, 0.2);
  int corrected = 0;
  for (int i = 0; i < 20000; ++i) {
    Vector3d previous;
    do previous = random_point(rng, {-1.2, -0.2, -1}, {3, 2.2, 1});
    while (penetration(colliders, previous) > 0.0);
    Vector3d position = previous + Vector3d(step(rng), step(rng), step(rng));
    const bool inside = penetration(colliders, position) > 0;
    const double correction = resolve_point(colliders, previous, position);
    EXPECT_LE(penetration(colliders, position), 1e-12) << "previous " << previous.transpose();
    EXPECT_EQ(correction > 0, inside) << "a correction is reported exactly when one was needed";
    corrected += inside;
  }
  EXPECT_GT(corrected, 500) << "the sample should push many points out";
}

TEST(ResolvePoint, DeepInsideAnyColliderComesOutAtThickness) {
  std::mt19937 rng(10);
  for (const CapsuleCollider& capsule : random_tapered_capsules(rng, 40)) {
    const std::vector<Collider> colliders = {make(capsule, 0.01, 0.0)};
    for (int i = 0; i < 40; ++i) {
      Vector3d position = random_point(rng, Vector3d::Constant(-1.5), Vector3d::Constant(1.5));
      resolve_point(colliders, position, position);
      EXPECT_LE(penetration(colliders, position), 1e-12);
      EXPECT_GE(query_surface(colliders[0], position).distance, 0.01 - 1e-12);
    }
  }
}

// ---------------------------------------------------------------------------
// Moving colliders: carry_with and the entry-side response

TEST(CarryWith, MovesPointsRigidlyWithTheCollider) {
  const Collider before = make(CapsuleCollider{{0, 0, 0}, {0, 1, 0}, 0.1, 0.05});
  // The capsule turns 90 degrees about z (its axis from +y to -x) and moves by (1, 2, 3).
  const Collider after = make(CapsuleCollider{{1, 2, 3}, {0, 2, 3}, 0.1, 0.05});
  std::mt19937 rng(21);
  for (int i = 0; i < 200; ++i) {
    const Vector3d p = random_point(rng, Vector3d::Constant(-1), Vector3d::Constant(1));
    const Vector3d q = carry_with(before, after, p);
    EXPECT_NEAR(q.x(), 1.0 - p.y(), 1e-12);
    EXPECT_NEAR(q.y(), 2.0 + p.x(), 1e-12);
    EXPECT_NEAR(q.z(), 3.0 + p.z(), 1e-12);
    EXPECT_NEAR(query_surface(after, q).distance, query_surface(before, p).distance, 1e-12)
        << "the distance to a rigidly moved capsule is kept";
  }
  const Collider sphere0 = make(SphereCollider{{0, 0, 0}, 0.2}), sphere1 = make(SphereCollider{{0.5, 0, -1}, 0.2});
  EXPECT_EQ(carry_with(sphere0, sphere1, Vector3d(1, 1, 1)), Vector3d(1.5, 1, 0));
  const Collider plane = make(PlaneCollider{});
  EXPECT_EQ(carry_with(plane, plane, Vector3d(1, 1, 1)), Vector3d(1, 1, 1));
}

/// A leg (capsule along z, radius 0.1) sweeps 0.15 in +x through a point at
/// the origin that sat 0.12 in front of its axis: the point ends 0.03 behind
/// the new axis, where the nearest surface is the far side.
TEST(ResolvePoint, AColliderThatMovedPastAPointPushesItOutOnTheSideItCameFrom) {
  const std::vector<Collider> before = {make(CapsuleCollider{{-0.12, 0, -1}, {-0.12, 0, 1}, 0.1, 0.1}, 0.004, 0.0)};
  const std::vector<Collider> after = {make(CapsuleCollider{{0.03, 0, -1}, {0.03, 0, 1}, 0.1, 0.1}, 0.004, 0.0)};
  Vector3d position(0, 0, 0);
  EXPECT_NEAR(resolve_point(before, after, Vector3d(0, 0, 0), position), 0.134, 1e-12);
  EXPECT_NEAR(position.x(), 0.134, 1e-12) << "in front of the leg, where it was";
  EXPECT_NEAR(position.y(), 0.0, 1e-12);
  // Without the motion the nearest surface wins: out through the back.
  Vector3d static_position(0, 0, 0);
  resolve_point(after, after, Vector3d(0, 0, 0), static_position);
  EXPECT_NEAR(static_position.x(), 0.03 - 0.104, 1e-12);
}

/// The same sweep with the point also moving: the entry is found along the
/// point's path relative to the leg, and it leaves through that side's
/// tangent plane, outside the thickened capsule and never behind it.
TEST(ResolvePoint, EntrySideResponseLeavesEveryPointOutsideOnItsSide) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int flipped = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vector3d a0(unit(rng), unit(rng), unit(rng)), b0 = a0 + Vector3d(0.1 * unit(rng), 0.6, 0.1 * unit(rng));
    const Vector3d move(0.3 * unit(rng), 0.05 * unit(rng), 0.3 * unit(rng));
    const Collider from = make(CapsuleCollider{a0, b0, 0.1, 0.06}, 0.004, 0.0);
    const Collider to = make(CapsuleCollider{a0 + move, b0 + move, 0.1, 0.06}, 0.004, 0.0);
    Vector3d start;
    do start = a0 + Vector3d(0.3 * unit(rng), 0.6 * (unit(rng) + 1) / 2, 0.3 * unit(rng));
    while (query_surface(from, start).distance <= 0.004);
    Vector3d position = start + Vector3d(0.02 * unit(rng), 0.02 * unit(rng), 0.02 * unit(rng));
    // The oracle: where the path relative to the leg first enters it, by dense sampling.
    const Vector3d carried = carry_with(from, to, start);
    Vector3d entry_normal = Vector3d::Zero();
    for (int k = 1; k <= 20000; ++k) {
      const Vector3d x = carried + (k / 20000.0) * (position - carried);
      if (query_surface(to, x).distance < 0.004) {
        entry_normal = query_surface(to, x).normal;
        break;
      }
    }
    // Only points that end inside are resolved (a path through and out again
    // would need a leg faster than 0.2 m per step at these sizes).
    if (entry_normal == Vector3d::Zero() || query_surface(to, position).distance >= 0.004) continue;
    flipped += query_surface(to, position).normal.dot(entry_normal) < 0.5;
    resolve_point({from}, {to}, start, position);
    EXPECT_GE(query_surface(to, position).distance, 0.004 - 1e-12);
    EXPECT_GT(query_surface(to, position).normal.dot(entry_normal), 0.0) << "start " << start.transpose();
  }
  EXPECT_GT(flipped, 20) << "the sample must include points the nearest surface would flip";
}

/// Falling onto the floor y = 0 with sideways motion 1/16 and a normal
/// correction of 1/32 (dyadic, so the expected values are exact).
Vector3d land_on_floor(double mu) {
  const std::vector<Collider> floor = {make(PlaneCollider{}, 0.0, mu)};
  Vector3d position(0.0625, -0.03125, 0.0);
  EXPECT_EQ(resolve_point(floor, {0.0, 0.125, 0.0}, position), 0.03125);
  EXPECT_EQ(position.y(), 0.0);
  return position;
}

TEST(ResolvePoint, FrictionFollowsCoulomb) {
  EXPECT_EQ(land_on_floor(0.0).x(), 0.0625) << "mu = 0 keeps the tangential motion";
  EXPECT_EQ(land_on_floor(10.0).x(), 0.0) << "inside the friction cone the point sticks";
  EXPECT_EQ(land_on_floor(2.0).x(), 0.0) << "exactly on the cone (|dt| = mu dn) it sticks too";
  EXPECT_DOUBLE_EQ(land_on_floor(1.0).x(), 0.0625 - 1.0 * 0.03125) << "sliding loses mu dn";
  EXPECT_DOUBLE_EQ(land_on_floor(0.5).x(), 0.0625 - 0.5 * 0.03125);
  EXPECT_DOUBLE_EQ(land_on_floor(1.9).x(), 0.0625 - 1.9 * 0.03125);
  EXPECT_EQ(land_on_floor(1.0).z(), 0.0) << "friction only opposes the motion";
}

TEST(ResolvePoint, FrictionOnACurvedSurfaceReducesTangentialMotionByMuDn) {
  const SphereCollider sphere{{0, 0, 0}, 1.0};
  const Vector3d previous(0.0, 1.5, 0.0);
  for (const double mu : {0.0, 0.2, 0.7, 100.0}) {
    const std::vector<Collider> colliders = {make(sphere, 0.0, mu)};
    Vector3d position(0.1, 0.9, 0.0);
    const double dn = resolve_point(colliders, previous, position);
    EXPECT_NEAR(dn, 1.0 - std::hypot(0.1, 0.9), 1e-15);
    // The reference: the same projection, then the tangential part of the step shortened.
    const Vector3d n = Vector3d(0.1, 0.9, 0.0).normalized();
    const Vector3d projected = n;
    const Vector3d d = projected - previous;
    const Vector3d dt = d - n * n.dot(d);
    const Vector3d expected = dt.norm() <= mu * dn ? Vector3d(projected - dt)
                                                   : Vector3d(projected - dt * (mu * dn / dt.norm()));
    EXPECT_LT((position - expected).norm(), 1e-15) << "mu " << mu;
    EXPECT_LE(penetration(colliders, position), 1e-15);
  }
}

TEST(ResolvePoint, SweepsAreCappedInASharpCorner) {
  // A 45-degree wedge: y >= 0 and x >= y. Pushed out of the floor, the point
  // is pushed out of the wall back into the floor; each sweep halves that,
  // so it never settles and the cap of 8 sweeps ends it.
  const std::vector<Collider> wedge = {make(PlaneCollider{{0, 0, 0}, {0, 1, 0}}, 0.0, 0.0),
                                       make(PlaneCollider{{0, 0, 0}, {1, -1, 0}}, 0.0, 0.0)};
  Vector3d position(-0.1, -0.05, 0.0);
  const double correction = resolve_point(wedge, position, position);
  // Sweep 1: (-0.1, 0) then (-0.05, -0.05); sweep 2: (-0.05, 0) then
  // (-0.025, -0.025); ... sweep 8 ends at (-0.1, -0.1) / 2^8.
  EXPECT_LT((position - Vector3d(-0.1, -0.1, 0.0) / 256.0).norm(), 1e-15) << position.transpose();
  EXPECT_NEAR(correction, 0.1 / std::sqrt(2.0), 1e-15) << "the largest single correction";
}

TEST(ResolvePoint, OverlappingSpheresSettle) {
  // Two overlapping unit spheres; a point inside both near their lens is
  // pushed out of one into the other. Sweeps continue until it is outside both.
  const std::vector<Collider> body = {make(SphereCollider{{-0.5, 0, 0}, 1.0}, 0.0, 0.0),
                                      make(SphereCollider{{0.5, 0, 0}, 1.0}, 0.0, 0.0)};
  Vector3d position(0.0, 0.3, 0.0);
  resolve_point(body, position, position);
  EXPECT_LE(penetration(body, position), 1e-12) << position.transpose();
}

TEST(NearestSurface, IsTheExactNearestWithinReachAndABoundBeyond) {
  // Random points outside a plane, a sphere and two tapered capsules: the
  // clearance is the smallest exact distance less thickness wherever that
  // is within reach, else a lower bound of it; the plane is the nearest
  // thickened surface's, through the point's projection onto it.
  const std::vector<Collider> colliders = {make(PlaneCollider{{0, -0.5, 0}, {0, 1, 0}}, 0.002, 0.3),
                                           make(SphereCollider{{0.3, 0.0, 0.0}, 0.1}, 0.004, 0.3),
                                           make(CapsuleCollider{{-0.2, 0, 0}, {-0.2, 0.4, 0}, 0.06, 0.03}, 0.004, 0.3),
                                           make(CapsuleCollider{{0, 0.1, -0.3}, {0, 0.1, 0.3}, 0.05, 0.05}, 0.003, 0.3)};
  const double reach = 0.01;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> x(-0.45, 0.45), y(-0.5, 0.55), z(-0.4, 0.4);
  int exact = 0, bounded = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vector3d p(x(rng), y(rng), z(rng));
    double nearest = std::numeric_limits<double>::infinity();
    for (const Collider& c : colliders) nearest = std::min(nearest, query_surface(c, p).distance - c.thickness);
    if (nearest < 0.0) continue;  // resolve_point leaves no point there
    const SurfaceNearby n = nearest_surface(colliders, p, reach);
    if (nearest < reach) {
      ++exact;
      ASSERT_NEAR(n.clearance, nearest, 1e-12) << p.transpose();
      ASSERT_TRUE(n.has_plane);
      ASSERT_NEAR(n.normal.norm(), 1.0, 1e-12);
      ASSERT_LT((n.point + n.clearance * n.normal - p).norm(), 1e-12) << "p lies along the normal from the plane's point";
      double on = std::numeric_limits<double>::infinity();
      for (const Collider& c : colliders) on = std::min(on, query_surface(c, n.point).distance - c.thickness);
      ASSERT_NEAR(on, 0.0, 1e-12) << "the plane's point lies on the thickened surface";
    } else {
      ++bounded;
      ASSERT_LE(n.clearance, nearest + 1e-12) << p.transpose();
      ASSERT_GE(n.clearance, std::min(nearest, reach) - 1e-12) << "beyond reach, a bound no smaller than the reach";
    }
  }
  EXPECT_GT(exact, 200);
  EXPECT_GT(bounded, 2000);
  EXPECT_EQ(nearest_surface({}, Vector3d::Zero(), reach).clearance, std::numeric_limits<double>::infinity());
}

TEST(Penetration, IsTheDeepestIntrusionIntoTheThicknessBand) {
  const std::vector<Collider> colliders = {make(PlaneCollider{}, 0.01, 0.0),
                                           make(SphereCollider{{0, 1, 0}, 0.5}, 0.02, 0.0)};
  EXPECT_EQ(penetration(colliders, {0, 0.3, 0}), 0.0);
  EXPECT_NEAR(penetration(colliders, {0, 0.005, 0}), 0.005, 1e-15);
  EXPECT_NEAR(penetration(colliders, {0, -0.1, 0}), 0.11, 1e-15);
  EXPECT_NEAR(penetration(colliders, {0, 0.6, 0}), 0.12, 1e-15);
  EXPECT_EQ(penetration({}, {0, -5, 0}), 0.0);
}

TEST(Depth, IsTheDeepestIntrusionBelowTheSurfaceItself) {
  const std::vector<Collider> colliders = {make(PlaneCollider{}, 0.01, 0.0),
                                           make(SphereCollider{{0, 1, 0}, 0.5}, 0.02, 0.0)};
  EXPECT_EQ(depth(colliders, {0, 0.3, 0}), 0.0);
  EXPECT_EQ(depth(colliders, {0, 0.005, 0}), 0.0) << "within the thickness but outside the surface";
  EXPECT_NEAR(depth(colliders, {0, -0.1, 0}), 0.1, 1e-15);
  EXPECT_NEAR(depth(colliders, {0, 0.6, 0}), 0.1, 1e-15);
  EXPECT_EQ(depth({}, {0, -5, 0}), 0.0);
  // Inside a single collider depth is penetration less thickness, everywhere.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<Collider> capsule = {make(CapsuleCollider{{0, 0, 0}, {0, 1, 0}, 0.3, 0.1}, 0.02, 0.0)};
  int inside = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vector3d p(0.4 * u(rng), 0.5 + 0.7 * u(rng), 0.4 * u(rng));
    const double expected = std::max(0.0, -query_surface(capsule[0], p).distance);
    EXPECT_NEAR(depth(capsule, p), expected, 1e-15);
    if (expected > 0.0) {
      ++inside;
      EXPECT_NEAR(depth(capsule, p), penetration(capsule, p) - 0.02, 1e-15);
    }
  }
  EXPECT_GT(inside, 50);
}

// ---------------------------------------------------------------------------
// validate_colliders

void expect_refused(const Collider& bad, const std::string& who, const std::string& field) {
  const std::vector<Collider> colliders = {make(PlaneCollider{}), make(SphereCollider{}), bad};
  try {
    validate_colliders(colliders);
    ADD_FAILURE() << "accepted a bad " << who << " " << field;
  } catch (const ArgumentError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("collider 2 (" + who + ")"), std::string::npos) << message;
    EXPECT_NE(message.find(field), std::string::npos) << message;
  }
}

TEST(ValidateColliders, AcceptsTheDefaults) {
  EXPECT_NO_THROW(validate_colliders({}));
  EXPECT_NO_THROW(validate_colliders({make(SphereCollider{}, kMostContactThickness, 0.3), make(PlaneCollider{}, 0.0, 0.0)}));
  EXPECT_NO_THROW(validate_colliders({Collider{PlaneCollider{}}, Collider{SphereCollider{}},
                                      Collider{CapsuleCollider{}}, make(CapsuleCollider{{0, 0, 0}, {1, 0, 0}, 0.1, 0.0})}));
}

TEST(ValidateColliders, NamesTheColliderAndTheField) {
  const double nan = std::nan("");
  expect_refused(make(SphereCollider{{0, 0, 0}, 0.0}), "sphere", "radius");
  expect_refused(make(SphereCollider{{0, 0, 0}, -0.1}), "sphere", "radius");
  expect_refused(make(SphereCollider{{0, nan, 0}, 0.1}), "sphere", "center");
  expect_refused(make(PlaneCollider{{0, 0, 0}, {0, 0, 0}}), "plane", "normal");
  expect_refused(make(PlaneCollider{{0, 0, 0}, {0, HUGE_VAL, 0}}), "plane", "normal");
  expect_refused(make(CapsuleCollider{{0, 0, 0}, {1, 0, 0}, 0.0, 0.0}), "capsule", "radius_a and radius_b");
  expect_refused(make(CapsuleCollider{{0, 0, 0}, {1, 0, 0}, 0.1, -0.2}), "capsule", "radius_b");
  expect_refused(make(CapsuleCollider{{0, 0, 0}, {nan, 0, 0}, 0.1, 0.1}), "capsule", "b");
  expect_refused(make(SphereCollider{}, -0.001, 0.3), "sphere", "thickness");
  expect_refused(make(CapsuleCollider{}, std::nextafter(kMostContactThickness, 1.0), 0.3), "capsule", "thickness must be at most 0.05 m");
  expect_refused(make(PlaneCollider{}, HUGE_VAL, 0.3), "plane", "thickness");
  expect_refused(make(SphereCollider{}, 0.001, -0.3), "sphere", "friction");
  expect_refused(make(PlaneCollider{}, 0.001, nan), "plane", "friction");
}

}  // namespace
}  // namespace mrcloth
