#include "uniform_refine.h"

#include "errors.h"
#include "quad_refiner.h"

namespace mrcloth {

double uniform_refine_steps(const QuadMesh& mesh, int levels) {
  if (levels <= 0) return 0.0;
  double active = 0.0, splits = 0.0;
  for (const QuadRecord& record : quadtree(mesh)) active += record.active ? 1.0 : 0.0;
  for (int level = 0; level < levels && splits <= kMostFaces; ++level, active *= 4.0) splits += active;
  return splits + active;
}

bool uniform_refine(QuadMesh& mesh, int levels, const RefineProgress& progress) {
  if (levels < 0) throw ArgumentError("uniform refinement levels must be >= 0, got " + std::to_string(levels));
  if (levels == 0) return true;
  // Each level makes four faces of one: refuse what memory cannot hold
  // before spending minutes on it.
  double faces = static_cast<double>(mesh.n_faces());
  for (int level = 0; level < levels && faces <= kMostFaces; ++level) faces *= 4.0;
  if (faces > kMostFaces)
    throw ArgumentError("uniform refinement by " + std::to_string(levels) + " levels would make more than " +
                        std::to_string(static_cast<long long>(kMostFaces)) + " faces from " +
                        std::to_string(mesh.n_faces()) + "; expected fewer levels (each makes four faces of one)");
  QuadRefiner refiner(mesh);
  // Each split makes four active faces of one, so the steps are known from
  // the first level's (below 2 kMostFaces: an int).
  const int total = static_cast<int>(uniform_refine_steps(mesh, levels));
  int done = 0;
  for (int pass = 0; pass < levels; ++pass) {
    std::vector<int> active;
    const auto& forest = quadtree(mesh);
    for (std::size_t i = 0; i < forest.size(); ++i)
      if (forest[i].active) active.push_back(static_cast<int>(i));
    for (std::size_t k = 0; k < active.size(); ++k) {
      refiner.split(active[k]);
      ++done;
      if (progress && k + 1 < active.size() && (k + 1) % kRefineProgressSteps == 0 && !progress(done, total))
        return false;
    }
    if (progress && !progress(done, total)) return false;
  }
  const int splits = done;
  if (!progress) return refiner.finish();
  return refiner.finish([&](int added) { return progress(splits + added, total); }) && progress(total, total);
}

}  // namespace mrcloth
