#pragma once
// Building the quadtree forest of a fresh all-quad mesh, and re-deriving the
// mesh's faces and T-node flags from the forest after refinement.
#include "quad_mesh.h"

#include <functional>

namespace mrcloth {

/// Makes `mesh` refinable: one level-1 active root record per face (corners in
/// face order), mode 1 and R 0 on every vertex. Every face must be a quad;
/// throws ArgumentError naming the first face that is not. Replaces any forest.
void init_forest(QuadMesh& mesh);

/// Per active face (face order), where each of its vertices (in the face's
/// own order, as f.vertices() visits them) lies along its record's
/// boundary: k + t on edge k (corner k to corner k + 1) at fraction t, so
/// corner k is at k and a T-node at the midpoint k + 0.5.
std::vector<std::vector<double>> active_face_boundary_params(const QuadMesh& mesh);

/// The first face (in face order) whose vertex loop is not its record's
/// polygon (active_face_polygon, from any start) or whose level layer is
/// not its record's level; -1 when there is none. Each face's quad layer
/// must name a record in range, and parent pairs must not form a cycle.
int first_face_unlike_its_record(const QuadMesh& mesh);

/// Vertex loop of an active record as it appears in the mesh: its four corners
/// with every vertex lying inside its edges (hanging nodes, recursively) inserted.
std::vector<int> active_face_polygon(const QuadMesh& mesh, const QuadRecord& record);

/// Replaces all faces of `mesh` by the active records' polygons (in record
/// order), sets the level and quad face layers, and recomputes hanging flags.
/// Vertices and their indices are untouched. `progress`, if given, is
/// called with the faces added so far every `every` faces (none after the
/// last); when it returns false the rebuild stops there, false is returned
/// and the mesh (part of its faces) must be discarded.
bool rebuild_active_faces(QuadMesh& mesh, const std::function<bool(int faces_added)>& progress = {},
                          int every = 65536);

/// Recomputes the hanging flag of every vertex from the forest: a vertex is
/// hanging iff it lies strictly inside a corner-to-corner edge of an active record.
void update_hanging_nodes(QuadMesh& mesh);

/// Level at which each vertex was created (coarse = 1): the lowest level of
/// any record that has it as a corner. Element i belongs to vertex i.
std::vector<int> vertex_levels(const QuadMesh& mesh);

}  // namespace mrcloth
