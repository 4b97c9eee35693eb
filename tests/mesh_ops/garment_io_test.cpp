// Loading, saving and exporting garments (garment_io) and the unit table (units).
// Fixtures are tiny text meshes written by the tests into a scratch folder.
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/mode_painting.h"
#include "mesh_ops/quad_refiner.h"
#include "mesh_ops/quadtree_forest.h"
#include "mesh_ops/units.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <clocale>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using mrcloth::QuadMesh;

namespace {

/// A fresh folder per test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const char* root = std::getenv("MRCLOTH_TEST_TMP");
    const fs::path base = root && *root ? fs::path(root) : fs::temp_directory_path() / "mrcloth-test";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = base / (std::string("garment_io-") + info->test_suite_name() + "-" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

std::string write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The message of the InputError that loading `path` must throw.
std::string load_error(const std::string& path, const std::string& units = "m") {
  try {
    mrcloth::load_garment(path, {units});
  } catch (const mrcloth::InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError for " << path;
  return {};
}

#define EXPECT_LOAD_ERROR(path, problem)                                          \
  do {                                                                            \
    const std::string path_ = (path); /* evaluated once: it may write a file */   \
    const std::string message_ = load_error(path_);                               \
    EXPECT_EQ(message_.rfind(path_ + ": ", 0), 0u) << message_;                   \
    EXPECT_NE(message_.find(problem), std::string::npos) << message_;             \
  } while (false)

// A 4 x 3 vertex grid of 3 x 2 quads. Coordinates are decimals that a float
// cannot hold, so a single-precision read would show.
const char* const kX[4] = {"0.3", "1.7", "2.9", "-4.1"};
const char* const kY[3] = {"-0.7", "0.45", "1.3"};
const char* const kZ[3] = {"0.1", "0.0123456789", "7.77"};
constexpr int kGridVertices = 12;
constexpr int kGridFaces = 6;

std::vector<std::string> grid_vertex_lines() {
  std::vector<std::string> lines;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) lines.push_back(std::string(kX[i]) + " " + kY[j] + " " + kZ[j]);
  return lines;
}

std::vector<std::array<int, 4>> grid_faces() {
  std::vector<std::array<int, 4>> faces;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) faces.push_back({j * 4 + i, j * 4 + i + 1, (j + 1) * 4 + i + 1, (j + 1) * 4 + i});
  return faces;
}

OpenMesh::Vec3d grid_point_in_file(int v) {
  return {std::strtod(kX[v % 4], nullptr), std::strtod(kY[v / 4], nullptr), std::strtod(kZ[v / 4], nullptr)};
}

std::string grid_obj() {
  std::string text = "# grid\no grid\n";
  for (const auto& line : grid_vertex_lines()) text += "v " + line + "\n";
  text += "vt 0 0\n";
  for (const auto& f : grid_faces())
    text += "f " + std::to_string(f[0] + 1) + "/1 " + std::to_string(f[1] + 1) + "/1 " + std::to_string(f[2] + 1) +
            "/1 " + std::to_string(f[3] + 1) + "/1\n";
  return text;
}

std::string grid_off() {
  std::string text = "OFF\n# grid\n12 6 0\n";
  for (const auto& line : grid_vertex_lines()) text += line + "\n";
  for (const auto& f : grid_faces())
    text += "4 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + " " +
            std::to_string(f[3]) + "\n";
  return text;
}

std::string ply_header(int n_vertices, int n_faces) {
  return "ply\nformat ascii 1.0\ncomment grid\nelement vertex " + std::to_string(n_vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(n_faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string grid_ply() {
  std::string text = ply_header(kGridVertices, kGridFaces);
  for (const auto& line : grid_vertex_lines()) text += line + "\n";
  for (const auto& f : grid_faces())
    text += "4 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + " " +
            std::to_string(f[3]) + "\n";
  return text;
}

/// Face vertex loop rotated to start at its smallest index, for comparisons
/// that must not depend on where OpenMesh starts a face.
std::vector<int> canonical_loop(const QuadMesh& mesh, OpenMesh::FaceHandle f) {
  std::vector<int> loop;
  for (const auto v : mesh.fv_range(f)) loop.push_back(v.idx());
  std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
  return loop;
}

void expect_grid_as_read(const mrcloth::LoadResult& loaded, double scale) {
  const QuadMesh& mesh = loaded.mesh;
  ASSERT_EQ(mesh.n_vertices(), static_cast<std::size_t>(kGridVertices));
  ASSERT_EQ(mesh.n_faces(), static_cast<std::size_t>(kGridFaces));
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  for (int v = 0; v < kGridVertices; ++v) {
    const OpenMesh::Vec3d expected = grid_point_in_file(v);
    const OpenMesh::Vec3d& actual = mesh.point(QuadMesh::VertexHandle(v));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(actual[k], expected[k] * scale) << "vertex " << v << " axis " << k;
  }
  const auto faces = grid_faces();
  for (int f = 0; f < kGridFaces; ++f) {
    std::vector<int> expected(faces[f].begin(), faces[f].end());
    std::rotate(expected.begin(), std::min_element(expected.begin(), expected.end()), expected.end());
    EXPECT_EQ(canonical_loop(mesh, QuadMesh::FaceHandle(f)), expected) << "face " << f;
  }
  // Made refinable: one root record per face, every vertex at the default mode.
  EXPECT_EQ(mrcloth::quadtree(mesh).size(), static_cast<std::size_t>(kGridFaces));
  EXPECT_EQ(mrcloth::count_roots(mesh), static_cast<std::size_t>(kGridFaces));
  const auto layers = mrcloth::get_layers(mesh);
  for (const auto v : mesh.vertices()) EXPECT_EQ(mesh.property(layers.mode, v), mrcloth::kDefaultMode);
}

// Three quads sharing the edge 0-1.
const char* const kThreeQuadsOnOneEdgeObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 -1 0\nv 1 -1 0\nv 0 0 1\nv 1 0 1\n"
    "f 1 2 3 4\nf 2 1 5 6\nf 1 2 8 7\n";

}  // namespace

// --- units -------------------------------------------------------------------

TEST(Units, TableOfAcceptedUnits) {
  EXPECT_EQ(mrcloth::metres_per_unit("m"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("metres"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("meters"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("metre"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("meter"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("dm"), 0.1);
  EXPECT_EQ(mrcloth::metres_per_unit("cm"), 0.01);
  EXPECT_EQ(mrcloth::metres_per_unit("mm"), 0.001);
  EXPECT_EQ(mrcloth::metres_per_unit("inch"), 0.0254);
  EXPECT_EQ(mrcloth::metres_per_unit("in"), 0.0254);
}

TEST(Units, NamesAreCaseInsensitive) {
  EXPECT_EQ(mrcloth::metres_per_unit("DM"), 0.1);
  EXPECT_EQ(mrcloth::metres_per_unit("Cm"), 0.01);
  EXPECT_EQ(mrcloth::metres_per_unit("INCH"), 0.0254);
  EXPECT_EQ(mrcloth::metres_per_unit("Metres"), 1.0);
}

// In the process's locale (Qt sets the user's): a Turkish one lowered
// "INCH" to "Inch" (std::tolower's I), refusing it, and ".OBJ" likewise.
TEST(Units, NamesAreCaseInsensitiveInATurkishLocale) {
  const std::string before = std::setlocale(LC_ALL, nullptr);
  if (!std::setlocale(LC_ALL, "tr_TR.UTF-8") && !std::setlocale(LC_ALL, "tr_TR.utf8"))
    GTEST_SKIP() << "no Turkish locale on this machine (locale-gen tr_TR.UTF-8 makes one)";
  const bool turkish_lowering = std::tolower('I') != 'i';
  const double inch = mrcloth::metres_per_unit("INCH");
  std::setlocale(LC_ALL, before.c_str());
  EXPECT_TRUE(turkish_lowering) << "the locale should lower I otherwise, or this test shows nothing";
  EXPECT_EQ(inch, 0.0254);
  EXPECT_EQ(mrcloth::ascii_lower("INCH.OBJ \xC4\xB0"), "inch.obj \xC4\xB0");
}

TEST(Units, UnknownUnitIsRefusedWithTheAcceptedList) {
  for (const std::string unit : {"furlong", "", "km", "m "}) {
    try {
      mrcloth::metres_per_unit(unit);
      ADD_FAILURE() << "unit '" << unit << "' was accepted";
    } catch (const mrcloth::ArgumentError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("unknown unit '" + unit + "'"), std::string::npos) << message;
      EXPECT_NE(message.find("m, dm, cm, mm, inch"), std::string::npos) << message;
    }
  }
}

TEST(Units, LoadWithUnknownUnitIsAnArgumentError) {
  ScratchDir dir;
  const std::string path = write_file(dir.file("grid.obj"), grid_obj());
  EXPECT_THROW(mrcloth::load_garment(path, {"yards"}), mrcloth::ArgumentError);
}

// --- loading good files ------------------------------------------------------

TEST(GarmentLoad, ObjQuadGridInDecimetres) {
  ScratchDir dir;
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()), {"dm"}), 0.1);
}

TEST(GarmentLoad, OffQuadGridInDecimetres) {
  ScratchDir dir;
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("grid.off"), grid_off()), {"dm"}), 0.1);
}

TEST(GarmentLoad, PlyQuadGridInDecimetres) {
  ScratchDir dir;
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("grid.ply"), grid_ply()), {"dm"}), 0.1);
}

TEST(GarmentLoad, PlyWithMoreVertexPropertiesKeepsDoubles) {
  // x, y, z are picked out by name, in any order, among other properties.
  ScratchDir dir;
  const std::string path = write_file(dir.file("rich.ply"),
                                      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double z\n"
                                      "property uchar red\nproperty float x\nproperty float confidence\n"
                                      "property float y\nelement face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n0.1 7 0.3 0 -0.7\n0.1 7 1.7 0.5 -0.7\n0.2 7 1.7 1 0.45\n"
                                      "0.2 7 0.3 0 0.45\n4 0 1 2 3\n");
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path, {"mm"});
  ASSERT_EQ(loaded.mesh.n_vertices(), 4u);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  EXPECT_EQ(loaded.mesh.point(QuadMesh::VertexHandle(1)), OpenMesh::Vec3d(1.7 * 0.001, -0.7 * 0.001, 0.1 * 0.001));
  EXPECT_EQ(loaded.mesh.point(QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(1.7 * 0.001, 0.45 * 0.001, 0.2 * 0.001));
}

TEST(GarmentLoad, DefaultUnitIsMetresAndExtensionCaseDoesNotMatter) {
  ScratchDir dir;
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("GRID.OBJ"), grid_obj())), 1.0);
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("grid.Off"), grid_off()), {"cm"}), 0.01);
}

TEST(GarmentLoad, TrianglesAndPentagonsAreSplitIntoQuads) {
  // A pentagon 0-4, a triangle on its edge 4-0 and a quad on its edge 1-2:
  // 8 vertices, 10 edges, 3 faces -> 8 + 10 + 3 vertices and 5 + 3 + 4 quads.
  ScratchDir dir;
  const std::string path = write_file(dir.file("mixed.obj"),
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 1.5 0\nv 0 1 0\n"
                                      "v -1 0.5 0\nv 2 0 0\nv 2 1 0\n"
                                      "f 1 2 3 4 5\nf 1 5 6\nf 2 7 8 3\n");
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path);
  const QuadMesh& mesh = loaded.mesh;
  EXPECT_EQ(mesh.n_vertices(), 21u);
  EXPECT_EQ(mesh.n_faces(), 12u);
  EXPECT_EQ(mesh.n_edges(), 32u);  // Euler: V - E + F = 1 for a disc
  for (const auto f : mesh.faces()) EXPECT_EQ(mesh.valence(f), 4u) << "face " << f.idx();
  EXPECT_EQ(mrcloth::quadtree(mesh).size(), 12u);
  // The file's vertices keep their indices; then edge midpoints, then centres.
  EXPECT_EQ(mesh.point(QuadMesh::VertexHandle(3)), OpenMesh::Vec3d(0.5, 1.5, 0));
  EXPECT_EQ(mesh.point(QuadMesh::VertexHandle(7)), OpenMesh::Vec3d(2, 1, 0));
  const OpenMesh::Vec3d triangle_centre = mesh.point(QuadMesh::VertexHandle(19));
  EXPECT_NEAR(triangle_centre[0], -1.0 / 3.0, 1e-15);
  EXPECT_NEAR(triangle_centre[1], 0.5, 1e-15);
  EXPECT_EQ(mesh.point(QuadMesh::VertexHandle(20)), OpenMesh::Vec3d(1.5, 0.5, 0));
  // Every edge midpoint exists once: the boundary has 2 * 8 edges, all halves.
  std::size_t boundary = 0;
  for (const auto e : mesh.edges()) boundary += mesh.is_boundary(e) ? 1 : 0;
  EXPECT_EQ(boundary, 16u);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  const std::string& warning = loaded.warnings[0];
  EXPECT_EQ(warning.rfind(path + ": ", 0), 0u) << warning;
  EXPECT_NE(warning.find("1 triangle and 1 n-gon"), std::string::npos) << warning;
  EXPECT_NE(warning.find("split into quads"), std::string::npos) << warning;
  EXPECT_NE(warning.find("21 vertices instead of 8"), std::string::npos) << warning;
}

TEST(GarmentLoad, AllTriangleOffIsSplitWithPluralWarning) {
  ScratchDir dir;
  const std::string path =
      write_file(dir.file("two.off"), "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path);
  EXPECT_EQ(loaded.mesh.n_vertices(), 4u + 5u + 2u);
  EXPECT_EQ(loaded.mesh.n_faces(), 6u);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("2 triangles and 0 n-gons"), std::string::npos) << loaded.warnings[0];
}

// --- refusing bad files --------------------------------------------------------

TEST(GarmentLoadErrors, MissingFile) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(dir.file("absent.obj"), "cannot open file (it does not exist)");
  // A name decoded from bytes that were not UTF-8 (a Latin-1 "caf\xe9.obj"
  // reaches the loader as "caf\uFFFD.obj"): said so, not only "missing".
  EXPECT_LOAD_ERROR(dir.file("caf\xEF\xBF\xBD.obj"), "its name holds U+FFFD, the mark of bytes that were not UTF-8");
}

TEST(GarmentLoadErrors, FolderInsteadOfFile) {
  ScratchDir dir;
  fs::create_directories(dir.file("folder.obj"));
  EXPECT_LOAD_ERROR(dir.file("folder.obj"), "cannot open file");
}

TEST(GarmentLoadErrors, UnknownExtension) {
  ScratchDir dir;
  const std::string stl = write_file(dir.file("shirt.stl"), "solid x\nendsolid x\n");
  EXPECT_LOAD_ERROR(stl, "unknown mesh format (extension '.stl'); expected one of .obj, .off, .ply, .om");
  const std::string bare = write_file(dir.file("shirt"), grid_obj());
  EXPECT_LOAD_ERROR(bare, "unknown mesh format (extension none)");
}

TEST(GarmentLoadErrors, EmptyFiles) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("empty.obj"), ""), "the file is empty");
  EXPECT_LOAD_ERROR(write_file(dir.file("empty.off"), ""), "the file is empty");
  EXPECT_LOAD_ERROR(write_file(dir.file("comments.obj"), "# nothing here\n"), "the file has no vertices");
  EXPECT_LOAD_ERROR(write_file(dir.file("points.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\n"), "the file has no faces");
  EXPECT_LOAD_ERROR(write_file(dir.file("points.off"), "OFF\n3 0 0\n0 0 0\n1 0 0\n1 1 0\n"), "the file has no faces");
}

TEST(GarmentLoadErrors, NonFiniteCoordinateObj) {
  ScratchDir dir;
  const std::string quad_faces = "v 1 0 0\nv 1 1 0\nf 1 2 3 4\n";
  EXPECT_LOAD_ERROR(write_file(dir.file("nan.obj"), "v nan 0 0\nv 0 1 0\n" + quad_faces),
                    "vertex 0 (line 1) has a non-finite coordinate (nan)");
  EXPECT_LOAD_ERROR(write_file(dir.file("huge.obj"), "# c\nv 0 0 0\nv 0 1 0\nv 1 1e999 0\nv 1 0 0\nf 1 2 3 4\n"),
                    "vertex 2 (line 4) has a non-finite coordinate (1e999)");
  EXPECT_LOAD_ERROR(write_file(dir.file("inf.obj"), "v 0 0 -inf\nv 0 1 0\n" + quad_faces),
                    "vertex 0 (line 1) has a non-finite coordinate (-inf)");
  EXPECT_LOAD_ERROR(write_file(dir.file("word.obj"), "v 0 0 zero\nv 0 1 0\n" + quad_faces),
                    "vertex 0 (line 1) has a coordinate that is not a number ('zero')");
}

TEST(GarmentLoadErrors, NonFiniteCoordinateOffAndPly) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("nan.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 NaN 0\n0 1 0\n4 0 1 2 3\n"),
                    "vertex 2 (line 5) has a non-finite coordinate (NaN)");
  EXPECT_LOAD_ERROR(
      write_file(dir.file("inf.ply"), ply_header(4, 1) + "0 0 0\n1 0 0\n1 1 0\n0 inf 0\n4 0 1 2 3\n"),
      "vertex 3 (line 14) has a non-finite coordinate (inf)");
}

TEST(GarmentLoadErrors, NonManifoldEdge) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("fan.obj"), kThreeQuadsOnOneEdgeObj),
                    "face 2 (line 11) would be a third face on its edge from vertex 0 (line 1) to vertex 1 (line 2); "
                    "expected an oriented 2-manifold quad mesh");
  // With texture coordinates the OBJ reader takes another path after add_face.
  EXPECT_LOAD_ERROR(write_file(dir.file("fan_uv.obj"),
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 -1 0\nv 1 -1 0\nv 0 0 1\nv 1 0 1\nvt 0 0\n"
                               "f 1/1 2/1 3/1 4/1\nf 2/1 1/1 5/1 6/1\nf 1/1 2/1 8/1 7/1\nf 5/1 6/1 8/1\n"),
                    "face 2 (line 12) would be a third face on its edge from vertex 0 (line 1) to vertex 1 (line 2)");
  EXPECT_LOAD_ERROR(write_file(dir.file("fan.off"),
                               "OFF\n8 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 -1 0\n1 -1 0\n0 0 1\n1 0 1\n"
                               "4 0 1 2 3\n4 1 0 4 5\n4 1 0 6 7\n"),
                    "face 2 (line 13) would be a third face on its edge from vertex 1 (line 4) to vertex 0 (line 3)");
}

TEST(GarmentLoadErrors, AFaceWoundTheOtherWayIsNamedWithItsEdge) {
  // Two squares sharing the edge 1-2, the second wound clockwise.
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("flipped.obj"),
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 3 6 5\n"),
                    "face 1 (line 8) runs its edge from vertex 1 (line 2) to vertex 2 (line 3) the way face 0 (line 7) does: "
                    "one of them is wound the other way round");
}

TEST(GarmentLoadErrors, NonManifoldVertex) {
  // Four quads close a disc around vertex 4; a fifth quad then touches that
  // interior vertex from above.
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("spike.off"),
                               "OFF\n12 5 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n0 2 0\n1 2 0\n2 2 0\n"
                               "1 1 1\n2 1 1\n2 2 1\n"
                               "4 0 1 4 3\n4 1 2 5 4\n4 3 4 7 6\n4 4 5 8 7\n4 4 9 10 11\n"),
                    "face 4 (line 19) would join the faces before it only at a vertex (a bow-tie)");
}

TEST(GarmentLoadErrors, RepeatedVertexInFace) {
  ScratchDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n";
  EXPECT_LOAD_ERROR(write_file(dir.file("repeat.obj"), vertices + "f 1 2 3 4\nf 2 5 5 6\n"),
                    "face 1 (line 8) uses vertex 4 (line 5) more than once");
  EXPECT_LOAD_ERROR(write_file(dir.file("repeat.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 1 3\n"),
                    "face 0 (line 7) uses vertex 1 (line 4) more than once");
  EXPECT_LOAD_ERROR(write_file(dir.file("repeat.ply"), ply_header(4, 1) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 3 2 3\n"),
                    "face 0 (line 15) uses vertex 3 (line 14) more than once");
}

TEST(GarmentLoadErrors, VertexIndexOutOfRange) {
  ScratchDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  EXPECT_LOAD_ERROR(write_file(dir.file("range.obj"), vertices + "f 1 2 3 9\n"),
                    "face 0 (line 5) refers to vertex 9, which does not exist (4 vertices are defined before it");
  EXPECT_LOAD_ERROR(write_file(dir.file("zero.obj"), vertices + "f 1 2 3 4\nf 0 1 2 3\n"),
                    "face 1 (line 6) refers to vertex 0, which does not exist");
  EXPECT_LOAD_ERROR(write_file(dir.file("range.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 7\n"),
                    "face 0 (line 7) refers to vertex 7 (counted from 0), which does not exist (the file has 4 vertices)");
  EXPECT_LOAD_ERROR(write_file(dir.file("range.ply"), ply_header(4, 2) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                                                          "4 0 1 2 3\n3 0 2 12\n"),
                    "face 1 (line 16) refers to vertex 12 (counted from 0), which does not exist (the file has 4 vertices)");
}

/// OpenMesh's OBJ reader aborts the process (an assertion Debian's build
/// keeps) on a face whose first corner has no vertex index: refused first.
TEST(GarmentLoadErrors, ACornerWithoutAVertexIndexIsRefusedBeforeTheReaderAborts) {
  ScratchDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  for (const std::string face : {"f /1 2 3 4", "f /1/1 2 3 4", "f /1", "f 1 2 3 /4"})
    EXPECT_LOAD_ERROR(write_file(dir.file("slash.obj"), vertices + "f 1 2 3 4\n" + face + "\n"),
                      "face 1 (line 6) has a corner that is not a vertex index ('/");
  // An earlier problem the scan sees is still the one named.
  EXPECT_LOAD_ERROR(write_file(dir.file("earlier.obj"), vertices + "f 1 2 3 9\nf /1 2 3 4\n"),
                    "face 0 (line 5) refers to vertex 9");
}

/// OpenMesh's PLY reader crashes on a property before any element and
/// loops for ever on a type it does not know: both refused with the line.
TEST(GarmentLoadErrors, PlyPropertiesOpenMeshCannotReadAreRefusedWithTheirLine) {
  ScratchDir dir;
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  std::string header = ply_header(4, 1);
  const std::string orphan = "ply\nformat ascii 1.0\nproperty float x\n" + header.substr(header.find("element vertex"));
  EXPECT_LOAD_ERROR(write_file(dir.file("orphan.ply"), orphan + body),
                    "the PLY header's property (line 3) comes before any element");
  std::string unknown = header;
  unknown.replace(unknown.find("uchar int"), 9, "uchar intx");
  EXPECT_LOAD_ERROR(write_file(dir.file("unknown.ply"), unknown + body), "is 'property list uchar intx");
}

/// OpenMesh's PLY reader reads its header word by word and loops for ever on
/// a word it cannot convert; it pushes four billion corners for a count of
/// -1: each refused first, naming the line.
TEST(GarmentLoadErrors, PlyHeadersAndDataOpenMeshWouldMisreadNameTheirLine) {
  ScratchDir dir;
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  const std::string header = ply_header(4, 1);
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = header + body;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const auto refused = [&](const std::string& name, const std::string& text, const std::string& problem) {
    EXPECT_LOAD_ERROR(write_file(dir.file(name), text), problem);
  };
  refused("format.ply", with("format ascii 1.0", "format ascii infinity 1.0"),
          "the PLY header's line 2 is 'format ascii infinity 1.0'; expected 'format ascii 1.0'");
  refused("version.ply", with("ascii 1.0", "ascii one"), "line 2 is 'format ascii one'");
  refused("count.ply", with("element vertex 4", "element vertex 9ace"),
          "the PLY header's element (line 4) is 'element vertex 9ace'; expected 'element <name> <count>' with a "
          "count from 0 to 4294967295");
  refused("negative.ply", with("element face 1", "element face -1"), "element (line 8) is 'element face -1'");
  refused("huge.ply", with("element face 1", "element face 4294967296"), "(line 8) is 'element face 4294967296'");
  refused("typo.ply", with("element face", "elemnt face"),
          "the PLY header's line 8 is 'elemnt face 1'; expected comment, obj_info, element, property or end_header");
  refused("end.ply", with("end_header", "end_header 0"), "end (line 10) is 'end_header 0'; expected 'end_header' alone");
  refused("twice.ply", with("element face 1", "element vertex 4"),
          "element (line 8) is a second 'vertex' element (the first is on line 4)");
  refused("list.ply", with("property float z", "property list uchar float z"), "(line 7) makes z a list");
  refused("vertex_list.ply", with("property float z", "property float z\nproperty list uchar int rings"),
          "property (line 8) is a list ('rings' of element 'vertex'); expected lists only for the faces' "
          "vertex_indices");
  refused("length.ply", with("list uchar int", "list float int"),
          "gives its list length as float; expected uchar, uint8, uint16 or int");
  refused("no_y.ply", with("property float y\n", ""), "vertex element (line 4) has 0 properties named y");
  refused("corners.ply", with("4 0 1 2 3", "-1 0 1 2 3"),
          "face 0 (line 15) has '-1' for its number of corners; expected a uchar count");
  refused("many.ply", with("4 0 1 2 3", "200 0 1 2 3"),
          "the PLY data ends at face 0; expected the 1 items the header's element 'face' (line 8) counts");
  refused("short.ply", with("element vertex 4", "element vertex 400"), "the PLY data ends at vertex");
  refused("index.ply", with("4 0 1 2 3", "4 0 1 2 -3"),
          "face 0 (line 15) has '-3' among its vertex indices; expected 4 indices from 0");
  refused("word.ply", with("1 1 0", "1 1 zero"), "vertex 2 (line 13) has a coordinate that is not a number ('zero')");
  refused("magic.ply", with("ply\n", "ply 1\n"), "the first line is not 'ply'; expected a PLY file");
  refused("face_first.ply",
          "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nelement vertex 0\n"
          "property float x\nproperty float y\nproperty float z\nend_header\n",
          "face element (line 3) comes before its vertex element");
}

/// Other scalars of a vertex or face are checked against their type too
/// (OpenMesh reads colours as numbers: a word stops its stream).
TEST(GarmentLoadErrors, PlyScalarsMustBeNumbersOfTheirType) {
  ScratchDir dir;
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_LOAD_ERROR(write_file(dir.file("red.ply"), header + "0 0 0 255\n1 0 0 256\n1 1 0 0\n0 1 0 0\n4 0 1 2 3\n"),
                    "vertex 1 (line 12) has '256' for its red; expected a uchar number");
  EXPECT_LOAD_ERROR(write_file(dir.file("word.ply"), header + "0 0 0 255\n1 0 0 1\n1 1 0 x\n0 1 0 0\n4 0 1 2 3\n"),
                    "vertex 2 (line 13) has 'x' for its red");
  const mrcloth::LoadResult loaded =
      mrcloth::load_garment(write_file(dir.file("fine.ply"), header + "0 0 0 255\n1 0 0 +7\n1 1 0 0\n0 1 0 0\n"
                                                                      "4 0 1 2 3\n"));
  EXPECT_EQ(loaded.mesh.n_faces(), 1u);
}

/// A binary PLY as written by hand: x, y, z as float (or double), a colour,
/// faces as uchar counts of int indices; `big` for big-endian.
std::string binary_quad_ply(bool big, const std::string& header_extra, std::int32_t corner_count) {
  std::string text = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\nelement vertex 4\nproperty float x\nproperty double y\nproperty float z\n"
                     "property uchar red\nelement face 1\nproperty list int int vertex_indices\n" + header_extra +
                     "end_header\n";
  const auto put = [&](const void* value, std::size_t size) {
    char bytes[8];
    std::memcpy(bytes, value, size);
    if (big) std::reverse(bytes, bytes + size);
    text.append(bytes, size);
  };
  const double corners[4][3] = {{0, 0, 0}, {1.25, 0, 0}, {1.25, 0.1, 0.5}, {0, 0.1, 0.5}};
  for (const auto& p : corners) {
    const float x = static_cast<float>(p[0]), z = static_cast<float>(p[2]);
    put(&x, 4);
    put(&p[1], 8);
    put(&z, 4);
    text += '\x07';
  }
  put(&corner_count, 4);
  for (std::int32_t k = 0; k < 4; ++k) put(&k, 4);
  return text;
}

/// OpenMesh's reader starts binary data 12 bytes after the header's last
/// word: a comment before end_header shifted it; the reader now gets a
/// header without comments.
TEST(GarmentLoad, BinaryPlyReadsInEitherByteOrderWhateverItsHeaderComments) {
  ScratchDir dir;
  for (const bool big : {false, true}) {
    for (const std::string extra : {"", "comment made by hand\n", "obj_info x\ncomment two\n\n"}) {
      const std::string name = std::string(big ? "big" : "little") + std::to_string(extra.size()) + ".ply";
      const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file(name), binary_quad_ply(big, extra, 4)));
      ASSERT_EQ(loaded.mesh.n_vertices(), 4u) << name;
      ASSERT_EQ(loaded.mesh.n_faces(), 1u) << name;
      EXPECT_EQ(loaded.mesh.point(QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(1.25, 0.1f, 0.5)) << name;
    }
  }
}

TEST(GarmentLoadErrors, BinaryPlyCutShortOrWithAHugeCornerCountIsRefused) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("minus.ply"), binary_quad_ply(false, "", -1)),
                    "the PLY binary data's face 0 has 4294967295 corners (as OpenMesh reads its int count), but only "
                    "16 bytes of data remain");
  std::string cut = binary_quad_ply(true, "", 4);
  cut.resize(cut.size() - 20);
  EXPECT_LOAD_ERROR(write_file(dir.file("cut.ply"), cut), "the PLY data ends at face 0");
  cut.resize(cut.size() - 30);  // 38 bytes of data: two 17-byte vertices
  EXPECT_LOAD_ERROR(write_file(dir.file("cut_more.ply"), cut), "the PLY data ends at vertex 2");
  std::string integer = binary_quad_ply(false, "", 4);
  integer.replace(integer.find("float x"), 7, "int x");
  EXPECT_LOAD_ERROR(write_file(dir.file("int.ply"), integer), "stores x as int; expected float or double");
}

TEST(GarmentLoad, UpperCaseMagicPlyReads) {
  ScratchDir dir;
  const std::string text = "PLY" + ply_header(4, 1).substr(3) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  EXPECT_EQ(mrcloth::load_garment(write_file(dir.file("upper.ply"), text)).mesh.n_faces(), 1u);
}

/// OpenMesh's OFF reader, given no counts, reserved for whatever its
/// variables held (77 GB under AddressSanitizer, which stops there).
TEST(GarmentLoadErrors, OffWithoutCountsIsRefused) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("bare.off"), "OFF\n"),
                    "the OFF header has no vertex and face counts; expected 'V F E' after OFF");
  EXPECT_LOAD_ERROR(write_file(dir.file("one.off"), "OFF\n# only vertices\n4\n0 0 0\n"),
                    "the OFF header has no vertex and face counts (line 3)");
}

TEST(GarmentLoadErrors, FirstProblemInFileOrderIsReported) {
  ScratchDir dir;
  // Face 1 repeats a vertex (seen by the OBJ scan), face 2 is out of range.
  EXPECT_LOAD_ERROR(write_file(dir.file("two.obj"),
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 1 2 3\nf 1 2 3 7\n"),
                    "face 1 (line 6) uses vertex 0 (line 1) more than once");
  // Face 1 cannot join face 0 (found by the importer) before face 2 repeats a vertex.
  EXPECT_LOAD_ERROR(write_file(dir.file("order.obj"),
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 -1 0\n"
                               "f 1 2 3 4\nf 1 2 3 5\nf 1 4 4 5\n"),
                    "face 1 (line 7) runs its edge from vertex 0 (line 1) to vertex 1 (line 2) the way face 0 (line 6) does");
}

TEST(GarmentLoadErrors, TextThatIsNotLinesOfUtf8IsNamed) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("mac.obj"), "v 0 0 0\rv 1 0 0\rv 1 1 0\rv 0 1 0\rf 1 2 3 4\r"),
                    "the file ends its lines with carriage returns alone (classic Mac OS); expected line ends LF or CR LF");
  std::string utf16 = "\xFF\xFE";
  for (const char c : std::string("v 0 0 0\n")) utf16 += std::string{c, '\0'};
  EXPECT_LOAD_ERROR(write_file(dir.file("wide.obj"), utf16), "the file is UTF-16 text");
  EXPECT_LOAD_ERROR(write_file(dir.file("wide.off"), utf16), "the file is UTF-16 text");
  EXPECT_LOAD_ERROR(write_file(dir.file("mac.off"), "OFF\r4 1 0\r0 0 0\r1 0 0\r1 1 0\r0 1 0\r4 0 1 2 3\r"),
                    "the file ends its lines with carriage returns alone");
  // A folder is named as one, whatever its name's suffix.
  std::filesystem::create_directory(dir.file("folder.obj"));
  std::filesystem::create_directory(dir.file("folder"));
  EXPECT_LOAD_ERROR(dir.file("folder.obj"), "cannot open file (it is a folder)");
  EXPECT_LOAD_ERROR(dir.file("folder"), "cannot open file (it is a folder)");
}

TEST(GarmentLoadErrors, OpenMeshDiagnosticsStayQuiet) {
  ScratchDir dir;
  const std::string fan = write_file(dir.file("fan.obj"), kThreeQuadsOnOneEdgeObj);
  const std::string range = write_file(dir.file("range.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 7\n");
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  EXPECT_THROW(mrcloth::load_garment(fan), mrcloth::InputError);
  EXPECT_THROW(mrcloth::load_garment(range), mrcloth::InputError);
  EXPECT_THROW(mrcloth::load_garment(dir.file("absent.ply")), mrcloth::InputError);
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
  EXPECT_TRUE(::omerr().is_enabled());
  EXPECT_TRUE(::omlog().is_enabled());
}

// --- saving --------------------------------------------------------------------

TEST(GarmentSave, OmKeepsPointsBitwiseAndEveryLayer) {
  ScratchDir dir;
  mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()), {"inch"});
  QuadMesh& mesh = loaded.mesh;
  // A hierarchy of three levels with hanging vertices, as refinement makes
  // it (the loader checks faces against their records).
  mrcloth::QuadRefiner refiner(mesh);
  const mrcloth::QuadSplit split = refiner.split(1);
  refiner.split(split.children[2]);
  ASSERT_TRUE(refiner.finish());
  const mrcloth::Layers l = mrcloth::get_layers(mesh);
  for (const auto v : mesh.vertices()) {
    const int i = v.idx();
    mesh.property(l.mode, v) = i % 4 + 1;
    mesh.property(l.r_value, v) = i / 3.0 + 1e-300;
  }
  const auto& forest = mesh.property(l.quadtree);
  ASSERT_GT(mrcloth::count_hanging(mesh), 0u);
  ASSERT_EQ(mrcloth::faces_per_level(mesh), (std::vector<std::size_t>{0, 5, 3, 4}));

  const std::string path = dir.file("saved.om");
  mrcloth::save_mesh(mesh, path);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"grid.obj", "saved.om"}));

  const mrcloth::LoadResult back = mrcloth::load_garment(path);
  const QuadMesh& copy = back.mesh;
  EXPECT_TRUE(back.warnings.empty());
  ASSERT_EQ(copy.n_vertices(), mesh.n_vertices());
  ASSERT_EQ(copy.n_faces(), mesh.n_faces());
  const mrcloth::Layers c = mrcloth::get_layers(copy);
  for (const auto v : mesh.vertices()) {
    const auto w = QuadMesh::VertexHandle(v.idx());
    EXPECT_EQ(std::memcmp(mesh.point(v).data(), copy.point(w).data(), 3 * sizeof(double)), 0) << v.idx();
    EXPECT_EQ(copy.property(c.mode, w), mesh.property(l.mode, v));
    EXPECT_EQ(std::memcmp(&copy.property(c.r_value, w), &mesh.property(l.r_value, v), sizeof(double)), 0);
    EXPECT_EQ(copy.property(c.hanging, w), mesh.property(l.hanging, v)) << v.idx();
    EXPECT_EQ(copy.property(c.parents, w), mesh.property(l.parents, v));
  }
  for (const auto f : mesh.faces()) {
    const auto g = QuadMesh::FaceHandle(f.idx());
    EXPECT_EQ(copy.property(c.level, g), mesh.property(l.level, f));
    EXPECT_EQ(copy.property(c.quad, g), mesh.property(l.quad, f));
    EXPECT_EQ(canonical_loop(copy, g), canonical_loop(mesh, f));
  }
  const auto& restored = copy.property(c.quadtree);
  ASSERT_EQ(restored.size(), forest.size());
  for (std::size_t i = 0; i < forest.size(); ++i) {
    EXPECT_EQ(restored[i].level, forest[i].level) << i;
    EXPECT_EQ(restored[i].active, forest[i].active) << i;
    EXPECT_EQ(restored[i].parent, forest[i].parent) << i;
    EXPECT_EQ(restored[i].children, forest[i].children) << i;
    EXPECT_EQ(restored[i].corners, forest[i].corners) << i;
  }
}

/// Layers that disagree with the hierarchy (a file of an older mrcloth,
/// without the checksum, damaged; or edited by another program) are refused:
/// a face whose level or polygon is not its record's would simulate with
/// another level's stiffness, and parents naming a later vertex form a
/// cycle the polygon walk recursed along without end.
TEST(GarmentLoadErrors, StoredLayersThatDisagreeWithTheHierarchyAreRefused) {
  ScratchDir dir;
  const auto refined = [&dir] {
    QuadMesh mesh = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj())).mesh;
    mrcloth::QuadRefiner refiner(mesh);
    refiner.split(1);
    EXPECT_TRUE(refiner.finish());
    return mesh;
  };
  QuadMesh level = refined();
  const mrcloth::Layers l = mrcloth::get_layers(level);
  level.property(l.level, QuadMesh::FaceHandle(4)) += 1;
  mrcloth::save_mesh(level, dir.file("level.om"));
  EXPECT_LOAD_ERROR(dir.file("level.om"), "the stored refinement hierarchy is damaged (face 4 is not the polygon or "
                                          "level of its record)");

  QuadMesh twice = refined();
  twice.property(l.quad, QuadMesh::FaceHandle(2)) = twice.property(l.quad, QuadMesh::FaceHandle(3));
  mrcloth::save_mesh(twice, dir.file("twice.om"));
  EXPECT_LOAD_ERROR(dir.file("twice.om"), "(face 3 names no active record, or one an earlier face names)");

  QuadMesh cycle = refined();
  const int last = static_cast<int>(cycle.n_vertices()) - 1;
  // The last vertex the midpoint of coarse edge 0-1, and 1 that of 0-last.
  cycle.property(l.parents, QuadMesh::VertexHandle(last)) = OpenMesh::Vec2i(0, 1);
  cycle.property(l.parents, QuadMesh::VertexHandle(1)) = OpenMesh::Vec2i(0, last);
  mrcloth::save_mesh(cycle, dir.file("cycle.om"));
  EXPECT_LOAD_ERROR(dir.file("cycle.om"), "the stored layers are damaged (vertex 1 names edge ends 0, " +
                                              std::to_string(last) + ")");
}

TEST(GarmentLoadErrors, WhatNoGarmentCanBeIsRefusedAtLoading) {
  ScratchDir dir;
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  // Two quads that share only a corner: a bow-tie vertex.
  EXPECT_LOAD_ERROR(write_file(dir.file("bowtie.obj"),
                               square + "v 2 1 0\nv 2 2 0\nv 1 2 0\nf 1 2 3 4\nf 3 5 6 7\n"),
                    "vertex 2 (line 3) is non-manifold (two fans of faces meet only at it, a bow-tie)");
  EXPECT_LOAD_ERROR(write_file(dir.file("loose.obj"), square + "v 5 5 5\nv 6 6 6\nf 1 2 3 4\n"),
                    "vertex 4 (line 5) belongs to no face (nor do 1 more)");
  EXPECT_LOAD_ERROR(write_file(dir.file("line.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n" + square +
                                                         "f 5 6 7 8\nf 1 2 3 4\n"),
                    "face 1 (line 10) has no area");
  // Crossed as a bow-tie: the halves cancel.
  EXPECT_LOAD_ERROR(write_file(dir.file("twisted.obj"), "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n"),
                    "face 0 (line 5) has no area");
  // Beyond float range OpenMesh's reader would drop the vertex and shift the faces.
  EXPECT_LOAD_ERROR(write_file(dir.file("huge.obj"), "v 0 0 0\nv 1e39 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"),
                    "vertex 1 (line 2) has a coordinate beyond single precision's range (1e39)");
  // OpenMesh's PLY reader never returns from a header without its end.
  EXPECT_LOAD_ERROR(write_file(dir.file("open.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"),
                    "the PLY header has no 'end_header' line");
}

TEST(GarmentLoadErrors, OffHeadersOpenMeshWouldMisreadAreRefused) {
  ScratchDir dir;
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  // More than the data holds: OpenMesh read faces as vertices, or allocated for 1e12.
  EXPECT_LOAD_ERROR(write_file(dir.file("few.off"), "OFF\n5 1 0\n" + body),
                    "the OFF header (line 2) declares 5 vertices and 1 faces, but only 5 lines of data follow");
  EXPECT_LOAD_ERROR(write_file(dir.file("huge.off"), "OFF\n999999999999 1 0\n" + body), "declares 999999999999 vertices");
  EXPECT_LOAD_ERROR(write_file(dir.file("words.off"), "OFF\nabc 1 0\n" + body),
                    "the OFF header's vertex count 'abc' (line 2) is not a count");
  // Not an OFF variant: OpenMesh took "OFFX" for one.
  EXPECT_LOAD_ERROR(write_file(dir.file("offx.off"), "OFFX\n4 1 0\n" + body), "the file starts with 'OFFX'");
  // The counts on the header's line are legal, though OpenMesh reads them only on their own.
  const mrcloth::LoadResult same_line = mrcloth::load_garment(write_file(dir.file("same.off"), "OFF 4 1 0\n" + body));
  EXPECT_EQ(same_line.mesh.n_vertices(), 4u);
  EXPECT_EQ(same_line.mesh.n_faces(), 1u);
}

TEST(GarmentLoad, UnweldedSeamsAreNamedInAWarning) {
  ScratchDir dir;
  // Two squares side by side, their shared side written twice (as panels are exported).
  const std::string panels = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\n"
                             "f 1 2 3 4\nf 5 6 7 8\n";
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("panels.obj"), panels));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("2 pairs of boundary vertices lie on one another, the first vertex 1 (line 2) on vertex 4 (line 5): "),
            std::string::npos)
      << loaded.warnings[0];
  // Welded, nothing to say.
  const std::string welded = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 5 6 3\n";
  EXPECT_TRUE(mrcloth::load_garment(write_file(dir.file("welded.obj"), welded)).warnings.empty());
  // The two ends of one very short edge are no seam: welding them would collapse the face.
  const std::string sliver = "v 0 0 0\nv 1 0 0\nv 1 1e-9 0\nv 0 1e-9 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\nf 4 3 6 5\n";
  EXPECT_TRUE(mrcloth::load_garment(write_file(dir.file("sliver.obj"), sliver)).warnings.empty());
}

TEST(GarmentLoad, AConcaveFaceIsNamedInAWarning) {
  // A dart: corner 2 of (0,0) (2,0) (0.5,0.5) (0,2) turns inwards, and the
  // bilinear split folds a child over another.
  ScratchDir dir;
  const std::string dart = "v 0 0 0\nv 2 0 0\nv 0.5 0.5 0\nv 0 2 0\nf 1 2 3 4\n";
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("dart.obj"), dart));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("dart.obj: face 0 (line 5) is concave at its corner 2: refining it folds a child face over another"),
            std::string::npos)
      << loaded.warnings[0];
  // The same turned the other way (clockwise) is as concave; a kite is not.
  EXPECT_EQ(mrcloth::load_garment(write_file(dir.file("dart_cw.obj"), "v 0 0 0\nv 0 2 0\nv 0.5 0.5 0\nv 2 0 0\nf 1 2 3 4\n"))
                .warnings.size(), 1u);
  EXPECT_TRUE(mrcloth::load_garment(write_file(dir.file("kite.obj"), "v 0 0 0\nv 2 0 0\nv 1.5 1.5 0\nv 0 2 0\nf 1 2 3 4\n"))
                  .warnings.empty());
}

TEST(GarmentLoad, LinesContinuedByABackslashAreJoinedAndLaterLinesKeepTheirNumbers) {
  ScratchDir dir;
  const std::string square = "v 0 0 0\nv 1 0 \\\n0\nv 1 1 0\nv 0 1 0\n";
  const mrcloth::LoadResult joined = mrcloth::load_garment(write_file(dir.file("joined.obj"), square + "f 1 2 \\\n3 4\n"));
  EXPECT_EQ(joined.mesh.n_vertices(), 4u);
  EXPECT_EQ(joined.mesh.n_faces(), 1u);
  EXPECT_EQ(joined.mesh.point(QuadMesh::VertexHandle(1)), OpenMesh::Vec3d(1, 0, 0));
  // Line 6 (after the continued line 2-3) is named as line 6.
  EXPECT_LOAD_ERROR(write_file(dir.file("bad.obj"), square + "f 1 2 3 9\n"), "face 0 (line 6) refers to vertex 9");
}

TEST(GarmentLoad, AByteOrderMarkBeforeTheFirstVertexIsSkipped) {
  ScratchDir dir;
  const mrcloth::LoadResult marked =
      mrcloth::load_garment(write_file(dir.file("marked.obj"), "\xEF\xBB\xBF" + grid_obj().substr(std::string("# grid\no grid\n").size())));
  expect_grid_as_read(marked, 1.0);
}

TEST(GarmentLoadErrors, ADamagedStoredHierarchyIsRefused) {
  ScratchDir dir;
  mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  QuadMesh& mesh = loaded.mesh;
  const mrcloth::Layers l = mrcloth::get_layers(mesh);
  // As a cut-short file reads: a child that is not there, a corner that is no vertex.
  mesh.property(l.quadtree)[2].children = {6, 7, 8, 9};
  mrcloth::save_mesh(mesh, dir.file("child.om"));
  EXPECT_LOAD_ERROR(dir.file("child.om"), "the stored refinement hierarchy is damaged (record 2 has a child out of place)");
  mesh.property(l.quadtree)[2].children = {-1, -1, -1, -1};
  mesh.property(l.quadtree)[3].corners[1] = 12;
  mrcloth::save_mesh(mesh, dir.file("corner.om"));
  EXPECT_LOAD_ERROR(dir.file("corner.om"), "(record 3 has a corner that is not a vertex)");
  mesh.property(l.quadtree)[3].corners[1] = 1;
  mesh.property(l.quadtree)[4].active = 0;
  mrcloth::save_mesh(mesh, dir.file("inactive.om"));
  EXPECT_LOAD_ERROR(dir.file("inactive.om"), "(5 active records for 6 faces)");
}

TEST(GarmentSave, OmWithoutForestIsMadeRefinable) {
  // A .om written by plain OpenMesh has no mrcloth layers: it loads like any mesh.
  ScratchDir dir;
  QuadMesh plain;
  const mrcloth::LoadResult grid = mrcloth::load_garment(write_file(dir.file("grid.off"), grid_off()));
  for (const auto v : grid.mesh.vertices()) plain.add_vertex(grid.mesh.point(v));
  for (const auto& f : grid_faces())
    plain.add_face({QuadMesh::VertexHandle(f[0]), QuadMesh::VertexHandle(f[1]), QuadMesh::VertexHandle(f[2]),
                    QuadMesh::VertexHandle(f[3])});
  const std::string path = dir.file("plain.om");
  ::omlog().disable();  // the OM writer reports its byte count there
  const bool written = OpenMesh::IO::write_mesh(plain, path, OpenMesh::IO::Options::Binary);
  ::omlog().enable();
  ASSERT_TRUE(written);
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path, {"dm"});
  expect_grid_as_read(loaded, 0.1);
}

TEST(GarmentSave, TextFormatsRoundTripDoublesExactly) {
  ScratchDir dir;
  mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.ply"), grid_ply()));
  QuadMesh& mesh = loaded.mesh;
  // Values no decimal short form or float would keep.
  mesh.point(QuadMesh::VertexHandle(0)) = OpenMesh::Vec3d(1.0 / 3.0, -2.0 / 7.0, 1e-310);
  mesh.point(QuadMesh::VertexHandle(5)) = OpenMesh::Vec3d(std::nextafter(1.0, 2.0), 123456.789e10, -0.0);
  for (const std::string name : {"out.obj", "out.off", "out.ply", "OUT.OBJ"}) {
    const std::string path = dir.file(name);
    mrcloth::save_mesh(mesh, path);
    const mrcloth::LoadResult back = mrcloth::load_garment(path);
    // Vertex 5 so far off turns faces around it inside out (concave), and
    // only that is said: every coordinate was read back exactly.
    for (const std::string& warning : back.warnings)
      EXPECT_NE(warning.find("is concave"), std::string::npos) << name << ": " << warning;
    ASSERT_EQ(back.mesh.n_vertices(), mesh.n_vertices()) << name;
    ASSERT_EQ(back.mesh.n_faces(), mesh.n_faces()) << name;
    for (const auto v : mesh.vertices()) {
      EXPECT_EQ(std::memcmp(mesh.point(v).data(), back.mesh.point(v).data(), 3 * sizeof(double)), 0)
          << name << " vertex " << v.idx();
    }
    for (const auto f : mesh.faces()) EXPECT_EQ(canonical_loop(back.mesh, f), canonical_loop(mesh, f)) << name;
  }
}

/// The `f` lines of an OBJ, as written.
std::vector<std::string> obj_faces(const std::string& text) {
  std::vector<std::string> faces;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("f ", 0) == 0) faces.push_back(line);
  return faces;
}

// A simulated frame exported triangulated keeps the rest shape's triangles:
// a square fans along its diagonal 1-3; in a frame where corner 2 has moved
// next to that diagonal the frame alone would fan along 2-4 (the DCC tool
// reading a sequence saw the diagonals flip from frame to frame).
TEST(GarmentExport, FramesTriangulateAsTheirRestShape) {
  ScratchDir dir;
  const QuadMesh rest =
      mrcloth::load_garment(write_file(dir.file("square.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")).mesh;
  QuadMesh frame = rest;
  frame.set_point(QuadMesh::VertexHandle(1), OpenMesh::Vec3d(0.45, 0.55, 0.2));
  mrcloth::ExportOptions options;
  options.triangulate = true;
  mrcloth::export_surface(rest, dir.file("rest.obj"), options);
  mrcloth::export_surface(frame, dir.file("alone.obj"), options);
  options.triangles_of = &rest;
  mrcloth::export_surface(frame, dir.file("frame.obj"), options);
  const std::vector<std::string> rest_faces = obj_faces(read_file(dir.file("rest.obj")));
  ASSERT_EQ(rest_faces.size(), 2u);
  EXPECT_NE(obj_faces(read_file(dir.file("alone.obj"))), rest_faces) << "the frame alone fans the other way";
  EXPECT_EQ(obj_faces(read_file(dir.file("frame.obj"))), rest_faces);
  EXPECT_NE(read_file(dir.file("frame.obj")).find("v 0.45 0.55 0.2"), std::string::npos) << "the frame's positions";
  // Another mesh to triangulate as is refused.
  const QuadMesh other = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj())).mesh;
  options.triangles_of = &other;
  try {
    mrcloth::export_surface(frame, dir.file("wrong.obj"), options);
    ADD_FAILURE() << "another mesh to triangulate as was taken";
  } catch (const mrcloth::ArgumentError& error) {
    EXPECT_EQ(std::string(error.what()), dir.file("wrong.obj") + ": the mesh to triangulate as has " +
                                             std::to_string(other.n_vertices()) + " vertices and " +
                                             std::to_string(other.n_faces()) +
                                             " faces, the mesh exported 4 and 1; expected the same mesh at other positions");
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("wrong.obj")));
}

TEST(GarmentSave, FailedSavesLeaveNoFileBehind) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::vector<std::string> before = dir.entries();

  const std::string nowhere = dir.file("no_such_folder/out.om");
  try {
    mrcloth::save_mesh(loaded.mesh, nowhere);
    ADD_FAILURE() << "saved into a missing folder";
  } catch (const mrcloth::OutputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(nowhere + ": cannot write file", 0), 0u) << e.what();
  }
  EXPECT_THROW(mrcloth::save_mesh(loaded.mesh, dir.file("out.stl")), mrcloth::ArgumentError);
  EXPECT_THROW(mrcloth::save_mesh(loaded.mesh, dir.file("out")), mrcloth::ArgumentError);
  EXPECT_THROW(mrcloth::export_surface(loaded.mesh, dir.file("out.off")), mrcloth::ArgumentError);
  EXPECT_THROW(mrcloth::export_surface(loaded.mesh, dir.file("no_such_folder/out.ply")), mrcloth::OutputError);
  EXPECT_EQ(dir.entries(), before);

  fs::create_directories(dir.file("taken.om"));
  EXPECT_THROW(mrcloth::save_mesh(loaded.mesh, dir.file("taken.om")), mrcloth::OutputError);
  std::vector<std::string> expected = before;
  expected.push_back("taken.om");
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(dir.entries(), expected);
  EXPECT_TRUE(fs::is_empty(dir.file("taken.om")));
}

TEST(GarmentSave, TheLongestLegalNamesAreWritten) {
  // The temporary file beside the target adds ~20 bytes to its name; a
  // target name of 255 bytes (NAME_MAX), ASCII or multi-byte, still saves.
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::string ascii = std::string(252, 'a') + ".om";
  std::string wide;
  while (wide.size() + 3 + 4 <= 255) wide += "\xe6\x97\xa5";  // U+65E5, three bytes each
  wide += ".obj";
  for (const std::string& name : {ascii, wide}) {
    ASSERT_LE(name.size(), 255u);
    mrcloth::save_mesh(loaded.mesh, dir.file(name));
    EXPECT_EQ(mrcloth::load_garment(dir.file(name)).mesh.n_faces(), static_cast<std::size_t>(kGridFaces)) << name.size();
  }
  std::vector<std::string> expected{"grid.obj", ascii, wide};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(dir.entries(), expected);
}

TEST(GarmentSave, AFileWhereTheFolderShouldBeIsNamedAsSuch) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::string path = dir.file("grid.obj/out.om");
  try {
    mrcloth::save_mesh(loaded.mesh, path);
    ADD_FAILURE() << "saved below a file";
  } catch (const mrcloth::OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("grid.obj' is a file, not a folder"), std::string::npos) << e.what();
  }
}

TEST(GarmentSave, OmBytesAreOpenMeshsOwn) {
  // write_om encodes in memory (OpenMesh's writer asserts on a failed
  // write: a full disk aborted the host); the bytes are the ones OpenMesh
  // writes to a file itself, but for the checksum layer's eight, which
  // hold the FNV-1a hash of all the others.
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  mrcloth::save_mesh(loaded.mesh, dir.file("ours.om"));
  ASSERT_TRUE(OpenMesh::IO::write_mesh(loaded.mesh, dir.file("openmesh.om"), OpenMesh::IO::Options::Binary));
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  std::string ours = bytes(dir.file("ours.om"));
  const std::string theirs = bytes(dir.file("openmesh.om"));
  EXPECT_GT(ours.size(), 100u);
  const std::size_t name = ours.find(mrcloth::layer::checksum);
  ASSERT_NE(name, std::string::npos);
  const std::size_t type = name + std::string(mrcloth::layer::checksum).size();
  const std::size_t value = type + 1 + static_cast<unsigned char>(ours[type]) + 4;
  ASSERT_LE(value + 8, ours.size());
  std::uint64_t hash = 14695981039346656037ull, stored = 0;
  for (std::size_t k = 0; k < ours.size(); ++k)
    hash = (hash ^ ((k >= value && k < value + 8) ? 0u : static_cast<unsigned char>(ours[k]))) * 1099511628211ull;
  for (std::size_t k = 0; k < 8; ++k) stored |= std::uint64_t{static_cast<unsigned char>(ours[value + k])} << (8 * k);
  EXPECT_EQ(stored, hash);
  ours.replace(value, 8, std::string(8, '\0'));
  EXPECT_EQ(ours, theirs);
}

TEST(GarmentSave, AnOmRoundTripAddsNoLayers) {
  // A mesh never analysed has no curvature or computed-mode layers; saved
  // as .om and loaded it still has none (the reader needs them made first),
  // and saving it again gives the same bytes. One analysed keeps its own.
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const auto has = [](const mrcloth::QuadMesh& mesh, const char* name) {
    OpenMesh::VPropHandleT<double> real;
    OpenMesh::VPropHandleT<int> whole;
    return mesh.get_property_handle(real, name) || mesh.get_property_handle(whole, name);
  };
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  mrcloth::save_mesh(loaded.mesh, dir.file("first.om"));
  const mrcloth::LoadResult again = mrcloth::load_garment(dir.file("first.om"));
  for (const char* name : {mrcloth::layer::mean_curvature, mrcloth::layer::curvature_deviation, mrcloth::layer::computed_mode})
    EXPECT_FALSE(has(again.mesh, name)) << name;
  mrcloth::save_mesh(again.mesh, dir.file("second.om"));
  EXPECT_EQ(bytes(dir.file("second.om")), bytes(dir.file("first.om")));

  mrcloth::QuadMesh analysed = mrcloth::copy_mesh(loaded.mesh);
  mrcloth::set_vertex_layer(analysed, mrcloth::layer::mean_curvature, std::vector<double>(analysed.n_vertices(), 2.5));
  mrcloth::save_mesh(analysed, dir.file("analysed.om"));
  const mrcloth::LoadResult kept = mrcloth::load_garment(dir.file("analysed.om"));
  EXPECT_TRUE(has(kept.mesh, mrcloth::layer::mean_curvature));
  EXPECT_FALSE(has(kept.mesh, mrcloth::layer::curvature_deviation));
  EXPECT_EQ(mrcloth::vertex_layer(kept.mesh, mrcloth::layer::mean_curvature),
            std::vector<double>(analysed.n_vertices(), 2.5));
}

TEST(GarmentSave, AnOmOfMrclothLoadedInOtherUnitsIsWarnedOf) {
  // save_mesh writes metres: a units option scales the mesh (as the option
  // says) but not its layers in metres, so the load says so; in metres,
  // nothing is said.
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  mrcloth::save_mesh(loaded.mesh, dir.file("saved.om"));
  EXPECT_TRUE(mrcloth::load_garment(dir.file("saved.om")).warnings.empty());
  mrcloth::LoadOptions centimetres;
  centimetres.units = "cm";
  const mrcloth::LoadResult scaled = mrcloth::load_garment(dir.file("saved.om"), centimetres);
  ASSERT_EQ(scaled.warnings.size(), 1u);
  EXPECT_EQ(scaled.warnings[0], dir.file("saved.om") +
                                    ": mrcloth saved this mesh in metres; units 'cm' scale it by 0.01 (its curvature "
                                    "layers, in 1/m, are not rescaled): give units 'm' to load it as saved");
  EXPECT_EQ(scaled.mesh.point(scaled.mesh.vertex_handle(5)), loaded.mesh.point(loaded.mesh.vertex_handle(5)) * 0.01);
}

TEST(GarmentSave, SaveReplacesAnExistingFile) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::string path = write_file(dir.file("out.obj"), "old contents\n");
  mrcloth::save_mesh(loaded.mesh, path);
  EXPECT_EQ(mrcloth::load_garment(path).mesh.n_faces(), static_cast<std::size_t>(kGridFaces));
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"grid.obj", "out.obj"}));
}

// --- exporting -----------------------------------------------------------------

TEST(GarmentExport, PaletteHasDistinctColoursAndGreyForUnset) {
  const auto grey = mrcloth::palette_color(0);
  EXPECT_EQ(mrcloth::palette_color(-4), grey);
  std::vector<std::array<unsigned char, 3>> colours;
  for (int value = 1; value <= 9; ++value) {
    const auto colour = mrcloth::palette_color(value);
    EXPECT_NE(colour, grey) << value;
    EXPECT_EQ(std::count(colours.begin(), colours.end(), colour), 0) << "value " << value << " repeats a colour";
    colours.push_back(colour);
  }
  EXPECT_EQ(mrcloth::palette_color(1), (std::array<unsigned char, 3>{31, 119, 180}));
  // Every mode a mesh may hold has its own colour (10 drew as 1 before).
  std::set<std::array<unsigned char, 3>> all{grey};
  for (int value = 1; value <= mrcloth::kLargestMode; ++value)
    EXPECT_TRUE(all.insert(mrcloth::palette_color(value)).second) << "value " << value << " repeats a colour";
}

TEST(GarmentExport, PlyWithModeColoursReadsBackInOpenMesh) {
  ScratchDir dir;
  mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()), {"dm"});
  QuadMesh& mesh = loaded.mesh;
  const auto mode = mrcloth::get_layers(mesh).mode;
  for (const auto v : mesh.vertices()) mesh.property(mode, v) = v.idx() % 5;  // includes 0 (grey)
  const std::string path = dir.file("modes.ply");
  mrcloth::export_surface(mesh, path, {mrcloth::ColorBy::mode, false});

  OpenMesh::PolyMesh_ArrayKernelT<> back;
  back.request_vertex_colors();
  OpenMesh::IO::Options options(OpenMesh::IO::Options::VertexColor);
  ASSERT_TRUE(OpenMesh::IO::read_mesh(back, path, options));
  EXPECT_TRUE(options.check(OpenMesh::IO::Options::VertexColor));
  ASSERT_EQ(back.n_vertices(), static_cast<std::size_t>(kGridVertices));
  ASSERT_EQ(back.n_faces(), static_cast<std::size_t>(kGridFaces));
  for (const auto v : back.vertices()) {
    const auto expected = mrcloth::palette_color(v.idx() % 5);
    const auto colour = back.color(v);
    EXPECT_EQ((std::array<unsigned char, 3>{colour[0], colour[1], colour[2]}), expected) << "vertex " << v.idx();
    const OpenMesh::Vec3d& p = mesh.point(QuadMesh::VertexHandle(v.idx()));
    EXPECT_NEAR(back.point(v)[0], p[0], 1e-6);
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"grid.obj", "modes.ply"}));
}

TEST(GarmentExport, ObjTriangulatedWithLevelColours) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.off"), grid_off()));
  const std::string path = dir.file("levels.obj");
  mrcloth::export_surface(loaded.mesh, path, {mrcloth::ColorBy::level, true});
  std::istringstream text(read_file(path));
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  const auto level1 = mrcloth::palette_color(1);
  for (std::string line; std::getline(text, line);) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    std::vector<double> numbers;
    for (double x; words >> x;) numbers.push_back(x);
    if (key == "v") {
      ASSERT_EQ(numbers.size(), 6u) << line;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(std::lround(numbers[3 + k] * 255.0), level1[k]) << line;
      ++vertices;
    } else if (key == "f") {
      EXPECT_EQ(numbers.size(), 3u) << line;
      ++triangles;
    }
  }
  EXPECT_EQ(vertices, static_cast<std::size_t>(kGridVertices));
  EXPECT_EQ(triangles, 2u * kGridFaces);
}

// Level colours follow the faces, as the previews show them: a vertex takes
// the finest level of its faces. Two quads side by side, the left one split:
// every vertex but the right quad's two far corners is level 2 (its corners
// and the shared edge's ends were level 1, coarse specks in the refined quad).
TEST(GarmentExport, LevelColoursAreTheFinestOfEachVertexsFaces) {
  ScratchDir dir;
  QuadMesh mesh = mrcloth::load_garment(write_file(dir.file("two.obj"),
                                                   "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
                                                   "f 1 2 5 4\nf 2 3 6 5\n")).mesh;
  mrcloth::QuadRefiner refiner(mesh);
  refiner.split(0);
  ASSERT_TRUE(refiner.finish());
  const std::string path = dir.file("levels.obj");
  mrcloth::export_surface(mesh, path, {mrcloth::ColorBy::level, false});
  std::istringstream text(read_file(path));
  std::vector<std::array<long, 3>> colours;
  for (std::string line; std::getline(text, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream words(line.substr(2));
    std::vector<double> numbers;
    for (double x; words >> x;) numbers.push_back(x);
    ASSERT_EQ(numbers.size(), 6u) << line;
    colours.push_back({std::lround(numbers[3] * 255.0), std::lround(numbers[4] * 255.0), std::lround(numbers[5] * 255.0)});
  }
  ASSERT_EQ(colours.size(), mesh.n_vertices());
  const auto as_long = [](const std::array<unsigned char, 3>& c) { return std::array<long, 3>{c[0], c[1], c[2]}; };
  const auto level1 = as_long(mrcloth::palette_color(1)), level2 = as_long(mrcloth::palette_color(2));
  for (std::size_t v = 0; v < colours.size(); ++v)
    EXPECT_EQ(colours[v], v == 2 || v == 5 ? level1 : level2) << "vertex " << v;
}

TEST(GarmentExport, UncolouredPlyHasNoColourProperties) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::string path = dir.file("plain.ply");
  mrcloth::export_surface(loaded.mesh, path);
  const std::string text = read_file(path);
  EXPECT_EQ(text.find("red"), std::string::npos);
  EXPECT_NE(text.find("element face 6\n"), std::string::npos);
  const mrcloth::LoadResult back = mrcloth::load_garment(path);
  EXPECT_EQ(back.mesh.n_faces(), static_cast<std::size_t>(kGridFaces));
}

// --- real data -----------------------------------------------------------------

TEST(GarmentRealData, MakeHumanSkirtHelperInDecimetres) {
  const std::string path = std::string(MRCLOTH_SHARED_DATA) + "/garments/makehuman/skirthelper.obj";
  if (!fs::exists(path)) GTEST_SKIP() << "shared data not found at " << path;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path, {"dm"});
  const QuadMesh& mesh = loaded.mesh;
  EXPECT_EQ(mesh.n_vertices(), 720u);
  EXPECT_EQ(mesh.n_faces(), 684u);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const auto v : mesh.vertices()) {
    low = std::min(low, mesh.point(v)[1]);
    high = std::max(high, mesh.point(v)[1]);
  }
  // The file's y spans -7.2846 .. 1.8385 decimetres.
  EXPECT_NEAR(low, -0.72846, 1e-12);
  EXPECT_NEAR(high, 0.18385, 1e-12);
  EXPECT_EQ(mrcloth::quadtree(mesh).size(), 684u);
}

namespace {

/// Little-endian bytes of a 32-bit value, as binary OFF stores it.
template <class T>
void append_le(std::string& bytes, T value) {
  static_assert(sizeof(T) == 4);
  char raw[4];
  std::memcpy(raw, &value, 4);
  bytes.append(raw, 4);
}

/// A unit square in binary OFF: "OFF BINARY", counts, floats, one quad.
std::string binary_off_square(std::uint32_t vertices = 4, std::uint32_t faces = 1, std::uint32_t corners = 4) {
  std::string bytes = "OFF BINARY\n";
  append_le(bytes, vertices);
  append_le(bytes, faces);
  append_le(bytes, std::uint32_t{0});
  const float points[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (const auto& p : points)
    for (const float c : p) append_le(bytes, c);
  append_le(bytes, corners);
  for (std::uint32_t k = 0; k < 4; ++k) append_le(bytes, k);
  return bytes;
}

}  // namespace

// OpenMesh's OFF reader keeps what the last file it checked by name said
// of itself (binary, colours, normals) and applies it to text it is handed
// as a stream: the ASCII OFF read after a binary one was read as binary.
TEST(GarmentLoad, OffReadsDoNotInheritTheLastFilesLayout) {
  ScratchDir dir;
  const mrcloth::LoadResult binary = mrcloth::load_garment(write_file(dir.file("square.off"), binary_off_square()));
  EXPECT_EQ(binary.mesh.n_faces(), 1u);
  // A comment makes the loader hand OpenMesh a cleaned copy as a stream.
  const std::string text = "OFF\n# a comment\n4 1 0\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n4 0 1 2 3\n";
  const mrcloth::LoadResult ascii = mrcloth::load_garment(write_file(dir.file("commented.off"), text));
  ASSERT_EQ(ascii.mesh.n_vertices(), 4u);
  EXPECT_EQ(ascii.mesh.point(mrcloth::QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(2, 2, 0));
  // And a coloured OFF's layout does not carry over either.
  const std::string coloured = "COFF\n4 1 0\n0 0 0 255 0 0\n3 0 0 0 255 0\n3 3 0 0 0 255\n0 3 0 9 9 9\n4 0 1 2 3\n";
  EXPECT_EQ(mrcloth::load_garment(write_file(dir.file("coloured.off"), coloured)).mesh.n_vertices(), 4u);
  const mrcloth::LoadResult again = mrcloth::load_garment(write_file(dir.file("again.off"), text));
  EXPECT_EQ(again.mesh.point(mrcloth::QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(2, 2, 0));
}

// OpenMesh's binary OFF reader trusts its counts: a face count of 2^32 - 1
// kept it reading past the end of the file for minutes (found by the
// mutation sweep), a corner count as large pushes billions of corners.
TEST(GarmentLoadErrors, BinaryOffCountsAreCheckedAgainstTheData) {
  ScratchDir dir;
  const mrcloth::LoadResult square = mrcloth::load_garment(write_file(dir.file("square.off"), binary_off_square()));
  ASSERT_EQ(square.mesh.n_vertices(), 4u);
  EXPECT_EQ(square.mesh.point(mrcloth::QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(1, 1, 0));
  EXPECT_LOAD_ERROR(write_file(dir.file("faces.off"), binary_off_square(4, 0xFFFFFFFFu)),
                    "the binary OFF header declares 4 vertices and 4294967295 faces, which need at least 17179869228 "
                    "bytes; 68 follow");
  EXPECT_LOAD_ERROR(write_file(dir.file("vertices.off"), binary_off_square(6)),
                    "the binary OFF header declares 6 vertices and 1 faces, which need at least 76 bytes; 68 follow");
  // One vertex more than written: the face's bytes are read from its last corner on.
  EXPECT_LOAD_ERROR(write_file(dir.file("askew.off"), binary_off_square(5)), "face 0 (byte 83) has corner count 2 and 1 indices' bytes left");
  EXPECT_LOAD_ERROR(write_file(dir.file("corners.off"), binary_off_square(4, 1, 0x7FFFFFFFu)),
                    "face 0 (byte 71) has corner count 2147483647 and 4 indices' bytes left");
  EXPECT_LOAD_ERROR(write_file(dir.file("two.off"), binary_off_square(4, 1, 2)),
                    "face 0 (byte 71) has corner count 2 and 4 indices' bytes left; expected at least 3 corners");
  std::string far = binary_off_square();
  far[far.size() - 4] = 9;  // the last corner names vertex 9
  EXPECT_LOAD_ERROR(write_file(dir.file("far.off"), far), "face 0 names vertex 9; expected an index below 4");
  EXPECT_LOAD_ERROR(write_file(dir.file("one_line.off"), "OFF BINARY " + binary_off_square().substr(11, 20)),
                    "the binary OFF has no line end after 'OFF BINARY'");
  EXPECT_LOAD_ERROR(write_file(dir.file("short.off"), binary_off_square().substr(0, 19)),
                    "the binary OFF ends before its vertex, face and edge counts");
  std::string coloured = binary_off_square();
  coloured.insert(0, "C");
  EXPECT_LOAD_ERROR(write_file(dir.file("coloured.off"), coloured),
                    "binary COFF (with normals, colours or texture coordinates) is not supported");
  EXPECT_LOAD_ERROR(write_file(dir.file("second.off"), "# made by hand\n" + binary_off_square()),
                    "the 'OFF BINARY' line is line 2; expected it first");
}
