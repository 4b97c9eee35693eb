#include "plugin/render/scene.h"

namespace mrcloth::render {

void BoundingBox::add(const Eigen::Vector3d& p) {
  if (!p.allFinite()) return;
  min = min.cwiseMin(p);
  max = max.cwiseMax(p);
}

BoundingBox bounds(const Surface& surface) {
  BoundingBox box;
  const auto rows = static_cast<int>(surface.positions.rows());
  for (const auto& face : surface.faces)
    for (int v : face)
      if (v >= 0 && v < rows) box.add(surface.positions.row(v).transpose());
  return box;
}

BoundingBox bounds(const Scene& scene) {
  BoundingBox box;
  for (const auto& surface : scene.surfaces) {
    const BoundingBox b = bounds(surface);
    if (b.empty()) continue;
    box.add(b.min);
    box.add(b.max);
  }
  return box;
}

}  // namespace mrcloth::render
