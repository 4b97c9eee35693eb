#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/mode_layer.h"
#include "solver/implicit_integrator.h"
#include "mesh_ops/errors.h"
#include "solver/self_contact.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

namespace mrcloth {
namespace {

// Sheets given as (origin, u step, v step, nu x nv vertices) in one mesh,
// vertex ids sheet by sheet, row by row.
struct SheetSpec {
  Eigen::Vector3d origin, du, dv;
  int nu, nv;
};
QuadMesh sheets(const std::vector<SheetSpec>& specs) {
  QuadMesh mesh;
  int base = 0;
  for (const SheetSpec& s : specs) {
    for (int j = 0; j < s.nv; ++j)
      for (int i = 0; i < s.nu; ++i) {
        const Eigen::Vector3d p = s.origin + i * s.du + j * s.dv;
        mesh.add_vertex(QuadMesh::Point(p.x(), p.y(), p.z()));
      }
    const auto vid = [&](int i, int j) { return mesh.vertex_handle(base + j * s.nu + i); };
    for (int j = 0; j + 1 < s.nv; ++j)
      for (int i = 0; i + 1 < s.nu; ++i) mesh.add_face(vid(i, j), vid(i, j + 1), vid(i + 1, j + 1), vid(i + 1, j));
    base += s.nu * s.nv;
  }
  init_forest(mesh);
  return mesh;
}

// Every edge against every triangle, no broad phase: the oracle.
int brute_force_crossings(const ContactSurface& s, const Positions& x) {
  int crossings = 0;
  for (const auto& e : s.edges)
    for (const auto& t : s.triangles) {
      bool shared = false;
      for (int a : {e[0], e[1]})
        for (int b : {t[0], t[1], t[2]})
          for (int u : s.support[a])
            for (int v : s.support[b]) shared |= u == v;
      if (shared) continue;
      const Eigen::Vector3d p = x.row(e[0]).transpose(), q = x.row(e[1]).transpose();
      const Eigen::Vector3d a = x.row(t[0]).transpose(), b = x.row(t[1]).transpose(), c = x.row(t[2]).transpose();
      // Signed volumes: the edge crosses the plane and the line passes
      // inside all three sides.
      const auto volume = [](const Eigen::Vector3d& o, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                             const Eigen::Vector3d& w) { return (u - o).cross(v - o).dot(w - o); };
      const double dp = volume(a, b, c, p), dq = volume(a, b, c, q);
      if (!(dp * dq < 0.0)) continue;
      const double s1 = volume(p, q, a, b), s2 = volume(p, q, b, c), s3 = volume(p, q, c, a);
      if ((s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0)) ++crossings;
    }
  return crossings;
}

TEST(ContactSurface, AGridGivesTwoTrianglesPerQuadAndEachEdgeOnce) {
  const QuadMesh mesh = test::make_grid(4, 3, 0.1);
  const DynamicsModel m = build_dynamics(mesh, {});
  const ContactSurface s = contact_surface(m);
  EXPECT_EQ(s.triangles.size(), 2u * 4 * 3);
  // 4 x 4 horizontal, 5 x 3 vertical, one diagonal per quad.
  EXPECT_EQ(s.edges.size(), 4u * 4 + 5 * 3 + 4 * 3);
  for (int v = 0; v < m.num_vertices; ++v) EXPECT_EQ(s.support[v], std::vector<int>{v});
}

TEST(ContactSurface, ATNodeIsSupportedByItsParents) {
  QuadMesh mesh = test::make_sheet(5, 0.4);
  paint_modes_sphere(mesh, {-0.2, 0.0, -0.2}, 0.1, 3);
  adaptive_refine(mesh, {8.0, 2, true});
  const DynamicsModel m = build_dynamics(mesh, {});
  ASSERT_FALSE(m.hanging_vertices.empty());
  const ContactSurface s = contact_surface(m);
  const Layers layers = get_layers(mesh);
  for (int h : m.hanging_vertices) {
    const OpenMesh::Vec2i parents = mesh.property(layers.parents, mesh.vertex_handle(h));
    for (int p : {parents[0], parents[1]}) {
      // Every free or pinned vertex a parent rests on supports the T-node.
      for (int u : s.support[p])
        EXPECT_TRUE(std::binary_search(s.support[h].begin(), s.support[h].end(), u)) << "T-node " << h;
    }
    EXPECT_FALSE(std::binary_search(s.support[h].begin(), s.support[h].end(), h));
  }
  // An edge rests on what either end rests on, each vertex once, sorted.
  ASSERT_EQ(s.edge_support.size(), s.edges.size());
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    std::set<int> both(s.support[s.edges[e][0]].begin(), s.support[s.edges[e][0]].end());
    both.insert(s.support[s.edges[e][1]].begin(), s.support[s.edges[e][1]].end());
    EXPECT_EQ(s.edge_support[e], std::vector<int>(both.begin(), both.end())) << "edge " << e;
  }
  // Triangles use corners only: no T-node lies inside a triangle's edge
  // list twice, and the area equals the sheet's.
  double area = 0.0;
  for (const auto& t : s.triangles)
    area += 0.5 * (m.rest.row(t[1]) - m.rest.row(t[0])).cross(m.rest.row(t[2]) - m.rest.row(t[0])).norm();
  EXPECT_NEAR(area, 0.4 * 0.4, 1e-12);
}

TEST(CountSelfCrossings, AgreesWithTheBruteForceOracle) {
  // A horizontal sheet and a vertical one through it: 2 x 2 cm cells.
  const QuadMesh mesh = sheets({{{0, 0, 0}, {0.02, 0, 0}, {0, 0, 0.02}, 8, 8},
                                {{0.011, -0.05, 0.031}, {0.02, 0, 0}, {0, 0.02, 0}, 5, 6}});
  const DynamicsModel m = build_dynamics(mesh, {});
  const ContactSurface s = contact_surface(m);
  const int crossed = count_self_crossings(s, m.rest);
  EXPECT_EQ(crossed, brute_force_crossings(s, m.rest));
  EXPECT_GT(crossed, 0);
  // Crumpled at random: still the oracle's count.
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int trial = 0; trial < 5; ++trial) {
    Positions x = m.rest;
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] += noise(rng);
    EXPECT_EQ(count_self_crossings(s, x), brute_force_crossings(s, x)) << "trial " << trial;
    for (const int workers : {2, 3}) {
      WorkerPool pool(workers);  // edges counted in parts: the same count
      EXPECT_EQ(count_self_crossings(s, x, &pool), brute_force_crossings(s, x)) << "trial " << trial << ", " << workers;
    }
  }
  // Apart, nothing crosses.
  Positions apart = m.rest;
  for (int v = 64; v < m.num_vertices; ++v) apart(v, 1) += 0.2;
  EXPECT_EQ(count_self_crossings(s, apart), 0);
  // A crumpled copy 500 m off along each axis: the cells between span too
  // large a block to index densely, so the grid hashes them; the same count.
  Positions far = m.rest;
  for (Eigen::Index i = 0; i < far.size(); ++i) far.data()[i] += noise(rng);
  const int near_count = count_self_crossings(s, far);
  EXPECT_EQ(near_count, brute_force_crossings(s, far));
  for (int v = 64; v < m.num_vertices; ++v) far.row(v).array() += 500.0;
  EXPECT_EQ(count_self_crossings(s, far), brute_force_crossings(s, far));
  for (int v = 64; v < m.num_vertices; ++v) far.row(v).array() -= 500.0;
  EXPECT_EQ(count_self_crossings(s, far), near_count);
}

IntegratorOptions contact_options(double thickness) {
  IntegratorOptions o;
  o.time_step = 1.0 / 120;
  o.self_contact.thickness = thickness;
  return o;
}

// Runs `steps` steps; returns the largest self-crossing count met at any
// step and the final full positions.
std::pair<int, Positions> run(const DynamicsModel& m, const IntegratorOptions& o, int steps) {
  ImplicitIntegrator integrator;
  integrator.precompute(m, o);
  ClothState state = rest_state(m);
  const ContactSurface surface = contact_surface(m);
  int worst = 0;
  for (int k = 0; k < steps; ++k) {
    integrator.step(state, state.pinned, std::vector<Collider>{});
    worst = std::max(worst, count_self_crossings(surface, full_positions(m, state.positions, state.pinned)));
  }
  return {worst, full_positions(m, state.positions, state.pinned)};
}

// Two 11 x 11 sheets: a 0.5 m drum pinned at its rim, and a 0.3 m sheet 2 cm
// above its middle, free to fall onto it.
DynamicsModel drum_and_falling_sheet(int n = 11) {
  const QuadMesh mesh = sheets({{{-0.25, 0, -0.25}, {0.05, 0, 0}, {0, 0, 0.05}, n, n},
                                {{-0.15, 0.02, -0.15}, {0.03, 0, 0}, {0, 0, 0.03}, n, n}});
  DynamicsOptions d;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      if (k == 0 || i == 0 || k == n - 1 || i == n - 1) d.pinned.push_back(k * n + i);
  return build_dynamics(mesh, d);
}

// A small sheet dropped on a larger one pinned at its rim like a drum:
// with cloth-cloth contact it rests on it a thickness above, without it
// falls through.
TEST(SelfContact, AFallingSheetRestsOnTheOneBelow) {
  const int n = 11;
  const DynamicsModel m = drum_and_falling_sheet(n);
  const double thickness = 0.004;
  const auto [crossed_with, with] = run(m, contact_options(thickness), 120);
  const auto [crossed_without, without] = run(m, contact_options(0.0), 120);
  EXPECT_EQ(crossed_with, 0);
  EXPECT_EQ(crossed_without, 0);  // it falls through flat, within a step
  // Each upper vertex over the lower sheet's triangle under it.
  const ContactSurface s = contact_surface(m);
  double lowest = 1e9;
  for (int v = n * n; v < 2 * n * n; ++v) {
    const Eigen::Vector3d p = with.row(v).transpose();
    for (int t = 0; t < 2 * (n - 1) * (n - 1); ++t) {
      const auto& tri = s.triangles[t];
      const Eigen::Vector3d a = with.row(tri[0]).transpose(), b = with.row(tri[1]).transpose(),
                            c = with.row(tri[2]).transpose();
      const Eigen::Vector3d normal = (b - a).cross(c - a);
      const double area2 = normal.squaredNorm();
      const double bv = (p - a).cross(c - a).dot(normal) / area2, bw = (b - a).cross(p - a).dot(normal) / area2;
      if (bv < 0 || bw < 0 || bv + bw > 1) continue;
      lowest = std::min(lowest, (p - a).dot(normal.normalized()) * (normal.y() > 0 ? 1 : -1));
    }
  }
  EXPECT_GT(lowest, 0.5 * thickness);
  EXPECT_LT(lowest, 3.0 * thickness);
  const int middle = (n * n) / 2;
  EXPECT_LT(without(n * n + middle, 1), without(middle, 1) - 0.1);
}

// A step whose cloth-cloth contact pushed anything takes another round, so
// the limiter sees what the push stretched (before, a round ended on the
// body's checks and the limiter alone, and the trousers with contact but no
// neighbourhood stretched to 72 % where they had reached 37 % only because
// their waistband held every step at all eight rounds).
TEST(SelfContact, AStepWhoseContactPushedTakesAnotherRound) {
  const DynamicsModel m = drum_and_falling_sheet();
  const auto most_rounds = [&](double thickness) {
    ImplicitIntegrator integrator;
    integrator.precompute(m, contact_options(thickness));
    ClothState state = rest_state(m);
    int most = 0;
    for (int k = 0; k < 120; ++k) most = std::max(most, integrator.step(state, state.pinned, std::vector<Collider>{}).rounds);
    return most;
  };
  EXPECT_EQ(most_rounds(0.0), 1);  // nothing to check and nothing stretched: one round
  EXPECT_GE(most_rounds(0.004), 2);
}

// A short strip dropped across another whose vertices never lie over the
// other's triangles: only edge-edge contact can hold it.
TEST(SelfContact, AStripFallingAcrossAnotherIsHeldByItsEdges) {
  // Lower strip along x, 1 cm wide, 5 cm cells, pinned at its four corners;
  // upper strip along z, 1 cm wide, 10 cm long, crossing the lower one
  // between the lower one's vertices and between its own.
  const QuadMesh mesh = sheets({{{-0.5, 0, -0.005}, {0.05, 0, 0}, {0, 0, 0.01}, 21, 2},
                                {{0.02, 0.01, -0.025}, {0.01, 0, 0}, {0, 0, 0.05}, 2, 2}});
  DynamicsOptions d;
  d.pinned = {0, 20, 21, 41};
  const DynamicsModel m = build_dynamics(mesh, d);
  const auto [crossed_with, with] = run(m, contact_options(0.003), 24);
  const auto [crossed_without, without] = run(m, contact_options(0.0), 24);
  EXPECT_EQ(crossed_with, 0);
  // The upper strip lies on the lower one, a thickness above; without
  // contact it falls through.
  const double lower = 0.5 * (with(10, 1) + with(31, 1));
  const double upper = with.bottomRows(4).col(1).mean();
  EXPECT_GT(upper - lower, 0.5 * 0.003);
  EXPECT_LT(upper - lower, 0.02);
  EXPECT_LT(without.bottomRows(4).col(1).mean(), 0.5 * (without(10, 1) + without(31, 1)) - 0.05);
}

// A strip `width` wide along z, its long axis along the polyline `path` in
// the x-y plane, `across` vertices across: vertex ids row by row (path
// point by path point).
QuadMesh strip_along(const std::vector<Eigen::Vector2d>& path, double width, int across) {
  QuadMesh mesh;
  for (const Eigen::Vector2d& p : path)
    for (int j = 0; j < across; ++j) mesh.add_vertex(QuadMesh::Point(p.x(), p.y(), width * j / (across - 1)));
  const auto vid = [&](int i, int j) { return mesh.vertex_handle(i * across + j); };
  for (int i = 0; i + 1 < static_cast<int>(path.size()); ++i)
    for (int j = 0; j + 1 < across; ++j) mesh.add_face(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1));
  init_forest(mesh);
  return mesh;
}

// A hairpin: along x at y = 0 for `length`, round a fold of `gap`, back
// along x at y = gap; `step` between path points on the straight parts.
std::vector<Eigen::Vector2d> hairpin(double length, double gap, double step) {
  std::vector<Eigen::Vector2d> path;
  const int n = static_cast<int>(std::lround(length / step));
  for (int i = 0; i <= n; ++i) path.emplace_back(i * step, 0.0);
  for (int k = 1; k < 4; ++k) {
    const double a = M_PI * k / 4;  // round the fold, centre (length, gap / 2)
    path.emplace_back(length + 0.5 * gap * std::sin(a), 0.5 * gap * (1.0 - std::cos(a)));
  }
  for (int i = n; i >= 0; --i) path.emplace_back(i * step, gap);
  return path;
}

TEST(SheetSupports, OnAFlatGridAreEveryVertexWithinTheBall) {
  const double h = 0.01;
  const QuadMesh mesh = test::make_grid(6, 6, h);
  const DynamicsModel m = build_dynamics(mesh, {});
  const ContactSurface s = contact_surface(m);
  for (const double radius : {0.0, 0.5 * h, 1.01 * h, 1.5 * h, 2.3 * h, 4.0 * h}) {
    const std::vector<std::vector<int>> near = sheet_supports(m, s, radius);
    for (int v = 0; v < m.num_vertices; ++v) {
      // The oracle: a flat grid's vertices within a ball of at least one
      // edge are joined inside it, so all of them (only v in a smaller one).
      std::vector<int> within{v};
      for (int u = 0; u < m.num_vertices; ++u)
        if (u != v && radius >= h && (m.rest.row(u) - m.rest.row(v)).norm() < radius) within.push_back(u);
      std::sort(within.begin(), within.end());
      EXPECT_EQ(near[v], within) << "vertex " << v << ", radius " << radius;
    }
  }
}

TEST(SheetSupports, LeaveOutALayerJoinedOnlyFarAlongTheSheet) {
  // Two layers 2 mm apart, joined by a fold 30 cm away.
  const QuadMesh mesh = strip_along(hairpin(0.3, 0.002, 0.01), 0.02, 3);
  const DynamicsModel m = build_dynamics(mesh, {});
  const ContactSurface s = contact_surface(m);
  const std::vector<std::vector<int>> near = sheet_supports(m, s, 0.026);
  const int middle_lower = 15 * 3 + 1;  // x = 0.15, y = 0, the middle of the width
  for (const int u : near[middle_lower]) {
    EXPECT_LT(m.rest(u, 1), 1e-12) << "vertex " << u << " of the upper layer";
    EXPECT_LT((m.rest.row(u) - m.rest.row(middle_lower)).norm(), 0.026);
  }
  // Its own layer within the ball: x = 0.13 .. 0.17, three across, and
  // the neighbours' neighbours across the width (z within 2.6 cm).
  EXPECT_EQ(near[middle_lower].size(), 5u * 3);
}

// The point of the neighbourhood: pleats whose faces lie closer than the
// thickness, joined a few millimetres along the sheet, are one sheet and
// left alone; the same cloth folded back on itself, joined 30 cm away, is
// two layers held a thickness apart.
TEST(SelfContact, APleatIsOneSheetAndAFoldTwoLayers) {
  const auto moved = [](const QuadMesh& mesh, double neighbourhood) {
    const DynamicsModel m = build_dynamics(mesh, {});
    SelfContactOptions options;
    options.thickness = 0.003;
    options.neighbourhood = neighbourhood;
    SelfContact contact;
    contact.precompute(m, options);
    Positions q(static_cast<Eigen::Index>(m.free_vertices.size()), 3);
    for (std::size_t f = 0; f < m.free_vertices.size(); ++f) q.row(static_cast<Eigen::Index>(f)) = m.rest.row(m.free_vertices[f]);
    contact.gather(m.rest, m.rest);
    return contact.project(q, Positions::Zero(m.num_vertices, 3));
  };
  // Accordion pleats 1.5 mm apart along x, 6 mm deep: neighbouring faces
  // (6.2 mm wide) 2.9 mm apart, joined within 13 mm.
  std::vector<Eigen::Vector2d> pleats;
  for (int i = 0; i < 10; ++i) pleats.emplace_back(0.0015 * i, 0.006 * (i % 2));
  const QuadMesh pleated = strip_along(pleats, 0.01, 3);
  EXPECT_GT(moved(pleated, 0.0), 0.0) << "without a neighbourhood the pleats push each other apart";
  EXPECT_EQ(moved(pleated, -1.0), 0.0) << "the default neighbourhood (26 mm) holds them";
  const QuadMesh folded = strip_along(hairpin(0.3, 0.002, 0.01), 0.02, 3);
  EXPECT_NEAR(moved(folded, -1.0), 0.001, 1e-9) << "the layers 2 mm apart are pushed to the 3 mm thickness";
  // Without it the fold's own elements, a millimetre apart round its bend,
  // push each other too, and farther.
  EXPECT_GT(moved(folded, 0.0), 0.002);
}

TEST(SelfContact, RefusesBadOptions) {
  const DynamicsModel m = build_dynamics(test::make_sheet(3, 0.1), {});
  SelfContact contact;
  EXPECT_THROW(contact.precompute(m, {-0.001, 0.01, 2}), ArgumentError);
  EXPECT_THROW(contact.precompute(m, {0.001, -0.01, 2}), ArgumentError);
  EXPECT_THROW(contact.precompute(m, {0.001, 0.01, 0}), ArgumentError);
  EXPECT_THROW(contact.precompute(m, {0.001, 0.01, 1, std::numeric_limits<double>::quiet_NaN()}), ArgumentError);
}

}  // namespace
}  // namespace mrcloth
