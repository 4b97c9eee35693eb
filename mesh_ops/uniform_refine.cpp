#include "uniform_refine.h"

#include "errors.h"
#include "quad_refiner.h"

namespace mrcloth {

void uniform_refine(QuadMesh& mesh, int levels) {
  if (levels < 0) throw ArgumentError("uniform refinement levels must be >= 0, got " + std::to_string(levels));
  if (levels == 0) return;
  // Each level makes four faces of one: refuse what memory cannot hold
  // before spending minutes on it.
  double faces = static_cast<double>(mesh.n_faces());
  for (int level = 0; level < levels && faces <= kMostFaces; ++level) faces *= 4.0;
  if (faces > kMostFaces)
    throw ArgumentError("uniform refinement by " + std::to_string(levels) + " levels would make more than " +
                        std::to_string(static_cast<long long>(kMostFaces)) + " faces from " +
                        std::to_string(mesh.n_faces()) + "; expected fewer levels (each makes four faces of one)");
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
