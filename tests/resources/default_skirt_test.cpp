// The embedded default garment loads as the clean tube the project relies on:
// all quads, manifold, two boundary loops, outward faces, body-sized, in metres.
#include "mesh_ops/garment_io.h"
#include "mesh_ops/quad_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

namespace {

using mrcloth::QuadMesh;

class DefaultSkirt : public ::testing::Test {
 protected:
  // Loaded once: every test only reads it.
  static void SetUpTestSuite() { loaded_ = new mrcloth::LoadResult(mrcloth::load_garment(MRCLOTH_DEFAULT_SKIRT)); }
  static void TearDownTestSuite() {
    delete loaded_;
    loaded_ = nullptr;
  }
  static const QuadMesh& mesh() { return loaded_->mesh; }
  static mrcloth::LoadResult* loaded_;
};
mrcloth::LoadResult* DefaultSkirt::loaded_ = nullptr;

/// Boundary loops as lists of vertex positions.
std::vector<std::vector<OpenMesh::Vec3d>> boundary_loops(const QuadMesh& mesh) {
  std::vector<std::vector<OpenMesh::Vec3d>> loops;
  std::set<int> seen;
  for (auto start : mesh.halfedges()) {
    if (!start.is_boundary() || seen.count(start.idx())) continue;
    std::vector<OpenMesh::Vec3d> loop;
    auto h = start;
    do {
      seen.insert(h.idx());
      loop.push_back(mesh.point(h.from()));
      h = h.next();
    } while (h != start);
    loops.push_back(loop);
  }
  return loops;
}

double perimeter(const std::vector<OpenMesh::Vec3d>& loop) {
  double length = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) length += (loop[(i + 1) % loop.size()] - loop[i]).norm();
  return length;
}

TEST_F(DefaultSkirt, LoadsWithoutWarnings) {
  EXPECT_TRUE(loaded_->warnings.empty()) << "first warning: " << (loaded_->warnings.empty() ? "" : loaded_->warnings[0]);
}

TEST_F(DefaultSkirt, IsAFortyByTwentyQuadTube) {
  EXPECT_EQ(mesh().n_vertices(), 800u) << "40 segments x 20 rings";
  EXPECT_EQ(mesh().n_faces(), 760u) << "40 segments x 19 rows";
  EXPECT_EQ(mesh().n_edges(), 1560u);
  for (auto f : mesh().faces()) ASSERT_EQ(f.valence(), 4u) << "face " << f.idx();
  // A tube (open cylinder) has Euler characteristic 0.
  EXPECT_EQ(int(mesh().n_vertices()) - int(mesh().n_edges()) + int(mesh().n_faces()), 0);
  EXPECT_EQ(mrcloth::count_roots(mesh()), 760u) << "one quadtree root per face";
}

TEST_F(DefaultSkirt, HasWaistAndHemLoopsOnly) {
  auto loops = boundary_loops(mesh());
  ASSERT_EQ(loops.size(), 2u) << "open at the waist and at the hem, closed around (no seam)";
  std::sort(loops.begin(), loops.end(), [](const auto& a, const auto& b) { return a[0][1] > b[0][1]; });
  for (const auto& p : loops[0]) EXPECT_NEAR(p[1], 1.02, 1e-9) << "waist loop is level";
  for (const auto& p : loops[1]) EXPECT_NEAR(p[1], 0.55, 1e-9) << "hem loop is level";
  EXPECT_EQ(loops[0].size(), 40u);
  EXPECT_NEAR(perimeter(loops[0]), 0.70, 0.01) << "waist circumference, m";
  EXPECT_NEAR(perimeter(loops[1]), 1.50, 0.01) << "hem circumference, m";
}

TEST_F(DefaultSkirt, FacesPointOutward) {
  for (auto f : mesh().faces()) {
    const OpenMesh::Vec3d normal = mesh().calc_face_normal(f);
    const OpenMesh::Vec3d centre = mesh().calc_face_centroid(f);
    ASSERT_GT(normal[0] * centre[0] + normal[2] * centre[2], 0.0) << "face " << f.idx() << " faces the body";
  }
}

TEST_F(DefaultSkirt, FitsAStandingWomanInMetres) {
  OpenMesh::Vec3d lo(1e9, 1e9, 1e9), hi(-1e9, -1e9, -1e9);
  for (auto v : mesh().vertices()) {
    lo.minimize(mesh().point(v));
    hi.maximize(mesh().point(v));
  }
  EXPECT_NEAR(lo[1], 0.55, 1e-9) << "hem above the knees";
  EXPECT_NEAR(hi[1], 1.02, 1e-9) << "natural waist";
  EXPECT_NEAR(lo[0] + hi[0], 0.0, 1e-6) << "centred on the body axis";
  EXPECT_NEAR(lo[2] + hi[2], 0.0, 1e-6);
  EXPECT_GT(hi[0] - lo[0], hi[2] - lo[2]) << "wider side to side than front to back";
  EXPECT_LT(hi[0] - lo[0], 0.55) << "a skirt, not a tent";
}

}  // namespace
