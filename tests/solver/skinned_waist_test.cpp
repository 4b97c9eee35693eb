// The waist on a skinned body: pins skinned as the skin under them
// (waist_skin_weights, smooth_along_waist) on small bodies built here and,
// as a band round the waist, on the MakeHuman body walking.
#include "solver/body_skinned_mesh.h"
#include "solver/mesh_body.h"

#include "solver/character_sim.h"

#include "mesh_ops/errors.h"
#include "mesh_oracles.h"
#include "skinned_body_fixture.h"
#include "test_meshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

using Eigen::Vector3d;
using test::have_body;
using test::kCmuScale;
using test::Mesh;
using test::SkinnedBodyTest;

// ---- on small bodies built here ---------------------------------------------

TEST(SmoothAlongWaist, NeighboursMixByTheirKernelAndLonePinsKeepTheirOwn) {
  // Pins 0 and 1 a sigma apart, each skinned to one joint; pin 2 farther
  // than 3 sigma from both: 0 and 1 each take exp(-1/2) of the other's
  // joint (normalised), 2 keeps its list.
  const double sigma = 0.01, k = std::exp(-0.5);
  const Eigen::MatrixX3d pins = (Eigen::MatrixX3d(3, 3) << 0, 0, 0, 0.01, 0, 0, 0.2, 0, 0).finished();
  const std::vector<std::vector<std::pair<int, double>>> own = {{{4, 1.0}}, {{7, 1.0}}, {{2, 0.25}, {5, 0.75}}};
  const auto smooth = smooth_along_waist(own, pins, sigma);
  ASSERT_EQ(smooth.size(), 3u);
  ASSERT_EQ(smooth[0].size(), 2u);
  ASSERT_EQ(smooth[1].size(), 2u);
  EXPECT_EQ(smooth[0][0].first, 4);
  EXPECT_NEAR(smooth[0][0].second, 1.0 / (1.0 + k), 1e-15);
  EXPECT_EQ(smooth[0][1].first, 7);
  EXPECT_NEAR(smooth[0][1].second, k / (1.0 + k), 1e-15);
  EXPECT_NEAR(smooth[1][0].second, k / (1.0 + k), 1e-15);
  EXPECT_NEAR(smooth[1][1].second, 1.0 / (1.0 + k), 1e-15);
  EXPECT_EQ(smooth[2], own[2]);
  EXPECT_EQ(smooth_along_waist(own, pins, 0.0), own) << "sigma 0: the lists as given";
  // At random: every list still sums to 1.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::MatrixX3d many(40, 3);
  std::vector<std::vector<std::pair<int, double>>> lists(40);
  for (int i = 0; i < 40; ++i) {
    many.row(i) << 0.3 * std::cos(0.157 * i), 0.0, 0.3 * std::sin(0.157 * i);
    const double a = u(rng);
    lists[static_cast<std::size_t>(i)] = {{i % 5, a}, {5 + i % 3, 1.0 - a}};
  }
  for (const auto& list : smooth_along_waist(lists, many, 0.03)) {
    double total = 0.0;
    for (const auto& jw : list) total += jw.second;
    EXPECT_NEAR(total, 1.0, 1e-12);
  }
  EXPECT_THROW(smooth_along_waist(own, pins.topRows(2), sigma), ArgumentError);
  EXPECT_THROW(smooth_along_waist(own, pins, -0.01), ArgumentError);
  EXPECT_THROW(smooth_along_waist(own, pins, std::numeric_limits<double>::quiet_NaN()), ArgumentError);
}

TEST(WaistSkinWeights, RefusesBodiesItCannotSearchByName) {
  SkinnedBody open;  // one triangle: not a closed surface
  open.rest_vertices = (Eigen::MatrixX3d(3, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0).finished();
  open.triangles = {Eigen::Vector3i(0, 1, 2)};
  open.weights.assign(3, {{0, 1.0}});
  const Eigen::MatrixX3d pins = (Eigen::MatrixX3d(1, 3) << 0.2, 0.2, 0.1).finished();
  const auto message_of = [&](const SkinnedBody& body) {
    try {
      waist_skin_weights(body, body.rest_vertices, pins);
    } catch (const ArgumentError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message_of(open).rfind("waist_skin_weights: the body's surface: MeshBody: edge", 0), 0u) << message_of(open);
  SkinnedBody none = open;
  none.triangles.clear();
  EXPECT_EQ(message_of(none), "waist_skin_weights: the body has no triangles; expected its surface");
  // A closed one: a tetrahedron, every pin's weights blended from its corners.
  Mesh tetra;
  tetra.vertices = (Eigen::MatrixX3d(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1).finished();
  tetra.triangles = {Eigen::Vector3i(0, 2, 1), Eigen::Vector3i(0, 1, 3), Eigen::Vector3i(0, 3, 2), Eigen::Vector3i(1, 2, 3)};
  SkinnedBody closed;
  closed.rest_vertices = tetra.vertices;
  closed.triangles = tetra.triangles;
  closed.weights = {{{0, 1.0}}, {{1, 1.0}}, {{2, 1.0}}, {{3, 1.0}}};
  // Below the face z = 0, over the point (0.2, 0.3): barycentrics 0.5 / 0.2 / 0.3 on vertices 0 / 1 / 2.
  const Eigen::MatrixX3d below = (Eigen::MatrixX3d(1, 3) << 0.2, 0.3, -0.05).finished();
  const auto weights = waist_skin_weights(closed, closed.rest_vertices, below);
  ASSERT_EQ(weights.size(), 1u);
  ASSERT_EQ(weights[0].size(), 3u);
  const double expected[3] = {0.5, 0.2, 0.3};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(weights[0][static_cast<std::size_t>(k)].first, k);
    EXPECT_NEAR(weights[0][static_cast<std::size_t>(k)].second, expected[k], 1e-12);
  }
}

// ---- as a band on the MakeHuman body (the SkinnedBodyTest suite) ------------

/// A waist band (a short open tube, its top ring pinned) around the body's
/// waist in the reference pose of 07_06 from the A-pose, and its model.
struct WaistBand {
  DynamicsModel model;
  CharacterRunOptions options;
  Pose reference;
};
/// `around` vertices per ring, `rings` rings over `height` metres, centred
/// `above` metres over the hips joint.
WaistBand waist_band(const SkinnedBody& body, const Motion& walk, int around = 16, int rings = 3,
                     double height = 0.08, double above = 0.05) {
  WaistBand band;
  band.options.frames = 4;
  band.options.preroll_seconds = 0.2;
  band.options.garment_pose = mesh_pose(body, walk.skeleton);
  band.reference = reference_pose(walk, band.options);
  QuadMesh tube = test::make_tube(around, rings, 0.16, height);
  const Vector3d centre = band.reference.position(walk.skeleton.find("Hips")) + Vector3d(0, above, 0);
  for (auto v : tube.vertices()) tube.point(v) += QuadMesh::Point(centre.x(), centre.y(), centre.z());
  DynamicsOptions d;
  for (int i = 0; i < around; ++i) d.pinned.push_back((rings - 1) * around + i);  // the top ring
  band.model = build_dynamics(tube, d);
  return band;
}

TEST_F(SkinnedBodyTest, SkinnedWaistMovesAsTheSkinUnderIt) {
  // The pinned ring, given the skin weights of the body under it, must be
  // wherever skin() puts the same points as part of the body: a body made
  // of them (input mesh = the points in the A-pose) skinned by the pose.
  SKIP_WITHOUT_BODY();
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  WaistBand band = waist_band(*body_, walk);
  const Positions rest_pinned = pinned_rows(band.model, band.model.rest);
  band.options.waist_smoothing = 0.0;  // each pin exactly its own skin's weights (checked below)
  waist_follows_skin(band.options, *body_, walk, band.model);
  CapsulePosedBody nothing(CapsuleRig{}, walk.skeleton);  // no collisions: the pins alone
  ClothState state = rest_state(band.model);
  std::vector<Positions> frames;
  const CharacterRunReport report = simulate_on_character(band.model, state, walk, nothing, band.options, {}, &frames);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_LT(report.max_waist_error, 1e-12);

  SkinnedBody ring;
  const Vector3d moved = band.reference.position(0) - band.options.garment_pose.position(0);
  ring.input_vertices = rest_pinned.rowwise() - moved.transpose();
  ring.rest_vertices = ring.input_vertices;  // only its row count matters here
  ring.weights = band.options.waist_weights;
  ring.joint_rest = body_->joint_rest;
  ring.input_joints = body_->input_joints;
  ring.rest_correction = body_->rest_correction;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const double time = band.options.preroll_seconds + (f + 1) / band.options.fps;
    const Eigen::MatrixX3d expected = skin(ring, walk.skeleton, character_pose(walk, time, band.options));
    for (std::size_t k = 0; k < band.model.pinned_vertices.size(); ++k)
      EXPECT_LT((frames[f].row(band.model.pinned_vertices[k]) - expected.row(static_cast<Eigen::Index>(k))).norm(), 1e-12)
          << "frame " << f << " pinned " << k;
  }
  // The weights are the body's blended over the nearest point of its
  // surface by that point's barycentric coordinates (brute force: every
  // triangle, its plane or its edges).
  const Eigen::MatrixX3d placed = skin(*body_, walk.skeleton, band.reference);
  for (const int pin : {0, 3, 9}) {
    const Vector3d p = rest_pinned.row(pin).transpose();
    double best = std::numeric_limits<double>::infinity();
    std::map<int, double> expected;
    for (const Eigen::Vector3i& t : body_->triangles) {
      const Vector3d a = placed.row(t(0)).transpose(), b = placed.row(t(1)).transpose(), c = placed.row(t(2)).transpose();
      // Barycentrics of p's projection onto the plane; outside the triangle
      // the nearest point is on an edge.
      const Vector3d n = (b - a).cross(c - a);
      const Vector3d q = p - n.dot(p - a) / n.squaredNorm() * n;
      std::array<double, 3> w = {(c - b).cross(q - b).dot(n), (a - c).cross(q - c).dot(n), (b - a).cross(q - a).dot(n)};
      const double sum = w[0] + w[1] + w[2];
      for (double& x : w) x /= sum;
      Vector3d at = q;
      if (w[0] < 0.0 || w[1] < 0.0 || w[2] < 0.0) {
        double edge_best = std::numeric_limits<double>::infinity();
        const Vector3d corner[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) {
          const Vector3d& u = corner[k];
          const Vector3d& v = corner[(k + 1) % 3];
          const double s = std::clamp((p - u).dot(v - u) / (v - u).squaredNorm(), 0.0, 1.0);
          const Vector3d e = u + s * (v - u);
          if ((p - e).squaredNorm() < edge_best) {
            edge_best = (p - e).squaredNorm();
            at = e;
            w = {0.0, 0.0, 0.0};
            w[static_cast<std::size_t>(k)] = 1.0 - s;
            w[static_cast<std::size_t>((k + 1) % 3)] = s;
          }
        }
      }
      const double d = (p - at).norm();
      if (d >= best) continue;
      best = d;
      expected.clear();
      for (int k = 0; k < 3; ++k)
        for (const auto& [joint, weight] : body_->weights[static_cast<std::size_t>(t(k))])
          expected[joint] += w[static_cast<std::size_t>(k)] * weight;
    }
    double total = 0.0;
    for (const auto& [joint, weight] : band.options.waist_weights[static_cast<std::size_t>(pin)]) {
      EXPECT_NEAR(weight, expected[joint], 1e-9) << "pin " << pin << " joint " << joint;
      total += weight;
    }
    EXPECT_NEAR(total, 1.0, 1e-12) << "pin " << pin;
    for (const auto& [joint, weight] : expected) {
      if (weight <= 1e-9) continue;
      EXPECT_TRUE(std::any_of(band.options.waist_weights[static_cast<std::size_t>(pin)].begin(),
                              band.options.waist_weights[static_cast<std::size_t>(pin)].end(),
                              [&](const auto& jw) { return jw.first == joint; }))
          << "pin " << pin << " lacks joint " << joint;
    }
  }

  band.options.waist_weights.pop_back();
  ClothState again = rest_state(band.model);
  EXPECT_THROW(simulate_on_character(band.model, again, walk, nothing, band.options), ArgumentError) << "one list per pin";
}

// A circular band of 96 pins 1.1 cm apart at the hips' height, on the
// walk: with each pin's own skin weights it stretches as linear blend
// skinning stretches the skin under it, and more where the circle passes
// off the skin and takes farther skin's weights (250 % measured); averaged
// over 2 cm (the default) neighbouring pins turn about nearly the same
// joints (45 %), still moving exactly as their weights say. (The shared
// trousers' own waistband: character_trousers_test.js.)
TEST_F(SkinnedBodyTest, ASmoothedWaistKeepsTheBandsLength) {
  SKIP_WITHOUT_BODY();
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  WaistBand band = waist_band(*body_, walk, 96, 2, 0.04, 0.0);
  band.options.frames = 30;
  CapsulePosedBody nothing(CapsuleRig{}, walk.skeleton);
  const auto band_stretch = [&](double smoothing) {
    band.options.waist_smoothing = smoothing;
    waist_follows_skin(band.options, *body_, walk, band.model);
    for (const auto& list : band.options.waist_weights) {
      double total = 0.0;
      for (const auto& jw : list) total += jw.second;
      EXPECT_NEAR(total, 1.0, 1e-12);
    }
    ClothState state = rest_state(band.model);
    std::vector<Positions> frames;
    const CharacterRunReport report = simulate_on_character(band.model, state, walk, nothing, band.options, {}, &frames);
    EXPECT_LT(report.max_waist_error, 1e-12);
    double largest = 0.0;
    for (const Positions& x : frames) largest = std::max(largest, most_stretched(band.model, x).pinned_strain);
    return largest;
  };
  const double own = band_stretch(0.0), smoothed = band_stretch(0.02);
  std::printf("band stretch: own weights %.1f %%, smoothed over 2 cm %.1f %%\n", 100.0 * own, 100.0 * smoothed);
  EXPECT_GT(own, 0.10) << "the skin under the band stretches";
  EXPECT_LT(smoothed, 0.5 * own);
}

TEST_F(SkinnedBodyTest, AWaistSkinnedToThePelvisAloneIsPinnedToIt) {
  SKIP_WITHOUT_BODY();
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  WaistBand band = waist_band(*body_, walk);
  CapsulePosedBody nothing(CapsuleRig{}, walk.skeleton);
  ClothState rigid_state = rest_state(band.model);
  std::vector<Positions> rigid, skinned;
  simulate_on_character(band.model, rigid_state, walk, nothing, band.options, {}, &rigid);
  band.options.body_joints = body_->joint_rest;
  band.options.waist_weights.assign(band.model.pinned_vertices.size(), {{walk.skeleton.find("Hips"), 1.0}});
  ClothState skinned_state = rest_state(band.model);
  simulate_on_character(band.model, skinned_state, walk, nothing, band.options, {}, &skinned);
  ASSERT_EQ(rigid.size(), skinned.size());
  for (std::size_t f = 0; f < rigid.size(); ++f) EXPECT_LT((rigid[f] - skinned[f]).cwiseAbs().maxCoeff(), 1e-9) << "frame " << f;
}

}  // namespace
}  // namespace mrcloth
