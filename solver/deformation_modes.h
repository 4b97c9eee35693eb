#pragma once
// Deformation modes (paper sections 4.3, 4.4; SPEC stage 4): each vertex's
// features (mean curvature, its deviation over the instance) normalised
// and clustered with k-means into h classes, numbered 1..h in order of
// deformation.
#include "kmeans.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace mrcloth {

enum class FeatureNormalization {
  min_max,  ///< each feature scaled to [0, 1] by its min and max over the garment (SPEC's choice)
  z_score,  ///< each feature centred on its mean and divided by its population standard deviation
};

/// "minmax" / "zscore".
std::string normalization_name(FeatureNormalization normalization);
/// Inverse of normalization_name; ArgumentError naming the known ones.
FeatureNormalization normalization_from_name(const std::string& name);

struct ModeOptions {
  int modes = 3;                                             ///< h, the paper's 3; 1..kLargestMode (a mode layer's largest)
  FeatureNormalization normalization = FeatureNormalization::min_max;
  int restarts = 8;                                          ///< k-means++ seedings, the lowest inertia kept
  int max_iterations = 300;                                  ///< Lloyd iterations per restart
  std::uint64_t seed = 1;                                    ///< same seed and features, same modes
};

struct ModeReport {
  std::vector<int> modes;                ///< per vertex, 1..h; 1 the least deformed
  std::vector<int> sizes;                ///< vertices per mode (entry m - 1 for mode m), each > 0
  Eigen::MatrixXd centroids;             ///< h x 2, row m - 1: mode m's (mean curvature, deviation), 1/m
  Eigen::MatrixXd normalized_centroids;  ///< h x 2, the same in normalised units (what k-means saw)
  double inertia = 0.0;                  ///< k-means inertia, normalised units
  FeatureNormalization normalization = FeatureNormalization::min_max;
  Eigen::Vector2d offset{0, 0};          ///< normalised = (feature - offset) / scale, per feature
  Eigen::Vector2d scale{1, 1};           ///< > 0 (1 for a feature that is constant over the garment)
  std::uint64_t seed = 1;
  int restart = 0;                       ///< the k-means restart kept
  int iterations = 0;                    ///< its Lloyd iterations
  int restarts_done = 0;                 ///< k-means restarts run (options.restarts unless cancelled)
  bool cancelled = false;                ///< the progress callback stopped the clustering (modes of the restarts done)
};

/// Modes of the vertices whose features are mean_curvature[v] and
/// deviation[v] (1/m, same length, finite). Modes are numbered by their
/// centroid's mean curvature, ties by deviation. Throws ArgumentError for
/// mismatched or non-finite features and bad options (from kmeans, e.g.
/// more modes than distinct feature points). `progress` is k-means' (called
/// after every restart, false stops; see kmeans): the modes of a run it lets
/// finish are the same with it as without.
ModeReport deformation_modes(const Eigen::VectorXd& mean_curvature, const Eigen::VectorXd& deviation,
                             const ModeOptions& options = {}, const KMeansProgress& progress = {});

}  // namespace mrcloth
