#pragma once
// Small meshes built in code for tests: exact, planar or curved on purpose.
#include "mesh_ops/quad_mesh.h"
#include "mesh_ops/quadtree_forest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace mrcloth::test {

/// nx by ny quads on the plane z = 0 with the given spacing (metres), vertex
/// (i, j) at index j * (nx + 1) + i, made refinable.
inline QuadMesh make_grid(int nx, int ny, double spacing = 1.0) {
  QuadMesh mesh;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) mesh.add_vertex(QuadMesh::Point(i * spacing, j * spacing, 0.0));
  const auto vid = [&](int i, int j) { return mesh.vertex_handle(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) mesh.add_face(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1));
  init_forest(mesh);
  return mesh;
}

/// An open tube (around x around, ny rings-1 high) of the given radius: curved,
/// so its quads are not parallelograms after refinement in general.
inline QuadMesh make_tube(int around, int rings, double radius, double height) {
  QuadMesh mesh;
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * i / around;
      // A slight flare makes the side quads trapezoids, a harder mass case.
      const double r = radius * (1.0 + 0.3 * j / rings);
      mesh.add_vertex(QuadMesh::Point(r * std::cos(a), height * j / (rings - 1), r * std::sin(a)));
    }
  const auto vid = [&](int i, int j) { return mesh.vertex_handle(j * around + (i % around)); };
  for (int j = 0; j + 1 < rings; ++j)
    for (int i = 0; i < around; ++i) mesh.add_face(vid(i, j), vid(i, j + 1), vid(i + 1, j + 1), vid(i + 1, j));
  init_forest(mesh);
  return mesh;
}

/// A horizontal square sheet of `side` metres at height y, centred on the y
/// axis, with n x n vertices (n >= 2), vertex (i, k) at index k * n + i,
/// faces oriented with normal +y, made refinable.
inline QuadMesh make_sheet(int n, double side = 1.0, double y = 0.0) {
  QuadMesh mesh;
  const double step = side / (n - 1);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i) mesh.add_vertex(QuadMesh::Point(-0.5 * side + i * step, y, -0.5 * side + k * step));
  const auto vid = [&](int i, int k) { return mesh.vertex_handle(k * n + i); };
  for (int k = 0; k + 1 < n; ++k)
    for (int i = 0; i + 1 < n; ++i) mesh.add_face(vid(i, k), vid(i, k + 1), vid(i + 1, k + 1), vid(i + 1, k));
  init_forest(mesh);
  return mesh;
}

/// Shared real data folder (may be absent: callers skip).
inline std::string shared_data(const std::string& relative) {
  return std::string(MRCLOTH_SHARED_DATA) + "/" + relative;
}

/// A fresh, empty folder <tmp>/<suite>/<running test>/<name> (tmp:
/// MRCLOTH_TEST_TMP, else the system's): per test, because ctest runs the
/// tests of one binary side by side, and a folder shared by name was
/// removed under another test reading it.
inline std::filesystem::path fresh_folder(const std::string& suite, const std::string& name) {
  const char* env = std::getenv("MRCLOTH_TEST_TMP");
  const ::testing::TestInfo* running = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string test = running ? std::string(running->test_suite_name()) + "." + running->name() : "none";
  const std::filesystem::path dir =
      std::filesystem::path(env ? env : std::filesystem::temp_directory_path().string()) / suite / test / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace mrcloth::test
