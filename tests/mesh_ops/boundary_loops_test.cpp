// Boundary loops (boundary_loops / boundary_loop_by_name) on grids, tubes, the
// default skirt, and after adaptive refinement adds boundary midpoints.
#include "mesh_invariants.h"
#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

/// Indices of `loop` whose consecutive vertices (cyclically) are not joined by
/// a boundary edge of the mesh; empty for a proper boundary loop.
std::vector<std::size_t> broken_steps(const QuadMesh& mesh, const std::vector<int>& loop) {
  std::vector<std::size_t> broken;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const auto h = mesh.find_halfedge(mesh.vertex_handle(loop[k]), mesh.vertex_handle(loop[(k + 1) % loop.size()]));
    if (!h.is_valid() || !mesh.is_boundary(mesh.edge_handle(h))) broken.push_back(k);
  }
  return broken;
}

std::size_t distinct(const std::vector<int>& loop) { return std::set<int>(loop.begin(), loop.end()).size(); }

/// Message of the ArgumentError `f` throws, or "" when it does not throw one.
template <typename F>
std::string argument_error(F f) {
  try {
    f();
  } catch (const ArgumentError& e) {
    return e.what();
  }
  return "";
}

QuadMesh load_skirt() {
  return load_garment(std::string(MRCLOTH_RESOURCES) + "/garments/default_skirt.obj").mesh;
}

TEST(BoundaryLoops, GridHasOneLoopInBoundaryOrder) {
  for (const auto& [nx, ny] : std::vector<std::pair<int, int>>{{1, 1}, {3, 2}, {5, 4}}) {
    SCOPED_TRACE("grid " + std::to_string(nx) + "x" + std::to_string(ny));
    const QuadMesh mesh = test::make_grid(nx, ny);
    const auto loops = boundary_loops(mesh);
    ASSERT_EQ(loops.size(), 1u);
    EXPECT_EQ(loops[0].size(), static_cast<std::size_t>(2 * (nx + ny)));
    EXPECT_EQ(distinct(loops[0]), loops[0].size());
    EXPECT_TRUE(broken_steps(mesh, loops[0]).empty());
  }
  // Exact order: starting at the lowest index, along OpenMesh's boundary
  // halfedges (against the counter-clockwise faces: up the left side first).
  EXPECT_EQ(boundary_loops(test::make_grid(3, 2))[0], (std::vector<int>{0, 4, 8, 9, 10, 11, 7, 3, 2, 1}));
  EXPECT_EQ(boundary_loops(test::make_grid(1, 1))[0], (std::vector<int>{0, 2, 3, 1}));
}

TEST(BoundaryLoops, TubeHasTwoLoopsTopFirst) {
  const int around = 8, rings = 5;
  const QuadMesh mesh = test::make_tube(around, rings, 0.3, 0.5);
  const auto loops = boundary_loops(mesh);
  ASSERT_EQ(loops.size(), 2u);
  std::vector<int> top(around), bottom(around);
  std::iota(top.begin(), top.end(), (rings - 1) * around);
  std::iota(bottom.begin(), bottom.end(), 0);
  // Same vertices as the top and bottom rings, each in ring order one way or the other.
  EXPECT_EQ(std::set<int>(loops[0].begin(), loops[0].end()), std::set<int>(top.begin(), top.end()));
  EXPECT_EQ(std::set<int>(loops[1].begin(), loops[1].end()), std::set<int>(bottom.begin(), bottom.end()));
  for (const auto& loop : loops) {
    EXPECT_EQ(loop.size(), static_cast<std::size_t>(around));
    EXPECT_TRUE(broken_steps(mesh, loop).empty());
  }
  EXPECT_EQ(boundary_loop_by_name(mesh, "top"), loops[0]);
  EXPECT_EQ(boundary_loop_by_name(mesh, "bottom"), loops[1]);
  EXPECT_EQ(boundary_loop_by_name(mesh, "loop:1"), loops[1]);
}

TEST(BoundaryLoops, DefaultSkirtWaistAndHem) {
  const QuadMesh mesh = load_skirt();
  const auto loops = boundary_loops(mesh);
  ASSERT_EQ(loops.size(), 2u);
  const std::vector<int> top = boundary_loop_by_name(mesh, "top");
  const std::vector<int> bottom = boundary_loop_by_name(mesh, "bottom");
  EXPECT_EQ(top, loops[0]);
  EXPECT_EQ(bottom, loops[1]);
  EXPECT_EQ(boundary_loop_by_name(mesh, "loop:0"), top);
  ASSERT_EQ(top.size(), 40u);
  ASSERT_EQ(bottom.size(), 40u);
  EXPECT_EQ(distinct(top), 40u);
  EXPECT_EQ(distinct(bottom), 40u);
  for (int v : top) EXPECT_NEAR(mesh.point(mesh.vertex_handle(v))[1], 1.02, 1e-9) << "waist vertex " << v;
  for (int v : bottom) EXPECT_NEAR(mesh.point(mesh.vertex_handle(v))[1], 0.55, 1e-9) << "hem vertex " << v;
  EXPECT_TRUE(broken_steps(mesh, top).empty());
  EXPECT_TRUE(broken_steps(mesh, bottom).empty());
}

TEST(BoundaryLoops, BadNamesThrowNamingTheNameAndTheLoopCount) {
  const QuadMesh mesh = load_skirt();
  const std::string out_of_range = argument_error([&] { boundary_loop_by_name(mesh, "loop:5"); });
  EXPECT_NE(out_of_range.find("loop:5"), std::string::npos) << out_of_range;
  EXPECT_NE(out_of_range.find("2 boundary loops"), std::string::npos) << out_of_range;
  EXPECT_NE(argument_error([&] { boundary_loop_by_name(mesh, "loop:2"); }), "");
  const std::string unknown = argument_error([&] { boundary_loop_by_name(mesh, "waist"); });
  EXPECT_NE(unknown.find("waist"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("2 boundary loops"), std::string::npos) << unknown;
  for (const std::string bad : {"loop:", "loop:-1", "loop:1x", "Top", "", "loop:99999999999"})
    EXPECT_NE(argument_error([&] { boundary_loop_by_name(mesh, bad); }), "") << "name '" << bad << "'";
}

TEST(BoundaryLoops, ClosedMeshHasNoLoops) {
  // A cube of six quads, outward oriented.
  QuadMesh mesh;
  for (int k = 0; k < 8; ++k) mesh.add_vertex(QuadMesh::Point(k & 1, (k >> 1) & 1, (k >> 2) & 1));
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces)
    ASSERT_TRUE(mesh.add_face(mesh.vertex_handle(f[0]), mesh.vertex_handle(f[1]), mesh.vertex_handle(f[2]),
                              mesh.vertex_handle(f[3])).is_valid());
  init_forest(mesh);
  EXPECT_TRUE(boundary_loops(mesh).empty());
  const std::string message = argument_error([&] { boundary_loop_by_name(mesh, "top"); });
  EXPECT_NE(message.find("0 boundary loops"), std::string::npos) << message;
}

TEST(BoundaryLoops, AdaptiveRefinementAddsWaistMidpointsInOrder) {
  QuadMesh mesh = load_skirt();
  const std::vector<int> waist = boundary_loop_by_name(mesh, "top");
  // Ten consecutive waist vertices at mode 4: the nine faces holding two of
  // them sum 4+4+1+1 = 10 >= 8 and split; a face with one sums 7 and does not.
  const std::vector<int> painted(waist.begin(), waist.begin() + 10);
  set_modes(mesh, painted, 4);
  const AdaptiveRefineReport report = adaptive_refine(mesh, {8.0, 2, true});
  ASSERT_EQ(report.faces_refined_per_pass, (std::vector<std::size_t>{9}));
  ASSERT_EQ(report.faces_refined_for_balance, 0u);
  ASSERT_TRUE(test::face_forest_violations(mesh).empty());

  const std::vector<int> top = boundary_loop_by_name(mesh, "top");
  ASSERT_EQ(top.size(), 49u);
  EXPECT_EQ(boundary_loop_by_name(mesh, "bottom").size(), 40u);
  EXPECT_TRUE(broken_steps(mesh, top).empty());
  for (int v : top) EXPECT_NEAR(mesh.point(mesh.vertex_handle(v))[1], 1.02, 1e-9) << "waist vertex " << v;
  // New vertices have higher indices, so both loops start at the same old
  // vertex: dropping the new ones gives the old loop unchanged.
  std::vector<int> old_only;
  std::copy_if(top.begin(), top.end(), std::back_inserter(old_only), [](int v) { return v < 800; });
  EXPECT_EQ(old_only, waist);
  // Each new one is the midpoint of the two vertices beside it.
  const auto parents = get_layers(mesh).parents;
  int midpoints = 0;
  for (std::size_t k = 0; k < top.size(); ++k) {
    if (top[k] < 800) continue;
    ++midpoints;
    const auto p = mesh.property(parents, mesh.vertex_handle(top[k]));
    const int before = top[(k + top.size() - 1) % top.size()], after = top[(k + 1) % top.size()];
    EXPECT_EQ(std::min(p[0], p[1]), std::min(before, after)) << "midpoint " << top[k];
    EXPECT_EQ(std::max(p[0], p[1]), std::max(before, after)) << "midpoint " << top[k];
  }
  EXPECT_EQ(midpoints, 9);
}

}  // namespace
}  // namespace mrcloth
