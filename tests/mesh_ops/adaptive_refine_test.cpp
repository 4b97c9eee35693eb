#include "mesh_invariants.h"
#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/mode_layer.h"

#include <gtest/gtest.h>

#include <random>

namespace mrcloth {
namespace {

double r_of(const QuadMesh& mesh, int v) { return mesh.property(get_layers(mesh).r_value, mesh.vertex_handle(v)); }

// Two unit quads side by side (vertices 0 1 2 bottom, 3 4 5 top), modes 3 on
// the left four vertices and 1 on the right two. Worked by hand with
// delta 8, max level 3 (see Algorithms 2 and 3):
//  pass 1: left sum 12, right sum 3+1+1+3 = 8: both split. Old R -= 1, so
//          left corners 2, right corners 0; left midpoints and centre 2;
//          right midpoints (1,2),(5,4) -> 1, (2,5) -> 0, centre (2+0+0+2)/4 = 1.
//  pass 2: the left children have corners all 2 (sum 8): 4 splits. The right
//          children sum 6, 2, 2, 6: none. Every old R -= 1.
//  pass 3: left faces are at max level 3; right sums are now 2, -2, -2, 2: stop.
class HandWorkedExample : public ::testing::Test {
 protected:
  void SetUp() override {
    mesh = test::make_grid(2, 1);
    set_modes(mesh, {0, 1, 3, 4}, 3);  // 2 and 5 keep the default mode 1
  }
  QuadMesh mesh;
};

TEST_F(HandWorkedExample, PassesAndCounts) {
  const AdaptiveRefineReport report = adaptive_refine(mesh, {8.0, 3, false});
  EXPECT_EQ(report.faces_refined_per_pass, (std::vector<std::size_t>{2, 4}));
  EXPECT_EQ(report.faces_refined_for_balance, 0u);
  // Left quad: a 4x4 grid of level-3 faces (25 vertices); right quad: 2x2
  // level-2 faces adding 4 vertices beyond the shared edge.
  EXPECT_EQ(report.vertices, 25u + 6u);
  EXPECT_EQ(mesh.n_vertices(), 31u);
  EXPECT_EQ(report.faces, 20u);
  EXPECT_EQ(report.faces_per_level, (std::vector<std::size_t>{0, 0, 4, 16}));
  EXPECT_EQ(report.vertices_per_level, (std::vector<std::size_t>{0, 6, 9, 16}));
  // The shared edge carries two quarter points of the left side, hanging on
  // the right side's level-2 faces.
  EXPECT_EQ(report.hanging_nodes, 2u);
  EXPECT_TRUE(test::face_forest_violations(mesh).empty());
  EXPECT_TRUE(test::hanging_midpoint_violations(mesh).empty());
}

TEST_F(HandWorkedExample, RValuesFollowAlgorithm3) {
  adaptive_refine(mesh, {8.0, 3, false});
  // Coarse vertices: two decrements.
  EXPECT_EQ(r_of(mesh, 0), 1.0);
  EXPECT_EQ(r_of(mesh, 4), 1.0);
  EXPECT_EQ(r_of(mesh, 2), -1.0);
  EXPECT_EQ(r_of(mesh, 5), -1.0);
  // Pass-1 vertices, created in split order: left quad (midpoints of edges
  // 0-1, 1-4, 4-3, 3-0, then its centre), then the right quad (midpoints
  // 1-2, 2-5, 5-4 — 4-1 is shared — then its centre). One decrement each.
  const double pass1[] = {1, 1, 1, 1, 1, /*right*/ 0, -1, 0, 0};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(r_of(mesh, 6 + i), pass1[i]) << "vertex " << 6 + i;
  // Pass-2 vertices: fathers all at 1 after the decrement.
  for (int v = 15; v < 31; ++v) EXPECT_EQ(r_of(mesh, v), 1.0) << "vertex " << v;
}

TEST(AdaptiveRefine, MaxLevelCapsRefinement) {
  QuadMesh mesh = test::make_grid(2, 2);
  set_modes(mesh, {0, 1, 2, 3, 4, 5, 6, 7, 8}, 10);
  const AdaptiveRefineReport report = adaptive_refine(mesh, {4.0, 2, true});
  EXPECT_EQ(report.faces_per_level, (std::vector<std::size_t>{0, 0, 16}));
  EXPECT_EQ(report.faces_refined_per_pass, (std::vector<std::size_t>{4}));
}

TEST(AdaptiveRefine, APassBeyondTheMostFacesIsRefusedBeforeItSplits) {
  // Every face splits in every pass: 9 -> 36 active faces pass a bound of
  // 100, the second pass's 144 do not (maxLevel 1e9 once ran a 24 GB
  // machine out of memory: kMostFaces bounds it by default).
  QuadMesh mesh = test::make_grid(3, 3);
  set_modes(mesh, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}, 1000);
  AdaptiveRefineOptions options{4.0, 1000000000, false};
  options.most_faces = 100.0;
  try {
    adaptive_refine(mesh, options);
    ADD_FAILURE() << "refined past 100 faces";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("would make more than 100 faces (pass 2 splits 36 of them)"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(AdaptiveRefineOptions{}.most_faces, kMostFaces);
}

TEST(AdaptiveRefine, NothingReachesDeltaNothingChanges) {
  QuadMesh mesh = test::make_grid(3, 3);
  const AdaptiveRefineReport report = adaptive_refine(mesh, {5.0, 3, true});  // default modes sum to 4
  EXPECT_TRUE(report.faces_refined_per_pass.empty());
  EXPECT_EQ(mesh.n_vertices(), 16u);
  EXPECT_EQ(mesh.n_faces(), 9u);
}

TEST(AdaptiveRefine, BalanceSplitsTheFaceBetweenLevelsOneAndThree) {
  // 3x1 quads; the left quad's outer vertices are so hot that all its
  // children split again, while the middle quad never reaches delta, so
  // without balance level 3 meets level 1 across the left-middle edge.
  //  pass 1: left 20+1+1+20 = 42 >= 9, middle 4: one split. R: 19 and 0.
  //  pass 2: the left children all sum >= 19: four splits; middle sums 0.
  QuadMesh unbalanced = test::make_grid(3, 1);
  set_modes(unbalanced, {0, 4}, 20);
  QuadMesh balanced = copy_mesh(unbalanced);
  const auto a = adaptive_refine(unbalanced, {9.0, 3, false});
  const auto b = adaptive_refine(balanced, {9.0, 3, true});
  EXPECT_EQ(a.faces_refined_per_pass, (std::vector<std::size_t>{1, 4}));
  EXPECT_EQ(test::brute_force_max_level_difference(unbalanced), 2);
  EXPECT_EQ(test::max_neighbour_level_difference(unbalanced), 2);
  EXPECT_EQ(a.hanging_nodes, 3u);  // the quarter points and midpoint of the left-middle edge
  EXPECT_EQ(b.faces_refined_per_pass, a.faces_refined_per_pass);
  EXPECT_EQ(b.faces_refined_for_balance, 1u);  // the middle quad, and nothing else
  EXPECT_EQ(test::brute_force_max_level_difference(balanced), 1);
  EXPECT_EQ(b.faces_per_level, (std::vector<std::size_t>{0, 1, 4, 16}));
  EXPECT_EQ(b.hanging_nodes, 2u + 1u);  // two quarter points, one midpoint on middle-right
  EXPECT_TRUE(test::face_forest_violations(balanced).empty());
  EXPECT_TRUE(test::hanging_midpoint_violations(unbalanced).empty());
  EXPECT_TRUE(test::hanging_midpoint_violations(balanced).empty());
}

TEST(AdaptiveRefine, RandomModeLayersAreBalancedAgainstBruteForce) {
  std::mt19937 rng(12345);
  int unbalanced_seen = 0;
  for (int trial = 0; trial < 25; ++trial) {
    QuadMesh mesh = test::make_grid(5, 4, 0.1);
    std::uniform_int_distribution<int> mode(1, 4);
    for (auto v : mesh.vertices()) set_modes(mesh, {v.idx()}, mode(rng));
    QuadMesh loose = copy_mesh(mesh);
    const AdaptiveRefineOptions options{std::uniform_real_distribution<double>(6.0, 12.0)(rng), 4, true};
    const auto report = adaptive_refine(mesh, options);
    adaptive_refine(loose, {options.delta, options.max_level, false});
    unbalanced_seen += test::brute_force_max_level_difference(loose) > 1;

    SCOPED_TRACE("trial " + std::to_string(trial));
    EXPECT_LE(test::brute_force_max_level_difference(mesh), 1);
    EXPECT_EQ(test::max_neighbour_level_difference(mesh), test::brute_force_max_level_difference(mesh));
    EXPECT_TRUE(test::face_forest_violations(mesh).empty());
    EXPECT_TRUE(test::hanging_midpoint_violations(mesh).empty());
    EXPECT_TRUE(test::face_forest_violations(loose).empty());
    EXPECT_TRUE(test::hanging_midpoint_violations(loose).empty());
    EXPECT_EQ(test::euler_characteristic(mesh), 1);
    // Balance only adds splits: every face split without it is split with it.
    EXPECT_GE(mesh.n_vertices(), loose.n_vertices());
    EXPECT_EQ(report.hanging_nodes, count_hanging(mesh));
    // 2:1 balance means at most one hanging vertex inside any coarse edge half.
    for (auto f : mesh.faces()) EXPECT_LE(mesh.valence(f), 8u);
  }
  EXPECT_GT(unbalanced_seen, 0) << "the random layers never needed balancing; the test proves nothing";
}

TEST(AdaptiveRefine, InputValidation) {
  QuadMesh mesh = test::make_grid(1, 1);
  EXPECT_THROW(adaptive_refine(mesh, {8.0, 0, true}), ArgumentError);
  EXPECT_THROW(adaptive_refine(mesh, {std::nan(""), 3, true}), ArgumentError);
}

}  // namespace
}  // namespace mrcloth
