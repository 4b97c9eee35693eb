// ImplicitIntegrator on multi-resolution meshes: T-nodes and pins exact after
// every step, the fine rows beside a coarse edge (their bulge, against a
// brute-force oracle) and t_node_sag.
#include "solver/implicit_integrator.h"

#include "implicit_integrator_support.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

using test::options;
using test::refined_sheet;

TEST(ImplicitIntegrator, TNodesAndPinsAreExactAfterEveryStep) {
  const QuadMesh mesh = refined_sheet();
  DynamicsOptions d;
  d.pinned = {0, 10};  // two coarse corners
  const DynamicsModel m = build_dynamics(mesh, d);
  ImplicitIntegrator integrator;
  integrator.precompute(m, options(1.0 / 120));
  ClothState s = rest_state(m);
  const Layers l = get_layers(mesh);
  for (int k = 0; k < 120; ++k) {
    Positions targets = pinned_rows(m, m.rest);
    targets.col(1).array() += 0.1 * std::sin(0.1 * k);  // moving pins
    integrator.step(s, targets, {});
    const Positions x = full_positions(m, s.positions, s.pinned);
    for (std::size_t p = 0; p < m.pinned_vertices.size(); ++p) EXPECT_EQ(x.row(m.pinned_vertices[p]), targets.row(p));
    for (int v : m.hanging_vertices) {
      const OpenMesh::Vec2i par = mesh.property(l.parents, mesh.vertex_handle(v));
      EXPECT_LT((x.row(v) - 0.5 * (x.row(par[0]) + x.row(par[1]))).norm(), 1e-15) << "step " << k << " vertex " << v;
    }
  }
}

// On a cylinder curved along a coarse edge the chord's midpoint lies
// inside, R (1 - cos theta) off the surface; the fine row beside the edge
// bulges by the same amount, so the T-node moved by it lands on the
// cylinder and a spring from it across the interface reads its rest length.
TEST(ImplicitIntegrator, AFineRowsBulgePutsATNodeOnTheCylinder) {
  const double radius = 0.05, spacing = 0.02;  // fine spacing; the coarse edge is twice that
  const auto on_cylinder = [&](double u, double v) {  // isometric: arc length u around, v along the axis
    return Eigen::Vector3d(radius * std::sin(u / radius), v, radius * (1.0 - std::cos(u / radius)));
  };
  const Eigen::Vector3d a = on_cylinder(-spacing, 0.0), b = on_cylinder(spacing, 0.0);
  const Eigen::Vector3d chord_middle = 0.5 * (a + b);
  const Eigen::Vector3d c = on_cylinder(0.0, spacing), ca = on_cylinder(-spacing, spacing), cb = on_cylinder(spacing, spacing);
  const Eigen::Vector3d t_node = chord_middle + fine_row_bulge(c, ca, cb, 1.0);
  EXPECT_NEAR((t_node - on_cylinder(0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((t_node - c).norm(), spacing, 1e-15);
  // From the chord the spring reads longer than the cloth is: by sag^2 / 2.
  const double sag = radius * (1.0 - std::cos(spacing / radius));
  EXPECT_NEAR((chord_middle - c).norm(), std::sqrt(spacing * spacing + sag * sag), 1e-15);
  EXPECT_GT((chord_middle - c).norm() - spacing, 1e-5);
  // The cap shortens the bulge, keeping its direction.
  const Eigen::Vector3d capped = fine_row_bulge(c, ca, cb, 0.5 * sag);
  EXPECT_NEAR(capped.norm(), 0.5 * sag, 1e-15);
  EXPECT_NEAR(capped.normalized().dot(fine_row_bulge(c, ca, cb, 1.0).normalized()), 1.0, 1e-15);
}

// The fine rows against a brute-force oracle on the flat rest sheet: for a
// spring from T-node t (between a and b) to c off their edge, the row's
// ends lie at c + (a - t) and c + (b - t). Every across spring whose two
// places hold vertices must get its row, and only those; where the fine
// side turns a corner those vertices are T-nodes themselves.
TEST(ImplicitIntegrator, TNodeFineRowsAreTheRowsBesideTheCoarseEdge) {
  const DynamicsModel m = build_dynamics(refined_sheet(), {});
  const auto vertex_at = [&](const Eigen::RowVector3d& p) {
    for (int v = 0; v < m.num_vertices; ++v)
      if ((m.rest.row(v) - p).norm() < 1e-12) return v;
    return -1;
  };
  std::vector<char> hanging(static_cast<std::size_t>(m.num_vertices), 0);
  for (const int v : m.hanging_vertices) hanging[static_cast<std::size_t>(v)] = 1;
  std::map<int, FineRow> expected;
  for (std::size_t k = 0; k < m.springs.size(); ++k) {
    const Spring& s = m.springs[k];
    if (s.kind != SpringKind::stretch) continue;
    for (const auto& [t, c] : {std::make_pair(s.i, s.j), std::make_pair(s.j, s.i)}) {
      const std::vector<StencilTerm>& parents = m.stencil[static_cast<std::size_t>(t)];
      if (parents.size() != 2) continue;
      const int a = m.free_vertices[static_cast<std::size_t>(parents[0].free)];
      const int b = m.free_vertices[static_cast<std::size_t>(parents[1].free)];
      if (c == a || c == b) continue;
      const int ca = vertex_at(m.rest.row(c) + m.rest.row(a) - m.rest.row(t));
      const int cb = vertex_at(m.rest.row(c) + m.rest.row(b) - m.rest.row(t));
      if (ca >= 0 && cb >= 0 && !expected.count(static_cast<int>(k))) expected[static_cast<int>(k)] = {static_cast<int>(k), t, c, ca, cb};
    }
  }
  const std::vector<FineRow> rows = t_node_fine_rows(m);
  ASSERT_EQ(rows.size(), expected.size());
  int corners = 0;
  for (const FineRow& row : rows) {
    SCOPED_TRACE("spring " + std::to_string(row.spring));
    ASSERT_EQ(expected.count(row.spring), 1u);
    const FineRow& e = expected[row.spring];
    EXPECT_EQ(row.t_node, e.t_node);
    EXPECT_EQ(row.c, e.c);
    EXPECT_EQ(row.ca, e.ca);
    EXPECT_EQ(row.cb, e.cb);
    corners += hanging[static_cast<std::size_t>(row.ca)] || hanging[static_cast<std::size_t>(row.cb)];
  }
  EXPECT_GT(corners, 0) << "no row turns a corner: the test misses the T-node ends";
  EXPECT_LT(corners, static_cast<int>(rows.size())) << "every row turns a corner: the plain rows go untested";
}

// t_node_sag reads only springs that hang from T-nodes: a mesh without
// T-nodes gives the same bits with it, a refined one does not.
TEST(ImplicitIntegrator, TNodeSagChangesOnlyMeshesWithTNodes) {
  std::vector<Collider> sphere(1);
  sphere[0].shape = SphereCollider{{0.1, -0.25, 0.0}, 0.15};
  const auto run = [&](const DynamicsModel& m, bool sag) {
    IntegratorOptions o = options(1.0 / 60);
    o.t_node_sag = sag;
    ImplicitIntegrator integrator;
    integrator.precompute(m, o);
    ClothState s = rest_state(m);
    for (int k = 0; k < 60; ++k) integrator.step(s, s.pinned, sphere);
    return s.positions;
  };
  DynamicsOptions d;
  d.pinned = {0, 10};
  const DynamicsModel uniform = build_dynamics(test::make_sheet(11, 0.5), d);
  ASSERT_TRUE(uniform.hanging_vertices.empty());
  const Positions u0 = run(uniform, false), u1 = run(uniform, true);
  EXPECT_EQ(std::memcmp(u0.data(), u1.data(), sizeof(double) * u0.size()), 0);
  const DynamicsModel refined = build_dynamics(refined_sheet(), d);
  ASSERT_FALSE(refined.hanging_vertices.empty());
  const Positions r0 = run(refined, false), r1 = run(refined, true);
  EXPECT_TRUE(r0.allFinite() && r1.allFinite());
  EXPECT_GT((r0 - r1).cwiseAbs().maxCoeff(), 1e-9) << "no spring from a T-node found its fine row";
}

}  // namespace
}  // namespace mrcloth
