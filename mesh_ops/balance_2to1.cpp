#include "balance_2to1.h"

namespace mrcloth {
namespace {

// An active face of level L must split when a neighbour across one of its
// edges is at level L+2 or finer: that neighbour has split the halves of the
// edge, so a midpoint of a half-edge exists. Only the neighbour can have made
// it, because the face itself is unsplit.
bool has_too_fine_neighbour(const QuadRecord& q, const QuadRefiner& refiner) {
  for (int k = 0; k < 4; ++k) {
    const int a = q.corners[k];
    const int b = q.corners[(k + 1) % 4];
    const int m = refiner.midpoint(a, b);
    if (m >= 0 && (refiner.midpoint(a, m) >= 0 || refiner.midpoint(m, b) >= 0)) return true;
  }
  return false;
}

}  // namespace

std::size_t balance_2to1(QuadMesh& mesh, QuadRefiner& refiner) {
  std::size_t splits = 0;
  bool changed = true;
  // Sweeps until stable; records appended during a sweep are visited in the
  // same sweep, and a split can only unbalance coarser faces, so this ends.
  while (changed) {
    changed = false;
    for (std::size_t i = 0; i < quadtree(mesh).size(); ++i) {
      const QuadRecord q = quadtree(mesh)[i];
      if (!q.active || !has_too_fine_neighbour(q, refiner)) continue;
      refiner.split(static_cast<int>(i));
      ++splits;
      changed = true;
    }
  }
  return splits;
}

}  // namespace mrcloth
