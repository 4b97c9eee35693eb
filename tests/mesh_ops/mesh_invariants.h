#pragma once
// Invariant checks shared by the refinement tests. Each returns a list of
// violations (empty when the invariant holds) so a failing test says which
// element broke it.
#include "mesh_ops/quad_mesh.h"

#include <string>
#include <vector>

namespace mrcloth::test {

/// Faces are exactly the active records' polygons (cyclically), with matching
/// level and quad layers; no vertex is isolated.
std::vector<std::string> face_forest_violations(const QuadMesh& mesh);

/// Hanging vertices that are not bitwise at their parents' midpoint, or have invalid parents.
std::vector<std::string> hanging_midpoint_violations(const QuadMesh& mesh);

/// Largest level difference between two active faces sharing a mesh edge.
int max_neighbour_level_difference(const QuadMesh& mesh);

/// Brute force over all pairs of active records, by geometry only: two are
/// neighbours when a corner-to-corner edge of one overlaps one of the other's
/// in more than a point. Returns the largest level difference. O(F^2).
int brute_force_max_level_difference(const QuadMesh& mesh);

/// V - E + F of the mesh.
int euler_characteristic(const QuadMesh& mesh);

}  // namespace mrcloth::test
