#pragma once
// Boundary loops of a garment (waist, hems, cuffs), for pinning by name.
#include "quad_mesh.h"

#include <string>
#include <vector>

namespace mrcloth {

/// Every boundary loop of the active surface as vertex indices in boundary
/// order, sorted by decreasing mean height (y), so loop 0 is the highest.
std::vector<std::vector<int>> boundary_loops(const QuadMesh& mesh);

/// Vertices of a loop named "top" (highest mean y), "bottom" (lowest), or
/// "loop:N" (N-th of boundary_loops). Throws ArgumentError naming the name
/// and the mesh's loop count when there is no such loop.
std::vector<int> boundary_loop_by_name(const QuadMesh& mesh, const std::string& name);

}  // namespace mrcloth
