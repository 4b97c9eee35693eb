#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/lumped_mass.h"
#include "mesh_ops/mode_layer.h"
#include "solver/dynamics_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace mrcloth {
namespace {

int count(const DynamicsModel& m, SpringKind kind) {
  return static_cast<int>(std::count_if(m.springs.begin(), m.springs.end(), [&](const Spring& s) { return s.kind == kind; }));
}

QuadMesh refined_grid() {
  QuadMesh mesh = test::make_grid(4, 3, 0.1);
  set_modes(mesh, {0, 1, 5, 6}, 4);
  adaptive_refine(mesh, {8.0, 3, true});
  return mesh;
}

TEST(DynamicsModel, SpringCountsOnARegularGrid) {
  // 4 x 3 quads: stretch 4*4 + 3*5 edges, shear 2 per quad, bend: rows
  // 4 * 3 + columns 5 * 2 two-step pairs, plus 2 diagonal pairs through each
  // of the 3 * 2 interior vertices.
  const DynamicsModel m = build_dynamics(test::make_grid(4, 3), {});
  EXPECT_EQ(count(m, SpringKind::stretch), 31);
  EXPECT_EQ(count(m, SpringKind::shear), 24);
  EXPECT_EQ(count(m, SpringKind::bend), 22 + 12);
  for (const Spring& s : m.springs) EXPECT_EQ(s.rest, (m.rest.row(s.i) - m.rest.row(s.j)).norm());
}

TEST(DynamicsModel, StiffnessFollowsEquationOne) {
  DynamicsOptions o;
  o.alpha = 0.5;
  o.alpha_bend = 1.5;
  const DynamicsModel m = build_dynamics(refined_grid(), o);
  std::set<int> levels;
  for (const Spring& s : m.springs) {
    levels.insert(s.level);
    const double base = s.kind == SpringKind::stretch ? o.material.stretch_stiffness
                        : s.kind == SpringKind::shear ? o.material.shear_stiffness
                                                      : o.material.bend_stiffness;
    const double a = s.kind == SpringKind::bend ? o.alpha_bend : o.alpha;
    EXPECT_DOUBLE_EQ(s.stiffness, base * std::exp2(a * (s.level - 1)));
  }
  EXPECT_EQ(levels, (std::set<int>{1, 2, 3}));
}

TEST(DynamicsModel, InterpolationMatrixPutsTNodesAtTheirParentsMidpoint) {
  const QuadMesh mesh = refined_grid();
  const DynamicsModel m = build_dynamics(mesh, {});
  ASSERT_FALSE(m.hanging_vertices.empty());
  EXPECT_EQ(m.free_vertices.size() + m.hanging_vertices.size(), mesh.n_vertices());
  const Positions x = full_positions(m, free_rows(m, m.rest), pinned_rows(m, m.rest));
  const Layers l = get_layers(mesh);
  for (int v : m.hanging_vertices) {
    const OpenMesh::Vec2i p = mesh.property(l.parents, mesh.vertex_handle(v));
    EXPECT_EQ(x.row(v), 0.5 * (x.row(p[0]) + x.row(p[1]))) << "vertex " << v;
  }
  const Eigen::VectorXd row_sums = m.S * Eigen::VectorXd::Ones(m.S.cols());
  for (Eigen::Index v = 0; v < row_sums.size(); ++v) EXPECT_EQ(row_sums[v], 1.0);
  EXPECT_NEAR(m.free_mass.sum(), m.material.areal_density * garment_area(mesh), 1e-15);
}

TEST(DynamicsModel, PinnedVerticesLeaveTheUnknowns) {
  DynamicsOptions o;
  o.pinned = {0, 4};
  const DynamicsModel m = build_dynamics(test::make_grid(4, 3), o);
  EXPECT_EQ(m.pinned_vertices, (std::vector<int>{0, 4}));
  EXPECT_EQ(m.free_vertices.size(), 20u - 2u);
  EXPECT_EQ(m.P.nonZeros(), 2);
}

TEST(DynamicsModel, BadPinsAreRefused) {
  const QuadMesh mesh = refined_grid();
  DynamicsOptions o;
  o.pinned = {static_cast<int>(mesh.n_vertices())};
  EXPECT_THROW(build_dynamics(mesh, o), ArgumentError);
  const Layers l = get_layers(mesh);
  for (auto v : mesh.vertices())
    if (mesh.property(l.hanging, v)) {
      o.pinned = {v.idx()};
      try {
        build_dynamics(mesh, o);
        FAIL() << "pinning a hanging node must be refused";
      } catch (const ArgumentError& e) {
        EXPECT_NE(std::string(e.what()).find("hanging"), std::string::npos) << e.what();
      }
      break;
    }
}

}  // namespace
}  // namespace mrcloth
