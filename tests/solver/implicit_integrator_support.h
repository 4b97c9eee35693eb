#pragma once
// The sheets and integrator options shared by the ImplicitIntegrator tests
// (implicit_integrator_test.cpp on the solve, implicit_integrator_limiter_test.cpp,
// implicit_integrator_contact_test.cpp, implicit_integrator_tnode_test.cpp).
#include "mesh_ops/quad_mesh.h"
#include "solver/dynamics_model.h"
#include "solver/implicit_integrator.h"

#include <Eigen/Core>

#include <vector>

namespace mrcloth::test {

// A 0.5 m sheet of 11 x 11 vertices refined around one corner, so it has
// levels 1-3 and T-nodes.
QuadMesh refined_sheet();

/// Integrator options with time step h (s) and the given gravity (m/s^2), the rest their defaults.
IntegratorOptions options(double h, Eigen::Vector3d gravity = {0, -9.81, 0});

// The plain 0.5 m sheet of 11 x 11 vertices pinned at the given vertices.
DynamicsModel sheet_pinned_at(std::vector<int> pinned);

}  // namespace mrcloth::test
