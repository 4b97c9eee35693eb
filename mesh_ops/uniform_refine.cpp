#include "uniform_refine.h"

#include "errors.h"
#include "quad_refiner.h"

namespace mrcloth {

void uniform_refine(QuadMesh& mesh, int levels) {
  if (levels < 0) throw ArgumentError("uniform refinement levels must be >= 0, got " + std::to_string(levels));
  if (levels == 0) return;
  QuadRefiner refiner(mesh);
  for (int pass = 0; pass < levels; ++pass) {
    std::vector<int> active;
    const auto& forest = quadtree(mesh);
    for (std::size_t i = 0; i < forest.size(); ++i)
      if (forest[i].active) active.push_back(static_cast<int>(i));
    for (int record : active) refiner.split(record);
  }
  refiner.finish();
}

}  // namespace mrcloth
