#include "mesh_invariants.h"
#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/uniform_refine.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const char* env = std::getenv("MRCLOTH_TEST_TMP");
  fs::path dir = fs::path(env ? env : fs::temp_directory_path().string()) / "save_load_test";
  fs::create_directories(dir);
  return dir;
}

bool same_record(const QuadRecord& a, const QuadRecord& b) {
  return a.level == b.level && a.active == b.active && a.parent == b.parent && a.children == b.children &&
         a.corners == b.corners;
}

QuadMesh refined_tube() {
  QuadMesh mesh = test::make_tube(10, 5, 0.3, 0.5);
  paint_modes_sphere(mesh, {0.3, 0.25, 0.0}, 0.2, 3);
  set_modes(mesh, {0, 1, 2}, 2);
  adaptive_refine(mesh, {8.0, 3, true});
  return mesh;
}

TEST(SaveLoad, OmRoundTripKeepsHierarchyAndEveryLayer) {
  const QuadMesh saved = refined_tube();
  ASSERT_GT(count_hanging(saved), 0u) << "the fixture should have T-nodes";
  const fs::path path = temp_dir() / "refined.om";
  save_mesh(saved, path.string());
  const QuadMesh loaded = load_garment(path.string()).mesh;

  ASSERT_EQ(loaded.n_vertices(), saved.n_vertices());
  ASSERT_EQ(loaded.n_faces(), saved.n_faces());
  const Layers a = get_layers(saved), b = get_layers(loaded);
  for (auto v : saved.vertices()) {
    const auto w = loaded.vertex_handle(v.idx());
    EXPECT_EQ(saved.point(v), loaded.point(w)) << "vertex " << v.idx();
    EXPECT_EQ(saved.property(a.mode, v), loaded.property(b.mode, w));
    EXPECT_EQ(saved.property(a.r_value, v), loaded.property(b.r_value, w));
    EXPECT_EQ(saved.property(a.hanging, v), loaded.property(b.hanging, w));
    EXPECT_EQ(saved.property(a.parents, v), loaded.property(b.parents, w));
  }
  for (auto f : saved.faces()) {
    const auto g = loaded.face_handle(f.idx());
    EXPECT_EQ(saved.property(a.level, f), loaded.property(b.level, g));
    EXPECT_EQ(saved.property(a.quad, f), loaded.property(b.quad, g));
  }
  const auto& fa = quadtree(saved);
  const auto& fb = quadtree(loaded);
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t i = 0; i < fa.size(); ++i) EXPECT_TRUE(same_record(fa[i], fb[i])) << "record " << i;
  EXPECT_TRUE(test::face_forest_violations(loaded).empty());
}

TEST(SaveLoad, ALoadedRefinedMeshRefinesLikeTheOriginal) {
  // The midpoints are recovered from the parents layer: refining after a
  // round trip must reuse them exactly as refining the original does.
  QuadMesh original = refined_tube();
  const fs::path path = temp_dir() / "refine_again.om";
  save_mesh(original, path.string());
  QuadMesh loaded = load_garment(path.string()).mesh;
  uniform_refine(original, 1);
  uniform_refine(loaded, 1);
  ASSERT_EQ(loaded.n_vertices(), original.n_vertices());
  for (auto v : original.vertices()) EXPECT_EQ(original.point(v), loaded.point(loaded.vertex_handle(v.idx())));
  EXPECT_TRUE(test::face_forest_violations(loaded).empty());
  EXPECT_TRUE(test::hanging_midpoint_violations(loaded).empty());
}

TEST(SaveLoad, ActiveSurfaceExportKeepsTheActivePolygons) {
  const QuadMesh mesh = refined_tube();
  ASSERT_GT(count_hanging(mesh), 0u);
  const fs::path path = temp_dir() / "surface.obj";
  export_surface(mesh, path.string(), {ColorBy::level, false});
  // Faces with T-nodes are polygons, so loading splits every face into quads
  // once: one centre per face and one midpoint per edge are added.
  const LoadResult back = load_garment(path.string());
  EXPECT_EQ(back.warnings.size(), 1u);
  EXPECT_EQ(back.mesh.n_vertices(), mesh.n_vertices() + mesh.n_faces() + mesh.n_edges());
  for (auto v : mesh.vertices()) EXPECT_EQ(mesh.point(v), back.mesh.point(back.mesh.vertex_handle(v.idx())));
}

}  // namespace
}  // namespace mrcloth
