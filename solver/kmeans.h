#pragma once
// k-means (Lloyd) with k-means++ seeding and restarts, deterministic for a seed.
// Clusters per-vertex features of an instance (paper section 4: mean
// curvature and its deviation, h = 3 deformation modes) but works in any
// dimension. Features have whatever units the caller gives them; distances are
// plain Euclidean, so scale the columns first if they should weigh alike.
#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <vector>

namespace mrcloth {

struct KMeansOptions {
  int clusters = 3;          ///< k, >= 1 and <= the number of distinct points
  int restarts = 8;          ///< independent k-means++ seedings; the lowest inertia is kept (ties: the first); >= 1
  int max_iterations = 300;  ///< Lloyd iterations per restart, >= 1 (stops earlier when no label changes)
  std::uint64_t seed = 1;    ///< the same seed and data give bitwise the same result on every platform
  /// Optional k x d starting centroids for restart 0 (a warm start, e.g. the
  /// modes of a previous analysis); empty: restart 0 is seeded by k-means++
  /// like the others. Restarts 1.. are always k-means++. Must be finite; they
  /// need not be data points, and a centroid that attracts no point is
  /// re-seeded as any empty cluster is.
  Eigen::MatrixXd initial_centroids;
};

struct KMeansResult {
  std::vector<int> labels;    ///< per point (row), its cluster 0..k-1
  Eigen::MatrixXd centroids;  ///< k x d, the mean of each cluster's points (exactly as computed from labels)
  std::vector<int> sizes;     ///< points per cluster (every one > 0)
  double inertia = 0.0;       ///< sum over points of the squared distance to their centroid (feature units squared)
  int iterations = 0;         ///< Lloyd iterations (assign + update) of the kept restart
  int restart = 0;            ///< index of the kept restart
  bool converged = false;     ///< the kept restart stopped because no label changed (false: max_iterations ran out)
  int restarts_done = 0;      ///< restarts run: options.restarts, fewer when the progress callback stopped them
  bool cancelled = false;     ///< the progress callback returned false (the result is the best of the restarts done)
};

/// Called after each restart with the restarts done (1..total) and the total
/// (options.restarts); return false to stop before the next one.
using KMeansProgress = std::function<bool(int restarts_done, int restarts_total)>;

/// Clusters the rows of `points` (n x d, finite; row i is point i's feature
/// vector) into options.clusters groups, minimising the inertia locally by
/// Lloyd's algorithm from options.restarts k-means++ seedings and keeping the
/// best. Each point goes to its nearest centroid (ties: the lowest index); an
/// empty cluster is re-seeded with the point farthest from its centroid, so no
/// returned cluster is empty. Restart r draws from std::mt19937_64 seeded from
/// (options.seed, r) and accumulates in a fixed order, so the result depends on
/// nothing but the data and the options. Throws ArgumentError (from
/// "mesh_ops/errors.h") for bad options, an empty or non-finite input (naming
/// the row and column), initial centroids of the wrong shape or not finite, or
/// fewer distinct points than clusters. `progress`, if given, is called after
/// every restart; it does not change the result of the restarts it lets run,
/// and when it returns false the best of those done is returned with
/// `cancelled` set.
KMeansResult kmeans(const Eigen::MatrixXd& points, const KMeansOptions& options = {},
                    const KMeansProgress& progress = {});

}  // namespace mrcloth
