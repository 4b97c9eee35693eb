#pragma once
// Bending curvature of a recorded instance (paper section 4.2, SPEC stage 3).
//
// For a vertex Pi and a bend partner Pj at rest distance 2L, the cloth
// between them is taken as a circular arc of unchanged length 2L, so
//   sinc(K L) = |Pi Pj| / (2L),  K = (1/L) sinc^-1(|Pi Pj| / (2L)),
// with sinc^-1 on [0, pi]; a ratio >= 1 (stretched, not bent) gives 0. A
// vertex's curvature in a frame is the mean of K over its partners, and
// over the frames of a cache its features are the mean and the population
// standard deviation of that (SPEC stage 4).
#include "point_cache.h"

#include "mesh_ops/quad_mesh.h"

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace mrcloth {

/// 1 - sin(x)/x, accurate to full relative precision for small x too
/// (where the difference cancels), x >= 0.
double one_minus_sinc(double x);

/// sinc^-1 on [0, pi]: the x with sin(x)/x = ratio; 0 for ratio >= 1, pi for
/// ratio <= 0. Solved from 1 - ratio, so ratios within 1e-12 of 1 keep
/// their precision; the residual |sinc(x) - ratio| is at round-off.
double inverse_sinc(double ratio);

/// Curvature of the arc of length 2 * half_rest (metres, > 0) whose chord
/// is `distance` (metres): (1/L) sinc^-1(distance / 2L), in 1/m.
double arc_curvature(double distance, double half_rest);

/// The bend partner pairs of a mesh with their rest half-lengths: what the
/// curvature of any frame of that mesh needs. Rows follow mesh_ops'
/// bend_pairs (each pair once, i < j).
struct CurvaturePairs {
  int num_vertices = 0;
  std::vector<int> i, j;             ///< vertex indices of each pair
  std::vector<double> half_rest;     ///< L = rest distance / 2, metres, > 0
  std::vector<int> partners;         ///< per vertex, how many pairs it is in (0: curvature 0)
};

/// The median over `pairs` of distance in `frame` / rest distance.
double median_pair_stretch(const CurvaturePairs& pairs, const FramePositions& frame);

/// CurvatureFeatures::rounding_curvature of `frame` (1/m).
double rounding_curvature(const CurvaturePairs& pairs, const FramePositions& frame);

/// The pairs of `mesh`, at rest in its current points (metres). Throws
/// ArgumentError for a pair whose ends coincide at rest.
CurvaturePairs curvature_pairs(const QuadMesh& mesh);

/// Per-vertex curvature of one frame (num_vertices x 3, metres): the mean
/// of arc_curvature over each vertex's pairs, 1/m; 0 where it has none.
/// Throws ArgumentError when the frame's row count differs.
Eigen::VectorXd vertex_curvature(const CurvaturePairs& pairs, const FramePositions& frame);

/// Per-vertex mean and population standard deviation (1/N) of curvature
/// over the frames added, accumulated one frame at a time (Welford's
/// update: stable, and memory for the accumulators only).
class CurvatureAccumulator {
 public:
  explicit CurvatureAccumulator(int num_vertices);
  /// Adds one frame's per-vertex curvature (num_vertices values, 1/m).
  void add(const Eigen::VectorXd& curvature);
  int frames() const { return frames_; }
  Eigen::VectorXd mean() const { return mean_; }
  Eigen::VectorXd deviation() const;

 private:
  int frames_ = 0;
  Eigen::VectorXd mean_, squares_;  ///< running mean; sum of squared deviations from it
};

/// Features of every vertex over a recorded instance.
struct CurvatureFeatures {
  Eigen::VectorXd mean;       ///< per vertex, mean curvature over the frames, 1/m
  Eigen::VectorXd deviation;  ///< per vertex, population standard deviation, 1/m
  int frames = 0;             ///< frames analysed
  int first_frame = 0;        ///< index in the cache of the first one
  /// The median over pairs of distance / rest distance in the first frame
  /// analysed: about 1 for a cache of this mesh in its units (a garment
  /// stretches a few per cent), far from it for a cache in other units, with
  /// its vertices in another order, or of another mesh of as many vertices
  /// (whose pairs the inverse sinc reads as flat where they are stretched).
  double first_frame_stretch = 1.0;
  /// The mean curvature single-precision rounding of the cache's positions
  /// alone gives (1/m): a pair of median length L, a half ulp u = 6e-8 of
  /// the largest coordinate X, read through the inverse sinc: 2 sqrt(6 u X /
  /// L) / L. About 1 1/m for a 1 cm pair 1 m from the origin; a cache whose
  /// largest mean curvature is not well above it shows no bending.
  double rounding_curvature = 0.0;
  bool cancelled = false;     ///< the progress callback stopped the analysis (features of the frames so far)
};

struct CurvatureAnalysisOptions {
  int skip_frames = 0;   ///< cache frames to leave out at the start (a settling pre-roll), >= 0
  int max_frames = -1;   ///< at most this many frames after those (-1: all), != 0
};

/// Called after each frame; return false to stop.
using AnalysisProgress = std::function<bool(int frames_done, int frames_total)>;

/// Streams the PC2 cache at `pc2_path` (one frame in memory at a time) and
/// returns each vertex's curvature features. The cache must hold
/// pairs.num_vertices points (InputError naming the file otherwise) and at
/// least one frame after the skipped ones (ArgumentError).
CurvatureFeatures analyse_curvature(const std::string& pc2_path, const CurvaturePairs& pairs,
                                    const CurvatureAnalysisOptions& options = {},
                                    const AnalysisProgress& progress = {});

}  // namespace mrcloth
