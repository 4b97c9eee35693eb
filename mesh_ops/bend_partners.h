#pragma once
// Bend partners: the paper's "interleaved neighbours", vertices two grid steps
// apart, reached by a bend spring. Both the dynamics (bend springs) and the
// curvature analysis (section 4.2) use exactly these pairs.
//
// Definition, on the quadtree records (active or not) of a refinable mesh:
//  - Grid-line pairs: for two records of the same level that share a whole
//    corner-to-corner edge (p, q), at least one of them active, with
//    F = (p, q, r, s) and G = (q, p, t, u) in their own corner order (so s
//    and t are p's neighbours off the shared edge, r and u are q's), the
//    pairs (s, t) through p and (r, u) through q. On a regular grid these are
//    the vertices two steps away along the grid lines. Where an active face
//    borders a refined one of its own level, the refined record still counts,
//    so the coarse face keeps its bending across the level interface.
//  - Diagonal pairs: at a vertex p that is a corner of exactly four records of
//    one level, forming a closed fan (p interior to them, each sharing an edge
//    with the next), at least one of the four active: the corners opposite p
//    in the two diagonally opposite records, for both diagonals.
//  - Boundaries: a grid-line pair needs both records, so a pair never
//    crosses the boundary; along a boundary edge line, pairs exist as on the
//    interior. A boundary vertex has no diagonal pairs through it.
//  - Irregular vertices (not four records around): grid-line pairs still
//    come from every edge-sharing record pair (so a valence-3 or 5 vertex
//    bends across each of its edges); diagonal pairs do not exist there.
//  - Hanging vertices take part like any corner of the finer records.
// A pair is listed once (i < j) even when several record pairs give it; its
// `via` vertex and level are those of the first record pair in forest order.
// On an n x m regular grid an interior vertex two steps from every boundary
// has exactly 8 partners.
#include "quad_mesh.h"

#include <vector>

namespace mrcloth {

struct BendPair {
  int i = -1;       ///< vertex, i < j
  int j = -1;       ///< vertex two steps from i
  int via = -1;     ///< the vertex between them (the shared corner)
  int level = 1;    ///< level of the records that define the pair
  bool diagonal = false;  ///< true for a diagonal pair, false along a grid line
};

/// Every bend pair of the mesh, sorted by (i, j).
std::vector<BendPair> bend_pairs(const QuadMesh& mesh);

/// Bend partners of every vertex (indexed by vertex; each list sorted), from bend_pairs.
std::vector<std::vector<int>> bend_partners(const QuadMesh& mesh);

}  // namespace mrcloth
