// Deformation modes: normalisation, clustering into modes numbered by
// deformation, the report's numbers against brute force, and a sheet half
// rolled up whose rolled half must come out as the top mode.
#include "solver/deformation_modes.h"
#include "mesh_ops/mode_layer.h"

#include "mesh_ops/errors.h"
#include "solver/instance_curvature.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

struct Planted {
  Eigen::VectorXd mean, deviation;
  std::vector<int> group;  ///< 1..3 by construction, 1 the least deformed
};

/// Three groups of vertices with features near (0.5, 0.1), (5, 1) and
/// (20, 4) per metre, interleaved so order carries no information.
Planted planted(int per_group, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double centre[3][2] = {{0.5, 0.1}, {5.0, 1.0}, {20.0, 4.0}};
  const double spread[3][2] = {{0.05, 0.02}, {0.4, 0.1}, {1.0, 0.3}};
  Planted p;
  const int n = 3 * per_group;
  p.mean.resize(n);
  p.deviation.resize(n);
  for (int v = 0; v < n; ++v) {
    const int g = (v * 7) % 3;  // interleaved
    p.group.push_back(g + 1);
    p.mean[v] = centre[g][0] + spread[g][0] * noise(rng);
    p.deviation[v] = std::abs(centre[g][1] + spread[g][1] * noise(rng));
  }
  return p;
}

TEST(DeformationModes, RecoversPlantedGroupsNumberedByDeformation) {
  const Planted p = planted(150, 4);
  for (const FeatureNormalization normalization : {FeatureNormalization::min_max, FeatureNormalization::z_score}) {
    ModeOptions options;
    options.normalization = normalization;
    const ModeReport report = deformation_modes(p.mean, p.deviation, options);
    ASSERT_EQ(report.modes.size(), p.group.size());
    EXPECT_EQ(report.modes, p.group) << normalization_name(normalization);
    EXPECT_EQ(report.sizes, (std::vector<int>{150, 150, 150}));
    EXPECT_EQ(report.normalization, normalization);

    // The normaliser against brute force.
    for (int f = 0; f < 2; ++f) {
      const Eigen::VectorXd& x = f == 0 ? p.mean : p.deviation;
      if (normalization == FeatureNormalization::min_max) {
        EXPECT_EQ(report.offset[f], x.minCoeff());
        EXPECT_EQ(report.scale[f], x.maxCoeff() - x.minCoeff());
      } else {
        double mean = 0.0, squares = 0.0;
        for (Eigen::Index v = 0; v < x.size(); ++v) mean += x[v];
        mean /= static_cast<double>(x.size());
        for (Eigen::Index v = 0; v < x.size(); ++v) squares += (x[v] - mean) * (x[v] - mean);
        EXPECT_NEAR(report.offset[f], mean, 1e-12 * std::abs(mean));
        EXPECT_NEAR(report.scale[f], std::sqrt(squares / static_cast<double>(x.size())), 1e-12);
      }
    }
    // Centroids: the members' means, in both units; inertia from them.
    double inertia = 0.0;
    for (int m = 1; m <= 3; ++m) {
      Eigen::Vector2d sum(0, 0);
      int count = 0;
      for (std::size_t v = 0; v < p.group.size(); ++v)
        if (report.modes[v] == m) {
          sum += Eigen::Vector2d(p.mean[static_cast<Eigen::Index>(v)], p.deviation[static_cast<Eigen::Index>(v)]);
          ++count;
        }
      const Eigen::Vector2d centroid = sum / count;
      EXPECT_LT((report.centroids.row(m - 1).transpose() - centroid).norm(), 1e-12 * centroid.norm()) << m;
      const Eigen::Vector2d normalized = (centroid - report.offset).cwiseQuotient(report.scale);
      EXPECT_LT((report.normalized_centroids.row(m - 1).transpose() - normalized).norm(), 1e-10) << m;
      for (std::size_t v = 0; v < p.group.size(); ++v)
        if (report.modes[v] == m) {
          const Eigen::Vector2d x =
              (Eigen::Vector2d(p.mean[static_cast<Eigen::Index>(v)], p.deviation[static_cast<Eigen::Index>(v)]) - report.offset)
                  .cwiseQuotient(report.scale);
          inertia += (x - report.normalized_centroids.row(m - 1).transpose()).squaredNorm();
        }
    }
    EXPECT_NEAR(report.inertia, inertia, 1e-10 * inertia);
    // Numbered by deformation: centroid mean curvature increases with the mode.
    EXPECT_LT(report.centroids(0, 0), report.centroids(1, 0));
    EXPECT_LT(report.centroids(1, 0), report.centroids(2, 0));
  }
}

TEST(DeformationModes, SameSeedSameModes) {
  const Planted p = planted(60, 9);
  ModeOptions options;
  options.modes = 5;  // more modes than groups: the split is arbitrary, but repeatable
  options.seed = 77;
  const ModeReport a = deformation_modes(p.mean, p.deviation, options);
  const ModeReport b = deformation_modes(p.mean, p.deviation, options);
  EXPECT_EQ(a.modes, b.modes);
  EXPECT_EQ(a.centroids, b.centroids);
  EXPECT_EQ(a.inertia, b.inertia);
  EXPECT_EQ(a.seed, 77u);
  for (int m = 0; m + 1 < 5; ++m) EXPECT_LE(a.centroids(m, 0), a.centroids(m + 1, 0));
}

TEST(DeformationModes, ClusteringReportsProgressPerRestartAndCanBeStopped) {
  const Planted p = planted(60, 9);
  ModeOptions options;
  options.restarts = 6;
  std::vector<int> done_seen;
  const ModeReport watched = deformation_modes(p.mean, p.deviation, options, [&](int done, int total) {
    EXPECT_EQ(total, 6);
    done_seen.push_back(done);
    return true;
  });
  EXPECT_EQ(done_seen, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  const ModeReport plain = deformation_modes(p.mean, p.deviation, options);
  EXPECT_EQ(watched.modes, plain.modes);
  EXPECT_EQ(watched.centroids, plain.centroids);
  EXPECT_EQ(watched.inertia, plain.inertia);
  EXPECT_FALSE(watched.cancelled);
  EXPECT_EQ(watched.restarts_done, 6);

  int calls = 0;
  const ModeReport stopped = deformation_modes(p.mean, p.deviation, options, [&](int, int) { return ++calls < 2; });
  EXPECT_EQ(calls, 2);
  EXPECT_TRUE(stopped.cancelled);
  EXPECT_EQ(stopped.restarts_done, 2);
}

TEST(DeformationModes, TiesInMeanCurvatureGoByDeviation) {
  // Two groups with the same mean curvature: the steadier one is the lower mode.
  Eigen::VectorXd mean(30), deviation(30);
  for (int v = 0; v < 30; ++v) {
    const int g = v % 3;
    mean[v] = g == 2 ? 10.0 : 1.0;
    deviation[v] = g == 0 ? 5.0 : g == 1 ? 0.1 : 1.0;
  }
  const ModeReport report = deformation_modes(mean, deviation);
  for (int v = 0; v < 30; ++v) EXPECT_EQ(report.modes[static_cast<std::size_t>(v)], v % 3 == 1 ? 1 : v % 3 == 0 ? 2 : 3) << v;
}

TEST(DeformationModes, AConstantFeatureIsHarmless) {
  Eigen::VectorXd mean(12), deviation = Eigen::VectorXd::Zero(12);
  for (int v = 0; v < 12; ++v) mean[v] = v < 6 ? 0.0 : 3.0;
  ModeOptions options;
  options.modes = 2;
  for (const FeatureNormalization normalization : {FeatureNormalization::min_max, FeatureNormalization::z_score}) {
    options.normalization = normalization;
    const ModeReport report = deformation_modes(mean, deviation, options);
    EXPECT_EQ(report.scale[1], 1.0);
    for (int v = 0; v < 12; ++v) EXPECT_EQ(report.modes[static_cast<std::size_t>(v)], v < 6 ? 1 : 2);
    EXPECT_TRUE(report.normalized_centroids.allFinite());
  }
}

TEST(DeformationModes, RefusesBadFeaturesAndNames) {
  Eigen::VectorXd mean = Eigen::VectorXd::LinSpaced(10, 0.0, 9.0), deviation = Eigen::VectorXd::Zero(10);
  EXPECT_THROW(deformation_modes(mean, Eigen::VectorXd::Zero(9)), ArgumentError);
  mean[4] = std::nan("");
  try {
    deformation_modes(mean, deviation);
    ADD_FAILURE() << "a NaN feature";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 4"), std::string::npos) << e.what();
  }
  mean[4] = 4.0;
  ModeOptions options;
  options.modes = 11;
  EXPECT_THROW(deformation_modes(mean, deviation, options), ArgumentError) << "more modes than vertices";
  for (const int modes : {0, kLargestMode + 1}) {
    options.modes = modes;
    try {
      deformation_modes(mean, deviation, options);
      ADD_FAILURE() << modes << " modes";
    } catch (const ArgumentError& e) {
      EXPECT_NE(std::string(e.what()).find("expected 1 to 1000, the modes a mode layer holds"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(normalization_from_name(normalization_name(FeatureNormalization::z_score)), FeatureNormalization::z_score);
  EXPECT_EQ(normalization_from_name("minmax"), FeatureNormalization::min_max);
  try {
    normalization_from_name("log");
    ADD_FAILURE() << "an unknown normalisation";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("minmax or zscore"), std::string::npos) << e.what();
  }
}

TEST(DeformationModes, ARolledHalfOfASheetIsTheTopMode) {
  // A strip flat for u < u0 and rolled (without stretching) onto a
  // cylinder beyond, the radius changing from frame to frame: the analysis
  // of the frames gives two modes, the rolled part the upper one.
  const double spacing = 0.02;
  const QuadMesh grid = test::make_grid(20, 6, spacing);
  const CurvaturePairs pairs = curvature_pairs(grid);
  const double u0 = 10 * spacing;
  CurvatureAccumulator accumulator(pairs.num_vertices);
  for (int t = 0; t < 10; ++t) {
    const double radius = 0.06 + 0.01 * t;
    FramePositions x(static_cast<Eigen::Index>(grid.n_vertices()), 3);
    for (const auto v : grid.vertices()) {
      const double u = grid.point(v)[0], w = grid.point(v)[1];
      if (u <= u0) x.row(v.idx()) << u, w, 0.0;
      else x.row(v.idx()) << u0 + radius * std::sin((u - u0) / radius), w, radius * (1.0 - std::cos((u - u0) / radius));
    }
    accumulator.add(vertex_curvature(pairs, x));
  }
  ModeOptions options;
  options.modes = 2;
  const ModeReport report = deformation_modes(accumulator.mean(), accumulator.deviation(), options);
  for (const auto v : grid.vertices()) {
    const double u = grid.point(v)[0];
    // Two steps from the seam either way, the partners are all on one side.
    if (u <= u0 - 2 * spacing + 1e-12) {
      EXPECT_EQ(report.modes[static_cast<std::size_t>(v.idx())], 1) << "u " << u;
      EXPECT_EQ(accumulator.mean()[v.idx()], 0.0) << "flat: every partner at its rest distance";
    }
    if (u >= u0 + 2 * spacing - 1e-12) {
      EXPECT_EQ(report.modes[static_cast<std::size_t>(v.idx())], 2) << "u " << u;
    }
  }
  EXPECT_LT(report.centroids(0, 0), report.centroids(1, 0));
}

}  // namespace
}  // namespace mrcloth
