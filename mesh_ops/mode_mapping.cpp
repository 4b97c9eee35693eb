#include "mode_mapping.h"

#include "errors.h"
#include "mode_layer.h"
#include "mode_painting.h"

#include <algorithm>
#include <map>

namespace mrcloth {
namespace {

constexpr double kSamePosition = 1e-9;  ///< metres: a coarse vertex and its refined twin at rest

/// The roots (coarse faces) of a forest, in forest order.
std::vector<const QuadRecord*> roots_of(const std::vector<QuadRecord>& forest) {
  std::vector<const QuadRecord*> roots;
  for (const QuadRecord& record : forest)
    if (record.parent < 0) roots.push_back(&record);
  return roots;
}

void check_refinement_of(const QuadMesh& refined, const QuadMesh& coarse) {
  if (refined.n_vertices() < coarse.n_vertices()) {
    throw ArgumentError("the refined mesh has " + std::to_string(refined.n_vertices()) +
                        " vertices, fewer than the coarse mesh's " + std::to_string(coarse.n_vertices()) +
                        "; expected a refinement of the coarse mesh");
  }
  const std::vector<const QuadRecord*> fine_roots = roots_of(quadtree(refined));
  const std::vector<const QuadRecord*> coarse_roots = roots_of(quadtree(coarse));
  if (fine_roots.size() != coarse_roots.size()) {
    throw ArgumentError("the refined mesh has " + std::to_string(fine_roots.size()) +
                        " coarse faces, the coarse mesh " + std::to_string(coarse_roots.size()) +
                        "; expected a refinement of the coarse mesh");
  }
  for (std::size_t f = 0; f < fine_roots.size(); ++f) {
    if (fine_roots[f]->corners != coarse_roots[f]->corners)
      throw ArgumentError("coarse face " + std::to_string(f) +
                          " has other corners in the refined mesh; expected a refinement of the coarse mesh");
  }
  for (const auto v : coarse.vertices()) {
    const double gap = (coarse.point(v) - refined.point(refined.vertex_handle(static_cast<unsigned>(v.idx())))).norm();
    if (!(gap <= kSamePosition)) {
      throw ArgumentError("coarse vertex " + std::to_string(v.idx()) + " lies " + std::to_string(gap) +
                          " m from refined vertex " + std::to_string(v.idx()) +
                          "; expected the refined mesh at rest, refined from this coarse mesh");
    }
  }
}

}  // namespace

std::string mode_mapping_name(ModeMapping mapping) {
  switch (mapping) {
    case ModeMapping::stable_index: return "index";
    case ModeMapping::cell_highest: return "highest";
    case ModeMapping::cell_frequent: return "frequent";
  }
  return "index";
}

ModeMapping mode_mapping_from_name(const std::string& name) {
  for (const ModeMapping m : {ModeMapping::stable_index, ModeMapping::cell_highest, ModeMapping::cell_frequent})
    if (mode_mapping_name(m) == name) return m;
  throw ArgumentError("unknown mode mapping '" + name + "'; expected index, highest or frequent");
}

std::vector<std::vector<int>> coarse_vertex_cells(const QuadMesh& refined, int coarse_vertices) {
  const std::vector<QuadRecord>& forest = quadtree(refined);
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(coarse_vertices));
  for (int v = 0; v < coarse_vertices; ++v) cells[static_cast<std::size_t>(v)].push_back(v);
  std::vector<int> stack;
  for (const QuadRecord& root : forest) {
    if (root.parent >= 0) continue;
    for (std::size_t k = 0; k < 4; ++k) {
      const int corner = root.corners[k];
      if (corner < 0 || corner >= coarse_vertices) continue;
      // Child k holds corner k: its whole subtree is the quarter of this
      // coarse face nearest the corner.
      std::vector<int>& cell = cells[static_cast<std::size_t>(corner)];
      stack.clear();
      if (root.children[k] >= 0) stack.push_back(root.children[k]);
      while (!stack.empty()) {
        const QuadRecord& record = forest[static_cast<std::size_t>(stack.back())];
        stack.pop_back();
        for (const int c : record.corners) cell.push_back(c);
        for (const int child : record.children)
          if (child >= 0) stack.push_back(child);
      }
    }
  }
  for (std::vector<int>& cell : cells) {
    std::sort(cell.begin(), cell.end());
    cell.erase(std::unique(cell.begin(), cell.end()), cell.end());
  }
  return cells;
}

ModeMapReport map_modes(const QuadMesh& refined, QuadMesh& coarse, ModeMapping mapping) {
  check_refinement_of(refined, coarse);
  const int n = static_cast<int>(coarse.n_vertices());
  const std::vector<int> fine_modes = get_modes(refined);
  const std::vector<int> before = get_modes(coarse);
  const std::vector<std::vector<int>> cells = coarse_vertex_cells(refined, n);

  ModeMapReport report;
  report.modes.resize(static_cast<std::size_t>(n));
  report.cell_sizes.resize(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    const std::vector<int>& cell = cells[static_cast<std::size_t>(v)];
    std::map<int, int> counts;  // ordered: the ties go to the higher mode below
    int highest = 0;
    for (const int u : cell) {
      const int mode = fine_modes[static_cast<std::size_t>(u)];
      ++counts[mode];
      highest = std::max(highest, mode);
    }
    int frequent = 0, best = 0;
    for (const auto& [mode, count] : counts)
      if (count >= best) {
        best = count;
        frequent = mode;
      }
    const int own = fine_modes[static_cast<std::size_t>(v)];
    report.agree_highest += own == highest;
    report.agree_frequent += own == frequent;
    report.cell_sizes[static_cast<std::size_t>(v)] = static_cast<int>(cell.size());
    report.modes[static_cast<std::size_t>(v)] =
        mapping == ModeMapping::stable_index ? own : mapping == ModeMapping::cell_highest ? highest : frequent;
  }
  const Layers layers = ensure_layers(coarse);
  for (const auto v : coarse.vertices()) {
    const int mode = report.modes[static_cast<std::size_t>(v.idx())];
    report.changed += before[static_cast<std::size_t>(v.idx())] != mode;
    coarse.property(layers.mode, v) = mode;
  }
  // The mapped modes are the coarse mesh's computed ones: a brush stroke
  // painted on it afterwards is erased back to them (not to the default).
  set_computed_layer(coarse, report.modes);
  return report;
}

}  // namespace mrcloth
