// The default trousers load as the clean one-piece garment the project
// relies on: all quads, manifold, a sphere with three holes (waist and two
// ankles), outward faces, symmetric, body-sized, in metres.
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/quad_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

using mrcloth::QuadMesh;

class DefaultTrousers : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { loaded_ = new mrcloth::LoadResult(mrcloth::load_garment(MRCLOTH_DEFAULT_TROUSERS)); }
  static void TearDownTestSuite() {
    delete loaded_;
    loaded_ = nullptr;
  }
  static const QuadMesh& mesh() { return loaded_->mesh; }
  static mrcloth::LoadResult* loaded_;
};
mrcloth::LoadResult* DefaultTrousers::loaded_ = nullptr;

double perimeter(const QuadMesh& mesh, const std::vector<int>& loop) {
  double length = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i)
    length += (mesh.point(mesh.vertex_handle(loop[(i + 1) % loop.size()])) - mesh.point(mesh.vertex_handle(loop[i]))).norm();
  return length;
}

TEST_F(DefaultTrousers, LoadsWithoutWarnings) {
  EXPECT_TRUE(loaded_->warnings.empty()) << "first warning: " << (loaded_->warnings.empty() ? "" : loaded_->warnings[0]);
}

TEST_F(DefaultTrousers, IsAllQuadsAndASphereWithThreeHoles) {
  // Seat tube 24 x 6 rings, 5 crotch vertices, two legs of 13 rings of 18.
  EXPECT_EQ(mesh().n_vertices(), 617u) << "24 x 6 + 5 + 2 x 18 x 13";
  EXPECT_EQ(mesh().n_faces(), 588u) << "24 x 5 + 2 x 18 x 13";
  EXPECT_EQ(mesh().n_edges(), 1206u);
  for (auto f : mesh().faces()) ASSERT_EQ(f.valence(), 4u) << "face " << f.idx();
  // V - E + F = 2 - (number of holes) for a connected orientable surface.
  EXPECT_EQ(int(mesh().n_vertices()) - int(mesh().n_edges()) + int(mesh().n_faces()), -1);
  EXPECT_EQ(mrcloth::count_roots(mesh()), 588u) << "one quadtree root per face";
  for (auto v : mesh().vertices()) ASSERT_TRUE(v.is_manifold()) << "vertex " << v.idx();
  // The crotch vertices are where the legs meet: 6 faces at the front and
  // back centre of the seat ring, 4 at the five crotch vertices, 4 (or 3
  // on a boundary) everywhere else.
  int six = 0;
  for (auto v : mesh().vertices()) {
    const auto valence = v.valence();
    if (valence == 6) ++six;
    else ASSERT_TRUE(valence == 4 || (valence == 3 && v.is_boundary())) << "vertex " << v.idx() << " valence " << valence;
  }
  EXPECT_EQ(six, 2);
}

TEST_F(DefaultTrousers, HasAWaistAndTwoAnkleLoops) {
  const auto loops = mrcloth::boundary_loops(mesh());
  ASSERT_EQ(loops.size(), 3u) << "waist and two ankles";
  // Loop 0 is the highest: the waist.
  EXPECT_EQ(loops[0].size(), 24u);
  for (int v : loops[0]) EXPECT_NEAR(mesh().point(mesh().vertex_handle(v))[1], 1.00, 1e-9) << "waist loop is level";
  EXPECT_NEAR(perimeter(mesh(), loops[0]), 0.78, 0.01) << "waist circumference, m";
  double side[2] = {0.0, 0.0};
  for (int k = 1; k <= 2; ++k) {
    EXPECT_EQ(loops[k].size(), 18u);
    for (int v : loops[k]) {
      const auto p = mesh().point(mesh().vertex_handle(v));
      EXPECT_NEAR(p[1], 0.10, 1e-9) << "ankle loop is level, just above the feet";
      side[k - 1] += p[0] / loops[k].size();
    }
    EXPECT_NEAR(perimeter(mesh(), loops[k]), 2.0 * M_PI * 0.064, 0.01) << "ankle circumference, m";
  }
  EXPECT_NEAR(std::abs(side[0]), 0.075, 1e-3) << "ankle loops around the ankle joints";
  EXPECT_NEAR(side[0], -side[1], 1e-9) << "one ankle on each side";
}

/// The axis a face should point away from: the body's vertical axis above
/// the seat (where the legs split, y = 0.84), the nearer leg's below.
OpenMesh::Vec3d axis_point(const OpenMesh::Vec3d& p) {
  if (p[1] >= 0.84) return {0.0, p[1], 0.0};
  const double t = std::clamp((p[1] - 0.10) / (0.84 - 0.10), 0.0, 1.0);
  const double x = 0.075 + t * (0.09 - 0.075);
  return {p[0] >= 0.0 ? x : -x, p[1], 0.0};
}

TEST_F(DefaultTrousers, FacesPointOutward) {
  for (auto f : mesh().faces()) {
    const OpenMesh::Vec3d normal = mesh().calc_face_normal(f);
    const OpenMesh::Vec3d centre = mesh().calc_face_centroid(f);
    OpenMesh::Vec3d out = centre - axis_point(centre);
    out[1] = 0.0;
    ASSERT_GT(OpenMesh::dot(normal, out), 0.0) << "face " << f.idx() << " at " << centre << " faces the body";
  }
}

TEST_F(DefaultTrousers, IsMirrorSymmetric) {
  std::vector<OpenMesh::Vec3d> points;
  for (auto v : mesh().vertices()) points.push_back(mesh().point(v));
  for (const auto& p : points) {
    const OpenMesh::Vec3d mirrored(-p[0], p[1], p[2]);
    double nearest = 1e9;
    for (const auto& q : points) nearest = std::min(nearest, (q - mirrored).norm());
    ASSERT_LT(nearest, 1e-6) << p << " has no mirror image";
  }
}

TEST_F(DefaultTrousers, FitsAStandingWomanInMetres) {
  OpenMesh::Vec3d lo(1e9, 1e9, 1e9), hi(-1e9, -1e9, -1e9);
  for (auto v : mesh().vertices()) {
    lo.minimize(mesh().point(v));
    hi.maximize(mesh().point(v));
  }
  EXPECT_NEAR(lo[1], 0.10, 1e-9) << "ankles";
  EXPECT_NEAR(hi[1], 1.00, 1e-9) << "waist";
  EXPECT_NEAR(lo[0] + hi[0], 0.0, 1e-6) << "centred on the body axis";
  EXPECT_NEAR(lo[2] + hi[2], 0.0, 1e-6);
  EXPECT_NEAR(hi[0] - lo[0], 0.36, 0.01) << "hip width, m";
  // The crotch: the lowest point of the seat on the mid-plane x = 0.
  double crotch = 1e9;
  for (auto v : mesh().vertices())
    if (std::abs(mesh().point(v)[0]) < 1e-9) crotch = std::min(crotch, mesh().point(v)[1]);
  EXPECT_NEAR(crotch, 0.77, 1e-9);
  // Every edge between 2 and 7 cm: a simulation-ready resolution.
  for (auto e : mesh().edges()) {
    const double length = mesh().calc_edge_length(e);
    ASSERT_GT(length, 0.02) << "edge " << e.idx();
    ASSERT_LT(length, 0.07) << "edge " << e.idx();
  }
}

}  // namespace
