// ImplicitIntegrator's solve: rest and free fall exact, momentum conserved,
// the Newton steps against the plain iteration, bend springs, the presets at
// 30 Hz, identical bits run to run; and simulate's set-up (its progress
// callback, stopping it, a prepared integrator). Strain limiting, contacts and
// T-nodes have files of their own (implicit_integrator_*_test.cpp).
#include "mesh_ops/errors.h"
#include "solver/implicit_integrator.h"
#include "solver/material.h"
#include "solver/simulate.h"
#include "solver/spring_energy.h"

#include "implicit_integrator_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

using test::options;
using test::refined_sheet;
using test::sheet_pinned_at;

Eigen::RowVector3d centre_of_mass(const DynamicsModel& m, const Positions& q) {
  return (m.free_mass.transpose() * q) / m.free_mass.sum();
}

TEST(ImplicitIntegrator, RestIsAFixedPointWithoutGravity) {
  const QuadMesh mesh = refined_sheet();
  const DynamicsModel m = build_dynamics(mesh, {});
  ImplicitIntegrator integrator;
  integrator.precompute(m, options(1.0 / 120, {0, 0, 0}));
  ClothState s = rest_state(m);
  for (int k = 0; k < 20; ++k) integrator.step(s, s.pinned, {});
  EXPECT_LT((s.positions - free_rows(m, m.rest)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(s.velocities.cwiseAbs().maxCoeff(), 1e-10);
}

TEST(ImplicitIntegrator, FreeFallFollowsTheExactParabola) {
  DynamicsOptions d;
  d.material.damping = 0.0;
  const DynamicsModel m = build_dynamics(refined_sheet(), d);
  ImplicitIntegrator integrator;
  const double h = 1.0 / 60;
  integrator.precompute(m, options(h));
  ClothState s = rest_state(m);
  const Eigen::RowVector3d start = centre_of_mass(m, s.positions);
  for (int k = 1; k <= 60; ++k) {
    integrator.step(s, s.pinned, {});
    const double t = k * h;
    const Eigen::RowVector3d expected = start + Eigen::RowVector3d(0, -0.5 * 9.81 * t * t, 0);
    EXPECT_LT((centre_of_mass(m, s.positions) - expected).norm(), 1e-12) << "step " << k;
    // Rigid motion: every vertex, T-nodes included, falls the same way.
    const Positions x = full_positions(m, s.positions, s.pinned);
    EXPECT_LT((x.rowwise() - Eigen::RowVector3d(0, -0.5 * 9.81 * t * t, 0) - m.rest).cwiseAbs().maxCoeff(), 1e-12);
  }
}

// The rest state with every free vertex given a random velocity (m/s, each
// component in [-1, 1]).
ClothState moving_in_every_direction(const DynamicsModel& m) {
  ClothState s = rest_state(m);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Eigen::Index f = 0; f < s.velocities.rows(); ++f) s.velocities.row(f) << u(rng), u(rng), u(rng);
  return s;
}

TEST(ImplicitIntegrator, LinearMomentumIsConservedWithoutGravity) {
  DynamicsOptions d;
  d.material.damping = 0.0;
  const DynamicsModel m = build_dynamics(refined_sheet(), d);
  ImplicitIntegrator integrator;
  // Mass-weighted limiter projections: the default weights trade momentum
  // on unequal masses for convergence (TheLimitersMassExponent... in
  // implicit_integrator_limiter_test.cpp).
  IntegratorOptions o = options(1.0 / 120, {0, 0, 0});
  o.limiter_mass_exponent = 1.0;
  integrator.precompute(m, o);
  ClothState s = moving_in_every_direction(m);
  const Eigen::RowVector3d momentum = m.free_mass.transpose() * s.velocities;
  for (int k = 0; k < 50; ++k) {
    integrator.step(s, s.pinned, {});
    const Eigen::RowVector3d now = m.free_mass.transpose() * s.velocities;
    EXPECT_LT((now - momentum).norm(), 1e-12 * std::max(1.0, momentum.norm())) << "step " << k;
  }
}

// The refined sheet (T-nodes, levels 1-3), horizontal, pinned along one
// edge and let fall, without air damping: its mechanical energy (kinetic,
// gravity, springs) after `seconds`, as a fraction of the potential energy
// it would give up falling to hang at rest (its centre of mass 0.25 m down).
double energy_left_after_fall(int newton_cg, double seconds) {
  const QuadMesh mesh = refined_sheet();
  DynamicsOptions d;
  d.material.damping = 0.0;
  for (int i = 0; i < 11; ++i) d.pinned.push_back(i);  // the row at z = -0.25
  const DynamicsModel m = build_dynamics(mesh, d);
  IntegratorOptions o = options(1.0 / 120);
  o.newton_cg = newton_cg;
  ImplicitIntegrator integrator;
  integrator.precompute(m, o);
  ClothState s = rest_state(m);
  for (int k = 0; k < static_cast<int>(seconds * 120); ++k) integrator.step(s, s.pinned, {});
  const Positions x = full_positions(m, s.positions, s.pinned);
  const double g = 9.81, total_mass = m.mass.sum();
  double energy = spring_energy(m, x);
  for (Eigen::Index f = 0; f < s.positions.rows(); ++f)
    energy += m.free_mass[f] * (0.5 * s.velocities.row(f).squaredNorm() + g * s.positions(f, 1));
  return 1.0 + energy / (total_mass * g * 0.25);
}

// Each step of the plain iteration loses energy in every direction its Q
// makes stiffer than the springs are (sideways, where a taut spring's
// stiffness is its tension over its length, Q takes its full stiffness):
// a falling sheet swings out of it. The Newton steps scale each direction
// by the springs' own curvature and lose less.
TEST(ImplicitIntegrator, NewtonStepsLoseLessEnergyThanThePlainIteration) {
  const double plain = energy_left_after_fall(0, 1.0), newton = energy_left_after_fall(1, 1.0);
  // Measured: 0.35 of the fall's energy left with the plain iteration, 0.45 with the Newton steps.
  EXPECT_GT(newton, plain + 0.05) << "plain " << plain << ", Newton " << newton;
  EXPECT_GT(plain, 0.1);  // both still swing
}

// Conjugate gradients stop once converged: asked for far more iterations
// than the system has unknowns, they used to iterate on round-off until 0 / 0.
TEST(ImplicitIntegrator, NewtonStepsStopOnceConvergedHoweverManyAreAskedFor) {
  const double enough = energy_left_after_fall(2000, 0.1);
  const double many = energy_left_after_fall(1000000000, 0.1);
  ASSERT_TRUE(std::isfinite(many));
  EXPECT_EQ(many, enough) << "both stop at convergence, long before 2000 iterations";
}

class NewtonSteps : public ::testing::TestWithParam<BendModel> {};

TEST_P(NewtonSteps, ConserveLinearMomentumAndKeepTNodesExact) {
  const QuadMesh mesh = refined_sheet();
  DynamicsOptions d;
  d.material.damping = 0.0;
  d.bend_model = GetParam();
  const DynamicsModel m = build_dynamics(mesh, d);
  IntegratorOptions o = options(1.0 / 120, {0, 0, 0});
  o.limiter_mass_exponent = 1.0;
  o.newton_cg = 2;
  ImplicitIntegrator integrator;
  integrator.precompute(m, o);
  ClothState s = moving_in_every_direction(m);
  const Eigen::RowVector3d momentum = m.free_mass.transpose() * s.velocities;
  const Layers l = get_layers(mesh);
  for (int k = 0; k < 50; ++k) {
    integrator.step(s, s.pinned, {});
    const Eigen::RowVector3d now = m.free_mass.transpose() * s.velocities;
    EXPECT_LT((now - momentum).norm(), 1e-12 * std::max(1.0, momentum.norm())) << "step " << k;
    const Positions x = full_positions(m, s.positions, s.pinned);
    for (int v : m.hanging_vertices) {
      const OpenMesh::Vec2i par = mesh.property(l.parents, mesh.vertex_handle(v));
      EXPECT_LT((x.row(v) - 0.5 * (x.row(par[0]) + x.row(par[1]))).norm(), 1e-15) << "step " << k << " vertex " << v;
    }
  }
}

// A flat sheet bent onto a cylinder and let go (no gravity, no pins)
// unbends under second-difference bend springs, with either solve: the
// integrator's own gradient and Hessian of them point the right way.
TEST(ImplicitIntegrator, SecondDifferenceBendSpringsUnbendASheet) {
  const QuadMesh mesh = refined_sheet();
  DynamicsOptions d;
  d.bend_model = BendModel::second_difference;
  d.material.bend_stiffness = 1.0;
  d.material.damping = 2.0;
  const DynamicsModel m = build_dynamics(mesh, d);
  const auto bend_energy = [&](const Positions& x) {
    double energy = 0.0;
    for (const Spring& s : m.springs)
      if (s.kind == SpringKind::bend) energy += 0.5 * s.stiffness * std::pow(spring_vector(s, x).norm() - s.rest, 2);
    return energy;
  };
  for (int newton_cg : {0, 1}) {
    IntegratorOptions o = options(1.0 / 120, {0, 0, 0});
    o.newton_cg = newton_cg;
    ImplicitIntegrator integrator;
    integrator.precompute(m, o);
    ClothState s = rest_state(m);
    for (Eigen::Index f = 0; f < s.positions.rows(); ++f) {  // onto a cylinder of radius 0.3 m about the z axis
      const double angle = s.positions(f, 0) / 0.3;
      s.positions(f, 0) = 0.3 * std::sin(angle);
      s.positions(f, 1) = 0.3 * (1.0 - std::cos(angle));
    }
    const double before = bend_energy(full_positions(m, s.positions, s.pinned));
    for (int k = 0; k < 120; ++k) integrator.step(s, s.pinned, {});
    const double after = bend_energy(full_positions(m, s.positions, s.pinned));
    EXPECT_GT(before, 0.0);
    EXPECT_LT(after, 0.5 * before) << "Newton CG " << newton_cg << ": " << before << " J -> " << after << " J";
  }
}

INSTANTIATE_TEST_SUITE_P(BendModels, NewtonSteps, ::testing::Values(BendModel::distance, BendModel::second_difference));

TEST(ImplicitIntegrator, RejectsNegativeNewtonConjugateGradientIterations) {
  const DynamicsModel m = build_dynamics(refined_sheet(), {});
  IntegratorOptions o = options(1.0 / 120);
  o.newton_cg = -1;
  ImplicitIntegrator integrator;
  EXPECT_THROW(integrator.precompute(m, o), ArgumentError);
}

TEST(ImplicitIntegrator, StiffestPresetStaysFiniteAtThirtyHertz) {
  for (const std::string& preset : material_preset_names()) {
    DynamicsOptions d;
    d.material = material_preset(preset);
    d.pinned = {0, 10};
    const DynamicsModel m = build_dynamics(refined_sheet(), d);
    ImplicitIntegrator integrator;
    integrator.precompute(m, options(1.0 / 30));
    ClothState s = rest_state(m);
    bool finite = true;
    for (int k = 0; k < 1000 && finite; ++k) finite = integrator.step(s, s.pinned, {}).finite;
    EXPECT_TRUE(finite) << preset;
    EXPECT_LT(s.positions.cwiseAbs().maxCoeff(), 2.0) << preset << " blew up";
  }
}

TEST(ImplicitIntegrator, TwoRunsGiveIdenticalBits) {
  const QuadMesh mesh = refined_sheet();
  std::vector<Collider> colliders(1);
  colliders[0].shape = SphereCollider{{0, -0.3, 0}, 0.2};
  const auto run = [&] {
    const DynamicsModel m = build_dynamics(mesh, {});
    ImplicitIntegrator integrator;
    integrator.precompute(m, options(1.0 / 120));
    ClothState s = rest_state(m);
    for (int k = 0; k < 100; ++k) integrator.step(s, s.pinned, colliders);
    return s.positions;
  };
  const Positions a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), sizeof(double) * a.size()), 0);
}

TEST(ImplicitIntegrator, PrecomputeConsultsItsCallbackBetweenPhasesAndStopsWhenAsked) {
  const DynamicsModel m = sheet_pinned_at({0, 10});
  int calls = 0;
  ImplicitIntegrator whole;
  EXPECT_TRUE(whole.precompute(m, options(1.0 / 120), [&] { return ++calls > 0; }));
  EXPECT_GE(calls, 2) << "at least before and after the factorisation";
  for (int stop_at = 1; stop_at <= calls; ++stop_at) {
    int seen = 0;
    ImplicitIntegrator stopped;
    EXPECT_FALSE(stopped.precompute(m, options(1.0 / 120), [&] { return ++seen < stop_at; })) << stop_at;
    EXPECT_EQ(seen, stop_at) << "no phase after the one whose check said stop";
  }
}

// The set-up (the factorisation: 5.5 s at 175k vertices) reports as 0
// frames done and can be stopped: then no frame runs and no cache appears.
// A callback that lets it run changes nothing.
TEST(ImplicitIntegrator, SimulateCanBeStoppedDuringItsSetUpBeforeTheFirstFrame) {
  const DynamicsModel m = sheet_pinned_at({0, 10});
  SimulationOptions s;
  s.frames = 3;
  const std::filesystem::path cache =
      std::filesystem::temp_directory_path() / "mrcloth_simulate_setup_cancel_test.pc2";
  std::filesystem::remove(cache);
  s.cache_path = cache.string();

  std::vector<std::pair<int, int>> calls;
  ClothState watched = rest_state(m);
  std::vector<Positions> watched_frames;
  const SimulationReport full = simulate(m, watched, s, {}, [&](int done, int total) {
    calls.emplace_back(done, total);
    return true;
  }, &watched_frames);
  std::size_t setup_calls = 0;
  while (setup_calls < calls.size() && calls[setup_calls].first == 0) ++setup_calls;
  EXPECT_GE(setup_calls, 2u) << "the set-up is consulted before and between its phases";
  std::vector<std::pair<int, int>> frame_calls(calls.begin() + static_cast<std::ptrdiff_t>(setup_calls), calls.end());
  EXPECT_EQ(frame_calls, (std::vector<std::pair<int, int>>{{1, 3}, {2, 3}, {3, 3}}));
  for (std::size_t k = 0; k < setup_calls; ++k) EXPECT_EQ(calls[k].second, 3);
  EXPECT_FALSE(full.cancelled);
  EXPECT_TRUE(std::filesystem::exists(cache));
  std::filesystem::remove(cache);

  s.cache_path.clear();
  ClothState plain = rest_state(m);
  std::vector<Positions> plain_frames;
  simulate(m, plain, s, {}, {}, &plain_frames);
  ASSERT_EQ(plain_frames.size(), watched_frames.size());
  for (std::size_t f = 0; f < plain_frames.size(); ++f)
    EXPECT_EQ(std::memcmp(plain_frames[f].data(), watched_frames[f].data(),
                          sizeof(double) * static_cast<std::size_t>(plain_frames[f].size())), 0)
        << "frame " << f << " differs with a progress callback";

  s.cache_path = cache.string();
  for (std::size_t stop_at = 1; stop_at <= setup_calls; ++stop_at) {
    std::size_t seen = 0;
    ClothState state = rest_state(m);
    const Positions start = state.positions;
    const SimulationReport stopped = simulate(m, state, s, {}, [&](int done, int) {
      EXPECT_EQ(done, 0) << "a frame ran after the set-up was stopped";
      return ++seen < stop_at;
    });
    EXPECT_EQ(seen, stop_at);
    EXPECT_TRUE(stopped.cancelled) << stop_at;
    EXPECT_EQ(stopped.frames, 0);
    EXPECT_EQ(stopped.steps, 0);
    EXPECT_TRUE(stopped.cache_path.empty());
    EXPECT_FALSE(std::filesystem::exists(cache)) << "a cache from a run stopped in its set-up";
    EXPECT_EQ(state.positions, start) << "the state moved";
  }
  std::filesystem::remove(cache);
}

// A character's pre-roll and motion share one factorisation: a run given a
// prepared integrator steps to the same bits as one that factorises its
// own, also after the prepared one was copied for another run; one
// prepared for another step length is refused.
TEST(ImplicitIntegrator, SimulateWithAPreparedIntegratorGivesTheSameBits) {
  const DynamicsModel m = sheet_pinned_at({0, 10});
  SimulationOptions s;
  s.frames = 5;
  s.colliders.resize(1);
  s.colliders[0].shape = SphereCollider{m.rest.row(60).transpose() + Eigen::Vector3d(0.0, -0.05, 0.0), 0.04};
  ImplicitIntegrator prepared;
  prepared.precompute(m, integrator_options(s));
  std::vector<Positions> own, copied_once, copied_twice;
  ClothState a = rest_state(m), b = rest_state(m), c = rest_state(m);
  simulate(m, a, s, {}, {}, &own);
  simulate(m, b, s, {}, {}, &copied_once, {}, &prepared);
  simulate(m, c, s, {}, {}, &copied_twice, {}, &prepared);
  ASSERT_EQ(own.size(), 5u);
  for (std::size_t f = 0; f < own.size(); ++f) {
    EXPECT_TRUE(own[f] == copied_once[f]) << "frame " << f;
    EXPECT_TRUE(own[f] == copied_twice[f]) << "frame " << f;
  }
  EXPECT_TRUE(a.velocities == b.velocities && a.velocities == c.velocities);
  SimulationOptions other = s;
  other.fps = 24;
  ClothState d = rest_state(m);
  EXPECT_THROW(simulate(m, d, other, {}, {}, nullptr, {}, &prepared), std::logic_error);
}

}  // namespace
}  // namespace mrcloth
