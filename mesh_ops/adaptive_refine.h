#pragma once
// Algorithms 2 and 3 of the paper: refine where the deformation modes say so.
#include "quad_mesh.h"
#include "quad_refiner.h"

#include <vector>

namespace mrcloth {

struct AdaptiveRefineOptions {
  double delta = 8.0;    ///< refine a face when the sum of R over its 4 corners >= delta
  int max_level = 3;     ///< never create faces above this level (coarse = 1); >= 1
  bool balance = true;   ///< enforce 2:1 balance between neighbouring active faces
  double most_faces = kMostFaces;  ///< refuse a pass that would make more active faces (quad_refiner.h)
};

struct AdaptiveRefineReport {
  std::vector<std::size_t> faces_refined_per_pass;  ///< Algorithm 2 passes, last one refined something
  std::size_t faces_refined_for_balance = 0;        ///< extra splits made by 2:1 balance
  std::size_t hanging_nodes = 0;                    ///< vertices flagged hanging at the end
  std::size_t vertices = 0;                         ///< final vertex count
  std::size_t faces = 0;                            ///< final active face count
  std::vector<std::size_t> vertices_per_level;      ///< element L: vertices created at level L
  std::vector<std::size_t> faces_per_level;         ///< element L: active faces of level L
  double milliseconds = 0.0;                        ///< wall time of the whole refinement
};

/// Refines `mesh` in place. R starts as each vertex's mode; each pass splits
/// every face active at its start whose corners' R sum >= delta and whose level
/// is below max_level, then updates R (Algorithm 3: old vertices R -= 1, a new
/// centre gets the mean of its face's 4 corners, a new midpoint the mean of its
/// edge's 2 ends, both from the already-decremented values). Passes stop when
/// one splits nothing. Throws ArgumentError for max_level < 1, a non-finite
/// delta, or a pass that would make more than options.most_faces active
/// faces (the mesh is then partly refined: refine a copy).
AdaptiveRefineReport adaptive_refine(QuadMesh& mesh, const AdaptiveRefineOptions& options);

}  // namespace mrcloth
