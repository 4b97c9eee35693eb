#pragma once
// The multi-resolution mass-spring system of paper section 6, built once from
// the active surface of a refined mesh (Algorithm 4). Nothing in it changes
// during animation: that is the point of the method.
//
// Spring sets (all deduplicated by vertex pair, rest length = rest distance):
//  - stretch: the four corner-to-corner edges of every active quadtree record.
//    A coarse face with a hanging node on an edge keeps its own spring along
//    the whole edge (paper: "the coarse face keeps its own springs") and the
//    finer faces have their springs to the hanging node.
//  - shear: both corner diagonals of every active record.
//  - bend: every bend pair of mesh_ops/bend_partners.h (two steps along grid
//    lines and diagonals, same-level records, including across the interface
//    where an active face borders a refined face of its own level).
//  Boundaries have no special springs: a pair exists only where its records do.
//  Irregular vertices get stretch and shear springs from their faces and
//  bend springs across each edge, none diagonal (see bend_partners.h).
//  A spring's level is the level of the records that define it.
// Stiffness (eq. 1): k_L = k * 2^(alpha * (L - 1)) for stretch and shear and
// k_L = k * 2^(alpha_bend * (L - 1)) for bend, so coarse springs have the
// material's stiffness.
//
// Degrees of freedom: a vertex is pinned (follows a target), hanging (a T-node:
// exactly the midpoint of its parents, chains compose) or free. Full positions
// are x = S q + P p, with q the free positions (#free x 3), p the pinned
// targets (#pinned x 3), and S, P sparse interpolation matrices whose rows sum
// to 1. A hanging vertex has no mass of its own (lumped_mass gives it to its
// parents), so forces on it act on its parents through S^T.
#include "material.h"

#include "mesh_ops/quad_mesh.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace mrcloth {

/// Row-major n x 3 positions, one row per vertex (metres).
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

enum class SpringKind { stretch, shear, bend };

/// How a bend pair (i, via, j) resists bending.
enum class BendModel {
  distance,           ///< the paper's: a spring i-j, E = k/2 (|xi - xj| - rest)^2 (quartic in the curvature about flat)
  second_difference,  ///< experimental: E = k/2 (|xi - 2 xvia + xj| - rest)^2 (quadratic in the curvature; with alpha_bend 2 the same curvature stores the same energy at every level)
};

struct Spring {
  int i = -1, j = -1;        ///< full vertex indices
  int via = -1;              ///< a second-difference bend spring's middle vertex (its length is |xi - 2 xvia + xj|); -1: a distance spring
  double rest = 0.0;         ///< rest length, metres (a second-difference spring's: |Xi - 2 Xvia + Xj| at rest)
  double stiffness = 0.0;    ///< N/m, already scaled by level
  SpringKind kind = SpringKind::stretch;
  int level = 1;
};

struct DynamicsOptions {
  Material material;         ///< density, stiffnesses, damping, stretch limit
  // Defaults chosen by draping an adaptively refined sheet and the uniform
  // high-resolution sheet and comparing shapes (tests/solver/drape_consistency_test.cpp;
  // README): alpha 0 and alpha_bend 2 match best, as spring scaling predicts
  // (a stretch spring's N/m is spacing-independent on a square grid, a bend
  // spring's must grow as 1/h^2, i.e. x4 per level).
  double alpha = 0.0;        ///< eq. 1 exponent for stretch and shear (0 = same k at every level)
  double alpha_bend = 2.0;   ///< eq. 1 exponent for bend springs
  BendModel bend_model = BendModel::distance;  ///< see BendModel (README, The free swing)
  std::vector<int> pinned;   ///< full vertex ids that follow targets; none may be hanging
};

/// One term of a full vertex's position in free coordinates: x_v = sum w * q_free.
struct StencilTerm {
  int free = -1;
  double weight = 0.0;
};

struct DynamicsModel {
  int num_vertices = 0;
  Positions rest;                              ///< #V x 3 rest positions
  Eigen::VectorXd mass;                        ///< #V lumped masses, kg (0 for hanging vertices)
  std::vector<Spring> springs;                 ///< stretch, then shear, then bend
  std::vector<int> free_vertices;              ///< free index -> full vertex
  std::vector<int> pinned_vertices;            ///< pinned index -> full vertex
  std::vector<int> hanging_vertices;           ///< full vertices that are T-nodes
  Eigen::SparseMatrix<double> S;               ///< #V x #free
  Eigen::SparseMatrix<double> P;               ///< #V x #pinned
  Eigen::VectorXd free_mass;                   ///< #free, diag of S^T M S (kg)
  std::vector<std::vector<StencilTerm>> stencil;  ///< per full vertex: its S row (free terms only)
  std::vector<std::array<std::int32_t, 4>> corners;  ///< per active quadtree record: its corners (full ids, face orientation)
  Material material;
  double alpha = 0.0, alpha_bend = 2.0;
  BendModel bend_model = BendModel::distance;
};

/// Builds the model from a refinable mesh (its points are the rest state).
/// Throws ArgumentError for a pinned id out of range or hanging, or a
/// non-positive stiffness or density.
DynamicsModel build_dynamics(const QuadMesh& mesh, const DynamicsOptions& options);

/// The same, consulting `keep_going` between its phases (the stretch and
/// shear springs, the bend pairs, the bend springs, the interpolation rows:
/// 1.4 s at 148k vertices): none when it returned false. The model built
/// is the same.
std::optional<DynamicsModel> build_dynamics(const QuadMesh& mesh, const DynamicsOptions& options,
                                            const std::function<bool()>& keep_going);

/// Full positions x = S q + P p.
Positions full_positions(const DynamicsModel& model, const Positions& free, const Positions& pinned);

/// Free positions taken from full positions (rows of the free vertices).
Positions free_rows(const DynamicsModel& model, const Positions& full);

/// Pinned rows of full positions.
Positions pinned_rows(const DynamicsModel& model, const Positions& full);

/// A copy of `mesh` (hierarchy and layers included) with its points moved
/// to full positions x (#V x 3, e.g. a simulated frame).
QuadMesh mesh_at_positions(const QuadMesh& mesh, const Positions& x);

/// Largest strain (|xi - xj| - rest) / rest over stretch springs (0 if none is stretched).
double max_stretch(const DynamicsModel& model, const Positions& full);

/// The most stretched stretch spring: its strain (as max_stretch) and end
/// vertices (full ids; -1 when no spring is stretched); and how far a tear
/// opened: the largest excess over its rest length (metres) of a spring at
/// least doubled in length (0 when none is). Relative strain alone calls a
/// 2 mm edge stretched 4 mm by a collision push "torn"; a spring doubled
/// and centimetres longer is cloth parted around something.
/// The peak is also split by who sets a spring's length: a spring whose
/// ends both follow pins (pinned vertices, or T-nodes between them) is
/// stretched by whatever drives the pins (a waistband following the skin
/// of a walking body), not by the cloth, and no solver setting changes it.
struct StretchPeak {
  double strain = 0.0;
  int i = -1, j = -1;
  double tear_opening = 0.0;
  double cloth_strain = 0.0;   ///< the largest strain of a spring with an end the solver moves (0 if none is stretched)
  double pinned_strain = 0.0;  ///< the largest strain of a spring whose ends both follow pins (0 if none is stretched)
  /// Whether the most stretched spring's ends both follow pins.
  bool pinned() const { return pinned_strain > cloth_strain; }
};
StretchPeak most_stretched(const DynamicsModel& model, const Positions& full);

}  // namespace mrcloth
