#include "adaptive_refine.h"

#include "balance_2to1.h"
#include "errors.h"
#include "quad_refiner.h"

#include <chrono>
#include <cmath>

namespace mrcloth {
namespace {

// Step 5-7 of Algorithm 2: the faces active now whose corners' R sum reaches delta.
std::vector<int> faces_to_split(const QuadMesh& mesh, const Layers& l, const AdaptiveRefineOptions& o) {
  std::vector<int> selected;
  const auto& forest = mesh.property(l.quadtree);
  for (std::size_t i = 0; i < forest.size(); ++i) {
    const QuadRecord& q = forest[i];
    if (!q.active || q.level >= o.max_level) continue;
    double sum = 0.0;
    for (int c : q.corners) sum += mesh.property(l.r_value, mesh.vertex_handle(c));
    if (sum >= o.delta) selected.push_back(static_cast<int>(i));
  }
  return selected;
}

/// The faces active now (the mesh's own are stale until the refiner finishes).
std::size_t active_faces(const QuadMesh& mesh) {
  std::size_t count = 0;
  for (const QuadRecord& record : quadtree(mesh)) count += record.active ? 1 : 0;
  return count;
}

}  // namespace

AdaptiveRefineReport adaptive_refine(QuadMesh& mesh, const AdaptiveRefineOptions& options) {
  if (options.max_level < 1)
    throw ArgumentError("maxLevel must be >= 1 (coarse faces have level 1), got " +
                        std::to_string(options.max_level));
  if (!std::isfinite(options.delta))
    throw ArgumentError("delta must be a finite number");
  const auto start = std::chrono::steady_clock::now();
  const Layers l = get_layers(mesh);
  AdaptiveRefineReport report;

  for (auto v : mesh.vertices()) mesh.property(l.r_value, v) = mesh.property(l.mode, v);
  QuadRefiner refiner(mesh);
  for (;;) {
    const std::vector<int> selected = faces_to_split(mesh, l, options);
    if (selected.empty()) break;
    // A split turns one active face into four: refuse the pass that would
    // pass the bound, before its memory is taken (maxLevel 1e9 was accepted).
    const double faces = static_cast<double>(active_faces(mesh)) + 3.0 * static_cast<double>(selected.size());
    if (faces > options.most_faces)
      throw ArgumentError("adaptive refinement to maxLevel " + std::to_string(options.max_level) + " would make more than " +
                          std::to_string(static_cast<long long>(options.most_faces)) + " faces (pass " +
                          std::to_string(report.faces_refined_per_pass.size() + 1) + " splits " +
                          std::to_string(selected.size()) + " of them); expected a lower maxLevel or a higher delta");
    // Algorithm 3 in the order of the paper's pseudo-code: old vertices lose
    // one first, then the splits give new vertices the mean of their fathers'
    // (already decremented) R. The decisions above used the pre-pass values.
    for (auto v : mesh.vertices()) mesh.property(l.r_value, v) -= 1.0;
    for (int record : selected) refiner.split(record);
    report.faces_refined_per_pass.push_back(selected.size());
  }
  if (options.balance) report.faces_refined_for_balance = balance_2to1(mesh, refiner);
  refiner.finish();

  report.hanging_nodes = count_hanging(mesh);
  report.vertices = mesh.n_vertices();
  report.faces = mesh.n_faces();
  report.vertices_per_level = vertices_per_level(mesh);
  report.faces_per_level = faces_per_level(mesh);
  report.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace mrcloth
