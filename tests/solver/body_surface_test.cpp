// Drawing surfaces of collision bodies: tessellated capsules lie on the
// exact capsule, are closed and face outwards; the body cache holds the
// body at the garment cache's frame times.
#include "solver/body_surface.h"
#include "solver/character_sim.h"
#include "solver/point_cache.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

namespace mrcloth {
namespace {

Collider capsule(Eigen::Vector3d a, Eigen::Vector3d b, double ra, double rb) {
  Collider c;
  c.shape = CapsuleCollider{a, b, ra, rb};
  return c;
}

/// Edge -> how many faces use it in each direction.
std::map<std::pair<int, int>, int> directed_edges(const BodySurface& s) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& face : s.faces)
    for (std::size_t k = 0; k < face.size(); ++k) ++edges[{face[k], face[(k + 1) % face.size()]}];
  return edges;
}

/// Signed volume of a closed polygon surface (fans from vertex 0 of each face).
double signed_volume(const BodySurface& s) {
  double volume = 0.0;
  for (const auto& face : s.faces)
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Eigen::Vector3d a = s.vertices.row(face[0]), b = s.vertices.row(face[k]), c = s.vertices.row(face[k + 1]);
      volume += a.dot(b.cross(c)) / 6.0;
    }
  return volume;
}

TEST(CapsuleSurface, CountsForOneCapsule) {
  const int segments = 12, rings = 3;
  const BodySurface s = capsule_surface({capsule({0, 0, 0}, {0, 1, 0}, 0.2, 0.1)}, segments, rings);
  // Two poles, and 2 (rings + 1) profile points minus the poles as rings.
  EXPECT_EQ(s.vertices.rows(), 2 + (2 * (rings + 1) - 2) * segments);
  // Per segment: two pole triangles and one quad between each pair of rings.
  EXPECT_EQ(s.faces.size(), static_cast<std::size_t>(segments * (2 + (2 * (rings + 1) - 3))));
}

TEST(CapsuleSurface, VerticesLieOnTheExactTaperedCapsule) {
  const std::vector<Collider> capsules = {capsule({0.1, 0.2, 0.3}, {0.4, 0.9, -0.2}, 0.15, 0.05),
                                          capsule({0, 0, 0}, {0, 0, 0.5}, 0.08, 0.08),
                                          capsule({1, 0, 0}, {1, 0.3, 0}, 0.05, 0.2)};
  const BodySurface s = capsule_surface(capsules, 16, 4);
  ASSERT_EQ(s.vertices.rows(), 3 * (2 + 8 * 16));
  const int per_capsule = 2 + 8 * 16;
  for (Eigen::Index v = 0; v < s.vertices.rows(); ++v) {
    const Collider& c = capsules[static_cast<std::size_t>(v / per_capsule)];
    EXPECT_NEAR(query_surface(c, s.vertices.row(v).transpose()).distance, 0.0, 1e-12) << "vertex " << v;
  }
}

TEST(CapsuleSurface, ClosedAndOutwardFacing) {
  const std::vector<Collider> capsules = {capsule({0, 0, 0}, {0.3, 0.5, 0.1}, 0.12, 0.04),
                                          capsule({2, 0, 0}, {2, 1, 0}, 0.1, 0.1)};
  const BodySurface s = capsule_surface(capsules, 10, 2);
  // Closed and consistently oriented: every directed edge once, its reverse once.
  for (const auto& [edge, count] : directed_edges(s)) {
    EXPECT_EQ(count, 1) << edge.first << "-" << edge.second;
    const auto reverse = directed_edges(s).count({edge.second, edge.first});
    EXPECT_EQ(reverse, 1u) << edge.first << "-" << edge.second;
  }
  // Outward: positive volume, below the exact volume of the (convex) capsules and near it.
  const double pi = 3.14159265358979323846;
  const double cylinder = pi * 0.1 * 0.1 * 1.0 + 4.0 / 3.0 * pi * 0.001;
  const BodySurface second = capsule_surface({capsules[1]}, 64, 16);
  EXPECT_GT(signed_volume(second), 0.97 * cylinder);
  EXPECT_LT(signed_volume(second), cylinder);
  EXPECT_GT(signed_volume(s), 0.0);
}

TEST(CapsuleSurface, NestedSpheresGiveTheLargerSphere) {
  const BodySurface s = capsule_surface({capsule({0, 0, 0}, {0, 0.01, 0}, 0.2, 0.05)}, 8, 2);
  for (Eigen::Index v = 0; v < s.vertices.rows(); ++v)
    EXPECT_NEAR(s.vertices.row(v).norm(), 0.2, 1e-12) << "vertex " << v;
}

TEST(CapsuleSurface, PlanesAndSpheresAreSkippedAndBadCountsRefused) {
  Collider plane;
  plane.shape = PlaneCollider{};
  EXPECT_EQ(capsule_surface({plane}).vertices.rows(), 0);
  EXPECT_THROW(capsule_surface({}, 2, 1), std::exception);
  EXPECT_THROW(capsule_surface({}, 8, 0), std::exception);
}

TEST(CapsuleSurface, AppendShiftsIndices) {
  BodySurface a = capsule_surface({capsule({0, 0, 0}, {0, 1, 0}, 0.1, 0.1)}, 4, 1);
  const BodySurface b = capsule_surface({capsule({1, 0, 0}, {1, 1, 0}, 0.1, 0.1)}, 4, 1);
  const BodySurface both = capsule_surface({capsule({0, 0, 0}, {0, 1, 0}, 0.1, 0.1),
                                            capsule({1, 0, 0}, {1, 1, 0}, 0.1, 0.1)}, 4, 1);
  append_surface(a, b);
  EXPECT_EQ(a.vertices, both.vertices);
  EXPECT_EQ(a.faces, both.faces);
}

TEST(BodyCache, HoldsTheBodyAtTheGarmentsFrameTimes) {
  const Motion motion = read_bvh(std::string(MRCLOTH_RESOURCES) + "/characters/walk_instance.bvh");
  CapsulePosedBody body(make_capsule_rig(motion.skeleton), motion.skeleton);
  CharacterRunOptions options;
  options.frames = 5;
  options.fps = 30.0;
  options.preroll_seconds = 0.5;
  const auto folder = std::getenv("MRCLOTH_TEST_TMP") ? std::filesystem::path(std::getenv("MRCLOTH_TEST_TMP"))
                                                     : std::filesystem::temp_directory_path() / "mrcloth_body_cache_test";
  std::filesystem::create_directories(folder);
  const std::string cache = (folder / "body_cache_test.pc2").string();
  const std::string obj = (folder / "body_cache_test.obj").string();
  std::remove(obj.c_str());
  write_body_cache(motion, body, options, cache, obj);
  const PointCache read = read_pc2(cache);
  ASSERT_EQ(read.frames.size(), 5u);
  // Frame 1 on, as the garment's cache (its rest mesh is frame 0): a DCC
  // tool that reads the header's start plays the two together.
  EXPECT_EQ(read.start_frame, 1.0);
  EXPECT_EQ(read.sample_rate, 1.0);
  for (int f = 0; f < 5; ++f) {
    const BodySurface expected = body.surface(character_pose(motion, 0.5 + (f + 1) / 30.0, options));
    ASSERT_EQ(read.num_points, expected.vertices.rows());
    // PC2 stores floats.
    EXPECT_LT((read.frames[static_cast<std::size_t>(f)] - expected.vertices).cwiseAbs().maxCoeff(), 1e-6) << f;
  }
  EXPECT_TRUE(std::filesystem::exists(obj));
}

TEST(BodyCache, KeepsOnlyTheVerticesFacesUse) {
  // Two triangles over vertices 1, 2, 4, 5 of six: 0 and 3 are dropped,
  // the rest keep their order and the faces follow them.
  BodySurface surface;
  surface.vertices.resize(6, 3);
  for (int v = 0; v < 6; ++v) surface.vertices.row(v) << v, 10 * v, 100 * v;
  surface.faces = {{1, 2, 4}, {4, 2, 5}};
  surface.uvs = {{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)},
                 {Eigen::Vector2d(0, 1), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)}};
  const std::vector<int> kept = used_vertices(surface);
  EXPECT_EQ(kept, (std::vector<int>{1, 2, 4, 5}));
  const BodySurface compact = keep_vertices(surface, kept);
  ASSERT_EQ(compact.vertices.rows(), 4);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(compact.vertices.row(k), surface.vertices.row(kept[static_cast<std::size_t>(k)]));
  EXPECT_EQ(compact.faces, (std::vector<std::vector<int>>{{0, 1, 2}, {2, 1, 3}}));
  EXPECT_EQ(compact.uvs, surface.uvs);
  // A surface whose every vertex is used is kept whole.
  const BodySurface capsules = capsule_surface({capsule({0, 0, 0}, {0, 1, 0}, 0.1, 0.1)}, 6, 2);
  EXPECT_EQ(used_vertices(capsules).size(), static_cast<std::size_t>(capsules.vertices.rows()));
}

TEST(ClearGarmentOfBody, MovesPointsOutToTheThicknessAndKeepsTNodesAtMidpoints) {
  const Motion motion = read_bvh(std::string(MRCLOTH_RESOURCES) + "/characters/walk_instance.bvh");
  CapsuleRig rig = make_capsule_rig(motion.skeleton);
  const double thickness = rig.thickness;
  CapsulePosedBody body(rig, motion.skeleton);
  CharacterRunOptions options;
  const std::vector<Collider> capsules = posed_capsules(rig, reference_pose(motion, options));
  // The capsule with the longest axis (a limb: away from the others in its middle).
  std::size_t longest = 0;
  double length = 0.0;
  for (std::size_t k = 0; k < capsules.size(); ++k) {
    const auto& c = std::get<CapsuleCollider>(capsules[k].shape);
    if ((c.b - c.a).norm() > length) {
      length = (c.b - c.a).norm();
      longest = k;
    }
  }
  const auto& c = std::get<CapsuleCollider>(capsules[longest].shape);
  const Eigen::Vector3d axis = (c.b - c.a).normalized();
  const Eigen::Vector3d u = axis.cross(Eigen::Vector3d::UnitX()).normalized(), w = axis.cross(u);
  const Eigen::Vector3d middle = 0.5 * (c.a + c.b);
  const double radius = query_surface(capsules[longest], middle).distance;  // negative: the radius there
  const auto around = [&](double angle, double from_axis, double along) {
    return Eigen::Vector3d(middle + along * axis + from_axis * (std::cos(angle) * u + std::sin(angle) * w));
  };
  Eigen::MatrixX3d points(7, 3);
  // 0, 1: 2 mm inside, 1 cm apart along the axis; 2: their T-node.
  points.row(0) = around(0.0, -radius - 0.002, -0.005).transpose();
  points.row(1) = around(0.0, -radius - 0.002, 0.005).transpose();
  // 3, 4: outside at the thickness, 60 degrees apart around the axis; 5: their
  // T-node, whose midpoint is inside (the chord of the curved capsule).
  points.row(3) = around(-0.5, -radius + thickness, 0.0).transpose();
  points.row(4) = around(0.5, -radius + thickness, 0.0).transpose();
  // 6: half a metre outside.
  points.row(6) = (middle + 0.5 * u).transpose();
  const Eigen::MatrixX3d before = points;
  const GarmentClearance clearance = clear_garment_of_body(body, motion, options, points, {{2, 0, 1}, {5, 3, 4}});
  const CollisionScene& scene = body.scene();
  for (int v = 0; v < 6; ++v) {
    EXPECT_LE(scene.penetration(points.row(v).transpose()), 1e-9) << "vertex " << v;
    EXPECT_GE(query_surface(capsules[longest], points.row(v).transpose()).distance, thickness - 1e-9) << "vertex " << v;
  }
  // Out to the thickness, not beyond: the inside pair lands on it exactly.
  for (const int v : {0, 1})
    EXPECT_NEAR(query_surface(capsules[longest], points.row(v).transpose()).distance, thickness, 1e-9) << "vertex " << v;
  EXPECT_EQ(points.row(2), 0.5 * (points.row(0) + points.row(1))) << "T-node at its parents' midpoint";
  EXPECT_EQ(points.row(5), 0.5 * (points.row(3) + points.row(4))) << "T-node at its parents' midpoint";
  EXPECT_GT((points.row(3) - before.row(3)).norm(), 0.0) << "the outside pair moved out with its T-node";
  EXPECT_EQ(points.row(6), before.row(6)) << "a point far outside stays";
  EXPECT_EQ(clearance.moved, 6);
  double largest = 0.0;
  for (int v = 0; v < 7; ++v) largest = std::max(largest, (points.row(v) - before.row(v)).norm());
  EXPECT_EQ(clearance.largest_move, largest);
  Eigen::MatrixX3d bad = before;
  EXPECT_THROW(clear_garment_of_body(body, motion, options, bad, {{2, 0, 7}}), std::exception);
}

}  // namespace
}  // namespace mrcloth
