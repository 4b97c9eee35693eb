// ImplicitIntegrator and simulate with colliders: collision rounds, pins
// inside a collider (reported, yielding), what simulate measures (depths, the
// worst on any thread count), no vertex left inside, contact planes, the
// contact slack, and the same bits on any thread count against a MeshBody.
#include "mesh_ops/errors.h"
#include "solver/implicit_integrator.h"
#include "solver/mesh_body.h"
#include "solver/simulate.h"

#include "implicit_integrator_support.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

using test::options;
using test::refined_sheet;
using test::sheet_pinned_at;

/// The corners of an axis-aligned box, `half` metres from `centre` along
/// each axis, numbered for box_triangles().
Eigen::MatrixX3d box_corners(const Eigen::Vector3d& centre, double half) {
  Eigen::MatrixX3d box(8, 3);
  for (int v = 0; v < 8; ++v)
    box.row(v) << centre.x() + ((v & 1) ^ ((v >> 1) & 1) ? half : -half), centre.y() + (v & 2 ? half : -half),
        centre.z() + (v & 4 ? half : -half);
  return box;
}

/// The box's twelve triangles, counter-clockwise seen from outside.
std::vector<Eigen::Vector3i> box_triangles() {
  return {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
          {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
}

// simulate's collision_rounds reaches the integrator: one round a step when
// asked, and at least two by default (the first round's friction leaves
// stretch the second limits).
TEST(ImplicitIntegrator, SimulateTakesItsRoundsFromTheOptions) {
  // A sheet pinned at two corners swinging down onto a sphere: the limiter
  // moves points it holds beyond their slack, so steps take more than one
  // round of (limiting, checking) unless the options allow only one.
  const DynamicsModel m = sheet_pinned_at({0, 10});
  SimulationOptions s;
  s.frames = 12;
  s.colliders.resize(1);
  s.colliders[0].shape = SphereCollider{{0.0, -0.2, 0.0}, 0.12};
  ClothState state = rest_state(m);
  EXPECT_GT(simulate(m, state, s).mean_rounds, 1.0);
  s.collision_rounds = 1;
  state = rest_state(m);
  EXPECT_EQ(simulate(m, state, s).mean_rounds, 1.0);
  s.collision_rounds = 0;
  state = rest_state(m);
  EXPECT_THROW(simulate(m, state, s), ArgumentError);
}

TEST(ImplicitIntegrator, SimulateReportsPinsInsideAColliderApartFromTheCloth) {
  // A sphere around a pinned corner (as a thigh rises into a waist pinned
  // to the pelvis in a squat), with the pins kept at their targets: nothing
  // pushes the pin out, and the report says so instead of blaming the
  // cloth, whose nearest vertex is 4 cm off.
  const DynamicsModel m = sheet_pinned_at({0, 10});
  SimulationOptions s;
  s.frames = 6;
  s.pins_yield = false;
  const Eigen::Vector3d corner = m.rest.row(0).transpose();
  s.colliders.resize(1);
  s.colliders[0].shape = SphereCollider{corner + Eigen::Vector3d(0.0, 0.005, 0.0), 0.02};
  ClothState state = rest_state(m);
  const SimulationReport r = simulate(m, state, s);
  EXPECT_NEAR(r.max_pinned_depth, 0.015, 1e-12);
  EXPECT_EQ(r.pinned_depth_frame, 0);
  EXPECT_NEAR(r.max_depth, 0.015, 1e-12);
  EXPECT_NEAR(r.max_penetration, 0.015 + s.colliders[0].thickness, 1e-12);
  EXPECT_EQ(r.deepest_vertex, 0);
  EXPECT_TRUE(r.penetration_pinned());
  EXPECT_EQ(r.max_cloth_depth, 0.0);
  EXPECT_EQ(r.max_cloth_penetration, 0.0);
  EXPECT_EQ(r.initial_penetration, 0.0);  // what the first step pushes out: not the pin
  EXPECT_EQ(r.max_pin_yield, 0.0);
  EXPECT_EQ(r.pin_yield_frame, -1);
  // The sheet swinging down onto a sphere under its middle instead: the
  // deepest is the cloth's (within the thickness), and the pins are clear.
  s.frames = 12;
  s.colliders[0].shape = SphereCollider{Eigen::Vector3d(m.rest.row(60).transpose()) + Eigen::Vector3d(0.0, -0.12, 0.0), 0.1};
  state = rest_state(m);
  const SimulationReport free = simulate(m, state, s);
  EXPECT_GT(free.max_cloth_penetration, 0.0);
  EXPECT_EQ(free.max_cloth_penetration, free.max_penetration);
  EXPECT_EQ(free.max_cloth_depth, free.max_depth);
  EXPECT_FALSE(free.penetration_pinned());
  EXPECT_EQ(free.max_pinned_depth, 0.0);
  EXPECT_EQ(free.pinned_depth_frame, -1);
}

TEST(ImplicitIntegrator, PinsInsideAColliderYieldOntoItsSurface) {
  // The same sphere around a pinned corner, with pins yielding (the
  // default): every step moves the pin from its target (5 mm below the
  // sphere's centre, 15 mm deep) straight out onto the surface, the pinned
  // edge from it to the other corner is what stretches, and no vertex is
  // below the surface at any output frame.
  const DynamicsModel m = sheet_pinned_at({0, 10});
  SimulationOptions s;
  s.frames = 6;
  ASSERT_TRUE(s.pins_yield);
  const Eigen::Vector3d corner = m.rest.row(0).transpose();
  const Eigen::Vector3d centre = corner + Eigen::Vector3d(0.0, 0.005, 0.0);
  s.colliders.resize(1);
  s.colliders[0].shape = SphereCollider{centre, 0.02};
  ClothState state = rest_state(m);
  std::vector<Positions> frames;
  const SimulationReport r = simulate(m, state, s, {}, {}, &frames);
  EXPECT_NEAR(r.max_pin_yield, 0.015, 1e-12);
  EXPECT_EQ(r.pin_yield_frame, 0);
  EXPECT_LT(r.max_depth, 1e-12);
  EXPECT_EQ(r.max_pinned_depth, r.max_depth);
  for (const Positions& x : frames) {
    EXPECT_NEAR((x.row(0).transpose() - centre).norm(), 0.02, 1e-12);  // on the surface
    EXPECT_NEAR(x(0, 0), corner.x(), 1e-12);                             // straight below the centre
    EXPECT_NEAR(x(0, 2), corner.z(), 1e-12);
    EXPECT_EQ(x.row(10), m.rest.row(10));  // the other pin, outside, at its target
  }
}

TEST(ImplicitIntegrator, APinYieldsOutOfEveryOverlappingCollider) {
  // The target 15 mm inside one sphere, whose surface below it lies inside
  // a second sphere beside it (two capsules overlapping at a hip): the pin
  // ends outside both, in the crease, never below either surface.
  const DynamicsModel m = sheet_pinned_at({0, 10});
  SimulationOptions s;
  s.frames = 4;
  const Eigen::Vector3d corner = m.rest.row(0).transpose();
  const Eigen::Vector3d upper = corner + Eigen::Vector3d(0.0, 0.005, 0.0), lower = corner + Eigen::Vector3d(0.012, -0.03, 0.0);
  s.colliders.resize(2);
  s.colliders[0].shape = SphereCollider{upper, 0.02};
  s.colliders[1].shape = SphereCollider{lower, 0.02};
  ClothState state = rest_state(m);
  std::vector<Positions> frames;
  const SimulationReport r = simulate(m, state, s, {}, {}, &frames);
  EXPECT_GT(r.max_pin_yield, 0.015);
  EXPECT_EQ(r.max_pinned_depth, 0.0);
  for (const Positions& x : frames) {
    const Eigen::Vector3d pin = x.row(0).transpose();
    EXPECT_GE((pin - upper).norm(), 0.02 - 1e-12);
    EXPECT_GE((pin - lower).norm(), 0.02 - 1e-12);
  }
}

TEST(ImplicitIntegrator, SimulateMeasuresTheSameWorstOnAnyThreadCount) {
  // Two opposite pinned corners sit 3 cm deep in equal spheres (pins kept
  // at their targets): the deepest vertex is a tie at every frame, between
  // vertices in different threads' parts, which the first vertex wins.
  const DynamicsModel m = sheet_pinned_at({0, 120});
  SimulationOptions s;
  s.frames = 4;
  s.pins_yield = false;
  s.colliders.resize(2);
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d corner = m.rest.row(k == 0 ? 0 : 120).transpose();
    s.colliders[static_cast<std::size_t>(k)].shape = SphereCollider{corner + Eigen::Vector3d(0.0, 0.03, 0.0), 0.06};
  }
  std::vector<SimulationReport> reports;
  for (const int threads : {1, 2, 3}) {
    s.threads = threads;
    ClothState state = rest_state(m);
    reports.push_back(simulate(m, state, s));
  }
  EXPECT_EQ(reports[0].deepest_vertex, 0);
  EXPECT_NEAR(reports[0].max_depth, 0.03, 1e-12);
  for (const SimulationReport& r : reports) {
    EXPECT_EQ(r.deepest_vertex, reports[0].deepest_vertex);
    EXPECT_EQ(r.deepest_frame, reports[0].deepest_frame);
    EXPECT_EQ(r.max_penetration, reports[0].max_penetration);
    EXPECT_EQ(r.max_depth, reports[0].max_depth);
    EXPECT_EQ(r.max_stretch, reports[0].max_stretch);
    EXPECT_EQ(r.max_self_crossings, reports[0].max_self_crossings);
  }
}

TEST(ImplicitIntegrator, SimulateMeasuresHowDeepFaceCentresSinkBetweenTheirCorners) {
  // A coarse 0.5 m sheet (5 x 5 vertices, 12.5 cm faces) falls onto a
  // sphere of 10 cm radius: only vertices collide, so the faces resting on
  // it sink into it between their corners. The report's face depth is the
  // deepest face centre below the sphere over the output frames, checked
  // against the sphere's own distance at every recorded frame.
  const DynamicsModel m = build_dynamics(test::make_sheet(5, 0.5), DynamicsOptions{});
  SimulationOptions s;
  s.frames = 20;
  s.colliders.resize(1);
  const Eigen::Vector3d centre(0.0, -0.15, 0.0);
  const double radius = 0.1;
  s.colliders[0].shape = SphereCollider{centre, radius};
  ClothState state = rest_state(m);
  std::vector<Positions> frames;
  const SimulationReport report = simulate(m, state, s, {}, {}, &frames);
  ASSERT_EQ(frames.size(), 20u);
  double expected = 0.0;
  for (const Positions& x : frames)
    for (const auto& face : m.corners) {
      const Eigen::Vector3d c = 0.25 * (x.row(face[0]) + x.row(face[1]) + x.row(face[2]) + x.row(face[3])).transpose();
      expected = std::max(expected, radius - (c - centre).norm());
    }
  EXPECT_GT(expected, 0.01) << "the faces should sink in: the test means nothing otherwise";
  EXPECT_NEAR(report.max_face_depth, expected, 1e-12);
  EXPECT_LT(report.max_depth, 1e-3) << "the vertices stay outside";
}

TEST(ImplicitIntegrator, NoVertexEndsAStepInsideACollider) {
  const QuadMesh mesh = refined_sheet();
  const DynamicsModel m = build_dynamics(mesh, {});
  ImplicitIntegrator integrator;
  integrator.precompute(m, options(1.0 / 120));
  std::vector<Collider> colliders(2);
  colliders[0].shape = SphereCollider{{-0.1, -0.2, -0.1}, 0.15};
  colliders[1].shape = PlaneCollider{{0, -0.5, 0}, {0, 1, 0}};
  ClothState s = rest_state(m);
  double worst = 0.0, pushed = 0.0;
  for (int k = 0; k < 240; ++k) {
    pushed = std::max(pushed, integrator.step(s, s.pinned, colliders).max_correction);
    const Positions x = full_positions(m, s.positions, s.pinned);
    for (Eigen::Index v = 0; v < x.rows(); ++v) worst = std::max(worst, penetration(colliders, x.row(v).transpose()));
  }
  // A point pushed with friction keeps a plane across its push, tilted by
  // at most the friction angle; sliding along it within its slack it may
  // sink that much into the thickness (plus the sphere's curvature).
  const IntegratorOptions o = integrator.options();
  const double mu = colliders[0].friction, slack = o.contact_slack;
  const double stated = slack * mu / std::sqrt(1.0 + mu * mu) + slack * slack / (2.0 * 0.15) + 1e-4;
  EXPECT_LE(worst, stated) << "stated tolerance: 0.1 mm, and the slack along a plane tilted by friction";
  EXPECT_LT(worst, colliders[0].thickness) << "never inside the collider itself";
  EXPECT_GT(pushed, 0.0) << "the sheet never touched a collider; the test proves nothing";
}

// A free sheet lying on a sphere that rises as fast as a swinging limb (2.4 m/s): the sphere
// lifts the middle and the strain limiter must bring the lagging edges
// along. Returns the largest strain and the deepest penetration at the end
// of any step.
std::pair<double, double> lift(const QuadMesh& mesh, bool contact_planes) {
  const DynamicsModel m = build_dynamics(mesh, {});
  IntegratorOptions o = options(1.0 / 120);
  o.contact_planes = contact_planes;
  o.collision_rounds = 2;  // what a step can afford when collisions are costly
  ImplicitIntegrator integrator;
  integrator.precompute(m, o);
  ClothState s = rest_state(m);
  std::vector<Collider> sphere(1);
  double stretch = 0.0, deepest = 0.0;
  for (int k = 0; k < 60; ++k) {
    sphere[0].shape = SphereCollider{{0.0, -0.122 + 0.02 * k, 0.0}, 0.12};
    integrator.step(s, s.pinned, sphere);
    const Positions x = full_positions(m, s.positions, s.pinned);
    stretch = std::max(stretch, max_stretch(m, x));
    for (Eigen::Index v = 0; v < x.rows(); ++v) deepest = std::max(deepest, penetration(sphere, x.row(v).transpose()));
  }
  return {stretch, deepest};
}

TEST(ImplicitIntegrator, ContactPlanesLetTheLimiterPullFreeClothOverAContact) {
  for (const QuadMesh& mesh : {test::make_sheet(11, 0.5), refined_sheet()}) {
    const auto [with_planes, deep_with] = lift(mesh, true);
    const auto [without, deep_without] = lift(mesh, false);
    std::printf("lift (%d vertices): max strain %.4f with contact planes, %.4f without; deepest %.2e / %.2e m\n",
                static_cast<int>(mesh.n_vertices()), with_planes, without, deep_with, deep_without);
    EXPECT_GT(without, 0.09) << "the lift should overstretch the cloth without planes; the test proves nothing";
    EXPECT_LT(with_planes, 0.7 * without);  // measured 0.03-0.05 against 0.11-0.12 (0.07-0.10 against 0.16 with plain sweeps)
    EXPECT_LE(deep_with, 0.002 * 0.3 + 1e-4) << "the slack along a plane tilted by friction (mu 0.3)";
  }
}

TEST(ImplicitIntegrator, AnyThreadCountGivesTheSameBits) {
  // A refined sheet (T-nodes), pinned at two corners, falling onto a rising
  // box body (a MeshBody: memos, friction relative to its motion, points
  // carried out where they entered) and a sphere: each vertex's resolve is
  // its own, so one, two or three threads must give the same bits.
  DynamicsOptions d;
  d.pinned = {0, 10};
  const DynamicsModel m = build_dynamics(refined_sheet(), d);
  const Eigen::MatrixX3d box = box_corners({0.05, -0.3, 0.0}, 0.15);
  const std::vector<Eigen::Vector3i> faces = box_triangles();
  std::vector<Collider> sphere(1);
  sphere[0].shape = SphereCollider{{-0.2, -0.2, 0.1}, 0.1};
  const AnalyticScene fixed(sphere);
  const auto run = [&](int threads) {
    MeshBody body(box, faces, 0.004, 0.3);
    CompositeScene scene;
    scene.add(&fixed);
    scene.add(&body);
    IntegratorOptions o = options(1.0 / 120);
    o.threads = threads;
    o.contact_slack = 0.003;  // the checks after the first are per vertex too
    ImplicitIntegrator integrator;
    integrator.precompute(m, o);
    ClothState s = rest_state(m);
    double pushed = 0.0;
    for (int k = 0; k < 150; ++k) {
      body.update(box.rowwise() + Eigen::RowVector3d(0.0, 0.002 * k, 0.0));
      pushed = std::max(pushed, integrator.step(s, s.pinned, scene).max_correction);
    }
    EXPECT_GT(pushed, 0.0) << "the sheet never met the box or the sphere";
    return s;
  };
  const ClothState one = run(1);
  for (const int threads : {2, 3}) {
    const ClothState many = run(threads);
    EXPECT_EQ(std::memcmp(one.positions.data(), many.positions.data(), sizeof(double) * one.positions.size()), 0)
        << threads << " threads";
    EXPECT_EQ(std::memcmp(one.velocities.data(), many.velocities.data(), sizeof(double) * one.velocities.size()), 0)
        << threads << " threads";
  }
  IntegratorOptions none = options(1.0 / 120);
  none.threads = 0;
  ImplicitIntegrator refused;
  EXPECT_THROW(refused.precompute(m, none), ArgumentError);
}

/// Counts the resolves asked of a scene.
class CountingScene : public CollisionScene {
 public:
  explicit CountingScene(const CollisionScene& inner) : inner_(inner) {}
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                 ContactMemo* memo = nullptr, SurfaceNearby* nearby = nullptr) const override {
    ++resolves;
    return inner_.resolve(start, position, friction, memo, nearby);
  }
  double penetration(const Eigen::Vector3d& p) const override { return inner_.penetration(p); }
  double depth(const Eigen::Vector3d& p) const override { return inner_.depth(p); }
  bool empty() const override { return inner_.empty(); }
  mutable long resolves = 0;

 private:
  const CollisionScene& inner_;
};

TEST(CompositeScene, DepthAndPenetrationAreTheDeepestPartsAndAgreeWithDepths) {
  // A box body and a sphere overlapping it: on a grid through both, the
  // scene's depth and penetration are each the larger of its parts', to the
  // bit, and its depths() gives both at once.
  const Eigen::MatrixX3d box = box_corners(Eigen::Vector3d::Zero(), 0.15);
  const std::vector<Eigen::Vector3i> faces = box_triangles();
  const MeshBody body(box, faces, 0.004, 0.3);
  std::vector<Collider> sphere(1);
  sphere[0].shape = SphereCollider{{0.15, 0.0, 0.0}, 0.1};
  const AnalyticScene fixed(sphere);
  CompositeScene scene;
  scene.add(&fixed);
  scene.add(&body);
  int in_box_only = 0, in_sphere_only = 0, in_both = 0, outside = 0;
  for (double x = -0.3; x <= 0.3001; x += 0.0125)
    for (double y = -0.2; y <= 0.2001; y += 0.05)
      for (double z = -0.2; z <= 0.2001; z += 0.05) {
        const Eigen::Vector3d p(x, y, z);
        const double box_depth = body.depth(p), sphere_depth = fixed.depth(p);
        ASSERT_EQ(scene.depth(p), std::max(box_depth, sphere_depth)) << p.transpose();
        ASSERT_EQ(scene.penetration(p), std::max(body.penetration(p), fixed.penetration(p))) << p.transpose();
        const PointDepths both = scene.depths(p);
        ASSERT_EQ(both.depth, scene.depth(p)) << p.transpose();
        ASSERT_EQ(both.penetration, scene.penetration(p)) << p.transpose();
        in_box_only += box_depth > 0.0 && sphere_depth == 0.0;
        in_sphere_only += sphere_depth > 0.0 && box_depth == 0.0;
        in_both += box_depth > 0.0 && sphere_depth > 0.0;
        outside += box_depth == 0.0 && sphere_depth == 0.0;
      }
  EXPECT_GT(in_box_only, 0);
  EXPECT_GT(in_sphere_only, 0);
  EXPECT_GT(in_both, 0);
  EXPECT_GT(outside, 0);
}

TEST(ImplicitIntegrator, TheContactSlackSavesChecksAndKeepsEveryPointOut) {
  // A sheet pinned along two opposite edges, pushed up from below by a box
  // body rising into it at 0.6 m/s: the limiter drags the points the box
  // holds along its top face every round. With no slack every point the limiter moves is
  // checked again (the exact rule); with a slack a point may slide that far
  // along its contact plane first. The box is frictionless and its faces
  // flat, so its planes are exact: no point may end a step within the
  // thickness either way, and the slack must save checks.
  DynamicsOptions d;
  for (int v = 0; v < 17; ++v) d.pinned.insert(d.pinned.end(), {v, 16 * 17 + v});  // the rows at z = -0.25 and 0.25
  const DynamicsModel m = build_dynamics(test::make_sheet(17, 0.5), d);
  const Eigen::MatrixX3d box = box_corners({0.0, -0.25, 0.0}, 0.1);
  const std::vector<Eigen::Vector3i> faces = box_triangles();
  struct Run {
    long resolves = 0;
    double deepest = 0.0;  // into the thickness layer, at the end of any step
    double pushed = 0.0;
  };
  const auto run = [&](double slack) {
    MeshBody body(box, faces, 0.004, 0.0);
    const CountingScene scene(body);
    IntegratorOptions o = options(1.0 / 120);
    o.contact_slack = slack;
    // Plain sweeps: what the slack saves, not also what over-relaxed
    // sweeps move (with acceleration the slack saved 16 %: 25.9 against
    // 30.7 thousand re-checks).
    o.limiter_acceleration = 0.0;
    ImplicitIntegrator integrator;
    integrator.precompute(m, o);
    ClothState s = rest_state(m);
    Run r;
    for (int k = 0; k < 120; ++k) {
      body.update(box.rowwise() + Eigen::RowVector3d(0.0, 0.005 * k, 0.0));
      r.pushed = std::max(r.pushed, integrator.step(s, s.pinned, scene).max_correction);
      for (Eigen::Index f = 0; f < s.positions.rows(); ++f)
        r.deepest = std::max(r.deepest, body.penetration(s.positions.row(f).transpose()));
    }
    r.resolves = scene.resolves;
    return r;
  };
  const Run exact = run(0.0), slack = run(0.002);
  // Every step checks every free point once first; the rest are re-checks.
  const long first_checks = 120 * static_cast<long>(m.free_vertices.size());
  std::printf("contact slack 0: %ld re-checks, deepest %.3g m; 2 mm: %ld re-checks, deepest %.3g m\n",
              exact.resolves - first_checks, exact.deepest, slack.resolves - first_checks, slack.deepest);
  ASSERT_GT(exact.pushed, 0.005) << "the box never met the sheet; the test proves nothing";
  ASSERT_GT(exact.resolves - first_checks, 10 * 120) << "the limiter hardly moved a point; the test proves nothing";
  EXPECT_LE(exact.deepest, 1e-9);
  EXPECT_LE(slack.deepest, 1e-9) << "a point on a flat face stays in front of its plane";
  EXPECT_LT(slack.resolves - first_checks, 0.7 * (exact.resolves - first_checks));  // measured 17.5 against 28.5 thousand
  IntegratorOptions negative = options(1.0 / 120);
  negative.contact_slack = -1e-3;
  ImplicitIntegrator refused;
  EXPECT_THROW(refused.precompute(m, negative), ArgumentError);
}

}  // namespace
}  // namespace mrcloth
