#include "implicit_integrator_support.h"

#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/mode_layer.h"

#include <utility>

namespace mrcloth::test {

QuadMesh refined_sheet() {
  QuadMesh mesh = test::make_sheet(11, 0.5);
  paint_modes_sphere(mesh, {-0.25, 0.0, -0.25}, 0.2, 4);
  adaptive_refine(mesh, {8.0, 3, true});
  return mesh;
}

IntegratorOptions options(double h, Eigen::Vector3d gravity) {
  IntegratorOptions o;
  o.time_step = h;
  o.gravity = gravity;
  return o;
}

DynamicsModel sheet_pinned_at(std::vector<int> pinned) {
  DynamicsOptions d;
  d.pinned = std::move(pinned);
  return build_dynamics(test::make_sheet(11, 0.5), d);
}

}  // namespace mrcloth::test
