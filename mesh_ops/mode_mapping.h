#pragma once
// Deformation modes from a refined mesh onto its coarse mesh (paper section
// 4.4; SPEC stage 5). Refinement keeps vertex indices stable, so the
// paper's rule is that coarse vertex i takes the mode of refined vertex i.
// A coarse vertex stands for a whole patch of the refined mesh, though, and
// the options look at that patch: its cell, the refined vertices inside the
// quarter of each coarse face around it that holds it as a corner (on a
// regular grid, the dual cell: a square one coarse edge across).
#include "quad_mesh.h"

#include <string>
#include <vector>

namespace mrcloth {

enum class ModeMapping {
  stable_index,    ///< the paper's rule: the mode of the refined vertex with the same index
  cell_highest,    ///< the highest mode in the vertex's cell (refines wherever any wrinkle was)
  cell_frequent,   ///< the most frequent mode in its cell (ties: the higher)
};

/// "index" / "highest" / "frequent".
std::string mode_mapping_name(ModeMapping mapping);
/// Inverse of mode_mapping_name; ArgumentError naming the known ones.
ModeMapping mode_mapping_from_name(const std::string& name);

struct ModeMapReport {
  std::vector<int> modes;        ///< per coarse vertex, the mapped mode
  std::vector<int> cell_sizes;   ///< per coarse vertex, refined vertices in its cell (itself included)
  int agree_highest = 0;         ///< coarse vertices where the stable-index mode equals the cell's highest
  int agree_frequent = 0;        ///< ... equals the cell's most frequent
  int changed = 0;               ///< coarse vertices whose mode layer changed
};

/// The refined vertices of each coarse vertex's cell (indexed by coarse
/// vertex; each sorted, the vertex itself included), from `refined`'s
/// quadtree forest.
std::vector<std::vector<int>> coarse_vertex_cells(const QuadMesh& refined, int coarse_vertices);

/// Writes the modes of `refined` onto `coarse`'s mode layer by `mapping`
/// and reports how the rules agree. `refined` must be a refinement of
/// `coarse` (same coarse faces on the same vertex indices, those vertices
/// at the same rest positions to 1e-9 m): ArgumentError naming the first
/// difference otherwise.
ModeMapReport map_modes(const QuadMesh& refined, QuadMesh& coarse, ModeMapping mapping);

}  // namespace mrcloth
