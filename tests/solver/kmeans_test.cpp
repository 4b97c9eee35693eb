#include "mesh_ops/errors.h"
#include "solver/kmeans.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

// Test data from raw engine output converted here, so every platform tests the
// same points (the standard distributions are implementation-defined).
double unit(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

double gaussian(std::mt19937_64& g) {  // Box-Muller
  const double pi = 3.14159265358979323846;
  const double u1 = 1.0 - unit(g), u2 = unit(g);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * pi * u2);
}

Eigen::MatrixXd uniform_points(int n, int d, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  Eigen::MatrixXd p(n, d);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < d; ++c) p(i, c) = unit(g);
  return p;
}

KMeansOptions with(int clusters, int restarts = 8, std::uint64_t seed = 1) {
  KMeansOptions o;
  o.clusters = clusters;
  o.restarts = restarts;
  o.seed = seed;
  return o;
}

double squared_distance(const Eigen::MatrixXd& p, int i, const Eigen::MatrixXd& c, int j) {
  return (p.row(i) - c.row(j)).squaredNorm();
}

// The inertia of a labelling against the means of its own groups.
double partition_inertia(const Eigen::MatrixXd& p, const std::vector<int>& labels, int k) {
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(k, p.cols());
  std::vector<int> count(k, 0);
  for (int i = 0; i < p.rows(); ++i) sum.row(labels[i]) += p.row(i), ++count[labels[i]];
  double total = 0.0;
  for (int i = 0; i < p.rows(); ++i) total += (p.row(i) - sum.row(labels[i]) / count[labels[i]]).squaredNorm();
  return total;
}

// True when a and b are the same partition up to renaming the labels.
bool same_partition(const std::vector<int>& a, const std::vector<int>& b) {
  if (a.size() != b.size()) return false;
  std::map<int, int> ab, ba;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (ab.emplace(a[i], b[i]).first->second != b[i] || ba.emplace(b[i], a[i]).first->second != a[i]) return false;
  }
  return true;
}

// Everything a result claims, checked by brute force: labels in range, sizes
// are the label counts and positive, each centroid the mean of its points,
// each point at (one of) its nearest centroids, the inertia their sum.
void expect_self_consistent(const Eigen::MatrixXd& p, const KMeansResult& r, int k, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(r.labels.size(), static_cast<std::size_t>(p.rows()));
  ASSERT_EQ(r.centroids.rows(), k);
  ASSERT_EQ(r.centroids.cols(), p.cols());
  ASSERT_EQ(r.sizes.size(), static_cast<std::size_t>(k));
  std::vector<int> count(k, 0);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(k, p.cols());
  for (int i = 0; i < p.rows(); ++i) {
    ASSERT_GE(r.labels[i], 0);
    ASSERT_LT(r.labels[i], k);
    ++count[r.labels[i]];
    sum.row(r.labels[i]) += p.row(i);
  }
  for (int j = 0; j < k; ++j) {
    EXPECT_EQ(r.sizes[j], count[j]) << "cluster " << j;
    ASSERT_GT(count[j], 0) << "cluster " << j << " is empty";
    for (int c = 0; c < p.cols(); ++c)
      EXPECT_NEAR(r.centroids(j, c), sum(j, c) / count[j], 1e-12) << "cluster " << j << " coordinate " << c;
  }
  double inertia = 0.0;
  for (int i = 0; i < p.rows(); ++i) {
    const double own = squared_distance(p, i, r.centroids, r.labels[i]);
    inertia += own;
    for (int j = 0; j < k; ++j)
      EXPECT_LE(own, squared_distance(p, i, r.centroids, j) + 1e-12) << "point " << i << " is nearer cluster " << j;
  }
  EXPECT_NEAR(r.inertia, inertia, 1e-12 * std::max(1.0, inertia));
  EXPECT_TRUE(r.converged);
  EXPECT_GE(r.iterations, 1);
}

// The least inertia over every partition of the rows into exactly k non-empty
// groups, enumerated as restricted growth strings (a[0] = 0, a[i] <= 1 + max a[<i]).
double optimal_inertia(const Eigen::MatrixXd& p, int k) {
  const int n = static_cast<int>(p.rows());
  std::vector<int> a(n, 0);
  double best = std::numeric_limits<double>::infinity();
  std::function<void(int, int)> grow = [&](int i, int used) {
    if (n - i < k - used) return;  // too few points left to open the missing groups
    if (i == n) {
      best = std::min(best, partition_inertia(p, a, k));
      return;
    }
    for (int g = 0; g <= std::min(used, k - 1); ++g) {
      a[i] = g;
      grow(i + 1, std::max(used, g + 1));
    }
  };
  grow(0, 0);
  return best;
}

// Lloyd as the header states it, every distance computed, no bounds: each
// point to its nearest centroid (ties: the lowest index), every empty cluster
// in index order given the point farthest from its centroid (ties: the lowest
// index) whose cluster keeps a point and that does not coincide with a point
// given in the same pass, then the means; until no label changes.
struct Reference {
  std::vector<int> labels;
  Eigen::MatrixXd centroids;
  int iterations = 0;
};

double coordinate_sum_distance(const Eigen::MatrixXd& p, int i, const Eigen::MatrixXd& c, int j) {
  double s = 0.0;  // coordinate by coordinate, as an explicit loop rounds
  for (int q = 0; q < p.cols(); ++q) s += (p(i, q) - c(j, q)) * (p(i, q) - c(j, q));
  return s;
}

Reference reference_lloyd(const Eigen::MatrixXd& p, Eigen::MatrixXd c, int max_iterations) {
  const int n = static_cast<int>(p.rows()), k = static_cast<int>(c.rows());
  Reference ref;
  ref.labels.assign(n, -1);
  for (int it = 1; it <= max_iterations; ++it) {
    ref.iterations = it;
    bool changed = false;
    std::vector<double> distance(n);
    std::vector<int> size(k, 0);
    for (int i = 0; i < n; ++i) {
      int best = 0;
      for (int j = 1; j < k; ++j)
        if (coordinate_sum_distance(p, i, c, j) < coordinate_sum_distance(p, i, c, best)) best = j;
      changed = changed || ref.labels[i] != best;
      ref.labels[i] = best;
      distance[i] = coordinate_sum_distance(p, i, c, best);
      ++size[best];
    }
    std::vector<int> moved;
    for (int j = 0; j < k; ++j) {
      if (size[j] > 0) continue;
      int far = -1;
      for (int i = 0; i < n; ++i) {
        bool repeat = false;
        for (int m : moved) repeat = repeat || p.row(i) == p.row(m);
        if (size[ref.labels[i]] > 1 && !repeat && (far < 0 || distance[i] > distance[far])) far = i;
      }
      --size[ref.labels[far]];
      ref.labels[far] = j;
      size[j] = 1;
      moved.push_back(far);
      changed = true;
    }
    c.setZero();
    for (int i = 0; i < n; ++i) c.row(ref.labels[i]) += p.row(i);
    for (int j = 0; j < k; ++j) c.row(j) /= size[j];
    if (!changed) break;
  }
  ref.centroids = c;
  return ref;
}

bool bitwise_equal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

void expect_identical(const KMeansResult& a, const KMeansResult& b) {
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.sizes, b.sizes);
  EXPECT_TRUE(bitwise_equal(a.centroids, b.centroids));
  EXPECT_EQ(std::memcmp(&a.inertia, &b.inertia, sizeof(double)), 0) << a.inertia << " vs " << b.inertia;
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.restart, b.restart);
  EXPECT_EQ(a.converged, b.converged);
}

void expect_argument_error(const std::function<void()>& call, const std::string& expected) {
  try {
    call();
    ADD_FAILURE() << "no ArgumentError; expected one saying '" << expected << "'";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << "message: " << e.what();
  }
}

TEST(KMeans, RecoversPlantedBlobsExactly) {
  const Eigen::Vector2d centre[3] = {{0.0, 0.0}, {4.0, 1.0}, {1.0, 5.0}};
  const double sigma = 0.3;
  const int per_blob = 200;
  Eigen::MatrixXd p(3 * per_blob, 2);
  std::vector<int> planted(3 * per_blob);
  std::mt19937_64 g(11);
  // Interleaved, so the clusters are not contiguous runs of rows.
  for (int i = 0; i < 3 * per_blob; ++i) {
    planted[i] = i % 3;
    for (int c = 0; c < 2; ++c) p(i, c) = centre[planted[i]][c] + sigma * gaussian(g);
  }
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const KMeansResult r = kmeans(p, with(3, 8, seed));
    EXPECT_TRUE(same_partition(r.labels, planted)) << "seed " << seed;
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(r.sizes[j], per_blob) << "seed " << seed;
      // The blob a cluster is, by its first point; its centroid is that blob's sample mean.
      const int blob = planted[std::find(r.labels.begin(), r.labels.end(), j) - r.labels.begin()];
      EXPECT_LT((r.centroids.row(j).transpose() - centre[blob]).norm(), 0.1) << "seed " << seed << " blob " << blob;
    }
    expect_self_consistent(p, r, 3, "seed " + std::to_string(seed));
  }
}

TEST(KMeans, ResultIsSelfConsistentOnRandomData) {
  for (int d : {2, 3})
    for (int k = 2; k <= 5; ++k)
      for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const Eigen::MatrixXd p = uniform_points(300, d, 100 * seed + 10 * d + k);
        const KMeansResult r = kmeans(p, with(k, 4, seed));
        expect_self_consistent(p, r, k, "d " + std::to_string(d) + " k " + std::to_string(k) + " seed " +
                                            std::to_string(seed));
        EXPECT_GE(r.restart, 0);
        EXPECT_LT(r.restart, 4);
      }
}

TEST(KMeans, EqualsPlainLloydLabelForLabel) {
  // The implementation skips distances it can bound; from the same start it
  // must still take exactly plain Lloyd's steps. Starts are drawn from a box
  // four times the data's, so some attract no point and are re-seeded; the
  // grid data make exact ties.
  int compared = 0;
  for (int d : {1, 2, 3, 5})
    for (int k : {2, 3, 5, 8})
      for (std::uint64_t seed = 1; seed <= 3; ++seed)
        for (bool grid : {false, true}) {
          std::mt19937_64 g(1000 * seed + 100 * d + 10 * k + grid);
          Eigen::MatrixXd p = uniform_points(grid ? 200 : 1500, d, g());
          if (grid) p = (p * 12.0).array().floor().matrix();
          KMeansOptions o = with(k, 1, seed);
          o.initial_centroids.resize(k, d);
          for (int j = 0; j < k; ++j)
            for (int c = 0; c < d; ++c)
              o.initial_centroids(j, c) = grid ? std::floor(16.0 * unit(g)) - 1.5 : 4.0 * unit(g) - 1.5;
          const std::string what = "d " + std::to_string(d) + " k " + std::to_string(k) + " seed " +
                                   std::to_string(seed) + (grid ? " grid" : "");
          const KMeansResult r = kmeans(p, o);
          const Reference ref = reference_lloyd(p, o.initial_centroids, o.max_iterations);
          EXPECT_EQ(r.labels, ref.labels) << what;
          EXPECT_EQ(r.iterations, ref.iterations) << what;
          EXPECT_LT((r.centroids - ref.centroids).cwiseAbs().maxCoeff(), 1e-12) << what;
          ++compared;
        }
  EXPECT_EQ(compared, 96);
}

TEST(KMeans, FindsTheBruteForceOptimumOfSmallSets) {
  // Random 9-point sets have genuine Lloyd local optima: on some of these
  // instances a single k-means++ restart reaches the optimum only 7 % of the
  // time, so 20 restarts would pass or fail by the luck of the random stream.
  // 200 leave a miss probability below 1e-5 over all of them.
  for (int k : {2, 3, 4})
    for (std::uint64_t instance = 1; instance <= 12; ++instance) {
      const Eigen::MatrixXd p = uniform_points(9, 2, 1000 * k + instance);
      const double optimum = optimal_inertia(p, k);
      const KMeansResult r = kmeans(p, with(k, 200, instance));
      EXPECT_NEAR(r.inertia, optimum, 1e-12 * optimum) << "k " << k << " instance " << instance;
      expect_self_consistent(p, r, k, "k " + std::to_string(k) + " instance " + std::to_string(instance));
    }
}

TEST(KMeans, SeedingDrawsTheFirstCentreUniformlyAndTheNextBySquaredDistance) {
  // With one restart and one iteration the labels are the Voronoi cells of
  // the two seeds (label 0 the first seed's), so their distribution over many
  // seeds is that of the k-means++ draw: enumerate it exactly and compare.
  const int n = 7, draws = 4000;
  const Eigen::MatrixXd p = uniform_points(n, 2, 123);
  std::map<std::vector<int>, double> expected;
  for (int a = 0; a < n; ++a) {
    double total = 0.0;
    for (int i = 0; i < n; ++i) total += (p.row(i) - p.row(a)).squaredNorm();
    for (int b = 0; b < n; ++b) {
      if (b == a) continue;
      std::vector<int> cells(n);
      for (int i = 0; i < n; ++i)
        cells[i] = (p.row(i) - p.row(b)).squaredNorm() < (p.row(i) - p.row(a)).squaredNorm() ? 1 : 0;
      expected[cells] += (1.0 / n) * (p.row(b) - p.row(a)).squaredNorm() / total;
    }
  }
  std::map<std::vector<int>, int> seen;
  for (std::uint64_t seed = 1; seed <= draws; ++seed) {
    KMeansOptions o = with(2, 1, seed);
    o.max_iterations = 1;
    ++seen[kmeans(p, o).labels];
  }
  for (const auto& [cells, count] : seen) EXPECT_TRUE(expected.count(cells)) << "an impossible first assignment";
  for (const auto& [cells, probability] : expected) {
    const double frequency = seen.count(cells) ? double(seen.at(cells)) / draws : 0.0;
    const double sigma = std::sqrt(probability * (1.0 - probability) / draws);
    EXPECT_NEAR(frequency, probability, 5.0 * sigma + 1e-3);
  }
}

TEST(KMeans, MoreRestartsNeverRaiseTheInertiaAndTheFirstBestIsKept) {
  // Uniform data in 2-D with k = 6 has many local optima, so restarts matter.
  const Eigen::MatrixXd p = uniform_points(400, 2, 77);
  double previous = std::numeric_limits<double>::infinity();
  for (int restarts = 1; restarts <= 10; ++restarts) {
    const KMeansResult r = kmeans(p, with(6, restarts, 5));
    EXPECT_LE(r.inertia, previous) << restarts << " restarts";
    previous = r.inertia;
    // Restart r draws from (seed, r) whatever the count, so running only up to
    // the kept restart gives the same result again.
    expect_identical(r, kmeans(p, with(6, r.restart + 1, 5)));
  }
}

TEST(KMeans, AmongEqualInertiasTheFirstRestartIsKept) {
  // Well-separated blobs: nearly every restart ends in the same partition
  // (labels perhaps renamed) and so bitwise the same inertia, summed in point
  // order. The kept restart is then the first that reached it, which is the
  // first count of restarts that already gives the final inertia.
  Eigen::MatrixXd p(90, 2);
  std::mt19937_64 g(17);
  for (int i = 0; i < 90; ++i) p.row(i) << 10.0 * (i % 3) + 0.2 * gaussian(g), 10.0 * (i % 2) + 0.2 * gaussian(g);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const KMeansResult all = kmeans(p, with(3, 8, seed));
    int first = 0;
    while (kmeans(p, with(3, first + 1, seed)).inertia != all.inertia) ++first;
    EXPECT_EQ(all.restart, first) << "seed " << seed;
  }
}

TEST(KMeans, TheSeedDrivesTheSeeding) {
  const Eigen::MatrixXd p = uniform_points(500, 2, 3);
  std::vector<double> inertias;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) inertias.push_back(kmeans(p, with(5, 1, seed)).inertia);
  std::sort(inertias.begin(), inertias.end());
  EXPECT_GT(std::unique(inertias.begin(), inertias.end()) - inertias.begin(), 1)
      << "ten seeds with one restart each all found the same local optimum";
}

TEST(KMeans, ProgressIsCalledAfterEveryRestartAndChangesNothing) {
  const Eigen::MatrixXd p = uniform_points(300, 2, 21);
  const KMeansOptions options = with(6, 7, 3);
  std::vector<std::pair<int, int>> calls;
  const KMeansResult r = kmeans(p, options, [&](int done, int total) {
    calls.emplace_back(done, total);
    return true;
  });
  std::vector<std::pair<int, int>> expected;
  for (int done = 1; done <= 7; ++done) expected.emplace_back(done, 7);
  EXPECT_EQ(calls, expected) << "once per restart, with restarts done and the total";
  EXPECT_FALSE(r.cancelled);
  EXPECT_EQ(r.restarts_done, 7);
  const KMeansResult plain = kmeans(p, options);
  expect_identical(r, plain);
  EXPECT_FALSE(plain.cancelled);
  EXPECT_EQ(plain.restarts_done, 7);
}

TEST(KMeans, AProgressCallbackReturningFalseStopsAfterThatRestart) {
  const Eigen::MatrixXd p = uniform_points(300, 2, 21);
  int calls = 0;
  const KMeansResult r = kmeans(p, with(6, 50, 3), [&](int done, int total) {
    ++calls;
    EXPECT_EQ(total, 50);
    return done < 3;
  });
  EXPECT_EQ(calls, 3) << "no restart runs after the callback says stop";
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(r.restarts_done, 3);
  // The result is the best of the restarts done: what three restarts give.
  expect_identical(r, kmeans(p, with(6, 3, 3)));
  // Stopping at the last restart still says so (the caller asked to stop).
  const KMeansResult last = kmeans(p, with(6, 2, 3), [](int done, int) { return done < 2; });
  EXPECT_TRUE(last.cancelled);
  EXPECT_EQ(last.restarts_done, 2);
}

TEST(KMeans, SameSeedGivesBitwiseTheSameResultWhateverRanBefore) {
  const Eigen::MatrixXd p = uniform_points(1000, 2, 9);
  const KMeansOptions options = with(4, 6, 42);
  const KMeansResult first = kmeans(p, options);
  const KMeansResult unrelated = kmeans(uniform_points(200, 3, 10), with(3, 3, 7));
  EXPECT_EQ(unrelated.labels.size(), 200u);
  const KMeansResult second = kmeans(p, options);
  expect_identical(first, second);
}

TEST(KMeans, ScalingByAPowerOfTwoScalesEverythingExactly) {
  // Multiplying by 2^s is exact in floating point, so every comparison and
  // draw of the run is unchanged: no absolute tolerance hides in the method.
  const Eigen::MatrixXd p = uniform_points(300, 2, 21);
  const KMeansResult base = kmeans(p, with(4, 4, 3));
  for (int s : {-200, -20, 20, 200}) {
    const double f = std::ldexp(1.0, s);
    const KMeansResult r = kmeans(p * f, with(4, 4, 3));
    EXPECT_EQ(r.labels, base.labels) << "2^" << s;
    EXPECT_TRUE(bitwise_equal(r.centroids, base.centroids * f)) << "2^" << s;
    EXPECT_EQ(r.inertia, base.inertia * f * f) << "2^" << s;
    EXPECT_EQ(r.restart, base.restart) << "2^" << s;
  }
}

TEST(KMeans, OneClusterIsTheMean) {
  const Eigen::MatrixXd p = uniform_points(250, 3, 4) * 7.0;
  const KMeansResult r = kmeans(p, with(1));
  const Eigen::RowVectorXd mean = p.colwise().mean();
  double deviation = 0.0;
  for (int i = 0; i < p.rows(); ++i) deviation += (p.row(i) - mean).squaredNorm();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.centroids(0, c), mean(c), 1e-12);
  EXPECT_NEAR(r.inertia, deviation, 1e-12 * deviation);
  EXPECT_EQ(r.sizes, std::vector<int>{250});
  EXPECT_EQ(r.labels, std::vector<int>(250, 0));
}

TEST(KMeans, OneClusterPerDistinctPointHasZeroInertia) {
  const Eigen::MatrixXd p = uniform_points(7, 2, 8);
  const KMeansResult r = kmeans(p, with(7));
  EXPECT_EQ(r.inertia, 0.0);
  EXPECT_EQ(r.sizes, std::vector<int>(7, 1));
  for (int i = 0; i < 7; ++i) EXPECT_EQ(r.centroids.row(r.labels[i]), p.row(i)) << "point " << i;
  std::vector<int> sorted = r.labels;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
}

TEST(KMeans, HeavyDuplicatesGiveOneClusterPerValue) {
  const Eigen::RowVector2d a(0.0, 0.0), b(1.0, 0.0), c(10.0, 10.0);
  Eigen::MatrixXd p(101, 2);
  std::vector<int> value(101);
  for (int i = 0; i < 101; ++i) {
    value[i] = i == 57 ? 2 : (i - (i > 57)) % 2;  // A and B alternate, C once in the middle
    p.row(i) = value[i] == 0 ? a : value[i] == 1 ? b : c;
  }
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const KMeansResult r = kmeans(p, with(3, 8, seed));
    EXPECT_TRUE(same_partition(r.labels, value)) << "seed " << seed;
    EXPECT_EQ(r.inertia, 0.0) << "seed " << seed;
    std::vector<int> sizes = r.sizes;
    std::sort(sizes.begin(), sizes.end());
    EXPECT_EQ(sizes, (std::vector<int>{1, 50, 50})) << "seed " << seed;
    expect_self_consistent(p, r, 3, "seed " + std::to_string(seed));
  }
}

TEST(KMeans, AnEmptyClusterIsReseededWithTheFarthestPoint) {
  // A starting centroid far from everything attracts no point; the point
  // farthest from its centroid (10, at distance 10 from 0) takes it over.
  Eigen::MatrixXd p(4, 1);
  p << 0.0, 1.0, 2.0, 10.0;
  KMeansOptions o = with(2, 1);
  o.initial_centroids.resize(2, 1);
  o.initial_centroids << 0.0, 100.0;
  const KMeansResult r = kmeans(p, o);
  EXPECT_EQ(r.labels, (std::vector<int>{0, 0, 0, 1}));
  EXPECT_EQ(r.centroids(0, 0), 1.0);
  EXPECT_EQ(r.centroids(1, 0), 10.0);
  EXPECT_EQ(r.inertia, 2.0);
  EXPECT_EQ(r.restart, 0);
}

TEST(KMeans, SeveralEmptyClustersGetDistinctPoints) {
  // Three identical starts: every point ties to cluster 0, clusters 1 and 2
  // are empty. The farthest points from -5 are the two copies of 10, but the
  // second copy would only duplicate cluster 1, so cluster 2 gets 1.
  Eigen::MatrixXd p(13, 1);
  p << 0, 0, 0, 10, 0, 0, 1, 0, 0, 10, 0, 0, 0;
  KMeansOptions o = with(3, 1);
  o.initial_centroids = Eigen::MatrixXd::Constant(3, 1, -5.0);
  o.max_iterations = 1;  // the labels of the repair itself
  EXPECT_EQ(kmeans(p, o).labels, (std::vector<int>{0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 0, 0}));
  o.max_iterations = 300;
  const KMeansResult r = kmeans(p, o);
  EXPECT_EQ(r.labels, (std::vector<int>{0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 0, 0, 0}));
  EXPECT_EQ(r.sizes, (std::vector<int>{10, 2, 1}));
  EXPECT_EQ(r.inertia, 0.0);
  expect_self_consistent(p, r, 3, "three identical starts");
}

TEST(KMeans, InitialCentroidsSeedOnlyTheFirstRestart) {
  const Eigen::MatrixXd p = uniform_points(300, 2, 31);
  KMeansOptions warm = with(3, 1);
  warm.initial_centroids = kmeans(p, with(3)).centroids;
  const KMeansResult r = kmeans(p, warm);
  // Started at a converged solution, the first assignment already is the fixed point.
  EXPECT_EQ(r.iterations, 2);
  EXPECT_TRUE(bitwise_equal(r.centroids, warm.initial_centroids));
  // Later restarts are k-means++ ones and can only improve on it.
  warm.restarts = 5;
  EXPECT_LE(kmeans(p, warm).inertia, r.inertia);
}

TEST(KMeans, SeedingFavoursFarPoints) {
  // A tight blob and one far outlier, one restart, one Lloyd iteration: the
  // second centre is drawn proportionally to the squared distance, so it is
  // the outlier (or the first centre was); a uniform draw would almost always
  // put both centres in the blob and merge the outlier into a blob cluster.
  Eigen::MatrixXd p = uniform_points(1000, 2, 41) * 0.01;
  p.conservativeResize(1001, 2);
  p.row(1000) << 100.0, 100.0;
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    KMeansOptions o = with(2, 1, seed);
    o.max_iterations = 1;
    const KMeansResult r = kmeans(p, o);
    EXPECT_EQ(r.sizes[r.labels[1000]], 1) << "seed " << seed;
  }
}

TEST(KMeans, StopsAtMaxIterationsWithAConsistentResult) {
  const Eigen::MatrixXd p = uniform_points(2000, 2, 51);
  KMeansOptions o = with(8, 1);
  o.max_iterations = 1;
  const KMeansResult r = kmeans(p, o);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_FALSE(r.converged);
  // Not a fixed point, yet the centroids are the means of the labels and the inertia is theirs.
  EXPECT_NEAR(r.inertia, partition_inertia(p, r.labels, 8), 1e-12 * r.inertia);
  for (int j = 0; j < 8; ++j) {
    Eigen::RowVector2d sum(0.0, 0.0);
    for (int i = 0; i < p.rows(); ++i)
      if (r.labels[i] == j) sum += p.row(i);
    EXPECT_LT((r.centroids.row(j) - sum / r.sizes[j]).norm(), 1e-12) << "cluster " << j;
  }
}

TEST(KMeans, RejectsBadInput) {
  Eigen::MatrixXd p = uniform_points(30, 2, 61);
  p(17, 1) = std::numeric_limits<double>::quiet_NaN();
  expect_argument_error([&] { kmeans(p); }, "kmeans: point 17 coordinate 1 is not finite; expected finite features");
  p(17, 1) = 0.5;
  p(3, 0) = -std::numeric_limits<double>::infinity();
  expect_argument_error([&] { kmeans(p); }, "point 3 coordinate 0 is not finite");

  Eigen::MatrixXd two(40, 2);
  for (int i = 0; i < 40; ++i) two.row(i) << i % 2, 1.0;
  expect_argument_error([&] { kmeans(two, with(3)); }, "kmeans: 3 clusters requested but only 2 distinct points");
  expect_argument_error([&] { kmeans(Eigen::MatrixXd::Ones(5, 2), with(2)); }, "only 1 distinct point");
  expect_argument_error([&] { kmeans(uniform_points(4, 2, 1), with(5)); }, "5 clusters requested but only 4");

  const Eigen::MatrixXd good = uniform_points(30, 2, 62);
  expect_argument_error([&] { kmeans(good, with(0)); }, "kmeans: clusters must be >= 1 (got 0)");
  expect_argument_error([&] { kmeans(good, with(-2)); }, "clusters must be >= 1 (got -2)");
  expect_argument_error([&] { kmeans(good, with(3, 0)); }, "kmeans: restarts must be >= 1 (got 0)");
  KMeansOptions o = with(3);
  o.max_iterations = 0;
  expect_argument_error([&] { kmeans(good, o); }, "kmeans: max_iterations must be >= 1 (got 0)");

  expect_argument_error([&] { kmeans(Eigen::MatrixXd(0, 2)); }, "kmeans: no points (0 x 2)");
  expect_argument_error([&] { kmeans(Eigen::MatrixXd(5, 0)); }, "kmeans: no points (5 x 0)");

  KMeansOptions init = with(3);
  init.initial_centroids = Eigen::MatrixXd::Zero(2, 2);
  expect_argument_error([&] { kmeans(good, init); }, "initial centroids are 2 x 2; expected 3 x 2");
  init.initial_centroids = Eigen::MatrixXd::Zero(3, 2);
  init.initial_centroids(2, 1) = std::numeric_limits<double>::infinity();
  expect_argument_error([&] { kmeans(good, init); }, "initial centroid 2 coordinate 1 is not finite");
}

}  // namespace
}  // namespace mrcloth
