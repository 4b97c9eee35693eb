#pragma once
// Reading and painting the per-vertex deformation-mode layer.
#include "quad_mesh.h"

#include <vector>

namespace mrcloth {

/// The largest mode a vertex may take: k-means makes a handful, and lists
/// per mode (objectInfo's verticesPerMode) are as long as the largest.
constexpr int kLargestMode = 1000;

/// Throws ArgumentError for a mode outside 0..kLargestMode.
void check_mode(int mode);

/// Mode of every vertex, indexed by vertex.
std::vector<int> get_modes(const QuadMesh& mesh);

/// Sets `mode` on the given vertices. Throws ArgumentError naming the first
/// index outside [0, n_vertices) or a mode outside 0..kLargestMode; nothing changes then.
void set_modes(QuadMesh& mesh, const std::vector<int>& vertex_ids, int mode);

/// Sets `mode` on every vertex within `radius` metres of `center` (inclusive).
/// Returns the number of vertices painted. Throws ArgumentError for a negative
/// or non-finite radius or a mode outside 0..kLargestMode.
std::size_t paint_modes_sphere(QuadMesh& mesh, const OpenMesh::Vec3d& center, double radius, int mode);

}  // namespace mrcloth
