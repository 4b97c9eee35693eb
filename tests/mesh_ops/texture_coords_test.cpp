// Texture coordinates from an OBJ through refinement to every OBJ written:
// two unit quads side by side whose UVs are their x, y, the second's
// shifted by 10 in u (a seam along the shared edge), so the UV any corner
// must have is known from where it lies and which coarse face it refines.
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/obj_tokens.h"
#include "mesh_ops/quad_refiner.h"
#include "mesh_ops/quadtree_forest.h"
#include "mesh_ops/texture_coords.h"
#include "mesh_ops/uniform_refine.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

/// A scratch file for the running test.
std::string scratch(const std::string& name, const std::string& text = {}) {
  const char* root = std::getenv("MRCLOTH_TEST_TMP");
  const fs::path folder = (root && *root ? fs::path(root) : fs::temp_directory_path() / "mrcloth-test") /
                          ("texture_coords-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::create_directories(folder);
  const std::string path = (folder / name).string();
  if (!text.empty()) std::ofstream(path, std::ios::binary) << text;
  return path;
}

const char* const kTwoQuads =
    "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 11 0\nvt 12 0\nvt 12 1\nvt 11 1\n"
    "f 1/1 2/2 5/3 4/4\nf 2/-4 3/-3 6/-2 5/-1\n";  // the second face's texture indices count back

/// The UV of the point at `p` on coarse face `root` (0: u = x, 1: u = x + 10).
OpenMesh::Vec2d expected_uv(const OpenMesh::Vec3d& p, int root) { return {p[0] + 10.0 * root, p[1]}; }

int root_of(const std::vector<QuadRecord>& forest, int record) {
  while (forest[static_cast<std::size_t>(record)].parent >= 0) record = forest[static_cast<std::size_t>(record)].parent;
  return record;
}

/// Every record's corner UVs against the position of the corner vertex.
void expect_every_record_uv_at_its_corners(const QuadMesh& mesh) {
  ASSERT_TRUE(has_texture_coords(mesh));
  const auto& forest = quadtree(mesh);
  const auto& uvs = record_uvs(mesh);
  for (std::size_t r = 0; r < forest.size(); ++r)
    for (int k = 0; k < 4; ++k) {
      const OpenMesh::Vec3d p = mesh.point(mesh.vertex_handle(forest[r].corners[static_cast<std::size_t>(k)]));
      const OpenMesh::Vec2d want = expected_uv(p, root_of(forest, static_cast<int>(r)));
      EXPECT_LT((uvs[r].corner[static_cast<std::size_t>(k)] - want).norm(), 1e-12) << "record " << r << " corner " << k;
    }
}

/// Every face corner of an OBJ written by export_surface: its vertex's
/// position and its vt, checked against expected_uv (the face's root from
/// its centre: x < 1 is face 0). Returns the number of corners checked.
int expect_obj_uvs(const std::string& path) {
  std::ifstream in(path);
  std::vector<OpenMesh::Vec3d> points;
  std::vector<OpenMesh::Vec2d> texcoords;
  int corners = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      OpenMesh::Vec3d p;
      words >> p[0] >> p[1] >> p[2];
      points.push_back(p);
    } else if (tag == "vt") {
      OpenMesh::Vec2d uv;
      words >> uv[0] >> uv[1];
      texcoords.push_back(uv);
    } else if (tag == "f") {
      std::vector<std::pair<int, int>> face;
      for (std::string corner; words >> corner;) {
        const std::size_t slash = corner.find('/');
        EXPECT_NE(slash, std::string::npos) << "a face corner without a texture coordinate: " << line;
        if (slash == std::string::npos) return corners;
        face.emplace_back(std::stoi(corner.substr(0, slash)) - 1, std::stoi(corner.substr(slash + 1)) - 1);
      }
      OpenMesh::Vec3d centre(0, 0, 0);
      for (const auto& [v, t] : face) centre += points[static_cast<std::size_t>(v)] / static_cast<double>(face.size());
      for (const auto& [v, t] : face) {
        const OpenMesh::Vec2d want = expected_uv(points[static_cast<std::size_t>(v)], centre[0] < 1.0 ? 0 : 1);
        EXPECT_LT((texcoords[static_cast<std::size_t>(t)] - want).norm(), 1e-12) << line;
        ++corners;
      }
    }
  }
  return corners;
}

TEST(ObjTokens, IndicesCountFromOneOrBackFromTheEndAndCornersNameTheirTexture) {
  EXPECT_EQ(resolve_obj_index("1", 5), 0);
  EXPECT_EQ(resolve_obj_index("5", 5), 4);
  EXPECT_EQ(resolve_obj_index("-1", 5), 4);
  EXPECT_EQ(resolve_obj_index("-5", 5), 0);
  for (const char* bad : {"0", "6", "-6", "", "x", "2x", "+1"}) EXPECT_EQ(resolve_obj_index(bad, 5), -1) << bad;
  EXPECT_EQ(obj_corner_texture("3/7/2"), "7");
  EXPECT_EQ(obj_corner_texture("3/-1"), "-1");
  EXPECT_EQ(obj_corner_texture("3//2"), "");
  EXPECT_EQ(obj_corner_texture("3"), "");
}

TEST(TextureCoords, AnObjsUvsReachEveryRecordCornerSeamIncluded) {
  const LoadResult loaded = load_garment(scratch("two.obj", kTwoQuads));
  EXPECT_TRUE(loaded.warnings.empty());
  expect_every_record_uv_at_its_corners(loaded.mesh);
  // The shared vertices carry one UV per side.
  EXPECT_EQ(record_uvs(loaded.mesh).size(), 2u);
}

TEST(TextureCoords, RefinementInterpolatesTheParentsUvsAtEveryLevel) {
  QuadMesh mesh = load_garment(scratch("two.obj", kTwoQuads)).mesh;
  uniform_refine(mesh, 3);
  EXPECT_EQ(record_uvs(mesh).size(), quadtree(mesh).size());
  expect_every_record_uv_at_its_corners(mesh);
}

TEST(TextureCoords, ExportsWriteThemAtEveryCornerTNodesIncluded) {
  QuadMesh mesh = load_garment(scratch("two.obj", kTwoQuads)).mesh;
  // Split only the first face, then one of its children: the second face's
  // shared edge and the first's children carry T-nodes (polygons of five).
  QuadRefiner refiner(mesh);
  const QuadSplit first = refiner.split(0);
  refiner.split(first.children[1]);
  refiner.finish();
  std::size_t polygon_corners = 0;
  for (const auto& polygon : active_face_polygons(mesh)) polygon_corners += polygon.size();
  EXPECT_GT(polygon_corners, 4 * mesh.n_faces()) << "expected T-nodes in some polygons";
  const std::string polygons = scratch("polygons.obj");
  export_surface(mesh, polygons);
  EXPECT_EQ(expect_obj_uvs(polygons), static_cast<int>(polygon_corners));
  const std::string triangles = scratch("triangles.obj");
  ExportOptions triangulated;
  triangulated.triangulate = true;
  export_surface(mesh, triangles, triangulated);
  EXPECT_GT(expect_obj_uvs(triangles), static_cast<int>(polygon_corners));
}

TEST(TextureCoords, AnOmFileKeepsThemAndAMeshWithoutThemHasNone) {
  QuadMesh mesh = load_garment(scratch("two.obj", kTwoQuads)).mesh;
  uniform_refine(mesh, 2);
  const std::string om = scratch("refined.om");
  save_mesh(mesh, om);
  const QuadMesh back = load_garment(om).mesh;
  ASSERT_TRUE(has_texture_coords(back));
  const auto& saved = record_uvs(mesh);
  const auto& read = record_uvs(back);
  ASSERT_EQ(read.size(), saved.size());
  for (std::size_t r = 0; r < saved.size(); ++r)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(read[r].corner[k], saved[r].corner[k]) << "record " << r;
  // Without vt lines: none, no warning, and an OBJ written without vt.
  const LoadResult plain = load_garment(scratch("plain.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  EXPECT_FALSE(has_texture_coords(plain.mesh));
  EXPECT_TRUE(plain.warnings.empty());
  const std::string written = scratch("plain_out.obj");
  export_surface(plain.mesh, written);
  std::ifstream in(written);
  for (std::string line; std::getline(in, line);) EXPECT_NE(line.rfind("vt", 0), 0u) << line;
}

// A triangle and a pentagon are split into quads at their centres and edge
// midpoints; their UVs (here the points' x, y) are split the same way.
TEST(TextureCoords, FacesSplitIntoQuadsSplitTheirUvsAlike) {
  const LoadResult split = load_garment(scratch(
      "mixed.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0.5 0\nv 1.5 1.5 0\nv 0.5 2 0\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvt 2 0.5\nvt 1.5 1.5\nvt 0.5 2\n"
      "f 1/1 2/2 3/3\nf 2/2 4/4 5/5 6/6 3/3\n"));
  ASSERT_TRUE(has_texture_coords(split.mesh));
  EXPECT_EQ(quadtree(split.mesh).size(), 3u + 5u);
  QuadMesh mesh = split.mesh;
  uniform_refine(mesh, 2);
  const auto& forest = quadtree(mesh);
  const auto& uvs = record_uvs(mesh);
  for (std::size_t r = 0; r < forest.size(); ++r)
    for (int k = 0; k < 4; ++k) {
      const OpenMesh::Vec3d p = mesh.point(mesh.vertex_handle(forest[r].corners[static_cast<std::size_t>(k)]));
      EXPECT_LT((uvs[r].corner[static_cast<std::size_t>(k)] - OpenMesh::Vec2d(p[0], p[1])).norm(), 1e-12)
          << "record " << r << " corner " << k;
    }
}

TEST(TextureCoords, UvsThatCannotBeKeptAreDroppedWithAWarning) {
  const auto warning_of = [](const LoadResult& loaded) {
    return loaded.warnings.empty() ? std::string() : loaded.warnings.back();
  };
  // A corner without one.
  const LoadResult partial =
      load_garment(scratch("partial.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3 4\n"));
  EXPECT_FALSE(has_texture_coords(partial.mesh));
  EXPECT_NE(warning_of(partial).find("face 0 has a corner without one"), std::string::npos) << warning_of(partial);
  // A vt index that names nothing.
  const LoadResult dangling =
      load_garment(scratch("dangling.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/7\n"));
  EXPECT_FALSE(has_texture_coords(dangling.mesh));
  EXPECT_NE(warning_of(dangling).find("could not be read"), std::string::npos) << warning_of(dangling);
  QuadMesh one_face = dangling.mesh;
  EXPECT_THROW(set_record_uvs(one_face, std::vector<RecordUV>(3)), ArgumentError);
}

}  // namespace
}  // namespace mrcloth
