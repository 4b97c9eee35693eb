// Instance curvature (paper section 4.2): the inverse sinc against its
// definition, exact arcs on a cylinder, flat sheets, the per-vertex mean,
// the streaming features against two-pass formulas, and the PC2 stream.
#include "solver/instance_curvature.h"

#include "mesh_ops/bend_partners.h"
#include "mesh_ops/errors.h"
#include "solver/point_cache.h"
#include "test_meshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// 1 - sin(x)/x in long double, independently of the code under test: its
/// Taylor series (summed until the terms vanish) for small x, the closed
/// form (64-bit mantissa, cancellation costs at most 5 of its 19 digits)
/// above.
long double reference_one_minus_sinc(long double x) {
  if (x > 0.5L) return 1.0L - std::sin(x) / x;
  long double term = x * x / 6.0L, sum = 0.0L;
  for (int n = 1; n < 40 && term != 0.0L; ++n) {
    sum += term;
    term *= -x * x / ((2.0L * n + 2.0L) * (2.0L * n + 3.0L));
  }
  return sum;
}

TEST(InverseSinc, SolvesTheDefinitionOverTheWholeRange) {
  // sinc(x) = ratio on a dense grid of (0, 1): the residual, measured in
  // long double, is at double round-off, and x decreases with the ratio.
  double previous = kPi;
  for (int k = 1; k < 20000; ++k) {
    const double ratio = k / 20000.0;
    const double x = inverse_sinc(ratio);
    ASSERT_GE(x, 0.0);
    ASSERT_LE(x, kPi);
    const long double residual = (1.0L - reference_one_minus_sinc(x)) - static_cast<long double>(ratio);
    ASSERT_LT(std::abs(static_cast<double>(residual)), 1e-15) << "ratio " << ratio;
    ASSERT_LT(x, previous) << "ratio " << ratio;
    previous = x;
  }
}

TEST(InverseSinc, KeepsItsDigitsForRatiosNearOne) {
  // Within 1e-12 of 1 the answer is tiny and 1 - ratio carries all the
  // information: x must satisfy 1 - sinc(x) = 1 - ratio to 1e-12 relative.
  for (const double gap : {1e-16, 1e-15, 3e-14, 1e-13, 1e-12, 5e-12, 1e-10, 1e-8, 1e-6, 1e-3}) {
    const double ratio = 1.0 - gap;
    const long double s = 1.0L - static_cast<long double>(ratio);  // exact
    const double x = inverse_sinc(ratio);
    ASSERT_GT(x, 0.0) << gap;
    EXPECT_LT(std::abs(static_cast<double>((reference_one_minus_sinc(x) - s) / s)), 1e-12) << "gap " << gap;
    // The leading-order inverse, sqrt(6 s), to within its known correction.
    EXPECT_LT(std::abs(x / std::sqrt(6.0 * static_cast<double>(s)) - 1.0), 0.2 * static_cast<double>(s) + 1e-15) << gap;
  }
}

TEST(InverseSinc, EndsAndNearZero) {
  EXPECT_EQ(inverse_sinc(1.0), 0.0);
  EXPECT_EQ(inverse_sinc(1.0 + 1e-12), 0.0) << "stretched, not bent";
  EXPECT_EQ(inverse_sinc(3.0), 0.0);
  EXPECT_EQ(inverse_sinc(0.0), kPi);
  EXPECT_EQ(inverse_sinc(-0.1), kPi);
  for (const double ratio : {1e-300, 1e-15, 1e-12, 1e-6, 1e-3}) {
    const double x = inverse_sinc(ratio);
    EXPECT_LE(x, kPi);
    EXPECT_LT(std::abs(static_cast<double>((1.0L - reference_one_minus_sinc(x)) - ratio)), 1e-15) << ratio;
  }
  EXPECT_THROW(inverse_sinc(std::nan("")), ArgumentError);
}

TEST(InverseSinc, OneMinusSincMatchesItsSeries) {
  for (int k = 0; k <= 3000; ++k) {
    const double x = k * (kPi / 3000.0);
    const long double reference = reference_one_minus_sinc(x);
    if (reference == 0.0L) {
      EXPECT_EQ(one_minus_sinc(x), 0.0);
      continue;
    }
    EXPECT_LT(std::abs(static_cast<double>((one_minus_sinc(x) - reference) / reference)), 4e-15) << "x " << x;
  }
  EXPECT_LT(std::abs(one_minus_sinc(1e-9) - 1e-18 / 6.0) / (1e-18 / 6.0), 1e-15);
}

/// The grid rolled, without stretching, onto a cylinder of radius R whose
/// axis is the grid's y direction: (u, v) -> (R sin(u/R), v, R (1 - cos(u/R))).
FramePositions rolled(const QuadMesh& grid, double radius) {
  FramePositions x(static_cast<Eigen::Index>(grid.n_vertices()), 3);
  for (const auto v : grid.vertices()) {
    const auto& p = grid.point(v);
    x.row(v.idx()) << radius * std::sin(p[0] / radius), p[1], radius * (1.0 - std::cos(p[0] / radius));
  }
  return x;
}

FramePositions rest_frame(const QuadMesh& mesh) {
  FramePositions x(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (const auto v : mesh.vertices()) x.row(v.idx()) << mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2];
  return x;
}

TEST(InstanceCurvature, ACylinderBendsAcrossItsAxisOnly) {
  const double spacing = 0.02;
  const QuadMesh grid = test::make_grid(12, 9, spacing);
  const CurvaturePairs pairs = curvature_pairs(grid);
  const std::vector<BendPair> bends = bend_pairs(grid);
  ASSERT_EQ(pairs.i.size(), bends.size());
  for (const double radius : {0.05, 0.1, 0.37, 2.0}) {
    const FramePositions x = rolled(grid, radius);
    int across = 0, along = 0;
    for (std::size_t k = 0; k < bends.size(); ++k) {
      if (bends[k].diagonal) continue;
      const auto& a = grid.point(OpenMesh::VertexHandle(bends[k].i));
      const auto& b = grid.point(OpenMesh::VertexHandle(bends[k].j));
      const double K = arc_curvature((x.row(pairs.i[k]) - x.row(pairs.j[k])).norm(), pairs.half_rest[k]);
      if (a[1] == b[1]) {  // same v: the pair bends around the cylinder
        EXPECT_NEAR(K, 1.0 / radius, 1e-9) << "pair " << k << " radius " << radius;
        ++across;
      } else {  // same u: along the axis, straight
        EXPECT_EQ(K, 0.0) << "pair " << k;
        ++along;
      }
    }
    // 12 x 9 quads: rows of 13 vertices give 11 pairs across, 10 rows; 13 columns of 8 along.
    EXPECT_EQ(across, 11 * 10);
    EXPECT_EQ(along, 13 * 8);
  }
}

TEST(InstanceCurvature, AFlatSheetHasNone) {
  QuadMesh grid = test::make_grid(7, 5, 0.03);
  const CurvaturePairs pairs = curvature_pairs(grid);
  // At rest, and moved rigidly (rotated and translated) as a whole.
  FramePositions x = rest_frame(grid);
  EXPECT_EQ(vertex_curvature(pairs, x).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  FramePositions moved = (x * rotation.transpose()).rowwise() + Eigen::RowVector3d(1.0, -2.0, 0.5);
  // A rigid motion changes distances by round-off only: ratios within
  // 1e-15 of 1, curvatures below sqrt(6e-15)/L.
  EXPECT_LT(vertex_curvature(pairs, moved).cwiseAbs().maxCoeff(), std::sqrt(6.0 * 1e-15) / 0.03);
}

TEST(InstanceCurvature, AVertexTakesTheMeanOverItsPartners) {
  // A random deformation: each vertex's value against a brute-force mean
  // over bend_partners, and a regular interior vertex has 8 partners.
  const QuadMesh grid = test::make_grid(8, 8, 0.025);
  const CurvaturePairs pairs = curvature_pairs(grid);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.004);
  FramePositions x = rest_frame(grid);
  for (Eigen::Index v = 0; v < x.rows(); ++v) x.row(v) += Eigen::RowVector3d(noise(rng), noise(rng), noise(rng));
  const Eigen::VectorXd curvature = vertex_curvature(pairs, x);
  const std::vector<std::vector<int>> partners = bend_partners(grid);
  for (const auto v : grid.vertices()) {
    const int i = v.idx();
    double sum = 0.0;
    for (const int j : partners[static_cast<std::size_t>(i)]) {
      const auto d = grid.point(v) - grid.point(OpenMesh::VertexHandle(j));
      sum += (1.0 / (0.5 * d.norm())) * inverse_sinc((x.row(i) - x.row(j)).norm() / d.norm());
    }
    const double expected = partners[static_cast<std::size_t>(i)].empty() ? 0.0 : sum / partners[static_cast<std::size_t>(i)].size();
    EXPECT_NEAR(curvature[i], expected, 1e-12 * std::max(1.0, std::abs(expected))) << "vertex " << i;
    EXPECT_EQ(pairs.partners[static_cast<std::size_t>(i)], static_cast<int>(partners[static_cast<std::size_t>(i)].size()));
  }
  EXPECT_EQ(pairs.partners[4 * 9 + 4], 8);
  EXPECT_THROW(vertex_curvature(pairs, FramePositions::Zero(3, 3)), ArgumentError);
}

TEST(InstanceCurvature, FeaturesMatchTwoPassFormulas) {
  // A synthetic sequence with known per-vertex values: mean and population
  // deviation against the textbook two-pass formulas, including a vertex
  // with a large constant offset (a one-pass sum of squares would cancel).
  const int n = 5, frames = 37;
  CurvatureAccumulator accumulator(n);
  std::vector<Eigen::VectorXd> values;
  for (int t = 0; t < frames; ++t) {
    Eigen::VectorXd c(n);
    c << 1.0 + 0.5 * std::sin(0.3 * t), 2.0, 1e6 + 1e-3 * ((t % 3) - 1), 0.1 * t, std::cos(t) * std::cos(t);
    values.push_back(c);
    accumulator.add(c);
  }
  EXPECT_EQ(accumulator.frames(), frames);
  for (int v = 0; v < n; ++v) {
    double mean = 0.0;
    for (const auto& c : values) mean += c[v];
    mean /= frames;
    double variance = 0.0;
    for (const auto& c : values) variance += (c[v] - mean) * (c[v] - mean);
    variance /= frames;  // population form
    EXPECT_NEAR(accumulator.mean()[v], mean, 1e-12 * std::max(1.0, std::abs(mean))) << v;
    EXPECT_NEAR(accumulator.deviation()[v], std::sqrt(variance), 1e-12 * std::max(1.0, std::abs(mean))) << v;
  }
  EXPECT_EQ(accumulator.deviation()[1], 0.0) << "a constant has no deviation";
  // 0.1 t for t = 0..36: deviation sqrt((N^2 - 1) / 12) * 0.1.
  EXPECT_NEAR(accumulator.deviation()[3], 0.1 * std::sqrt((frames * frames - 1) / 12.0), 1e-12);
  EXPECT_THROW(accumulator.add(Eigen::VectorXd::Zero(4)), ArgumentError);
}

class CurvatureCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("mrcloth_curvature_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(CurvatureCache, StreamsACacheAsTheFramesInMemoryWould) {
  // A sheet rolling tighter frame by frame, written as PC2 (float32): the
  // streamed features equal those of the frames read back, accumulated in
  // memory, to round-off; skipping and limiting frames select the right ones.
  const QuadMesh grid = test::make_grid(10, 6, 0.02);
  const CurvaturePairs pairs = curvature_pairs(grid);
  const int frames = 12;
  {
    Pc2Writer writer(path("roll.pc2"), static_cast<int>(grid.n_vertices()));
    for (int t = 0; t < frames; ++t) writer.add_frame(rolled(grid, 0.5 / (1.0 + t)));
    writer.finish();
  }
  const PointCache all = read_pc2(path("roll.pc2"));
  const auto expect_features = [&](int skip, int count, const CurvatureFeatures& features) {
    CurvatureAccumulator reference(pairs.num_vertices);
    for (int t = skip; t < skip + count; ++t) reference.add(vertex_curvature(pairs, all.frames[static_cast<std::size_t>(t)]));
    ASSERT_EQ(features.frames, count);
    EXPECT_EQ(features.first_frame, skip);
    EXPECT_LT((features.mean - reference.mean()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((features.deviation - reference.deviation()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_GT(features.mean.maxCoeff(), 0.0);
  };
  expect_features(0, frames, analyse_curvature(path("roll.pc2"), pairs));
  CurvatureAnalysisOptions options;
  options.skip_frames = 3;
  expect_features(3, frames - 3, analyse_curvature(path("roll.pc2"), pairs, options));
  options.max_frames = 4;
  std::vector<int> reported;
  expect_features(3, 4, analyse_curvature(path("roll.pc2"), pairs, options, [&](int done, int total) {
                    reported.push_back(done);
                    EXPECT_EQ(total, 4);
                    return true;
                  }));
  EXPECT_EQ(reported, (std::vector<int>{1, 2, 3, 4}));

  // Cancelled after two frames: the features of those two.
  const CurvatureFeatures stopped =
      analyse_curvature(path("roll.pc2"), pairs, {}, [](int done, int) { return done < 2; });
  EXPECT_TRUE(stopped.cancelled);
  expect_features(0, 2, stopped);
}

TEST_F(CurvatureCache, RefusesAMismatchedOrExhaustedCache) {
  const QuadMesh grid = test::make_grid(4, 4, 0.02);
  const CurvaturePairs pairs = curvature_pairs(grid);
  {
    Pc2Writer writer(path("other.pc2"), 7);
    writer.add_frame(FramePositions::Zero(7, 3));
    writer.finish();
  }
  try {
    analyse_curvature(path("other.pc2"), pairs);
    ADD_FAILURE() << "a cache of another mesh";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("other.pc2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("7 points"), std::string::npos) << e.what();
  }
  {
    Pc2Writer writer(path("two.pc2"), static_cast<int>(grid.n_vertices()));
    writer.add_frame(rest_frame(grid));
    FramePositions broken = rest_frame(grid);
    broken(5, 1) = std::nan("");
    writer.add_frame(broken);
    writer.finish();
  }
  CurvatureAnalysisOptions options;
  options.skip_frames = 2;
  EXPECT_THROW(analyse_curvature(path("two.pc2"), pairs, options), ArgumentError);
  options.skip_frames = -1;
  EXPECT_THROW(analyse_curvature(path("two.pc2"), pairs, options), ArgumentError);
  options.skip_frames = 0;
  options.max_frames = 0;
  EXPECT_THROW(analyse_curvature(path("two.pc2"), pairs, options), ArgumentError);
  try {
    analyse_curvature(path("two.pc2"), pairs);
    ADD_FAILURE() << "a NaN position";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frame 1, point 5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(analyse_curvature(path("missing.pc2"), pairs), InputError);
}

TEST_F(CurvatureCache, ReaderServesFramesInAnyOrder) {
  std::vector<FramePositions> frames;
  {
    Pc2Writer writer(path("seq.pc2"), 4, 10.0, 1.0);
    for (int t = 0; t < 5; ++t) {
      frames.push_back(FramePositions::Constant(4, 3, 0.25 * t));
      frames.back()(t % 4, t % 3) = -1.5;
      writer.add_frame(frames.back());
    }
    writer.finish();
  }
  Pc2Reader reader(path("seq.pc2"));
  EXPECT_EQ(reader.num_points(), 4);
  EXPECT_EQ(reader.num_frames(), 5);
  EXPECT_EQ(reader.start_frame(), 10.0);
  for (const int t : {0, 1, 2, 4, 3, 3, 0, 4}) EXPECT_EQ(reader.frame(t), frames[static_cast<std::size_t>(t)]) << t;
  EXPECT_THROW(reader.frame(5), ArgumentError);
  EXPECT_THROW(reader.frame(-1), ArgumentError);
  EXPECT_EQ(read_pc2_frame(path("seq.pc2"), 2), frames[2]);
}

}  // namespace
}  // namespace mrcloth
