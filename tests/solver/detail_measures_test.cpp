#include "test_meshes.h"

#include "solver/detail_measures.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/uniform_refine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>
#include <string>

namespace mrcloth {
namespace {

Eigen::RowVector3d row_of(const QuadMesh& mesh, int v) {
  const auto& p = mesh.point(mesh.vertex_handle(v));
  return Eigen::RowVector3d(p[0], p[1], p[2]);
}

// The documented convention, written independently of the library: corner 0
// at (0,0), 1 at (1,0), 2 at (1,1), 3 at (0,1).
Eigen::RowVector3d bilinear(const QuadMesh& coarse, int root, double u, double v) {
  const auto& c = quadtree(coarse)[static_cast<std::size_t>(root)].corners;
  return (1 - u) * (1 - v) * row_of(coarse, c[0]) + u * (1 - v) * row_of(coarse, c[1]) + u * v * row_of(coarse, c[2]) +
         (1 - u) * v * row_of(coarse, c[3]);
}

double max_row_distance(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  EXPECT_EQ(a.rows(), b.rows());
  return (a - b).rowwise().norm().maxCoeff();
}

template <typename F>
void expect_throws_naming(F&& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no ArgumentError; expected one naming '" << needle << "'";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "message: " << e.what();
  }
}

// A mesh whose modes are 3 on the lower-left part of a 4x4 grid, refined
// adaptively with 2:1 balance: several levels and hanging vertices.
QuadMesh adaptive_grid() {
  QuadMesh mesh = test::make_grid(4, 4, 0.5);
  std::vector<int> painted;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) painted.push_back(j * 5 + i);
  set_modes(mesh, painted, 3);
  adaptive_refine(mesh, {8.0, 3, true});
  return mesh;
}

// A curved mesh refined adaptively: non-planar quads and hanging vertices.
QuadMesh adaptive_tube() {
  QuadMesh mesh = test::make_tube(6, 4, 0.3, 0.6);
  set_modes(mesh, {0, 1, 6, 7, 12, 13}, 3);
  adaptive_refine(mesh, {8.0, 3, true});
  return mesh;
}

// A smooth random displacement, then every hanging vertex put back at the
// midpoint of its parents (in index order: parents are always older), so the
// surface stays watertight as a simulated frame would.
FramePositions deform_keeping_t_nodes(const QuadMesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Eigen::Matrix3d k;
  Eigen::Vector3d phase, amp;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k(r, c) = 3.0 * uni(rng);
    phase(r) = 3.0 * uni(rng);
    amp(r) = 0.1 * uni(rng);
  }
  FramePositions x = mesh_positions(mesh);
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const Eigen::Vector3d p = x.row(i).transpose();
    for (int r = 0; r < 3; ++r) x(i, r) += amp(r) * std::sin(k.row(r).dot(p) + phase(r));
  }
  const Layers layers = get_layers(mesh);
  for (auto v : mesh.vertices()) {
    if (!mesh.property(layers.hanging, v)) continue;
    const OpenMesh::Vec2i par = mesh.property(layers.parents, v);
    x.row(v.idx()) = (x.row(par[0]) + x.row(par[1])) * 0.5;
  }
  return x;
}

FramePositions affine_map(const FramePositions& x) {
  Eigen::Matrix3d a;
  a << 1.3, -0.4, 0.2, 0.1, 0.9, -0.7, 0.5, 0.3, 1.1;
  const Eigen::RowVector3d t(0.25, -1.5, 2.0);
  FramePositions y = x * a.transpose();
  y.rowwise() += t;
  return y;
}

// ---------------------------------------------------------------- material_points

TEST(MaterialPoints, CoarseCornersFollowTheConvention) {
  for (const QuadMesh& mesh : {test::make_grid(3, 2, 0.5), test::make_tube(5, 3, 0.4, 0.5)}) {
    const std::vector<MaterialPoint> points = material_points(mesh);
    ASSERT_EQ(points.size(), mesh.n_vertices());
    const auto& forest = quadtree(mesh);
    const int roots = static_cast<int>(count_roots(mesh));
    const double cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
    std::vector<int> lowest(mesh.n_vertices(), -1);
    for (int r = 0; r < roots; ++r)
      for (int c : forest[static_cast<std::size_t>(r)].corners)
        if (lowest[static_cast<std::size_t>(c)] < 0) lowest[static_cast<std::size_t>(c)] = r;
    for (int r = 0; r < roots; ++r)
      for (int k = 0; k < 4; ++k) {
        const int c = forest[static_cast<std::size_t>(r)].corners[k];
        if (lowest[static_cast<std::size_t>(c)] != r) continue;
        const MaterialPoint& p = points[static_cast<std::size_t>(c)];
        EXPECT_EQ(p.root, r) << "vertex " << c;
        EXPECT_EQ(p.u, cu[k]) << "vertex " << c << " corner " << k;
        EXPECT_EQ(p.v, cv[k]) << "vertex " << c << " corner " << k;
      }
    for (std::size_t v = 0; v < points.size(); ++v) EXPECT_EQ(points[v].root, lowest[v]) << "vertex " << v;
  }
}

TEST(MaterialPoints, UniformTwiceIsDyadicAndBilinearInTheCoarseFaces) {
  for (const QuadMesh& coarse : {test::make_grid(3, 2, 0.5), test::make_tube(5, 3, 0.4, 0.5)}) {
    QuadMesh fine = copy_mesh(coarse);
    uniform_refine(fine, 2);
    const std::vector<MaterialPoint> points = material_points(fine);
    const std::vector<MaterialPoint> coarse_points = material_points(coarse);
    ASSERT_EQ(points.size(), fine.n_vertices());
    for (std::size_t v = 0; v < points.size(); ++v) {
      const MaterialPoint& p = points[v];
      ASSERT_GE(p.root, 0);
      ASSERT_LT(p.root, static_cast<int>(count_roots(coarse)));
      EXPECT_EQ(p.u * 4, std::round(p.u * 4)) << "vertex " << v;
      EXPECT_EQ(p.v * 4, std::round(p.v * 4)) << "vertex " << v;
      EXPECT_LT((bilinear(coarse, p.root, p.u, p.v) - row_of(fine, static_cast<int>(v))).norm(), 1e-12)
          << "vertex " << v << " at (" << p.root << ", " << p.u << ", " << p.v << ")";
      if (v < coarse_points.size()) {  // coarse vertices keep their name through refinement
        EXPECT_EQ(p.root, coarse_points[v].root);
        EXPECT_EQ(p.u, coarse_points[v].u);
        EXPECT_EQ(p.v, coarse_points[v].v);
      }
    }
  }
}

// ---------------------------------------------------------------- MaterialEvaluator

void expect_reproduces_own_vertices(const QuadMesh& mesh, const FramePositions& x, const char* what) {
  const MaterialEvaluator eval(mesh);
  const MaterialBinding binding = eval.bind(material_points(mesh));
  EXPECT_LT(max_row_distance(eval.evaluate(binding, x), x), 1e-12) << what;
}

TEST(MaterialEvaluator, ReproducesOwnVerticesUniform) {
  QuadMesh mesh = test::make_tube(6, 4, 0.3, 0.6);
  uniform_refine(mesh, 2);
  expect_reproduces_own_vertices(mesh, mesh_positions(mesh), "rest");
  expect_reproduces_own_vertices(mesh, deform_keeping_t_nodes(mesh, 7), "deformed");
}

TEST(MaterialEvaluator, ReproducesOwnVerticesAdaptiveWithHangingNodes) {
  for (const QuadMesh& mesh : {adaptive_grid(), adaptive_tube()}) {
    ASSERT_GT(count_hanging(mesh), 0u) << "the test needs T-nodes";
    ASSERT_GT(faces_per_level(mesh).size(), 3u) << "the test needs level-3 faces";
    expect_reproduces_own_vertices(mesh, mesh_positions(mesh), "rest");
    for (unsigned seed : {1u, 2u, 3u}) expect_reproduces_own_vertices(mesh, deform_keeping_t_nodes(mesh, seed), "deformed");
  }
}

TEST(MaterialEvaluator, OneEvaluatorManyFrames) {
  const QuadMesh mesh = adaptive_grid();
  const MaterialEvaluator eval(mesh);
  const std::vector<MaterialPoint> points = material_points(mesh);
  const MaterialBinding binding = eval.bind(points);
  ASSERT_EQ(binding.size(), points.size());
  for (std::size_t k = 0; k < binding.size(); ++k) {
    EXPECT_EQ(quadtree(mesh)[static_cast<std::size_t>(binding.leaf[k])].active, 1);
    const auto& w = binding.weights[k];
    EXPECT_DOUBLE_EQ(w[0] + w[1] + w[2] + w[3], 1.0);
  }
  for (unsigned seed : {11u, 12u}) {
    const FramePositions x = deform_keeping_t_nodes(mesh, seed);
    EXPECT_EQ(eval.evaluate(binding, x), eval.evaluate(points, x));
  }
}

TEST(MaterialEvaluator, CoarserMeshAtFinerPointsIsExactForAffineFrames) {
  const QuadMesh coarse = test::make_tube(6, 4, 0.3, 0.6);
  QuadMesh fine = copy_mesh(coarse);
  uniform_refine(fine, 3);
  const std::vector<MaterialPoint> fine_points = material_points(fine);
  const FramePositions fine_affine = affine_map(mesh_positions(fine));
  for (const QuadMesh& model : {coarse, adaptive_tube()}) {
    const MaterialEvaluator eval(model);
    const Eigen::MatrixX3d at_fine = eval.evaluate(fine_points, affine_map(mesh_positions(model)));
    EXPECT_LT(max_row_distance(at_fine, fine_affine), 1e-12) << "model of " << model.n_vertices() << " vertices";
  }
  // Must be able to fail: a non-affine frame of the coarse mesh is not the
  // refined surface's frame.
  const MaterialEvaluator eval(coarse);
  FramePositions bent = mesh_positions(coarse);
  bent.col(1) = bent.col(1).array().square();
  FramePositions fine_bent = mesh_positions(fine);
  fine_bent.col(1) = fine_bent.col(1).array().square();
  EXPECT_GT(max_row_distance(eval.evaluate(fine_points, bent), fine_bent), 1e-3);
}

TEST(MaterialEvaluator, ErrorsNameTheElement) {
  QuadMesh mesh = test::make_grid(2, 2);
  uniform_refine(mesh, 1);
  const MaterialEvaluator eval(mesh);
  const FramePositions x = mesh_positions(mesh);
  std::vector<MaterialPoint> points = material_points(mesh);
  points.resize(5);

  auto bad = points;
  bad[3].root = 4;  // the 2x2 grid has roots 0..3
  expect_throws_naming([&] { eval.bind(bad); }, "material point 3");
  expect_throws_naming([&] { eval.bind(bad); }, "root out of range");
  bad[3].root = -1;
  expect_throws_naming([&] { eval.bind(bad); }, "material point 3");
  bad = points;
  bad[2].u = 1.5;
  expect_throws_naming([&] { eval.bind(bad); }, "material point 2");
  bad[2].u = -1e-9;
  expect_throws_naming([&] { eval.bind(bad); }, "[0, 1]");
  bad = points;
  bad[4].v = std::nan("");
  expect_throws_naming([&] { eval.bind(bad); }, "material point 4");

  const FramePositions short_frame = x.topRows(x.rows() - 1);
  expect_throws_naming([&] { eval.evaluate(points, short_frame); }, std::to_string(x.rows() - 1) + " rows");
  const MaterialBinding binding = eval.bind(points);
  expect_throws_naming([&] { eval.evaluate(binding, short_frame); }, std::to_string(x.rows()) + " vertices");

  QuadMesh plain;  // never made refinable: no forest
  const auto a = plain.add_vertex({0, 0, 0}), b = plain.add_vertex({1, 0, 0}), c = plain.add_vertex({1, 1, 0}),
             d = plain.add_vertex({0, 1, 0});
  plain.add_face(a, b, c, d);
  EXPECT_THROW(MaterialEvaluator{plain}, ArgumentError);
  EXPECT_THROW(material_points(plain), ArgumentError);
}

TEST(MaterialPoints, ADamagedForestOrAForeignBindingIsRefusedNamingTheRecord) {
  QuadMesh mesh = test::make_grid(2, 2);
  uniform_refine(mesh, 1);
  const auto damaged = [&](const std::function<void(std::vector<QuadRecord>&)>& damage) {
    QuadMesh copy = copy_mesh(mesh);
    damage(copy.property(get_layers(copy).quadtree));
    return copy;
  };
  const auto refused = [](const QuadMesh& m, const std::string& part) {
    expect_throws_naming([&] { material_points(m); }, part);
  };
  refused(damaged([](auto& f) { f[1].parent = 5; }), "quad record 1 has parent 5 stored after it");
  refused(damaged([](auto& f) { f[0].children[0] = 0; }), "quad record 0 has child 0 out of order or range");
  refused(damaged([](auto& f) { f[2].corners[3] = 999; }),
          "quad record 2 has corner vertex 999; the mesh has " + std::to_string(mesh.n_vertices()) + " vertices");
  QuadMesh isolated = copy_mesh(mesh);
  isolated.add_vertex({5.0, 5.0, 0.0});
  refused(isolated, "vertex " + std::to_string(mesh.n_vertices()) + " is no corner of any quad record");

  // A binding belongs to the mesh it was made for.
  QuadMesh finer = copy_mesh(mesh);
  uniform_refine(finer, 1);
  const MaterialBinding foreign = MaterialEvaluator(finer).bind(material_points(mesh));
  expect_throws_naming([&] { MaterialEvaluator(mesh).evaluate(foreign, mesh_positions(mesh)); },
                       "binding was made for a mesh of " + std::to_string(finer.n_vertices()) +
                           " vertices; this evaluator's mesh has " + std::to_string(mesh.n_vertices()));
}

// ---------------------------------------------------------------- distances

TEST(PointDistances, SelfIsExactlyZero) {
  QuadMesh mesh = adaptive_tube();
  const Eigen::MatrixX3d x = deform_keeping_t_nodes(mesh, 5);
  const DistanceStats s = point_distances(x, x);
  EXPECT_EQ(s.rms, 0.0);
  EXPECT_EQ(s.p95, 0.0);
  EXPECT_EQ(s.max, 0.0);
}

TEST(PointDistances, KnownShift) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Eigen::MatrixX3d a(57, 3);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = uni(rng);
  const Eigen::RowVector3d t(0.3, -0.4, 1.2);  // |t| = 1.3
  const Eigen::MatrixX3d b = a.rowwise() + t;
  const DistanceStats s = point_distances(a, b);
  EXPECT_NEAR(s.rms, 1.3, 1e-12);
  EXPECT_NEAR(s.p95, 1.3, 1e-12);
  EXPECT_NEAR(s.max, 1.3, 1e-12);
}

TEST(PointDistances, NearestRankPercentile) {
  std::vector<int> d(100);
  std::iota(d.begin(), d.end(), 1);
  std::shuffle(d.begin(), d.end(), std::mt19937(9));
  Eigen::MatrixX3d a = Eigen::MatrixX3d::Zero(100, 3), b = Eigen::MatrixX3d::Zero(100, 3);
  for (int i = 0; i < 100; ++i) b(i, i % 3) = (i % 2 ? -1.0 : 1.0) * d[static_cast<std::size_t>(i)];
  DistanceStats s = point_distances(a, b);
  EXPECT_EQ(s.p95, 95.0);
  EXPECT_EQ(s.max, 100.0);
  EXPECT_NEAR(s.rms, std::sqrt(338350.0 / 100.0), 1e-12);
  // ceil(0.95 * 20) = 19th of 1..20; ceil(0.95 * 1) = the only one; ceil(0.95 * 21) = 20th.
  for (int n : {20, 1, 21}) {
    Eigen::MatrixX3d z = Eigen::MatrixX3d::Zero(n, 3), w = Eigen::MatrixX3d::Zero(n, 3);
    for (int i = 0; i < n; ++i) w(i, 2) = n - i;
    s = point_distances(z, w);
    EXPECT_EQ(s.p95, n == 20 ? 19.0 : n == 1 ? 1.0 : 20.0) << "n = " << n;
  }
}

TEST(PointDistances, Errors) {
  const Eigen::MatrixX3d a = Eigen::MatrixX3d::Zero(4, 3), b = Eigen::MatrixX3d::Zero(3, 3);
  expect_throws_naming([&] { point_distances(a, b); }, "3 rows");
  expect_throws_naming([&] { point_distances(Eigen::MatrixX3d(0, 3), Eigen::MatrixX3d(0, 3)); }, "no points");
  Eigen::MatrixX3d c = a;
  c(2, 1) = std::nan("");
  expect_throws_naming([&] { point_distances(a, c); }, "row 2");
}

// ---------------------------------------------------------------- wrinkle energy

TEST(WrinkleEnergy, FlatSheetHasNone) {
  QuadMesh mesh = test::make_grid(3, 2, 0.2);
  uniform_refine(mesh, 2);  // the high-resolution grid: 13 x 9 vertices
  const WrinkleEnergy w(mesh);
  EXPECT_EQ(w.interior_vertices().size(), 11u * 7u);
  for (int v : w.interior_vertices()) EXPECT_EQ(mesh.valence(mesh.vertex_handle(v)), 4u) << "vertex " << v;
  const FramePositions x = mesh_positions(mesh);
  EXPECT_LT(w.energy(x), 1e-20);
  FramePositions sheared = x;  // in-plane affine map
  sheared.col(0) = 1.7 * x.col(0) + 0.6 * x.col(1);
  sheared.col(1) = -0.3 * x.col(0) + 0.8 * x.col(1);
  sheared.col(0).array() += 0.37;
  EXPECT_LT(w.energy(sheared), 1e-20);
  EXPECT_LT(w.energy(affine_map(x)), 1e-20);  // the sheet tilted in space: still flat
  // Must be able to fail: one vertex lifted by 1 mm.
  FramePositions bump = x;
  // The vertex at the sheet's centre (refinement numbers vertices in split
  // order, so find it by position): it and its 4 neighbours are interior.
  Eigen::Index inner = 0;
  (x.rowwise() - Eigen::RowVector3d(0.3, 0.2, 0.0)).rowwise().squaredNorm().minCoeff(&inner);
  ASSERT_LT((x.row(inner) - Eigen::RowVector3d(0.3, 0.2, 0.0)).norm(), 1e-12);
  bump(inner, 2) = 1e-3;
  EXPECT_NEAR(w.energy(bump), 16e-6 + 4 * 1e-6, 1e-18);  // itself: (-4 * 1mm)^2, its 4 neighbours: (1mm)^2
}

TEST(WrinkleEnergy, SinusoidalFoldMatchesClosedForm) {
  const int nx = 24, ny = 7;
  const double hx = 0.013, hy = 0.021, amp = 0.004, k = 2.0 * M_PI / 0.09;
  QuadMesh mesh = test::make_grid(nx, ny);
  FramePositions x(mesh.n_vertices(), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) x.row(j * (nx + 1) + i) << i * hx, j * hy, amp * std::sin(k * i * hx);
  double expected = 0.0;
  std::vector<int> some;
  double expected_some = 0.0;
  for (int j = 1; j < ny; ++j)
    for (int i = 1; i < nx; ++i) {
      const double lap = amp * std::sin(k * i * hx) * 2.0 * (std::cos(k * hx) - 1.0);
      expected += lap * lap;
      if (i % 3 == 0) {
        some.push_back(j * (nx + 1) + i);
        expected_some += lap * lap;
      }
    }
  const WrinkleEnergy w(mesh);
  ASSERT_EQ(w.interior_vertices().size(), static_cast<std::size_t>((nx - 1) * (ny - 1)));
  ASSERT_GT(expected, 0.0);
  EXPECT_NEAR(w.energy(x), expected, 1e-9 * expected);
  EXPECT_NEAR(w.energy(x, some), expected_some, 1e-9 * expected_some);
  // Ratio: the fold against itself and against the flat sheet.
  EXPECT_DOUBLE_EQ(w.ratio(x, x), 1.0);
  FramePositions flat = x;
  flat.col(2).setZero();
  EXPECT_LT(w.ratio(flat, x), 1e-20);  // in-plane rounding only
  FramePositions exact_flat = mesh_positions(mesh);  // integer coordinates: energy exactly 0
  EXPECT_EQ(w.energy(exact_flat), 0.0);
  EXPECT_EQ(w.ratio(exact_flat, x), 0.0);
  EXPECT_TRUE(std::isnan(w.ratio(x, exact_flat)));
  FramePositions half = x;
  half.col(2) *= 0.5;
  EXPECT_NEAR(w.ratio(half, x), 0.25, 1e-12);
}

TEST(WrinkleEnergy, ModeRegionAndErrors) {
  QuadMesh mesh = test::make_grid(3, 3);  // vertices 0..15, interior 5 6 9 10
  set_modes(mesh, {0, 1, 5, 6, 10}, 3);
  EXPECT_EQ(vertices_with_mode(mesh, 3), (std::vector<int>{5, 6, 10}));
  EXPECT_EQ(vertices_with_mode(mesh, 3, false), (std::vector<int>{0, 1, 5, 6, 10}));
  EXPECT_EQ(vertices_with_mode(mesh, 1), (std::vector<int>{9}));

  const WrinkleEnergy w(mesh);
  const FramePositions x = mesh_positions(mesh);
  expect_throws_naming([&] { w.energy(x.topRows(15)); }, "15 rows");
  expect_throws_naming([&] { w.energy(x, {5, 16}); }, "vertex 16");
  expect_throws_naming([&] { w.energy(x, {-1}); }, "vertex -1");
}

}  // namespace
}  // namespace mrcloth
