#include "deformation_modes.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/mode_layer.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mrcloth {
namespace {

/// offset and scale of one feature column: normalised = (x - offset) / scale.
std::pair<double, double> normalizer(const Eigen::VectorXd& x, FeatureNormalization normalization) {
  double offset = 0.0, scale = 0.0;
  if (normalization == FeatureNormalization::min_max) {
    offset = x.minCoeff();
    scale = x.maxCoeff() - offset;
  } else {
    offset = x.mean();
    scale = std::sqrt((x.array() - offset).square().mean());
  }
  // A feature constant over the garment carries no information: leave it
  // at 0 rather than divide by zero.
  if (!(scale > 0.0)) scale = 1.0;
  return {offset, scale};
}

/// Refuses a mode count a mode layer cannot hold, features of other
/// lengths, and non-finite features (naming the vertex).
void check_features(const Eigen::VectorXd& mean_curvature, const Eigen::VectorXd& deviation, int modes) {
  if (modes < 1 || modes > kLargestMode)
    throw ArgumentError("deformation_modes: " + std::to_string(modes) + " modes asked for; expected 1 to " +
                        std::to_string(kLargestMode) + ", the modes a mode layer holds");
  if (mean_curvature.size() != deviation.size()) {
    throw ArgumentError("deformation_modes: " + std::to_string(mean_curvature.size()) + " mean curvatures but " +
                        std::to_string(deviation.size()) + " deviations; expected one of each per vertex");
  }
  for (Eigen::Index v = 0; v < mean_curvature.size(); ++v) {
    if (!std::isfinite(mean_curvature[v]) || !std::isfinite(deviation[v]))
      throw ArgumentError("deformation_modes: the features of vertex " + std::to_string(v) +
                          " are not finite; expected finite curvature features");
  }
}

/// Each cluster's members' mean features (h x 2, in the features' own
/// units) and member count.
std::pair<Eigen::MatrixXd, std::vector<int>> cluster_means(const Eigen::MatrixXd& features, const std::vector<int>& labels,
                                                           int h) {
  Eigen::MatrixXd centroids = Eigen::MatrixXd::Zero(h, 2);
  std::vector<int> sizes(static_cast<std::size_t>(h), 0);
  for (Eigen::Index v = 0; v < features.rows(); ++v) {
    const int c = labels[static_cast<std::size_t>(v)];
    centroids.row(c) += features.row(v);
    ++sizes[static_cast<std::size_t>(c)];
  }
  for (int c = 0; c < h; ++c) centroids.row(c) /= sizes[static_cast<std::size_t>(c)];
  return {std::move(centroids), std::move(sizes)};
}

/// The clusters in mode order (mode 1 first): mode 1 is the least deformed,
/// by centroid mean curvature, ties by deviation.
std::vector<int> clusters_by_deformation(const Eigen::MatrixXd& centroids) {
  std::vector<int> order(static_cast<std::size_t>(centroids.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (centroids(a, 0) != centroids(b, 0)) return centroids(a, 0) < centroids(b, 0);
    return centroids(a, 1) < centroids(b, 1);
  });
  return order;
}

}  // namespace

std::string normalization_name(FeatureNormalization normalization) {
  return normalization == FeatureNormalization::min_max ? "minmax" : "zscore";
}

FeatureNormalization normalization_from_name(const std::string& name) {
  if (name == "minmax") return FeatureNormalization::min_max;
  if (name == "zscore") return FeatureNormalization::z_score;
  throw ArgumentError("unknown feature normalization '" + name + "'; expected minmax or zscore");
}

ModeReport deformation_modes(const Eigen::VectorXd& mean_curvature, const Eigen::VectorXd& deviation,
                             const ModeOptions& options, const KMeansProgress& progress) {
  check_features(mean_curvature, deviation, options.modes);
  ModeReport report;
  report.normalization = options.normalization;
  report.seed = options.seed;
  const Eigen::Index n = mean_curvature.size();
  Eigen::MatrixXd features(n, 2);
  features.col(0) = mean_curvature;
  features.col(1) = deviation;
  Eigen::MatrixXd normalized(n, 2);
  for (int f = 0; f < 2; ++f) {
    const auto [offset, scale] = normalizer(features.col(f), options.normalization);
    report.offset[f] = offset;
    report.scale[f] = scale;
    normalized.col(f) = (features.col(f).array() - offset) / scale;
  }

  KMeansOptions k;
  k.clusters = options.modes;
  k.restarts = options.restarts;
  k.max_iterations = options.max_iterations;
  k.seed = options.seed;
  const KMeansResult clusters = kmeans(normalized, k, progress);
  report.restarts_done = clusters.restarts_done;
  report.cancelled = clusters.cancelled;
  report.inertia = clusters.inertia;
  report.restart = clusters.restart;
  report.iterations = clusters.iterations;

  const int h = options.modes;
  const auto [centroids, sizes] = cluster_means(features, clusters.labels, h);
  const std::vector<int> order = clusters_by_deformation(centroids);
  std::vector<int> mode_of_cluster(static_cast<std::size_t>(h));
  for (int m = 0; m < h; ++m) mode_of_cluster[static_cast<std::size_t>(order[static_cast<std::size_t>(m)])] = m + 1;

  report.modes.resize(static_cast<std::size_t>(n));
  for (Eigen::Index v = 0; v < n; ++v)
    report.modes[static_cast<std::size_t>(v)] = mode_of_cluster[static_cast<std::size_t>(clusters.labels[static_cast<std::size_t>(v)])];
  report.sizes.resize(static_cast<std::size_t>(h));
  report.centroids.resize(h, 2);
  report.normalized_centroids.resize(h, 2);
  for (int m = 0; m < h; ++m) {
    const int c = order[static_cast<std::size_t>(m)];
    report.sizes[static_cast<std::size_t>(m)] = sizes[static_cast<std::size_t>(c)];
    report.centroids.row(m) = centroids.row(c);
    report.normalized_centroids.row(m) = clusters.centroids.row(c);
  }
  return report;
}

}  // namespace mrcloth
