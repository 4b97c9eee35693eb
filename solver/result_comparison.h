#pragma once
// One model's recorded result against the high-resolution one, frame by
// frame, at the high-resolution mesh's material points (detail_measures.h):
// how far the model's surface is from the reference, and how much of the
// reference's bending (its wrinkles) the model keeps, over the whole garment
// and over the region of one deformation mode.
#include "detail_measures.h"
#include "simulate.h"

#include "mesh_ops/quad_mesh.h"

#include <string>
#include <vector>

namespace mrcloth {

struct ComparisonOptions {
  int region_mode = -1;  ///< the mode whose region is measured apart; -1: the reference's highest mode
  int max_frames = -1;   ///< compare at most this many frames from the first; -1: all
};

struct ComparisonReport {
  int frames = 0;                      ///< frames compared
  int points = 0;                      ///< material points (the reference's vertices)
  int region_mode = 0;                 ///< the mode of the region measured apart
  int region_points = 0;               ///< its interior vertices on the reference
  std::vector<DistanceStats> per_frame;  ///< distance of the model to the reference, metres, per frame
  double mean_rms = 0.0;               ///< mean over frames of the per-frame RMS distance, metres
  double mean_p95 = 0.0;               ///< mean over frames of the per-frame 95th percentile, metres
  double max_distance = 0.0;           ///< largest distance at any frame, metres
  double wrinkle_kept = 0.0;           ///< sum over frames of the model's bending energy / the reference's, whole garment
  double wrinkle_kept_region = 0.0;    ///< the same over the region (NaN when the region is empty or flat)
  /// Energy of the Laplacian's error (the Laplacian is linear: the energy of
  /// model - reference) over the reference's, summed over frames: 0 when every
  /// wrinkle is reproduced where it is, 1 for a model without them, above 1
  /// for bending in the wrong places. The ratios above count a coarser
  /// model's piecewise-bilinear kinks along its face edges as bending; this
  /// does not reward them.
  double wrinkle_error = 0.0;
  double wrinkle_error_region = 0.0;   ///< the same over the region (NaN when the region is empty or flat)
  std::vector<double> energy_per_frame;            ///< the model's, whole garment, metres^2
  std::vector<double> reference_energy_per_frame;  ///< the reference's, whole garment, metres^2
  bool cancelled = false;
};

/// Compares `model` (a mesh refined from the same coarse mesh as `reference`)
/// recorded in the PC2 `model_cache` with `reference` recorded in
/// `reference_cache`, frame k against frame k. Throws ArgumentError when the
/// meshes do not share their coarse mesh (its faces' corners in order, its
/// vertices at rest), a cache's point count is not its mesh's vertex count,
/// or the caches hold different frame counts and options.max_frames does not
/// stay within both, or their headers' start frames or sample rates differ
/// (frame k would be another time in each); InputError for an unreadable cache or a frame with a
/// non-finite point. `progress` (frames done, frames) may stop it early
/// (cancelled).
ComparisonReport compare_results(const QuadMesh& model, const std::string& model_cache, const QuadMesh& reference,
                                 const std::string& reference_cache, const ComparisonOptions& options = {},
                                 const SimulationProgress& progress = {});

}  // namespace mrcloth
