#include "kmeans.h"

#include "mesh_ops/errors.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>

// Bitwise reproducibility needs every a * b + c rounded twice on every
// platform, but GCC and Clang fuse them into one FMA wherever the target has
// it (every AArch64; x86-64 with -march=native): a different result than on a
// baseline x86-64 build. Contraction is turned off for this file. (-ffast-math
// or Clang's -ffp-contract=fast on the command line would still override it.)
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

namespace mrcloth {
namespace {

// The points copied row-major: every distance then reads d adjacent doubles,
// and no Eigen reduction (whose order depends on the SIMD width) is involved.
struct Rows {
  std::vector<double> x;  // n * d
  int n = 0, d = 0;
  const double* row(int i) const { return x.data() + static_cast<std::size_t>(i) * d; }
};

// One restart's outcome; centroids row-major k * d.
struct Run {
  std::vector<int> labels, sizes;
  std::vector<double> centroids;
  double inertia = 0.0;
  int iterations = 0;
  bool converged = false;
};

// Squared distance with the dimension fixed at compile time (D > 0) or read
// at run time (D == 0). Same operations in the same order either way, so the
// specialisations only make the hot loop faster, never change a bit.
template <int D>
double squared_distance_of(const double* a, const double* b, int d) {
  double s = 0.0;
  for (int c = 0; c < (D > 0 ? D : d); ++c) {
    const double t = a[c] - b[c];
    s += t * t;
  }
  return s;
}

double squared_distance(const double* a, const double* b, int d) { return squared_distance_of<0>(a, b, d); }

bool same_point(const double* a, const double* b, int d) {
  for (int c = 0; c < d; ++c)
    if (a[c] != b[c]) return false;
  return true;
}

void require_at_least_one(const char* name, int value) {
  if (value < 1)
    throw ArgumentError(std::string("kmeans: ") + name + " must be >= 1 (got " + std::to_string(value) + ")");
}

void validate(const Eigen::MatrixXd& points, const KMeansOptions& options) {
  require_at_least_one("clusters", options.clusters);
  require_at_least_one("restarts", options.restarts);
  require_at_least_one("max_iterations", options.max_iterations);
  if (points.rows() == 0 || points.cols() == 0)
    throw ArgumentError("kmeans: no points (" + std::to_string(points.rows()) + " x " + std::to_string(points.cols()) +
                        "); expected at least one row of at least one feature");
  // Row by row, so the first bad point named is the lowest-numbered one.
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (Eigen::Index c = 0; c < points.cols(); ++c)
      if (!std::isfinite(points(i, c)))
        throw ArgumentError("kmeans: point " + std::to_string(i) + " coordinate " + std::to_string(c) +
                            " is not finite; expected finite features");
  const Eigen::MatrixXd& init = options.initial_centroids;
  if (init.size() == 0) return;
  if (init.rows() != options.clusters || init.cols() != points.cols())
    throw ArgumentError("kmeans: initial centroids are " + std::to_string(init.rows()) + " x " +
                        std::to_string(init.cols()) + "; expected " + std::to_string(options.clusters) + " x " +
                        std::to_string(points.cols()) + " (clusters x features)");
  for (Eigen::Index j = 0; j < init.rows(); ++j)
    for (Eigen::Index c = 0; c < init.cols(); ++c)
      if (!std::isfinite(init(j, c)))
        throw ArgumentError("kmeans: initial centroid " + std::to_string(j) + " coordinate " + std::to_string(c) +
                            " is not finite; expected finite values");
}

Rows row_major(const Eigen::MatrixXd& m) {
  Rows r;
  r.n = static_cast<int>(m.rows());
  r.d = static_cast<int>(m.cols());
  r.x.resize(static_cast<std::size_t>(r.n) * r.d);
  for (int i = 0; i < r.n; ++i)
    for (int c = 0; c < r.d; ++c) r.x[static_cast<std::size_t>(i) * r.d + c] = m(i, c);
  return r;
}

// The number of distinct points, counted only up to `limit`: k-means++ needs k
// of them and nothing more is asked, so this stays O(n k d) instead of a sort.
int count_distinct(const Rows& p, int limit) {
  std::vector<int> found;
  for (int i = 0; i < p.n && static_cast<int>(found.size()) < limit; ++i) {
    bool seen = false;
    for (int f : found) seen = seen || same_point(p.row(i), p.row(f), p.d);
    if (!seen) found.push_back(i);
  }
  return static_cast<int>(found.size());
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Distinct restarts of one seed get distinct streams (splitmix64 is a bijection).
std::mt19937_64 restart_engine(std::uint64_t seed, int restart) {
  return std::mt19937_64(splitmix64(splitmix64(seed) ^ static_cast<std::uint64_t>(restart)));
}

// The standard distributions are implementation-defined; this is not: the top
// 53 bits of the engine's (fully specified) output, scaled into [0, 1).
double unit_double(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

// k-means++: the first centre uniform among the points, each next one drawn
// with probability proportional to its squared distance to the nearest centre
// chosen so far. With at least k distinct points some point is always at a
// positive distance, and a point at distance 0 is never drawn, so the k
// centres are distinct.
std::vector<double> seed_plus_plus(const Rows& p, int k, std::mt19937_64& engine) {
  std::vector<double> centres(static_cast<std::size_t>(k) * p.d);
  auto take = [&](int j, int i) {
    std::copy(p.row(i), p.row(i) + p.d, centres.data() + static_cast<std::size_t>(j) * p.d);
  };
  const int first = std::min(p.n - 1, static_cast<int>(unit_double(engine) * p.n));
  take(0, first);
  std::vector<double> nearest(p.n);
  for (int i = 0; i < p.n; ++i) nearest[i] = squared_distance(p.row(i), p.row(first), p.d);
  for (int j = 1; j < k; ++j) {
    double total = 0.0;
    for (double w : nearest) total += w;
    const double target = unit_double(engine) * total;
    int chosen = -1, last_positive = -1;
    double cumulative = 0.0;
    for (int i = 0; i < p.n && chosen < 0; ++i) {
      if (nearest[i] <= 0.0) continue;
      last_positive = i;
      cumulative += nearest[i];
      if (cumulative > target) chosen = i;
    }
    // The running sum repeats the total's additions, so it always passes the
    // target; the fallback only guards against an overflowing total.
    if (chosen < 0) chosen = last_positive;
    assert(chosen >= 0 && "at least k distinct points were checked");
    take(j, chosen);
    for (int i = 0; i < p.n; ++i) nearest[i] = std::min(nearest[i], squared_distance(p.row(i), p.row(chosen), p.d));
  }
  return centres;
}

// Gives every empty cluster, in index order, the point farthest from its
// centroid (ties: the lowest index) among points whose cluster keeps another
// point and that do not coincide with a point re-seeded before in this pass,
// so the new clusters are distinct. Such a point exists while fewer than k
// clusters are occupied, because the data hold at least k distinct points.
// `distance` is each point's squared distance to its centroid. Returns the
// points moved.
std::vector<int> reseed_empty(const Rows& p, int k, const std::vector<double>& distance, std::vector<int>& labels,
                              std::vector<int>& sizes) {
  std::vector<int> moved;
  for (int j = 0; j < k; ++j) {
    if (sizes[j] > 0) continue;
    int far = -1;
    for (int i = 0; i < p.n; ++i) {
      if (sizes[labels[i]] < 2 || (far >= 0 && distance[i] <= distance[far])) continue;
      bool repeat = false;
      for (int m : moved) repeat = repeat || same_point(p.row(i), p.row(m), p.d);
      if (!repeat) far = i;
    }
    assert(far >= 0 && "at least k distinct points were checked");
    --sizes[labels[far]];
    labels[far] = j;
    sizes[j] = 1;
    moved.push_back(far);
  }
  return moved;
}

// One Lloyd run between iterations. Hamerly's bounds (J. Comput. Graph.
// Stat. 2010) let later iterations skip most distances: per point an upper
// bound on the distance (not squared) to its own centroid and a lower bound on
// the distance to every other one, both brought up to date lazily from how far
// the centroids moved.
struct Lloyd {
  std::vector<int> labels;
  std::vector<double> upper, lower;
  std::vector<double> centroids;                 // k * d, row-major
  std::vector<double> own_shift, others_shift;  // per cluster: how far its centroid / any other moved last
  std::vector<double> sums;                      // k * d, of the points as labelled, in point order
  std::vector<int> sizes;
};

// Half the distance from each centroid to its nearest other one: a point
// closer than that to its centroid cannot be nearer any other.
std::vector<double> half_gaps(const std::vector<double>& centroids, int k, int d) {
  std::vector<double> gap(k, std::numeric_limits<double>::infinity());
  for (int j = 0; j < k; ++j)
    for (int m = j + 1; m < k; ++m) {
      const double* a = centroids.data() + static_cast<std::size_t>(j) * d;
      const double* b = centroids.data() + static_cast<std::size_t>(m) * d;
      const double g = 0.5 * std::sqrt(squared_distance(a, b, d));
      gap[j] = std::min(gap[j], g);
      gap[m] = std::min(gap[m], g);
    }
  return gap;
}

// Each point to its nearest centroid, ties to the lowest index, summing the
// clusters on the way (in point order, as sum_clusters does). Returns whether
// any label changed. A point keeps its label unexamined only when its bounds
// show its centroid nearer than every other by more than `slack`, which
// exceeds every rounding error in the bounds and in the squared distances: so
// the labels are exactly those of comparing all k squared distances, and the
// bounds only save time. The full scan is written as selects, not ifs: which
// centroid wins is close to random between neighbouring points.
template <int D>
bool assign_rows(const Rows& p, int k, double slack, Lloyd& s) {
  const int d = D > 0 ? D : p.d;
  const double* c = s.centroids.data();
  const std::vector<double> gap = half_gaps(s.centroids, k, d);
  s.sums.assign(static_cast<std::size_t>(k) * d, 0.0);
  s.sizes.assign(k, 0);
  bool changed = false;
  for (int i = 0; i < p.n; ++i) {
    const double* x = p.x.data() + static_cast<std::size_t>(i) * d;
    const int own = s.labels[i];
    bool scan = own < 0;
    if (!scan) {
      s.upper[i] += s.own_shift[own];
      s.lower[i] -= s.others_shift[own];
      const double limit = std::max(gap[own], s.lower[i]) - slack;
      if (!(s.upper[i] < limit)) {
        s.upper[i] = std::sqrt(squared_distance_of<D>(x, c + static_cast<std::size_t>(own) * d, d));
        scan = !(s.upper[i] < limit);
      }
    }
    int best = own;
    if (scan) {
      best = 0;
      double best_distance = squared_distance_of<D>(x, c, d), second = std::numeric_limits<double>::infinity();
      for (int j = 1; j < k; ++j) {
        const double t = squared_distance_of<D>(x, c + static_cast<std::size_t>(j) * d, d);
        const bool nearer = t < best_distance;
        second = nearer ? best_distance : std::min(second, t);
        best = nearer ? j : best;
        best_distance = nearer ? t : best_distance;
      }
      changed |= own != best;
      s.labels[i] = best;
      s.upper[i] = std::sqrt(best_distance);
      s.lower[i] = std::sqrt(second);
    }
    double* sum = s.sums.data() + static_cast<std::size_t>(best) * d;
    for (int q = 0; q < d; ++q) sum[q] += x[q];
    ++s.sizes[best];
  }
  return changed;
}

bool assign(const Rows& p, int k, double slack, Lloyd& s) {
  switch (p.d) {
    case 1: return assign_rows<1>(p, k, slack, s);
    case 2: return assign_rows<2>(p, k, slack, s);
    case 3: return assign_rows<3>(p, k, slack, s);
    default: return assign_rows<0>(p, k, slack, s);
  }
}

// Sums and sizes of the clusters from the labels alone, in point order.
void sum_clusters(const Rows& p, int k, Lloyd& s) {
  s.sums.assign(static_cast<std::size_t>(k) * p.d, 0.0);
  s.sizes.assign(k, 0);
  for (int i = 0; i < p.n; ++i) {
    double* sum = s.sums.data() + static_cast<std::size_t>(s.labels[i]) * p.d;
    for (int q = 0; q < p.d; ++q) sum[q] += p.row(i)[q];
    ++s.sizes[s.labels[i]];
  }
}

// Moves every centroid to the mean of its points (sum / count, so the same
// labels always give bitwise the same centroids) and records the shifts the
// bounds need: its own, and the largest among the others.
void update_centroids(int k, int d, Lloyd& s) {
  int largest = 0;
  for (int j = 0; j < k; ++j) {
    double* centroid = s.centroids.data() + static_cast<std::size_t>(j) * d;
    const double* sum = s.sums.data() + static_cast<std::size_t>(j) * d;
    double moved = 0.0;
    for (int q = 0; q < d; ++q) {
      const double mean = sum[q] / s.sizes[j];
      moved += (mean - centroid[q]) * (mean - centroid[q]);
      centroid[q] = mean;
    }
    s.own_shift[j] = std::sqrt(moved);
    if (s.own_shift[j] > s.own_shift[largest]) largest = j;
  }
  double second = 0.0;
  for (int j = 0; j < k; ++j)
    if (j != largest) second = std::max(second, s.own_shift[j]);
  for (int j = 0; j < k; ++j) s.others_shift[j] = j == largest ? second : s.own_shift[largest];
}

double inertia(const Rows& p, const std::vector<double>& centroids, const std::vector<int>& labels) {
  double sum = 0.0;
  for (int i = 0; i < p.n; ++i)
    sum += squared_distance(p.row(i), centroids.data() + static_cast<std::size_t>(labels[i]) * p.d, p.d);
  return sum;
}

// Lloyd from the given centres: assign, repair empty clusters, take means;
// stop once an assignment changes no label. The returned centroids are the
// means of the returned labels and the inertia is measured against them, also
// when the iterations run out. `extent` bounds every distance between points
// and centres; the slack of the bounds is a small multiple of it.
Run lloyd(const Rows& p, int k, std::vector<double> centres, int max_iterations, double extent) {
  Lloyd s;
  s.labels.assign(p.n, -1);
  s.upper.assign(p.n, std::numeric_limits<double>::infinity());
  s.lower.assign(p.n, 0.0);
  s.centroids = std::move(centres);
  s.own_shift.assign(k, 0.0);
  s.others_shift.assign(k, 0.0);
  // A bound gathers at most one rounding of its own size per iteration plus
  // a few relative ones per distance; this is several times their sum.
  const double slack = extent * (static_cast<double>(max_iterations) + 2.0 * p.d + 16.0) * 0x1.0p-50;
  Run run;
  for (int it = 1; it <= max_iterations; ++it) {
    run.iterations = it;
    bool changed = assign(p, k, slack, s);
    if (std::find(s.sizes.begin(), s.sizes.end(), 0) != s.sizes.end()) {
      std::vector<double> distance(p.n);
      for (int i = 0; i < p.n; ++i)
        distance[i] = squared_distance(p.row(i), s.centroids.data() + static_cast<std::size_t>(s.labels[i]) * p.d, p.d);
      for (int m : reseed_empty(p, k, distance, s.labels, s.sizes)) {
        s.upper[m] = std::numeric_limits<double>::infinity();  // examined in full next time
        s.lower[m] = 0.0;
      }
      sum_clusters(p, k, s);
      changed = true;
    }
    update_centroids(k, p.d, s);
    if (!changed) {
      run.converged = true;
      break;
    }
  }
  run.labels = std::move(s.labels);
  run.sizes = std::move(s.sizes);
  run.centroids = std::move(s.centroids);
  run.inertia = inertia(p, run.centroids, run.labels);
  return run;
}

// The diagonal of the box around the points and the given centres.
double extent_of(const Rows& p, const std::vector<double>& centres) {
  std::vector<double> low(p.x.begin(), p.x.begin() + p.d), high = low;
  auto grow = [&](const std::vector<double>& v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::size_t c = i % static_cast<std::size_t>(p.d);
      low[c] = std::min(low[c], v[i]);
      high[c] = std::max(high[c], v[i]);
    }
  };
  grow(p.x);
  grow(centres);
  return std::sqrt(squared_distance(high.data(), low.data(), p.d));
}

std::vector<double> initial_rows(const Eigen::MatrixXd& init) {
  Rows r = row_major(init);
  return std::move(r.x);
}

KMeansResult to_result(Run run, int restart, int k, int d) {
  KMeansResult result;
  result.labels = std::move(run.labels);
  result.sizes = std::move(run.sizes);
  result.centroids.resize(k, d);
  for (int j = 0; j < k; ++j)
    for (int c = 0; c < d; ++c) result.centroids(j, c) = run.centroids[static_cast<std::size_t>(j) * d + c];
  result.inertia = run.inertia;
  result.iterations = run.iterations;
  result.restart = restart;
  result.converged = run.converged;
  return result;
}

}  // namespace

KMeansResult kmeans(const Eigen::MatrixXd& points, const KMeansOptions& options, const KMeansProgress& progress) {
  validate(points, options);
  const int k = options.clusters;
  const Rows p = row_major(points);
  const int distinct = count_distinct(p, k);
  if (distinct < k)
    throw ArgumentError("kmeans: " + std::to_string(k) + " clusters requested but only " + std::to_string(distinct) +
                        (distinct == 1 ? " distinct point" : " distinct points"));
  Run best;
  int best_restart = -1, done = 0;
  bool cancelled = false;
  for (int r = 0; r < options.restarts && !cancelled; ++r) {
    std::vector<double> centres;
    if (r == 0 && options.initial_centroids.size() > 0) {
      centres = initial_rows(options.initial_centroids);
    } else {
      std::mt19937_64 engine = restart_engine(options.seed, r);
      centres = seed_plus_plus(p, k, engine);
    }
    const double extent = extent_of(p, centres);
    Run run = lloyd(p, k, std::move(centres), options.max_iterations, extent);
    // Strictly lower: among equal inertias the first restart is kept.
    if (best_restart < 0 || run.inertia < best.inertia) {
      best = std::move(run);
      best_restart = r;
    }
    done = r + 1;
    cancelled = progress && !progress(done, options.restarts);
  }
  KMeansResult result = to_result(std::move(best), best_restart, k, p.d);
  result.restarts_done = done;
  result.cancelled = cancelled;
  return result;
}

}  // namespace mrcloth
