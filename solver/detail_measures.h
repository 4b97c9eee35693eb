#pragma once
// Measures of detail: how close a multi-resolution (or low-resolution) result
// is to the high-resolution one. The paper compares them by eye; these turn
// the comparison into numbers (SPEC, "measures of detail").
//
// Every mesh compared here is refined, uniformly or adaptively, from the SAME
// coarse quad mesh, so a point of the cloth has a name that does not depend on
// the resolution: its *material coordinates* (root, u, v).
//  - root: index of the coarse face = the root record of its quadtree
//    (records 0 .. count_roots(mesh)-1 are the coarse faces).
//  - (u, v) in [0,1]^2: the coarse face's bilinear parameterisation, with the
//    face's corners (QuadRecord::corners, face orientation) at
//      corner 0 -> (0,0), corner 1 -> (1,0), corner 2 -> (1,1), corner 3 -> (0,1),
//    so u runs along corner0->corner1 and v along corner0->corner3.
// Splitting a record keeps this orientation in every child (child k holds the
// parent's corner k, see quad_refiner.cpp), so a record of level L covers a
// dyadic square of side 2^(1-L) and every vertex sits at dyadic (u, v): the
// coordinates are exact in double precision, never recovered from positions.
//
// Comparing two results = evaluating both at the same material points (the
// high-resolution mesh's vertices) and measuring the distances, or the bending
// energy of the evaluated surfaces.
#include "point_cache.h"

#include "mesh_ops/quad_mesh.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace mrcloth {

/// A point of the cloth independent of resolution (see the file comment).
struct MaterialPoint {
  int root = -1;   ///< coarse face index, 0 <= root < count_roots(mesh)
  double u = 0.0;  ///< along coarse corner 0 -> corner 1, in [0, 1]
  double v = 0.0;  ///< along coarse corner 0 -> corner 3, in [0, 1]
};

/// Material coordinates of every vertex of a refinable mesh, element i for
/// vertex i, computed exactly from the quadtree. A vertex on the boundary of
/// several coarse faces takes the coordinates in the coarse face of lowest
/// index, so the answer is the same for every mesh refined from one coarse
/// mesh. Throws ArgumentError for a mesh without a forest, or naming a vertex
/// that is no corner of any quad record (an isolated vertex has no material
/// position).
std::vector<MaterialPoint> material_points(const QuadMesh& mesh);

/// Where each material point falls in one refined mesh: the active leaf's
/// four corners and their bilinear weights. Built once per (mesh, points) by
/// MaterialEvaluator::bind, then reused for every frame.
struct MaterialBinding {
  int num_vertices = 0;                        ///< vertex count of the mesh bound to
  std::vector<int> leaf;                       ///< per point: the active quad record containing it
  std::vector<std::array<int, 4>> corners;     ///< per point: the leaf's corner vertices
  std::vector<std::array<double, 4>> weights;  ///< per point: bilinear weights of those corners, sum 1
  std::size_t size() const { return leaf.size(); }
};

/// Evaluates the surface of one refined mesh, in any of its frames, at
/// material points. The surface is the union of the active quads, each
/// bilinear in its corners; on a conforming mesh, or one whose hanging
/// vertices sit at the midpoints of their edges, it is continuous, so a point
/// on an edge between leaves gets the same value from either side.
class MaterialEvaluator {
 public:
  /// Keeps the forest of `mesh` (copied: the mesh may go away). Throws
  /// ArgumentError for a mesh without a forest or with an empty one.
  explicit MaterialEvaluator(const QuadMesh& mesh);

  /// Locates every point: descends the tree of its root to the active leaf
  /// containing (u, v) (a point on a split line goes to the upper/right
  /// child) and stores the leaf's bilinear weights at the local parameters.
  /// Throws ArgumentError naming the point for a root out of range or u, v
  /// outside [0, 1] or non-finite.
  MaterialBinding bind(const std::vector<MaterialPoint>& points) const;

  /// Per-frame step: row k = sum of the bound corners' positions times their
  /// weights. positions: this mesh's vertex positions of one frame,
  /// n_vertices x 3, metres. Returns binding.size() x 3, metres. Throws
  /// ArgumentError when the row count is not this mesh's vertex count or the
  /// binding belongs to a mesh with another vertex count.
  Eigen::MatrixX3d evaluate(const MaterialBinding& binding, const FramePositions& positions) const;

  /// bind + evaluate, for a single frame.
  Eigen::MatrixX3d evaluate(const std::vector<MaterialPoint>& points, const FramePositions& positions) const;

  int num_vertices() const { return num_vertices_; }
  int num_roots() const { return num_roots_; }

 private:
  std::vector<QuadRecord> forest_;
  int num_vertices_ = 0;
  int num_roots_ = 0;
};

/// Vertex positions of a mesh as a frame (n_vertices x 3, metres): the rest
/// frame, or the frame a caller has just written into the mesh.
FramePositions mesh_positions(const QuadMesh& mesh);

/// Summary of row-wise Euclidean distances, metres.
struct DistanceStats {
  double rms = 0.0;  ///< sqrt(mean of squared distances)
  double p95 = 0.0;  ///< nearest-rank 95th percentile: the ceil(0.95 n)-th smallest distance
  double max = 0.0;  ///< largest distance
};

/// Distances between row i of a and row i of b (both n x 3, metres, n >= 1).
/// The nearest-rank percentile is always one of the distances (no
/// interpolation), so it is exact and reproducible. Throws ArgumentError for
/// different row counts, no rows, or a non-finite coordinate (naming the row).
DistanceStats point_distances(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b);

/// Bending ("wrinkle") energy on the high-resolution material grid: with the
/// umbrella Laplacian on the mesh graph,
///   L_i = sum over edge neighbours j of x_j  -  deg(i) x_i,
/// energy = sum over a vertex subset of |L_i|^2 (metres^2). On a uniformly
/// refined mesh every interior vertex has 4 edge neighbours (except at
/// extraordinary coarse vertices), and L_i is then the second difference of
/// the grid, zero on any affine image of a flat regular grid: only bending
/// counts. Boundary vertices (3 or 2 neighbours) are left out by default
/// because their Laplacian measures the boundary's shape, not wrinkles.
class WrinkleEnergy {
 public:
  /// Keeps the edge graph of `mesh` (meant for the high-resolution, uniformly
  /// refined mesh; any polygon mesh works, the Laplacian is then the graph's).
  explicit WrinkleEnergy(const QuadMesh& mesh);

  /// Energy of one frame. positions: n_vertices x 3, metres (the mesh's own
  /// frame, or another model evaluated at this mesh's material points).
  /// vertices: the subset summed, each index in [0, n_vertices); empty = all
  /// interior vertices. An explicit subset is summed as given (boundary
  /// vertices included if listed). Returns metres^2. Throws ArgumentError for
  /// a wrong row count or an index out of range (naming it).
  double energy(const Eigen::MatrixX3d& positions, const std::vector<int>& vertices = {}) const;

  /// Share of the reference's bending kept by a model over the same subset:
  /// energy(model) / energy(reference); model and reference are both
  /// n_vertices x 3 on this mesh's vertices (metres). Returns NaN when the
  /// reference energy is exactly 0 (nothing to keep: a flat frame), so a
  /// per-frame loop can skip it instead of stopping. A flat frame with
  /// rounding noise gives a tiny, meaningless denominator: for a garment,
  /// prefer summing energies over frames before dividing.
  double ratio(const Eigen::MatrixX3d& model, const Eigen::MatrixX3d& reference,
               const std::vector<int>& vertices = {}) const;

  const std::vector<int>& interior_vertices() const { return interior_; }
  int num_vertices() const { return static_cast<int>(offsets_.size()) - 1; }

 private:
  std::vector<int> offsets_;     ///< CSR: neighbours of i are neighbours_[offsets_[i] .. offsets_[i+1])
  std::vector<int> neighbours_;
  std::vector<int> interior_;    ///< vertices not on a boundary and not isolated, ascending
};

/// Vertices whose mode (layer mrcloth:mode) equals `mode`, ascending: "the
/// top-mode region" for mode = the highest mode. With interior_only, boundary
/// vertices are left out (what WrinkleEnergy::energy should sum for wrinkles).
/// Throws ArgumentError for a mesh without the mode layer.
std::vector<int> vertices_with_mode(const QuadMesh& mesh, int mode, bool interior_only = true);

}  // namespace mrcloth
