#pragma once
// Helpers shared by the garment_io tests (garment_load_test.cpp,
// garment_load_errors_test.cpp, garment_save_test.cpp): a scratch folder per
// test, files written into it, and a small quad grid in OBJ, OFF and PLY.
#include "mesh_ops/garment_io.h"
#include "mesh_ops/quad_mesh.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace mrcloth::test {

/// A fresh folder per test, removed afterwards.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::vector<std::string> entries() const;

 private:
  std::filesystem::path path_;
};

/// Writes `text` to `path` byte for byte and returns `path`.
std::string write_file(const std::string& path, const std::string& text);

/// The message of the InputError that loading `path` must throw.
std::string load_error(const std::string& path, const std::string& units = "m");

/// Expects loading `path` to throw an InputError whose message starts with
/// "path: " and holds `problem`.
#define EXPECT_LOAD_ERROR(path, problem)                                          \
  do {                                                                            \
    const std::string path_ = (path); /* evaluated once: it may write a file */   \
    const std::string message_ = ::mrcloth::test::load_error(path_);              \
    EXPECT_EQ(message_.rfind(path_ + ": ", 0), 0u) << message_;                   \
    EXPECT_NE(message_.find(problem), std::string::npos) << message_;             \
  } while (false)

// The grid of grid_obj, grid_off and grid_ply: 4 x 3 vertices, 3 x 2 quads.
constexpr int kGridVertices = 12;
constexpr int kGridFaces = 6;

/// The grid's quads as vertex indices from 0, in file order.
std::vector<std::array<int, 4>> grid_faces();

/// The grid as OBJ text (one texture coordinate shared by every corner).
std::string grid_obj();

/// The grid as ASCII OFF text.
std::string grid_off();

/// An ASCII PLY header: float x, y, z vertices, faces as uchar-counted int lists.
std::string ply_header(int n_vertices, int n_faces);

/// The grid as ASCII PLY text.
std::string grid_ply();

/// Face vertex loop rotated to start at its smallest index, for comparisons
/// that must not depend on where OpenMesh starts a face.
std::vector<int> canonical_loop(const QuadMesh& mesh, OpenMesh::FaceHandle f);

/// Expects `loaded` to be the grid as its file gives it, times `scale`, made
/// refinable, without warnings.
void expect_grid_as_read(const mrcloth::LoadResult& loaded, double scale);

/// A binary PLY as written by hand: x, y, z as float (or double), a colour,
/// faces as uchar counts of int indices; `big` for big-endian.
std::string binary_quad_ply(bool big, const std::string& header_extra, std::int32_t corner_count);

/// A unit square in binary OFF: "OFF BINARY", counts, floats, one quad.
std::string binary_off_square(std::uint32_t vertices = 4, std::uint32_t faces = 1, std::uint32_t corners = 4);

}  // namespace mrcloth::test
