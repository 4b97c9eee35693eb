#include "garment_io_support.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/mode_painting.h"
#include "mesh_ops/quadtree_forest.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>

namespace mrcloth::test {

namespace fs = std::filesystem;

namespace {

// A 4 x 3 vertex grid of 3 x 2 quads. Coordinates are decimals that a float
// cannot hold, so a single-precision read would show.
const char* const kX[4] = {"0.3", "1.7", "2.9", "-4.1"};
const char* const kY[3] = {"-0.7", "0.45", "1.3"};
const char* const kZ[3] = {"0.1", "0.0123456789", "7.77"};

std::vector<std::string> grid_vertex_lines() {
  std::vector<std::string> lines;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) lines.push_back(std::string(kX[i]) + " " + kY[j] + " " + kZ[j]);
  return lines;
}

OpenMesh::Vec3d grid_point_in_file(int v) {
  return {std::strtod(kX[v % 4], nullptr), std::strtod(kY[v / 4], nullptr), std::strtod(kZ[v / 4], nullptr)};
}

/// Little-endian bytes of a 32-bit value, as binary OFF stores it.
template <class T>
void append_le(std::string& bytes, T value) {
  static_assert(sizeof(T) == 4);
  char raw[4];
  std::memcpy(raw, &value, 4);
  bytes.append(raw, 4);
}

}  // namespace

ScratchDir::ScratchDir() {
  const char* root = std::getenv("MRCLOTH_TEST_TMP");
  const fs::path base = root && *root ? fs::path(root) : fs::temp_directory_path() / "mrcloth-test";
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  path_ = base / (std::string("garment_io-") + info->test_suite_name() + "-" + info->name());
  fs::remove_all(path_);
  fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

std::vector<std::string> ScratchDir::entries() const {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(path_)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

std::string load_error(const std::string& path, const std::string& units) {
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

std::vector<std::array<int, 4>> grid_faces() {
  std::vector<std::array<int, 4>> faces;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) faces.push_back({j * 4 + i, j * 4 + i + 1, (j + 1) * 4 + i + 1, (j + 1) * 4 + i});
  return faces;
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

std::string binary_off_square(std::uint32_t vertices, std::uint32_t faces, std::uint32_t corners) {
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

}  // namespace mrcloth::test
