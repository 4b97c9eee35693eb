#pragma once
// What ImplicitIntegrator::precompute derives from the model alone: the
// global step's matrix, the strain limiter's spring order, weights, merged
// constraint terms and tethers, and the order the collision checks visit
// the free vertices in. (chain_spectral_radius and t_node_fine_rows, defined
// with these, are declared in implicit_integrator.h: callers of the
// integrator use them too.)
#include "dynamics_model.h"
#include "implicit_integrator.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <utility>
#include <vector>

namespace mrcloth {

/// Q = M/h^2 + S^T L S (#free x #free, N/m), L the springs' Laplacian with
/// each bend spring split at its middle vertex (implicit_integrator.h);
/// `h` the time step, seconds.
Eigen::SparseMatrix<double> system_matrix(const DynamicsModel& model, double h);

/// Per vertex (#V), its free index if its position is exactly one free
/// vertex's (stencil weight 1, no pinned part), else -1.
std::vector<int> direct_free_indices(const DynamicsModel& model);

/// Per free vertex (#free), the limiter's projection weight
/// mass^-`mass_exponent` (`free_mass` in kg, exponent in [0, 1]).
Eigen::VectorXd projection_weights(const Eigen::VectorXd& free_mass, double mass_exponent);

/// Indices into model.springs of the stretch springs, in breadth-first
/// order over the spring graph (the limiter's sweep order).
std::vector<int> wavefront_order(const DynamicsModel& model);

/// The free vertices spring `s`'s vector x_i - x_j depends on, each once
/// with its net weight d(x_i - x_j) / d(free vertex) (unitless, may be 0),
/// in the order first met along i's stencil, then j's.
std::vector<std::pair<int, double>> merged_stencil_terms(const DynamicsModel& model, const Spring& s);

/// Each free vertex's tether to its nearest pinned vertex over the cloth
/// (rest lengths in metres); `direct_free` as from direct_free_indices.
/// Empty without pins.
std::vector<ImplicitIntegrator::Tether> tethers_to_pins(const DynamicsModel& model, const std::vector<int>& direct_free);

/// The row indices of `points` (#P x 3, metres) in Morton order of their
/// positions.
std::vector<int> spatial_order(const Positions& points);

}  // namespace mrcloth
