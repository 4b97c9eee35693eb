// MeshBody (BVH closest point, pseudo-normal sign, resolve, friction)
// against brute force on meshes built here (the oracles: mesh_oracles.h).
#include "solver/mesh_body.h"

#include "mesh_ops/errors.h"
#include "solver/colliders.h"
#include "mesh_oracles.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

using Eigen::Vector3d;
using Eigen::Vector3i;
using test::brute_distance;
using test::expect_matches_brute_force;
using test::icosphere;
using test::Mesh;
using test::sample_points;
using test::subdivided_cube;
using test::transformed;
using test::winding_number;

// ---- MeshBody on meshes built here -------------------------------------------

TEST(MeshBody, SignedDistanceMatchesBruteForceOnSphereAndCube) {
  std::mt19937 rng(7);
  for (const auto& [name, mesh] : {std::pair<std::string, Mesh>{"icosphere", icosphere(3)}, {"cube", subdivided_cube(5)}}) {
    const MeshBody body(mesh.vertices, mesh.triangles, 0.01, 0.3);
    // Far points (beyond any margin) and deep ones, not just near ones.
    expect_matches_brute_force(body, mesh, sample_points(mesh, rng, 1200, 0.3), name);
    expect_matches_brute_force(body, mesh, sample_points(mesh, rng, 400, 1.5), name + " far");
  }
}

TEST(MeshBody, NearestPointNamesTheInputVerticesAndItsBarycentrics) {
  // The tree renumbers triangles and vertices: the answer must come back in
  // the input's rows, and rebuild the nearest point at the brute-force
  // distance.
  std::mt19937 rng(5);
  for (const auto& [name, mesh] : {std::pair<std::string, Mesh>{"icosphere", icosphere(3)}, {"cube", subdivided_cube(5)}}) {
    const MeshBody body(mesh.vertices, mesh.triangles);
    for (const Vector3d& p : sample_points(mesh, rng, 600, 0.5)) {
      const MeshBody::SurfacePoint at = body.nearest_point(p);
      Vector3d rebuilt = Vector3d::Zero();
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) {
        ASSERT_GE(at.weights[static_cast<std::size_t>(k)], -1e-12) << name;
        sum += at.weights[static_cast<std::size_t>(k)];
        rebuilt += at.weights[static_cast<std::size_t>(k)] * mesh.vertex(at.vertices[static_cast<std::size_t>(k)]);
      }
      ASSERT_NEAR(sum, 1.0, 1e-12) << name;
      const double expected = brute_distance(mesh, p);
      ASSERT_NEAR(at.distance, expected, 1e-12) << name << " at (" << p.transpose() << ")";
      ASSERT_NEAR((p - rebuilt).norm(), expected, 1e-12) << name << " at (" << p.transpose() << ")";
      // The three are one of the input's triangles.
      ASSERT_TRUE(std::any_of(mesh.triangles.begin(), mesh.triangles.end(), [&](const Eigen::Vector3i& t) {
        return t(0) == at.vertices[0] && t(1) == at.vertices[1] && t(2) == at.vertices[2];
      })) << name;
    }
  }
}

TEST(MeshBody, StaysExactAfterUpdate) {
  std::mt19937 rng(11);
  Mesh sphere = icosphere(3);
  const MeshBody check(sphere.vertices, sphere.triangles);
  MeshBody body(sphere.vertices, sphere.triangles, 0.01, 0.3);
  // A wobbly, non-convex star shape: concave creases where edge and vertex
  // pseudo-normals matter, and triangles far from where the tree was built.
  Mesh wobbly = sphere;
  for (Eigen::Index i = 0; i < wobbly.vertices.rows(); ++i) {
    const Vector3d p = sphere.vertex(static_cast<int>(i));
    const double r = 1.0 + 0.35 * std::sin(3.0 * p.x()) * std::sin(4.0 * p.y()) * std::cos(2.0 * p.z());
    wobbly.vertices.row(i) = (r * p + Vector3d(0.4, -0.2, 2.0)).transpose();
  }
  body.update(wobbly.vertices);
  expect_matches_brute_force(body, wobbly, sample_points(wobbly, rng, 1200, 0.3), "wobbly sphere");

  Mesh cube = subdivided_cube(4);
  MeshBody moving(cube.vertices, cube.triangles, 0.01, 0.3);
  const Eigen::Matrix3d a = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix() *
                            Vector3d(1.6, 0.7, 1.1).asDiagonal();
  Mesh sheared = cube;
  sheared.vertices = transformed(cube, a, Vector3d(-3, 1, 0.5));
  moving.update(sheared.vertices);
  expect_matches_brute_force(moving, sheared, sample_points(sheared, rng, 1200, 0.4), "moved cube");
}

// The body renumbers its vertices internally (in the order its tree's
// leaves use them): the order they come in changes no answer, to the bit,
// in the first pose and after an update, with turned triangles left out,
// and an unused vertex (as the hands' are) may sit anywhere.
TEST(MeshBody, AnswersDoNotDependOnTheVertexOrder) {
  std::mt19937 rng(23);
  const Mesh cube = subdivided_cube(5);
  const Eigen::Index n = cube.vertices.rows();
  // Reversed order, and an unused vertex put first.
  Mesh shuffled;
  shuffled.vertices.resize(n + 1, 3);
  shuffled.vertices.row(0) = Eigen::RowVector3d(9.0, 9.0, 9.0);
  const auto moved_to = [&](int v) { return static_cast<int>(n) - v; };
  for (Eigen::Index v = 0; v < n; ++v) shuffled.vertices.row(moved_to(static_cast<int>(v))) = cube.vertices.row(v);
  for (const Vector3i& t : cube.triangles) shuffled.triangles.push_back({moved_to(t(0)), moved_to(t(1)), moved_to(t(2))});
  MeshBody a(cube.vertices, cube.triangles, 0.02, 0.3), b(shuffled.vertices, shuffled.triangles, 0.02, 0.3);
  const auto same = [&](const std::vector<Vector3d>& points, const std::string& where) {
    int differ = 0;
    for (const Vector3d& p : points) {
      const SurfaceQuery qa = a.query(p), qb = b.query(p);
      Vector3d ra = p + Vector3d(0.0, -0.01, 0.0), rb = ra;
      const double ca = a.resolve(p, ra), cb = b.resolve(p, rb);
      differ += !(qa.distance == qb.distance && qa.normal == qb.normal && ca == cb && ra == rb &&
                  a.penetration(p) == b.penetration(p));
    }
    EXPECT_EQ(differ, 0) << where;
  };
  same(sample_points(cube, rng, 800, 0.3), "first pose");
  // A new pose (sheared and moved), with the triangles of one face left out.
  const Eigen::Matrix3d shear = Eigen::AngleAxisd(0.4, Vector3d(1, 1, 0).normalized()).toRotationMatrix() *
                                Vector3d(1.3, 0.8, 1.1).asDiagonal();
  Mesh posed = cube;
  posed.vertices = transformed(cube, shear, Vector3d(0.2, -0.1, 0.3));
  Eigen::MatrixX3d posed_shuffled = shuffled.vertices;
  for (Eigen::Index v = 0; v < n; ++v) posed_shuffled.row(moved_to(static_cast<int>(v))) = posed.vertices.row(v);
  std::vector<char> ignored(cube.triangles.size(), 0);
  int left_out = 0;
  for (std::size_t t = 0; t < cube.triangles.size(); ++t) {
    const Vector3d c = (cube.vertex(cube.triangles[t](0)) + cube.vertex(cube.triangles[t](1)) + cube.vertex(cube.triangles[t](2))) / 3.0;
    if (c.z() > 0.99 && c.x() > 0.2) ignored[t] = 1, ++left_out;
  }
  ASSERT_GT(left_out, 0);
  a.update(posed.vertices, ignored);
  b.update(posed_shuffled, ignored);
  same(sample_points(posed, rng, 800, 0.3), "after an update, triangles left out");
}

/// Brute force, written apart from the library: where segment a-b first
/// crosses a triangle of `mesh` against its outward normal (smallest t), by
/// the plane crossing and three edge-side tests.
bool brute_first_entry(const Mesh& mesh, const Vector3d& a, const Vector3d& b, Vector3d& hit, Vector3d& normal) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vector3i& t : mesh.triangles) {
    const Vector3d p0 = mesh.vertex(t(0)), p1 = mesh.vertex(t(1)), p2 = mesh.vertex(t(2));
    const Vector3d n = (p1 - p0).cross(p2 - p0);
    const double da = (a - p0).dot(n), db = (b - p0).dot(n);
    if (!(da >= 0.0 && db < 0.0)) continue;  // not from outside to inside this plane
    const double s = da / (da - db);
    const Vector3d q = a + s * (b - a);
    if ((p1 - p0).cross(q - p0).dot(n) < 0 || (p2 - p1).cross(q - p1).dot(n) < 0 || (p0 - p2).cross(q - p2).dot(n) < 0)
      continue;
    if (s < best) {
      best = s;
      hit = q;
      normal = n.normalized();
    }
  }
  return best <= 1.0;
}

TEST(MeshBody, ResolveLeavesNoPointWithinThickness) {
  // On convex meshes: a point in the thickness layer goes out along the
  // normal by its penetration; a point inside that entered on its way from
  // its start goes out where it entered (brute-force oracle), thickness
  // off that face; one that started inside too, by its penetration.
  std::mt19937 rng(3);
  const double thickness = 0.02;
  for (const auto& [name, mesh] : {std::pair<std::string, Mesh>{"icosphere", icosphere(3)}, {"cube", subdivided_cube(5)}}) {
    const MeshBody body(mesh.vertices, mesh.triangles, thickness, 0.3);
    int pushed = 0, entered = 0;
    for (const Vector3d& p : sample_points(mesh, rng, 1500, 0.5)) {
      for (const Vector3d& offset : {Vector3d(0.01, -0.02, 0.005), Vector3d(0.2, 0.3, -0.25)}) {
        const Vector3d start = p + offset;
        Vector3d position = p;
        const double before = body.penetration(p);
        const double correction = body.resolve(start, position);
        EXPECT_GE(body.query(position).distance, thickness - 1e-12) << name << " from (" << p.transpose() << ")";
        EXPECT_LE(body.penetration(position), 1e-12);
        Vector3d hit, normal;
        if (before == 0.0) {
          EXPECT_EQ(correction, 0.0);
          EXPECT_EQ(position, p) << "a clear point is left alone";
        } else if (body.query(p).distance < 0.0 && brute_first_entry(mesh, start, p, hit, normal)) {
          ++entered;
          EXPECT_LT((position - (hit + thickness * normal)).norm(), 1e-12) << name << ": out where it entered";
          EXPECT_NEAR(correction, (hit + thickness * normal - p).norm(), 1e-12);
        } else {
          ++pushed;
          EXPECT_NEAR(correction, before, 1e-12) << "the push is the penetration depth (convex mesh)";
        }
      }
    }
    EXPECT_GT(pushed, 300) << name;
    EXPECT_GT(entered, 200) << name;
  }
}

TEST(MeshBody, ResolveSaysWhatIsNear) {
  // After a resolve, for points left outside: within the nearby reach (1
  // cm beyond the thickness) the clearance is the brute-force distance less
  // the thickness, and the plane passes through the point's projection onto
  // the thickened surface; beyond it the clearance is a lower bound of at
  // least the reach. A pushed point lies on its plane with no clearance.
  std::mt19937 rng(8);
  const double thickness = 0.02, reach = 0.01;
  for (const auto& [name, mesh] : {std::pair<std::string, Mesh>{"icosphere", icosphere(3)}, {"cube", subdivided_cube(5)}}) {
    const MeshBody body(mesh.vertices, mesh.triangles, thickness, 0.3);
    int near = 0, far = 0, pushed = 0;
    for (const Vector3d& p : sample_points(mesh, rng, 1500, 0.1)) {
      Vector3d position = p, plain = p;
      SurfaceNearby n;
      const Vector3d start = p + Vector3d(0.003, 0.004, -0.002);
      const double correction = body.resolve(start, position, true, nullptr, &n);
      ASSERT_EQ(body.resolve(start, plain, true), correction) << "asking what is near changes no answer";
      ASSERT_EQ(plain, position);
      const double distance = brute_distance(mesh, position);
      if (correction > 0.0) {
        ++pushed;
        EXPECT_EQ(n.clearance, 0.0);
        ASSERT_TRUE(n.has_plane);
        EXPECT_LT((n.point - position).norm(), 1e-12);
        EXPECT_NEAR(n.normal.norm(), 1.0, 1e-12);
      } else if (distance - thickness < reach) {
        ++near;
        ASSERT_NEAR(n.clearance, distance - thickness, 1e-12) << name << " at (" << p.transpose() << ")";
        ASSERT_TRUE(n.has_plane);
        EXPECT_LT((n.point + n.clearance * n.normal - position).norm(), 1e-12);
        EXPECT_NEAR(brute_distance(mesh, n.point), thickness, 1e-12) << "the plane's point is on the thickened surface";
      } else {
        ++far;
        EXPECT_LE(n.clearance, distance - thickness + 1e-12) << name;
        EXPECT_GE(n.clearance, reach - 1e-12) << name;
      }
    }
    EXPECT_GT(pushed, 200) << name;
    EXPECT_GT(near, 50) << name;
    EXPECT_GT(far, 100) << name;
  }
}

TEST(MeshBody, ALimbThatPassedMostOfTheWayThroughAPointCarriesItOut) {
  // A slab 4 cm thick (a shin, seen edge-on) moves 3.5 cm down in one step
  // onto a point resting 5 mm below it: the point ends 1 cm below the
  // slab's top face and 3 cm above its bottom. The nearest face is the top,
  // the wrong side: the slab came from above. The point must leave by the
  // bottom, the face it entered, carried along by the slab. The same
  // moving up.
  Mesh slab = subdivided_cube(4);
  slab.vertices.col(1) *= 0.02;
  const double thickness = 0.004;
  for (const double direction : {-1.0, 1.0}) {
    MeshBody body(slab.vertices, slab.triangles, thickness, 0.3);
    Mesh moved = slab;
    moved.vertices.col(1).array() += direction * 0.035;
    body.update(moved.vertices);
    const Vector3d start(0.1, direction * 0.025, -0.2);
    Vector3d position = start;
    ASSERT_LT(body.query(position).distance, -0.009) << "the slab moved over the point";
    const double correction = body.resolve(start, position);
    EXPECT_NEAR(position.y(), direction * (0.035 + 0.02 + thickness), 1e-12) << "out of the face it entered";
    EXPECT_NEAR(position.x(), 0.1, 1e-12);
    EXPECT_NEAR(position.z(), -0.2, 1e-12);
    EXPECT_NEAR(correction, 0.034, 1e-12);
  }
}

TEST(MeshBody, AMemoNeverChangesAnAnswer) {
  // Collision checks: each point resolved with friction, then nudged (as
  // the strain limiter does) and resolved again, five times, with and
  // without its memo; then the body moves and the memos carry into the next
  // pose. The answers must be the same, and most memos must hold the
  // triangle the next search starts from (the cube's crease points too,
  // where a nudge makes another side the nearest).
  std::mt19937 rng(5);
  std::normal_distribution<double> nudge(0.0, 0.0015);
  Mesh cube = subdivided_cube(6);
  MeshBody with(cube.vertices, cube.triangles, 0.02, 0.3), without(cube.vertices, cube.triangles, 0.02, 0.3);
  const auto same = [&](const Vector3d& start, Vector3d& a, Vector3d& b, bool friction, ContactMemo& memo,
                        const std::string& what) {
    const double ca = with.resolve(start, a, friction, &memo);
    const double cb = without.resolve(start, b, friction);
    ASSERT_LT((a - b).norm(), 1e-12) << what;
    ASSERT_NEAR(ca, cb, 1e-12) << what;
  };
  int remembered = 0;
  std::vector<Vector3d> points = sample_points(cube, rng, 600, 0.1);
  std::vector<ContactMemo> memos(points.size());
  for (int pose = 0; pose < 2; ++pose) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      Vector3d a = points[i], b = points[i];
      same(points[i] + Vector3d(0.004, -0.003, 0.002), a, b, true, memos[i], "round 0, point " + std::to_string(i));
      for (int round = 1; round < 6; ++round) {
        const Vector3d moved(nudge(rng), nudge(rng), nudge(rng));
        a += moved;
        b += moved;
        remembered += memos[i].radius > 0.0 && memos[i].nearest >= 0;
        same(points[i], a, b, false, memos[i], "round " + std::to_string(round) + ", point " + std::to_string(i));
      }
    }
    // The body moves: the memos' triangles have moved with it.
    Mesh moved = cube;
    moved.vertices.rowwise() += Eigen::RowVector3d(0.003, 0.0, -0.002);
    with.update(moved.vertices);
    without.update(moved.vertices);
  }
  EXPECT_GT(remembered, 3000) << "most searches should start from the memo's triangle";

  // A point remembered clear of everything (2.7 cm above the top face, no
  // triangle within the thickness and the nearby reach, 3 cm) and then
  // moved 1.2 cm down is within the 2 cm thickness: the memo must not call
  // it clear.
  MeshBody fresh(cube.vertices, cube.triangles, 0.02, 0.3);
  ContactMemo memo;
  Vector3d p(0.1, 1.027, 0.1);
  EXPECT_EQ(fresh.resolve(p, p, true, &memo), 0.0);
  ASSERT_GT(memo.radius, 0.0) << "a clear point is remembered";
  EXPECT_TRUE(memo.items.empty());
  p.y() -= 0.012;
  EXPECT_NEAR(fresh.resolve(p, p, false, &memo), 0.005, 1e-12);
  EXPECT_NEAR(p.y(), 1.02, 1e-12);
}

TEST(MeshBody, WhereAPointEnteredNextToAnotherPartTheMemoAnswersAsTheTree) {
  // Two cubes 1 mm apart (as thighs touching): a point just inside the
  // first whose way came from inside the second entered the first where
  // the second lies within the thickness, so the entry is refused and the
  // nearest surface answers; where the way came from outside both, the
  // entry stands. A memo must change neither answer.
  const Mesh a = subdivided_cube(4);
  Mesh two;
  two.vertices.resize(2 * a.vertices.rows(), 3);
  two.vertices << a.vertices, a.vertices.rowwise() + Eigen::RowVector3d(2.001, 0.0, 0.0);
  two.triangles = a.triangles;
  for (const Vector3i& t : a.triangles) two.triangles.push_back(t.array() + static_cast<int>(a.vertices.rows()));
  MeshBody with(two.vertices, two.triangles, 0.002, 0.3), without(two.vertices, two.triangles, 0.002, 0.3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> across(-0.8, 0.8);
  int refused = 0, entered = 0;
  for (int k = 0; k < 200; ++k) {
    const Vector3d p(0.999, across(rng), across(rng));
    // From inside the second cube (x 1.003), or from above the first's top.
    // The way from inside rises 3 or 12 mm: the entry point it gives lies 3
    // or 4.2 mm from where the memo was made, inside and beyond half the
    // memo's 8 mm radius.
    const double rise = k % 4 == 0 ? 0.003 : 0.012;
    const Vector3d start = k % 2 == 0 ? Vector3d(p + Vector3d(0.004, rise, 0.0)) : Vector3d(0.999, 1.003, p.z());
    const Vector3d from = k % 2 == 0 ? p : Vector3d(0.9995, 0.999, p.z());
    Vector3d x = from, y = from;
    ContactMemo memo;
    const double cx = with.resolve(start, x, false, &memo);
    const double cy = without.resolve(start, y, false);
    ASSERT_LT((x - y).norm(), 1e-12) << "point " << k;
    ASSERT_NEAR(cx, cy, 1e-12) << "point " << k;
    // Refused: pushed straight out of the first cube's side (y unchanged);
    // entered: out where the way crossed, shifted along the side.
    if (k % 2 == 0) refused += std::abs(x.y() - p.y()) < 1e-12;
    else entered += x.y() > 1.0;
  }
  EXPECT_EQ(refused, 100) << "an entry next to the other cube is refused";
  EXPECT_EQ(entered, 100) << "an entry from outside both stands";
}

TEST(MeshBody, AnOutsideSideCarriesOverOnlyWhereNoSurfaceCrossed) {
  // A memo says which side its point was on; after the body moves, a point
  // with nothing near is taken to be on that side only if no triangle swept
  // across its way. Each case is checked against a body without memos.
  Mesh cube = subdivided_cube(6);  // [0, 1]^3
  const double thickness = 0.02;
  MeshBody with(cube.vertices, cube.triangles, thickness, 0.0), without(cube.vertices, cube.triangles, thickness, 0.0);
  const auto move = [&](const Eigen::RowVector3d& by) {
    cube.vertices.rowwise() += by;
    with.update(cube.vertices);
    without.update(cube.vertices);
  };
  const auto same = [&](Vector3d a, ContactMemo& memo, const std::string& what) {
    Vector3d b = a;
    const double ca = with.resolve(a, a, false, &memo);
    const double cb = without.resolve(b, b, false);
    EXPECT_LT((a - b).norm(), 1e-12) << what;
    EXPECT_NEAR(ca, cb, 1e-12) << what;
    return ca;
  };
  // 1. Far above the top face, remembered outside; the cube rises 0.4 m in
  //    one update and swallows the point 0.2 m deep: it must be pushed out
  //    through the top (a carried "outside" would leave it there).
  ContactMemo memo;
  EXPECT_EQ(same(Vector3d(0.5, 1.2, 0.5), memo, "far above"), 0.0);
  ASSERT_GT(memo.radius, 0.0);
  ASSERT_TRUE(memo.outside);
  move({0.0, 0.4, 0.0});
  EXPECT_NEAR(same(Vector3d(0.5, 1.2, 0.5), memo, "swallowed"), 0.2 + thickness, 1e-12);
  // 2. The same for a point that moves through a face while the body moves
  //    a little: from 5 cm above the top face to 10 cm below it.
  ContactMemo through;
  EXPECT_EQ(same(Vector3d(0.3, 1.45, 0.3), through, "above"), 0.0);
  move({0.001, 0.0, 0.0});
  EXPECT_NEAR(same(Vector3d(0.3, 1.3, 0.3), through, "moved through"), 0.1 + thickness, 1e-12);
  // 3. Where nothing crossed (the body slides sideways, the point stays
  //    clear above), the carried side gives the same answer: clear.
  ContactMemo clear;
  EXPECT_EQ(same(Vector3d(0.6, 1.5, 0.6), clear, "clear"), 0.0);
  for (int step = 0; step < 5; ++step) {
    move({0.002, 0.0, -0.001});
    EXPECT_EQ(same(Vector3d(0.6, 1.5 - 0.004 * step, 0.6), clear, "still clear " + std::to_string(step)), 0.0);
  }
}

TEST(MeshBody, PointsFarOutsideAreClearAndDeepInsideAreFound) {
  const Mesh sphere = icosphere(3);
  const MeshBody body(sphere.vertices, sphere.triangles, 0.01, 0.0);
  // Outside, beyond thickness + margin, inside and outside the root box.
  EXPECT_EQ(body.penetration(Vector3d(0.9, 0.9, 0.9)), 0.0);
  EXPECT_EQ(body.penetration(Vector3d(5, 0, 0)), 0.0);
  Vector3d outside(0.0, 3.0, 0.0);
  EXPECT_EQ(body.resolve(outside, outside), 0.0);
  // The centre is ~1 deep, far beyond any margin: still inside.
  const double depth = body.query(Vector3d::Zero()).distance;
  EXPECT_LT(depth, -0.9);
  EXPECT_NEAR(body.penetration(Vector3d::Zero()), 0.01 - depth, 1e-15);
  EXPECT_NEAR(body.depth(Vector3d::Zero()), -depth, 1e-15) << "depth below the surface, thickness not counted";
  EXPECT_EQ(body.depth(Vector3d(0.0, 3.0, 0.0)), 0.0);
  // Just outside the surface, within the thickness: penetrating, not inside.
  const Vector3d near_surface = Vector3d(0.0, 1.0, 0.0) * (1.0 + 0.005);
  if (body.query(near_surface).distance > 0.0) {
    EXPECT_GT(body.penetration(near_surface), 0.0);
    EXPECT_EQ(body.depth(near_surface), 0.0);
  }
  Vector3d centre(0.05, 0.02, -0.03);
  const double correction = body.resolve(centre, centre);
  EXPECT_GT(correction, 0.9);
  EXPECT_NEAR(body.query(centre).distance, 0.01, 1e-12);
}

TEST(MeshBody, DepthsAreBothMeasuresWithOrWithoutAHint) {
  // depths() is penetration and depth from one search, started from the
  // hint a point's last measurement left. Points all over the cube (inside
  // deep and shallow, near, beyond the bounded search's reach, outside the
  // root box), measured with a hint each over three poses, with a patch of
  // the top face left out in the last two (the side beyond reach is then the
  // whole mesh's). Each answer is the signed distance's (query(), an
  // unbounded search of the seen surface): max(0, thickness - d) and
  // max(0, -d); on the closed cube also brute force's (distance to every
  // triangle, the winding number's side); and the same without the hint.
  std::mt19937 rng(17);
  Mesh cube = subdivided_cube(6);
  const double thickness = 0.004;
  MeshBody body(cube.vertices, cube.triangles, thickness, 0.3);
  std::vector<char> ignored(cube.triangles.size(), 0);
  for (std::size_t t = 0; t < cube.triangles.size(); ++t) {
    const Vector3d c = (cube.vertex(cube.triangles[t](0)) + cube.vertex(cube.triangles[t](1)) + cube.vertex(cube.triangles[t](2))) / 3.0;
    if (c.y() > 0.99 && std::abs(c.x()) < 0.5 && std::abs(c.z()) < 0.5) ignored[t] = 1;
  }
  std::vector<Vector3d> points = sample_points(cube, rng, 400, 0.02);
  const std::vector<Vector3d> far = sample_points(cube, rng, 400, 0.4);
  points.insert(points.end(), far.begin(), far.end());
  std::vector<int> hints(points.size(), -1);
  int inside = 0, penetrating = 0, hinted = 0, brute_checked = 0;
  for (int pose = 0; pose < 3; ++pose) {
    Mesh moved = cube;
    moved.vertices.rowwise() += Eigen::RowVector3d(0.004 * pose, -0.003 * pose, 0.002 * pose);
    body.update(moved.vertices, pose == 0 ? std::vector<char>{} : ignored);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::string where = "pose " + std::to_string(pose) + ", point " + std::to_string(i);
      hinted += hints[i] >= 0;
      const PointDepths both = body.depths(points[i], &hints[i]);
      const double signed_distance = body.query(points[i]).distance;
      ASSERT_NEAR(both.penetration, std::max(0.0, thickness - signed_distance), 1e-12) << where;
      ASSERT_NEAR(both.depth, std::max(0.0, -signed_distance), 1e-12) << where;
      if (pose == 0) {
        const double distance = brute_distance(moved, points[i]);
        if (distance > 1e-9) {
          const double brute = winding_number(moved, points[i]) > 0.5 ? -distance : distance;
          ASSERT_NEAR(both.penetration, std::max(0.0, thickness - brute), 1e-12) << where;
          ASSERT_NEAR(both.depth, std::max(0.0, -brute), 1e-12) << where;
          ++brute_checked;
        }
      }
      const PointDepths unhinted = body.depths(points[i]);
      ASSERT_EQ(unhinted.penetration, both.penetration) << where;
      ASSERT_EQ(unhinted.depth, both.depth) << where;
      ASSERT_EQ(body.penetration(points[i]), both.penetration) << where;
      ASSERT_EQ(body.depth(points[i]), both.depth) << where;
      inside += both.depth > 0.0;
      penetrating += both.penetration > 0.0 && both.depth == 0.0;
    }
  }
  EXPECT_GT(brute_checked, 700) << "the closed pose's points against brute force";
  EXPECT_GT(inside, 300) << "points inside the cube";
  EXPECT_GT(penetrating, 20) << "points within the thickness outside";
  EXPECT_GT(hinted, 1000) << "most later measurements start from a hint";
}

TEST(MeshBody, AMemoNearIgnoredTrianglesNeverChangesAnAnswer) {
  // Ignored (turned) triangles leave the seen surface open: a point can
  // pass from outside to what the tree calls inside without meeting a seen
  // triangle, so a memo there must not vouch for a side. A patch of the
  // cube's top face is ignored; points walk down through it in small
  // steps, resolved with and without memos: the answers must be the same.
  Mesh cube = subdivided_cube(6);
  const double thickness = 0.004;
  std::vector<char> ignored(cube.triangles.size(), 0);
  int patch = 0;
  for (std::size_t t = 0; t < cube.triangles.size(); ++t) {
    const Vector3d c = (cube.vertex(cube.triangles[t](0)) + cube.vertex(cube.triangles[t](1)) + cube.vertex(cube.triangles[t](2))) / 3.0;
    if (c.y() > 0.99 && std::abs(c.x()) < 0.5 && std::abs(c.z()) < 0.5) patch += ignored[t] = 1;
  }
  ASSERT_GT(patch, 8);
  MeshBody with(cube.vertices, cube.triangles, thickness, 0.3), without(cube.vertices, cube.triangles, thickness, 0.3);
  with.update(cube.vertices, ignored);
  without.update(cube.vertices, ignored);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> across(-0.45, 0.45), down(0.0005, 0.0049);
  int differing_sides = 0;
  for (int walk = 0; walk < 200; ++walk) {
    // The first walk is the case that failed: remembered 4.5 mm above the
    // patch with nothing seen near, then 4.9 mm down, 0.4 mm below it.
    Vector3d a = walk == 0 ? Vector3d(0.0, 1.0045, 0.0) : Vector3d(across(rng), 1.012, across(rng));
    ContactMemo memo;
    for (int round = 0; round < 8 && a.y() > 0.99; ++round) {
      Vector3d b = a;
      const double ca = with.resolve(a, a, false, &memo);
      const double cb = without.resolve(b, b, false);
      ASSERT_LT((a - b).norm(), 1e-12) << "walk " << walk << " round " << round;
      ASSERT_NEAR(ca, cb, 1e-12) << "walk " << walk << " round " << round;
      if (cb > 0.1) {
        ++differing_sides;  // the tree called it inside: pushed to the seen surface, far off
        break;
      }
      a.y() -= walk == 0 ? 0.0049 : down(rng);
    }
  }
  EXPECT_GT(differing_sides, 100) << "most walks should reach what the tree calls inside";
}

TEST(MeshBody, AboveAHoleLeftByIgnoredTrianglesThePointIsOutside) {
  // Ignored (turned) triangles leave a hole in the seen surface. A 10 cm
  // cube, its top's 1 cm cells next to the +x edge ignored at 0 < z < 1
  // cm: a point 2 mm above the hole, 4 mm in from that edge, is outside,
  // but its nearest seen triangle is the side face's, under the edge,
  // whose side calls it 4.5 mm inside (what the groin's fold did on a
  // walk). The whole mesh decides there: outside, not pushed, and inside
  // just under the hole.
  Mesh cube = subdivided_cube(10);
  cube.vertices *= 0.05;
  std::vector<char> ignored(cube.triangles.size(), 0);
  for (std::size_t t = 0; t < cube.triangles.size(); ++t) {
    const Vector3d c = (cube.vertex(cube.triangles[t](0)) + cube.vertex(cube.triangles[t](1)) + cube.vertex(cube.triangles[t](2))) / 3.0;
    if (c.y() > 0.0499 && c.x() > 0.04 && c.z() > 0.0 && c.z() < 0.01) ignored[t] = 1;
  }
  ASSERT_EQ(std::count(ignored.begin(), ignored.end(), 1), 2);
  MeshBody body(cube.vertices, cube.triangles, 0.001, 0.0), whole(cube.vertices, cube.triangles, 0.001, 0.0);
  body.update(cube.vertices, ignored);
  const Vector3d above(0.046, 0.052, 0.005);
  EXPECT_EQ(whole.depth(above), 0.0);
  EXPECT_EQ(body.depth(above), 0.0) << "above the top: outside";
  EXPECT_NEAR(body.query(above).distance, std::hypot(0.004, 0.002), 1e-12) << "the side face's edge is nearest, outside";
  Vector3d p = above;
  EXPECT_EQ(body.resolve(p, p, false), 0.0);
  EXPECT_EQ(p, above);
  const Vector3d under(0.046, 0.049, 0.005);  // inside, 1 mm under the hole
  EXPECT_GT(body.depth(under), 0.0009);
}

TEST(MeshBody, AMemoNearIgnoredTrianglesHandsOnNoSide) {
  // Near ignored triangles the nearest seen one can give the wrong side
  // (the seen surface is open there), so such a memo must not hand its side
  // on to the next pose. A cube's top patch is ignored; a small box inside
  // just under it is a second part. A point 3 mm under the patch, beside
  // that box's top edge, is called outside by the box (as it is, with or
  // without a memo). The body then moves a little and the point moves 7 cm
  // deeper in, 2 cm from everything, crossing nothing: it is inside (the
  // whole mesh's parity) and must be pushed out, memo or not.
  Mesh body = subdivided_cube(10);  // [-1, 1]^3
  Mesh part = subdivided_cube(2);
  const Eigen::RowVector3d half(0.05, 0.0225, 0.05), centre(0.0, 0.9725, 0.0);
  const auto first = static_cast<int>(body.vertices.rows());
  body.vertices.conservativeResize(first + part.vertices.rows(), 3);
  for (Eigen::Index i = 0; i < part.vertices.rows(); ++i)
    body.vertices.row(first + i) = part.vertices.row(i).cwiseProduct(half) + centre;
  for (const Vector3i& t : part.triangles) body.triangles.push_back(t + Vector3i::Constant(first));
  std::vector<char> ignored(body.triangles.size(), 0);
  for (std::size_t t = 0; t < body.triangles.size(); ++t) {
    const Vector3d c = (body.vertex(body.triangles[t](0)) + body.vertex(body.triangles[t](1)) + body.vertex(body.triangles[t](2))) / 3.0;
    if (c.y() > 0.999 && std::abs(c.x()) < 0.2 && std::abs(c.z()) < 0.2) ignored[t] = 1;
  }
  ASSERT_EQ(std::count(ignored.begin(), ignored.end(), 1), 2 * 2 * 2);
  const double thickness = 0.001;
  MeshBody with(body.vertices, body.triangles, thickness, 0.0), without(body.vertices, body.triangles, thickness, 0.0);
  with.update(body.vertices, ignored);
  without.update(body.vertices, ignored);
  ContactMemo memo;
  Vector3d a(0.052, 0.997, 0.0), b = a;
  EXPECT_EQ(with.resolve(a, a, false, &memo), 0.0);
  EXPECT_EQ(without.resolve(b, b, false), 0.0);
  ASSERT_GT(memo.radius, 0.0) << "the memo was made";
  ASSERT_FALSE(memo.sided) << "next to ignored triangles";
  body.vertices.col(0).array() += 1e-4;
  with.update(body.vertices, ignored);
  without.update(body.vertices, ignored);
  a = b = Vector3d(0.07, 0.98, 0.0);
  const double ca = with.resolve(a, a, false, &memo);
  const double cb = without.resolve(b, b, false);
  EXPECT_GT(cb, 0.015) << "2 cm inside: pushed out";
  EXPECT_NEAR(ca, cb, 1e-12) << "the memo must not change the answer";
  EXPECT_LT((a - b).norm(), 1e-12);
}

TEST(MeshBody, WhereTwoPartsOverlapAMemoVouchesForNoSideAndThePlaneForLittle) {
  // Skinning drives one part of the body into another (the thighs, a hand
  // into the hip). A point inside part A, 7 mm under its top, is 2 mm in
  // front of part B's side, which lies inside A: its closest triangle says
  // outside, and it is pushed out of B's side to the thickness. Moved 4.2
  // mm away from B, it is nearest to A's top, 5.9 mm behind it: the tree
  // calls it inside. A memo made next to B must not carry "outside" there;
  // and the plane the point was left on vouches for it only until A's top
  // (7 mm, behind) could become nearer than B's side (4 mm): 1.5 mm.
  const auto box = [](const Eigen::RowVector3d& lo, const Eigen::RowVector3d& hi) {
    Mesh b = subdivided_cube(4);  // [-1, 1]^3
    for (Eigen::Index i = 0; i < b.vertices.rows(); ++i)
      b.vertices.row(i) = lo + (b.vertices.row(i).array() + 1.0).matrix().cwiseProduct(hi - lo) / 2.0;
    return b;
  };
  Mesh body = box({-0.3, -0.3, -0.3}, {0.3, 0.0, 0.3});
  const Mesh part = box({-0.5, -0.2, -0.2}, {-0.002, 0.1, 0.2});
  const auto first = static_cast<int>(body.vertices.rows());
  body.vertices.conservativeResize(first + part.vertices.rows(), 3);
  body.vertices.bottomRows(part.vertices.rows()) = part.vertices;
  for (const Vector3i& t : part.triangles) body.triangles.push_back(t + Vector3i::Constant(first));
  const double thickness = 0.004;
  const MeshBody with(body.vertices, body.triangles, thickness, 0.0), without(body.vertices, body.triangles, thickness, 0.0);
  ContactMemo memo;
  SurfaceNearby nearby;
  const Vector3d p(0.0, -0.007, 0.0), q(0.0041, -0.0059, 0.0);
  Vector3d a = p, b = p;
  const double pa = with.resolve(a, a, false, &memo, &nearby), pb = without.resolve(b, b, false);
  EXPECT_NEAR(pa, 0.002, 1e-12) << "pushed out of B's side to the thickness";
  EXPECT_NEAR(pa, pb, 1e-12);
  ASSERT_GT(memo.radius, 0.0) << "the memo was made";
  EXPECT_GE(memo.nearest, 0) << "it remembers B's side";
  EXPECT_FALSE(memo.sided) << "next to a triangle, no side is carried";
  EXPECT_TRUE(nearby.has_plane);
  EXPECT_NEAR(nearby.normal.x(), 1.0, 1e-12) << "B's side";
  // Until A's top (7 mm behind) may be nearer than B's side (4 mm): 1.5 mm
  // where it ends. The push's resolve vouches for less (it found A's top
  // before the 2 mm push, which could have brought it that much nearer).
  EXPECT_GT(nearby.flip, 0.0);
  EXPECT_LE(nearby.flip, 0.5 * (0.007 - thickness) + 1e-12);
  Vector3d again = a;
  EXPECT_EQ(with.resolve(again, again, false, nullptr, &nearby), 0.0);
  EXPECT_NEAR(nearby.flip, 0.5 * (0.007 - thickness), 1e-12) << "resting there";
  EXPECT_NEAR(nearby.clearance, 0.0, 1e-12);
  a = b = q;
  const double qa = with.resolve(a, a, false, &memo), qb = without.resolve(b, b, false);
  EXPECT_NEAR(qb, 0.0059 + thickness, 1e-9) << "the tree: 5.9 mm inside A, pushed out of its top";
  EXPECT_NEAR(qa, qb, 1e-12) << "the memo must not change the answer";
  EXPECT_LT((a - b).norm(), 1e-12);
  // Farther below A's top than the search for flips looks (5 mm beyond the
  // nearest surface), the plane vouches for at least 2.5 mm.
  Vector3d deep(0.002, -0.02, 0.0);
  SurfaceNearby far_below;
  EXPECT_EQ(with.resolve(deep, deep, false, nullptr, &far_below), 0.0);
  EXPECT_GE(far_below.flip, 0.0025 - 1e-12);
}

TEST(MeshBody, FrictionMatchesTheAnalyticColliders) {
  // A point that ends within the thickness of the cube's top face, outside
  // it (interior of a face: the surface is the plane y = 1 there), must
  // move exactly as against a plane collider with the same thickness and
  // friction. (A point that ends inside, having entered on its way, goes
  // out where it entered: ResolveLeavesNoPointWithinThickness.)
  const Mesh cube = subdivided_cube(4);
  const double thickness = 0.004, mu = 0.5;
  const MeshBody body(cube.vertices, cube.triangles, thickness, mu);
  const std::vector<Collider> plane = {Collider{PlaneCollider{Vector3d(0, 1, 0), Vector3d(0, 1, 0)}, thickness, mu}};
  const Vector3d previous(0.1, 1.01, 0.2);
  int pushed = 0;
  for (const Vector3d& step : {Vector3d(0.001, -0.008, 0.0005), Vector3d(0.03, -0.0095, -0.01), Vector3d(0.0, -0.0099, 0.0),
                               Vector3d(-0.2, -0.007, 0.1), Vector3d(-0.2, -0.003, 0.1)}) {
    Vector3d mesh_position = previous + step, plane_position = previous + step;
    const double mesh_correction = body.resolve(previous, mesh_position);
    const double plane_correction = resolve_point(plane, previous, plane_position);
    pushed += mesh_correction > 0.0;
    EXPECT_NEAR(mesh_correction, plane_correction, 1e-12);
    EXPECT_LT((mesh_position - plane_position).norm(), 1e-12) << "step (" << step.transpose() << ")";
  }
  EXPECT_EQ(pushed, 4);
  // Static friction: a small slide is removed entirely; a large one is
  // reduced by exactly mu times the push.
  Vector3d sticks = previous + Vector3d(0.001, -0.0095, 0.0);
  body.resolve(previous, sticks);
  EXPECT_NEAR(sticks.x(), previous.x(), 1e-12);
  EXPECT_NEAR(sticks.y(), 1.0 + thickness, 1e-12);
  Vector3d slides = previous + Vector3d(0.05, -0.0095, 0.0);
  const double push = body.resolve(previous, slides);
  EXPECT_NEAR(push, 0.0035, 1e-12);
  EXPECT_NEAR(slides.x(), previous.x() + 0.05 - mu * push, 1e-12);
}

TEST(MeshBody, FrictionCarriesPointsWithTheMovingSurface) {
  // The cube slides along +x by 1 cm; a point resting in contact on its top
  // face, not moving itself, is dragged along up to the friction limit.
  const Mesh cube = subdivided_cube(4);
  const double thickness = 0.004;
  MeshBody body(cube.vertices, cube.triangles, thickness, 1.0);
  Mesh moved = cube;
  moved.vertices = transformed(cube, Eigen::Matrix3d::Identity(), Vector3d(0.01, 0.0, 0.0));
  body.update(moved.vertices);
  const Vector3d resting(0.2, 1.0 + thickness - 0.02, 0.1);  // 2 cm in: grip 2 cm >= 1 cm slide
  Vector3d position = resting;
  body.resolve(resting, position);
  EXPECT_NEAR(position.x(), resting.x() + 0.01, 1e-12) << "static friction: moves with the surface";
  EXPECT_NEAR(position.y(), 1.0 + thickness, 1e-12);
  Vector3d light = Vector3d(0.2, 1.0 + thickness - 0.004, 0.1);  // grip 4 mm < 1 cm slide
  Vector3d light_position = light;
  body.resolve(light, light_position);
  EXPECT_NEAR(light_position.x(), light.x() + 0.004, 1e-12) << "kinetic: dragged by mu times the push";
}

TEST(MeshBody, RefusesBadMeshesAndUpdates) {
  const Mesh cube = subdivided_cube(2);
  // Each refusal names what is wrong (the constructor's checks, in order).
  const auto refused = [](const std::function<void()>& make, const std::string& part) {
    try {
      make();
      ADD_FAILURE() << "no error; expected one naming '" << part << "'";
    } catch (const ArgumentError& error) {
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
    }
  };
  std::vector<Vector3i> open = cube.triangles;
  open.pop_back();
  refused([&] { MeshBody(cube.vertices, open); }, "has a triangle on one side only; expected a closed mesh");
  std::vector<Vector3i> inverted = cube.triangles;
  for (Vector3i& t : inverted) std::swap(t(1), t(2));
  refused([&] { MeshBody(cube.vertices, inverted); }, "the triangles enclose a negative volume");
  std::vector<Vector3i> out_of_range = cube.triangles;
  out_of_range[0](0) = 1000;
  refused([&] { MeshBody(cube.vertices, out_of_range); },
          "MeshBody: triangle 0 names vertex 1000; expected an index below " + std::to_string(cube.vertices.rows()));
  std::vector<Vector3i> doubled = cube.triangles;
  doubled.push_back(cube.triangles[0]);
  refused([&] { MeshBody(cube.vertices, doubled); }, "is used twice in the same direction");
  Eigen::MatrixX3d not_finite = cube.vertices;
  not_finite(3, 1) = std::nan("");
  refused([&] { MeshBody(not_finite, cube.triangles); }, "MeshBody: vertex 3 is not finite");
  refused([&] { MeshBody(cube.vertices, {}); }, "MeshBody: no triangles");
  refused([&] { MeshBody(cube.vertices, cube.triangles, -0.1); }, "MeshBody: thickness must be from 0 to");
  refused([&] { MeshBody(cube.vertices, cube.triangles, 0.004, -1.0); }, "MeshBody: friction must be a finite number >= 0");
  EXPECT_NO_THROW(MeshBody(cube.vertices, cube.triangles, kMostContactThickness));
  EXPECT_THROW(MeshBody(cube.vertices, cube.triangles, std::nextafter(kMostContactThickness, 1.0)), ArgumentError);
  MeshBody body(cube.vertices, cube.triangles);
  EXPECT_THROW(body.update(cube.vertices.topRows(5)), ArgumentError);
  EXPECT_THROW(body.update(cube.vertices, std::vector<char>(3, 0)), ArgumentError);
}

TEST(MeshBody, IgnoredTrianglesAreNotSurface) {
  // The cube [-1, 1]^3; ignoring the triangles of its top face (z = 1), a
  // point just above that face is nearest to the side faces' top edges, not
  // 1 mm from the top: the body is then open there.
  const Mesh cube = subdivided_cube(4);
  MeshBody body(cube.vertices, cube.triangles, 0.01, 0.3);
  const Vector3d above(0.1, 0.2, 1.001);
  EXPECT_NEAR(body.query(above).distance, 0.001, 1e-12);
  std::vector<char> top(cube.triangles.size(), 0);
  int ignored = 0;
  for (std::size_t t = 0; t < cube.triangles.size(); ++t) {
    const Vector3i& tri = cube.triangles[t];
    if (cube.vertex(tri(0)).z() > 0.999 && cube.vertex(tri(1)).z() > 0.999 && cube.vertex(tri(2)).z() > 0.999) {
      top[t] = 1;
      ++ignored;
    }
  }
  ASSERT_EQ(ignored, 2 * 4 * 4);
  body.update(cube.vertices, top);
  EXPECT_NEAR(std::abs(body.query(above).distance), (Vector3d(0.1, 1.0, 1.0) - above).norm(), 1e-12)
      << "the nearest surface is the top edge of the y = 1 side";
  EXPECT_EQ(body.penetration(above), 0.0);
  // The next update without flags sees the whole surface again.
  body.update(cube.vertices);
  EXPECT_NEAR(body.query(above).distance, 0.001, 1e-12);
}

TEST(MeshBody, FarFromTheSeenSurfaceTheWholeMeshDecidesTheSide) {
  // The cube with its top face left out: 2-40 cm above the top, a point is
  // nearest to a side face's top edge, whose pseudo-normal calls it inside.
  // More than 1 cm from every seen triangle the side comes from the whole
  // closed mesh: it must agree with the winding number, above the top and
  // anywhere else.
  const Mesh cube = subdivided_cube(4);
  MeshBody body(cube.vertices, cube.triangles, 0.01, 0.3);
  std::vector<char> top(cube.triangles.size(), 0);
  for (std::size_t t = 0; t < cube.triangles.size(); ++t) {
    const Vector3i& tri = cube.triangles[t];
    top[t] = cube.vertex(tri(0)).z() > 0.999 && cube.vertex(tri(1)).z() > 0.999 && cube.vertex(tri(2)).z() > 0.999;
  }
  body.update(cube.vertices, top);
  for (const double height : {0.02, 0.1, 0.4}) {
    const Vector3d above(0.1, -0.2, 1.0 + height);
    EXPECT_GT(body.query(above).distance, 0.0) << height << " m above the open top";
    EXPECT_EQ(body.depth(above), 0.0);
    EXPECT_EQ(body.penetration(above), 0.0);
  }
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> coordinate(-1.3, 1.3);
  int far = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vector3d p(coordinate(rng), coordinate(rng), coordinate(rng));
    const double distance = body.query(p).distance;
    if (!(std::abs(distance) > 0.01)) continue;
    ++far;
    EXPECT_EQ(distance < 0.0, winding_number(cube, p) > 0.5) << "(" << p.transpose() << ")";
  }
  EXPECT_GT(far, 2500);
}

}  // namespace
}  // namespace mrcloth
