#include "mesh_invariants.h"
#include "test_meshes.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/uniform_refine.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

TEST(UniformRefine, GridCountsAreExact) {
  // 3x3 quads: (3*2^n + 1)^2 vertices and 9 * 4^n faces.
  const std::size_t vertices[] = {16, 49, 169, 625};
  const std::size_t faces[] = {9, 36, 144, 576};
  for (int levels = 0; levels <= 3; ++levels) {
    QuadMesh mesh = test::make_grid(3, 3);
    uniform_refine(mesh, levels);
    EXPECT_EQ(mesh.n_vertices(), vertices[levels]) << "levels " << levels;
    EXPECT_EQ(mesh.n_faces(), faces[levels]) << "levels " << levels;
    EXPECT_EQ(count_hanging(mesh), 0u);
    EXPECT_TRUE(test::face_forest_violations(mesh).empty());
    EXPECT_EQ(test::euler_characteristic(mesh), 1);
  }
}

TEST(UniformRefine, MoreFacesThanMemoryHoldsAreRefusedBeforeAnyWork) {
  // 9 faces: 9 * 4^10 = 9.4 million faces pass the bound, 9 * 4^11 = 37.7 million do not.
  QuadMesh mesh = test::make_grid(3, 3);
  try {
    uniform_refine(mesh, 11);
    ADD_FAILURE() << "refined into 37.7 million faces";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("uniform refinement by 11 levels would make more than 20000000 faces from 9"),
              std::string::npos)
        << error.what();
  }
  EXPECT_THROW(uniform_refine(mesh, 1000000000), ArgumentError);
  EXPECT_EQ(mesh.n_faces(), 9u) << "untouched";
}

TEST(UniformRefine, ProgressCountsSplitsPerLevelThenTheFacesBuiltAndChangesNothing) {
  // 9 faces, 3 levels: 9 + 36 + 144 = 189 splits, reported after each
  // level, then the 576 faces of the result built.
  QuadMesh watched = test::make_grid(3, 3);
  EXPECT_EQ(uniform_refine_steps(watched, 3), 189.0 + 576.0);
  EXPECT_EQ(uniform_refine_steps(watched, 0), 0.0);
  std::vector<std::pair<int, int>> calls;
  EXPECT_TRUE(uniform_refine(watched, 3, [&](int done, int total) {
    calls.emplace_back(done, total);
    return true;
  }));
  EXPECT_EQ(calls, (std::vector<std::pair<int, int>>{{9, 765}, {45, 765}, {189, 765}, {765, 765}}));
  QuadMesh plain = test::make_grid(3, 3);
  uniform_refine(plain, 3);
  ASSERT_EQ(watched.n_vertices(), plain.n_vertices());
  ASSERT_EQ(watched.n_faces(), plain.n_faces());
  for (auto v : plain.vertices()) EXPECT_EQ(watched.point(v), plain.point(v)) << "vertex " << v.idx();
  for (auto f : plain.faces()) {
    std::vector<int> a, b;
    for (auto v : plain.fv_range(f)) a.push_back(v.idx());
    for (auto v : watched.fv_range(watched.face_handle(f.idx()))) b.push_back(v.idx());
    EXPECT_EQ(a, b) << "face " << f.idx();
  }
}

TEST(UniformRefine, ProgressComesWithinALongLevelAndTheBuildToo) {
  // 8 levels: the last splits 9 * 4^7 = 147,456 faces and 589,824 are
  // built, reported every 65,536 steps.
  QuadMesh mesh = test::make_grid(3, 3);
  const int total = static_cast<int>(uniform_refine_steps(mesh, 8));
  const int splits = 196605;
  EXPECT_EQ(total, splits + 589824);
  std::vector<int> done;
  EXPECT_TRUE(uniform_refine(mesh, 8, [&](int steps, int) {
    done.push_back(steps);
    return true;
  }));
  const int before_last = splits - 147456;
  std::vector<int> expected{9, 45, 189, 765, 3069, 12285, before_last, before_last + 65536, before_last + 131072, splits};
  for (int k = 1; k <= 8; ++k) expected.push_back(splits + 65536 * k);
  expected.push_back(total);
  EXPECT_EQ(done, expected);
  EXPECT_EQ(mesh.n_faces(), 589824u);
}

TEST(UniformRefine, AProgressCallbackReturningFalseStopsTheRefinement) {
  QuadMesh mesh = test::make_grid(3, 3);
  int calls = 0;
  EXPECT_FALSE(uniform_refine(mesh, 3, [&](int, int) { return ++calls < 2; }));
  EXPECT_EQ(calls, 2) << "no level after the one whose report said stop";
}

TEST(UniformRefine, RefiningInStepsEqualsRefiningAtOnce) {
  QuadMesh once = test::make_grid(3, 2);
  uniform_refine(once, 2);
  QuadMesh twice = test::make_grid(3, 2);
  uniform_refine(twice, 1);
  uniform_refine(twice, 1);
  ASSERT_EQ(once.n_vertices(), twice.n_vertices());
  for (auto v : once.vertices()) EXPECT_EQ(once.point(v), twice.point(twice.vertex_handle(v.idx())));
}

TEST(UniformRefine, CoarseVerticesKeepTheirIndicesAndPositions) {
  const QuadMesh coarse = test::make_tube(12, 6, 0.3, 0.5);
  QuadMesh fine = copy_mesh(coarse);
  uniform_refine(fine, 2);
  for (auto v : coarse.vertices()) EXPECT_EQ(coarse.point(v), fine.point(fine.vertex_handle(v.idx())));
  // Every level-1 record still names the same four coarse vertices.
  const auto& a = quadtree(coarse);
  const auto& b = quadtree(fine);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].corners, b[i].corners);
}

TEST(UniformRefine, MidpointsAreSharedNotDuplicated) {
  // A duplicated midpoint would leave two vertices at one position.
  QuadMesh mesh = test::make_tube(10, 5, 0.4, 0.6);
  uniform_refine(mesh, 2);
  std::vector<OpenMesh::Vec3d> points;
  for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
  std::sort(points.begin(), points.end(), [](const auto& p, const auto& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  });
  EXPECT_EQ(std::adjacent_find(points.begin(), points.end()), points.end());
  // A closed tube stays a tube: Euler characteristic 0, two boundary loops.
  EXPECT_EQ(test::euler_characteristic(mesh), 0);
}

TEST(UniformRefine, HierarchyRecordsAreConsistent) {
  QuadMesh mesh = test::make_grid(2, 2);
  uniform_refine(mesh, 2);
  const auto& forest = quadtree(mesh);
  ASSERT_EQ(forest.size(), 4u + 16u + 64u);
  for (std::size_t i = 0; i < forest.size(); ++i) {
    const QuadRecord& q = forest[i];
    EXPECT_EQ(q.active != 0, q.level == 3) << "record " << i;
    if (q.parent >= 0) {
      EXPECT_EQ(forest[q.parent].level + 1, q.level);
      const auto& siblings = forest[q.parent].children;
      EXPECT_NE(std::find(siblings.begin(), siblings.end(), static_cast<int>(i)), siblings.end());
    }
    if (!q.active)
      for (int k = 0; k < 4; ++k) {
        // Child k keeps corner k at position k.
        EXPECT_EQ(forest[q.children[k]].corners[k], q.corners[k]) << "record " << i << " child " << k;
        EXPECT_EQ(forest[q.children[k]].parent, static_cast<int>(i));
      }
  }
}

TEST(UniformRefine, NegativeLevelsAreRefused) {
  QuadMesh mesh = test::make_grid(1, 1);
  EXPECT_THROW(uniform_refine(mesh, -1), ArgumentError);
  EXPECT_EQ(mesh.n_vertices(), 4u);
}

TEST(UniformRefine, SharedSkirtCountsAreExact) {
  const std::string path = test::shared_data("garments/makehuman/skirthelper.obj");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data not found at " << path;
  QuadMesh mesh = load_garment(path, {"dm"}).mesh;
  ASSERT_EQ(mesh.n_vertices(), 720u);
  ASSERT_EQ(mesh.n_faces(), 684u);
  const QuadMesh coarse = copy_mesh(mesh);
  uniform_refine(mesh, 1);
  EXPECT_EQ(mesh.n_vertices(), 2808u);
  EXPECT_EQ(mesh.n_faces(), 2736u);
  uniform_refine(mesh, 1);
  EXPECT_EQ(mesh.n_vertices(), 11088u);
  EXPECT_EQ(mesh.n_faces(), 10944u);
  for (auto v : coarse.vertices()) EXPECT_EQ(coarse.point(v), mesh.point(mesh.vertex_handle(v.idx())));
}

}  // namespace
}  // namespace mrcloth
