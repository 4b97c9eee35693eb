#include "mode_layer.h"

#include "errors.h"

#include <cmath>

namespace mrcloth {
void check_mode(int mode) {
  if (mode < 0 || mode > kLargestMode)
    throw ArgumentError("mode must be from 0 to " + std::to_string(kLargestMode) + ", got " + std::to_string(mode));
}

std::vector<int> get_modes(const QuadMesh& mesh) {
  const auto mode = get_layers(mesh).mode;
  std::vector<int> modes(mesh.n_vertices());
  for (auto v : mesh.vertices()) modes[v.idx()] = mesh.property(mode, v);
  return modes;
}

void set_modes(QuadMesh& mesh, const std::vector<int>& vertex_ids, int mode) {
  check_mode(mode);
  const auto layer = get_layers(mesh).mode;
  const int n = static_cast<int>(mesh.n_vertices());
  for (std::size_t i = 0; i < vertex_ids.size(); ++i)
    if (vertex_ids[i] < 0 || vertex_ids[i] >= n)
      throw ArgumentError("vertex id " + std::to_string(vertex_ids[i]) + " (entry " + std::to_string(i) +
                          ") is out of range; the mesh has " + std::to_string(n) + " vertices");
  for (int id : vertex_ids) mesh.property(layer, mesh.vertex_handle(id)) = mode;
}

std::size_t paint_modes_sphere(QuadMesh& mesh, const OpenMesh::Vec3d& center, double radius, int mode) {
  check_mode(mode);
  if (!(radius >= 0.0) || !std::isfinite(radius))
    throw ArgumentError("brush radius must be a finite number >= 0 metres (got " + std::to_string(radius) + ")");
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(center[k])) throw ArgumentError("brush centre must be finite");
  const auto layer = get_layers(mesh).mode;
  std::size_t painted = 0;
  for (auto v : mesh.vertices()) {
    if ((mesh.point(v) - center).sqrnorm() > radius * radius) continue;
    mesh.property(layer, v) = mode;
    ++painted;
  }
  return painted;
}

}  // namespace mrcloth
