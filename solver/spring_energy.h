#pragma once
// One spring's energy and derivatives on its 2-vertex stencil, the shape
// every force in the solver takes (value, gradient, Hessian) so each can be
// checked against finite differences.
#include "dynamics_model.h"

#include <Eigen/Core>

namespace mrcloth {

/// E = k/2 (|xi - xj| - rest)^2. gradient_i = dE/dxi (dE/dxj = -gradient_i);
/// hessian = d2E/dxi2 (= d2E/dxj2 = -d2E/dxi dxj), the exact (possibly
/// indefinite) Hessian for |xi - xj| > 0.
struct SpringEvaluation {
  double energy = 0.0;           ///< J
  Eigen::Vector3d gradient_i;    ///< N (negative force on i)
  Eigen::Matrix3d hessian;       ///< N/m
};
SpringEvaluation evaluate_spring(const Eigen::Vector3d& xi, const Eigen::Vector3d& xj, double rest, double stiffness);

/// A spring's Hessian d2E/dxi2 with its negative part dropped, as
/// a I + b n n^T (n the unit direction xi - xj): the exact Hessian while
/// the spring is at least its rest length; a compressed spring's sideways
/// term, negative, is taken as 0, so the sum over springs is positive
/// semidefinite (what conjugate gradients need). a, b in N/m.
struct ProjectedSpringHessian {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double a = 0.0;  ///< N/m, sideways: stiffness (1 - rest / length), at least 0
  double b = 0.0;  ///< N/m, added along n (a + b = stiffness)
};
/// e = xi - xj (metres), rest (metres) and stiffness (N/m) of the spring.
ProjectedSpringHessian projected_spring_hessian(const Eigen::Vector3d& e, double rest, double stiffness);

/// A spring's vector at full positions x: xi - xj, or a second-difference
/// bend spring's xi - 2 xvia + xj (metres). Its energy is
/// stiffness/2 (|vector| - rest)^2 either way.
Eigen::Vector3d spring_vector(const Spring& s, const Positions& x);

/// Total spring energy of full positions x (#V x 3), J.
double spring_energy(const DynamicsModel& model, const Positions& x);

/// Spring forces on every full vertex (#V x 3), N: minus the energy gradient.
Positions spring_forces(const DynamicsModel& model, const Positions& x);

}  // namespace mrcloth
