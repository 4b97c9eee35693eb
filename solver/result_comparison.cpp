#include "result_comparison.h"

#include "point_cache.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/mode_layer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace mrcloth {
namespace {

/// Both meshes refined from one coarse garment: the same coarse faces, in
/// the same order, from the same corner, at the same place (a coarse mesh
/// re-exported with its faces reordered has the same count, and gave
/// meaningless distances).
void require_one_coarse_garment(const QuadMesh& model, const QuadMesh& reference) {
  std::vector<const QuadRecord*> model_roots, reference_roots;
  for (const QuadRecord& record : quadtree(model))
    if (record.parent < 0) model_roots.push_back(&record);
  for (const QuadRecord& record : quadtree(reference))
    if (record.parent < 0) reference_roots.push_back(&record);
  const auto corners = [](const QuadRecord& record) {
    return "(" + std::to_string(record.corners[0]) + ", " + std::to_string(record.corners[1]) + ", " +
           std::to_string(record.corners[2]) + ", " + std::to_string(record.corners[3]) + ")";
  };
  OpenMesh::Vec3d lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const auto v : reference.vertices()) {
    lo.minimize(reference.point(v));
    hi.maximize(reference.point(v));
  }
  const double tolerance = 1e-9 * (hi - lo).norm();
  for (std::size_t r = 0; r < reference_roots.size() && r < model_roots.size(); ++r) {
    if (model_roots[r]->corners != reference_roots[r]->corners)
      throw ArgumentError("coarse face " + std::to_string(r) + " has corners " + corners(*model_roots[r]) +
                          " in the model and " + corners(*reference_roots[r]) +
                          " in the reference: compared meshes must be refined from the same coarse mesh (one "
                          "re-exported with its faces reordered, or started at another corner, is another)");
    for (const int c : reference_roots[r]->corners) {
      const auto a = model.point(model.vertex_handle(static_cast<unsigned>(c)));
      const auto b = reference.point(reference.vertex_handle(static_cast<unsigned>(c)));
      if ((a - b).norm() > tolerance)
        throw ArgumentError("coarse vertex " + std::to_string(c) + " lies " + std::to_string((a - b).norm()) +
                            " m from where the reference has it: compared meshes must be refined from the same coarse "
                            "mesh, at rest (not a simulated or moved one)");
    }
  }
}

/// Refuses caches that cannot be compared frame by frame: point counts
/// other than their meshes' vertices, other timings, or other lengths
/// unless options.max_frames asks only for frames both hold.
void require_comparable_caches(const QuadMesh& model, const Pc2Reader& model_frames, const QuadMesh& reference,
                               const Pc2Reader& reference_frames, const ComparisonOptions& options) {
  const std::string& model_cache = model_frames.path();
  const std::string& reference_cache = reference_frames.path();
  if (model_frames.num_points() != static_cast<int>(model.n_vertices()))
    throw ArgumentError(model_cache + ": " + std::to_string(model_frames.num_points()) + " points, the model has " +
                        std::to_string(model.n_vertices()) + " vertices");
  if (reference_frames.num_points() != static_cast<int>(reference.n_vertices()))
    throw ArgumentError(reference_cache + ": " + std::to_string(reference_frames.num_points()) +
                        " points, the reference has " + std::to_string(reference.n_vertices()) + " vertices");
  // Frame k against frame k: the same time only if both are sampled alike
  // (a cache another tool wrote every second frame, or from frame 10, is not).
  if (model_frames.start_frame() != reference_frames.start_frame() ||
      model_frames.sample_rate() != reference_frames.sample_rate()) {
    const auto timing = [](const Pc2Reader& cache) {
      return cache.path() + " starts at frame " + number_text(cache.start_frame()) + " with a sample every " +
             number_text(cache.sample_rate()) + " frames";
    };
    throw ArgumentError(timing(model_frames) + ", " + timing(reference_frames) +
                        ": their frames are not at the same times; expected caches sampled alike (as every mrcloth run "
                        "writes them: from frame 1, every frame)");
  }
  // Caches of other lengths compare only over the frames both hold, asked for.
  const int shorter = std::min(model_frames.num_frames(), reference_frames.num_frames());
  if (model_frames.num_frames() != reference_frames.num_frames() && !(options.max_frames >= 0 && options.max_frames <= shorter))
    throw ArgumentError(model_cache + " holds " + std::to_string(model_frames.num_frames()) + " frames, " +
                        reference_cache + " " + std::to_string(reference_frames.num_frames()) +
                        "; expected the same, or maxFrames at most " + std::to_string(shorter));
}

}  // namespace

ComparisonReport compare_results(const QuadMesh& model, const std::string& model_cache, const QuadMesh& reference,
                                 const std::string& reference_cache, const ComparisonOptions& options,
                                 const SimulationProgress& progress) {
  if (count_roots(model) != count_roots(reference))
    throw ArgumentError("the model has " + std::to_string(count_roots(model)) + " coarse faces and the reference " +
                        std::to_string(count_roots(reference)) +
                        ": compared meshes must be refined from the same coarse mesh");
  require_one_coarse_garment(model, reference);
  Pc2Reader model_frames(model_cache);
  Pc2Reader reference_frames(reference_cache);
  require_comparable_caches(model, model_frames, reference, reference_frames, options);

  ComparisonReport report;
  const std::vector<MaterialPoint> points = material_points(reference);
  const MaterialEvaluator evaluator(model);
  const MaterialBinding binding = evaluator.bind(points);
  const WrinkleEnergy wrinkles(reference);
  const std::vector<int> modes = get_modes(reference);
  report.region_mode = options.region_mode >= 0 ? options.region_mode
                       : modes.empty()          ? kDefaultMode
                                                : *std::max_element(modes.begin(), modes.end());
  const std::vector<int> region = vertices_with_mode(reference, report.region_mode);
  report.points = static_cast<int>(points.size());
  report.region_points = static_cast<int>(region.size());

  const int frames = options.max_frames >= 0 ? std::min(options.max_frames, model_frames.num_frames())
                                             : model_frames.num_frames();
  double model_energy = 0.0, reference_energy = 0.0, model_region = 0.0, reference_region = 0.0;
  double error_energy = 0.0, error_region = 0.0;
  double rms_sum = 0.0, p95_sum = 0.0;
  for (int f = 0; f < frames; ++f) {
    const Eigen::MatrixX3d at_points = evaluator.evaluate(binding, model_frames.finite_frame(f));
    const Eigen::MatrixX3d truth = reference_frames.finite_frame(f);
    const DistanceStats d = point_distances(at_points, truth);
    report.per_frame.push_back(d);
    rms_sum += d.rms;
    p95_sum += d.p95;
    report.max_distance = std::max(report.max_distance, d.max);
    report.energy_per_frame.push_back(wrinkles.energy(at_points));
    report.reference_energy_per_frame.push_back(wrinkles.energy(truth));
    model_energy += report.energy_per_frame.back();
    reference_energy += report.reference_energy_per_frame.back();
    const Eigen::MatrixX3d difference = at_points - truth;
    error_energy += wrinkles.energy(difference);
    if (!region.empty()) {
      model_region += wrinkles.energy(at_points, region);
      reference_region += wrinkles.energy(truth, region);
      error_region += wrinkles.energy(difference, region);
    }
    ++report.frames;
    if (progress && !progress(report.frames, frames)) {
      report.cancelled = true;
      break;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (report.frames > 0) {
    report.mean_rms = rms_sum / report.frames;
    report.mean_p95 = p95_sum / report.frames;
  }
  // Summed over frames before dividing: a nearly flat frame cannot blow the ratio up.
  report.wrinkle_kept = reference_energy > 0.0 ? model_energy / reference_energy : nan;
  report.wrinkle_kept_region = reference_region > 0.0 ? model_region / reference_region : nan;
  report.wrinkle_error = reference_energy > 0.0 ? error_energy / reference_energy : nan;
  report.wrinkle_error_region = reference_region > 0.0 ? error_region / reference_region : nan;
  return report;
}

}  // namespace mrcloth
