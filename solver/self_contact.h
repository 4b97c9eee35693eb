#pragma once
// Cloth-cloth contact: keeps two layers of one garment `thickness` apart on
// the sides they were on, so a skirt's front panel cannot pass through its
// back panel between the legs.
//
// Each step gathers the pairs that may meet (a vertex and a triangle, two
// edges) from the boxes swept between the step's start and its dynamics'
// prediction, widened by thickness + `reach` for what the body collisions
// push later in the step; a pair is kept only if, at either end, it is
// over (or at most half an element beside) the other element and near it
// or on its other side. Its side is the sign of its separation at the
// step's start (the vertex above or below the triangle's plane; the second
// edge on one side of the first along their common normal).
//
// Every collision round projects each pair, Gauss-Seidel:
//  - still on its side and overlapping (the vertex over the triangle, the
//    closest points inside both edges): kept `thickness` apart;
//  - on the other side now: continuous collision detection finds when the
//    sign changed (bisection along the straight paths from the step's
//    start). If the pair overlapped then, the cloth passed through itself
//    and is pulled back to its side where it passed; if not, the vertex
//    went round the element (past a hem) and the pair takes the new side.
// A side is remembered into the next step while the pair overlaps at its
// start, so a crossing the rounds could not undo (the body pushed it back)
// is still undone later instead of becoming the pair's side. Each
// projection moves by at most `thickness`: pushes are velocity, and
// unbounded ones, where a body squeezes two layers together, grew until
// the cloth flew apart.
//
// The surface is every active quadtree record's two triangles (corners
// only: a T-node lies exactly on its coarse edge). Pairs whose elements
// share a vertex, or a T-node's parent, are never in contact, nor pairs
// joined at rest within the sheet's neighbourhood (`neighbourhood`): on a
// refined garment, elements a few edges apart across a wrinkle were held
// apart as if they were two layers, and the cloth tore (the trousers
// refined once on CMU 07_06: 1207 % and 23,950 crossings; with the
// neighbourhood left out 53 % and 485, against 33 % and 1591 without any
// cloth-cloth contact). Projection
// acts on the free coordinates, mass-weighted, through the stencils, so
// T-nodes stay exact and pinned vertices do not move.
#include "dynamics_model.h"
#include "worker_pool.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace mrcloth {

struct SelfContactOptions {
  double thickness = 0.0;  ///< metres kept between two layers of the cloth; 0: no cloth-cloth contact
  double reach = 0.01;     ///< metres beyond the thickness around each step's motion where pairs are gathered
  int passes = 1;          ///< Gauss-Seidel passes over the gathered pairs per collision round, >= 1
  /// Metres: two points of the cloth joined, at rest, by a path of edges
  /// that stays this close to the first are one stretch of sheet, never
  /// in contact (a fold needs more cloth than that between its layers);
  /// < 0: twice thickness + reach (26 mm at 3 mm; see sheet_neighbourhood);
  /// 0: only elements that share a vertex are left out.
  double neighbourhood = -1.0;
};

/// The neighbourhood `options` asks for, metres (its default resolved).
double sheet_neighbourhood(const SelfContactOptions& options);

/// The garment's contact surface: triangles and edges of corner vertices,
/// and which pairs of them may touch.
struct ContactSurface {
  std::vector<std::array<int, 3>> triangles;  ///< full vertex ids
  std::vector<std::array<int, 2>> edges;      ///< every triangle edge once, full vertex ids
  /// Per full vertex: the sorted full ids of the free or pinned vertices its
  /// position depends on (itself, or a T-node's ancestors).
  std::vector<std::vector<int>> support;
  /// Per edge: the sorted union of its two ends' supports.
  std::vector<std::vector<int>> edge_support;
};

/// Per full vertex v of `model`, the sorted supports of every vertex the
/// surface's edges join to v at rest without leaving the ball of radius
/// `radius` metres around v (v's own support included; empty where v's is).
std::vector<std::vector<int>> sheet_supports(const DynamicsModel& model, const ContactSurface& surface,
                                             double radius);

/// The active records' triangles of a model (a record with corners c0..c3
/// gives (c0, c1, c2) and (c0, c2, c3)), with their edges and supports.
ContactSurface contact_surface(const DynamicsModel& model);

/// Edge-triangle crossings of the surface with itself at full positions x
/// (#V x 3): pairs of an edge and a triangle with no support in common
/// where the edge passes through the triangle's interior. 0 for a cloth
/// that does not pass through itself. `pool`, if given, counts the edges in
/// parts (the same count).
int count_self_crossings(const ContactSurface& surface, const Positions& x, WorkerPool* pool = nullptr);

class SelfContact {
 public:
  /// Builds the surface of `model` (kept by reference: it must outlive this).
  /// Throws ArgumentError for a negative thickness or reach or passes < 1.
  void precompute(const DynamicsModel& model, const SelfContactOptions& options);
  bool enabled() const { return model_ != nullptr && options_.thickness > 0.0; }

  /// Gathers the step's pairs from the full positions at its start (x0) and
  /// after its dynamics (x1), both #V x 3, and fixes each pair's side.
  void gather(const Positions& x0, const Positions& x1);

  /// Moves free positions q (#free x 3) so every gathered pair that
  /// overlaps is `thickness` apart on its side; `pinned_part` is P p
  /// (#V x 3). Returns the largest single correction, metres.
  double project(Positions& q, const Positions& pinned_part);

  const ContactSurface& surface() const { return surface_; }

 private:
  struct Pair {
    std::uint64_t key;  // kind in the top bit, then the two element ids
    signed char side;   // +1 / -1: the sign of the separation to keep
    signed char raw;    // the sign of the separation at the step's start
  };
  const DynamicsModel* model_ = nullptr;
  SelfContactOptions options_;
  ContactSurface surface_;
  std::vector<std::vector<int>> near_support_;  // per full vertex: sheet_supports
  double cell_ = 0.0;              // broad-phase cell size, metres
  std::vector<Pair> pairs_;        // this step's, sorted by key
  std::vector<Pair> memory_;       // last step's pairs, sorted by key
  Positions start_;                // full positions at the step's start
};

}  // namespace mrcloth
