#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/lumped_mass.h"
#include "mesh_ops/mode_layer.h"
#include "solver/dynamics_model.h"
#include "solver/material.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

namespace mrcloth {
namespace {

int count(const DynamicsModel& m, SpringKind kind) {
  return static_cast<int>(std::count_if(m.springs.begin(), m.springs.end(), [&](const Spring& s) { return s.kind == kind; }));
}

QuadMesh refined_grid() {
  QuadMesh mesh = test::make_grid(4, 3, 0.1);
  set_modes(mesh, {0, 1, 5, 6}, 4);
  adaptive_refine(mesh, {8.0, 3, true});
  return mesh;
}

// A run given no material and one given "cotton" must simulate the same
// cloth: the default Material is the cotton preset, field for field.
TEST(Material, TheDefaultIsTheCottonPreset) {
  const Material fallback, cotton = material_preset("cotton");
  EXPECT_EQ(fallback.name, cotton.name);
  EXPECT_EQ(fallback.areal_density, cotton.areal_density);
  EXPECT_EQ(fallback.stretch_stiffness, cotton.stretch_stiffness);
  EXPECT_EQ(fallback.shear_stiffness, cotton.shear_stiffness);
  EXPECT_EQ(fallback.bend_stiffness, cotton.bend_stiffness);
  EXPECT_EQ(fallback.damping, cotton.damping);
  EXPECT_EQ(fallback.stretch_limit, cotton.stretch_limit);
  EXPECT_LT(material_preset("silk").stretch_stiffness, cotton.stretch_stiffness);
  EXPECT_GT(material_preset("denim").stretch_stiffness, cotton.stretch_stiffness);
}

TEST(DynamicsModel, BuildingConsultsItsCallbackBetweenPhasesAndStopsWhenAsked) {
  const QuadMesh mesh = test::make_sheet(9, 0.4);
  DynamicsOptions options;
  options.pinned = {0, 8};
  int calls = 0;
  const std::optional<DynamicsModel> watched = build_dynamics(mesh, options, [&] { return ++calls > 0; });
  ASSERT_TRUE(watched.has_value());
  EXPECT_EQ(calls, 4) << "after the stretch and shear springs, the bend pairs, the bend springs, the rows";
  const DynamicsModel plain = build_dynamics(mesh, options);
  EXPECT_EQ(watched->springs.size(), plain.springs.size());
  EXPECT_EQ(watched->free_vertices, plain.free_vertices);
  EXPECT_EQ(watched->free_mass, plain.free_mass);
  EXPECT_EQ(Eigen::MatrixXd(watched->S), Eigen::MatrixXd(plain.S));
  for (int stop_at = 1; stop_at <= 4; ++stop_at) {
    int seen = 0;
    EXPECT_FALSE(build_dynamics(mesh, options, [&] { return ++seen < stop_at; }).has_value()) << stop_at;
    EXPECT_EQ(seen, stop_at);
  }
}

TEST(DynamicsModel, SpringCountsOnARegularGrid) {
  // 4 x 3 quads: stretch 4*4 + 3*5 edges, shear 2 per quad, bend: rows
  // 4 * 3 + columns 5 * 2 two-step pairs, plus 2 diagonal pairs through each
  // of the 3 * 2 interior vertices.
  const DynamicsModel m = build_dynamics(test::make_grid(4, 3), {});
  EXPECT_EQ(count(m, SpringKind::stretch), 31);
  EXPECT_EQ(count(m, SpringKind::shear), 24);
  EXPECT_EQ(count(m, SpringKind::bend), 22 + 12);
  for (const Spring& s : m.springs) EXPECT_EQ(s.rest, (m.rest.row(s.i) - m.rest.row(s.j)).norm());
}

TEST(DynamicsModel, StiffnessFollowsEquationOne) {
  DynamicsOptions o;
  o.alpha = 0.5;
  o.alpha_bend = 1.5;
  const DynamicsModel m = build_dynamics(refined_grid(), o);
  std::set<int> levels;
  for (const Spring& s : m.springs) {
    levels.insert(s.level);
    const double base = s.kind == SpringKind::stretch ? o.material.stretch_stiffness
                        : s.kind == SpringKind::shear ? o.material.shear_stiffness
                                                      : o.material.bend_stiffness;
    const double a = s.kind == SpringKind::bend ? o.alpha_bend : o.alpha;
    EXPECT_DOUBLE_EQ(s.stiffness, base * std::exp2(a * (s.level - 1)));
  }
  EXPECT_EQ(levels, (std::set<int>{1, 2, 3}));
}

TEST(DynamicsModel, InterpolationMatrixPutsTNodesAtTheirParentsMidpoint) {
  const QuadMesh mesh = refined_grid();
  const DynamicsModel m = build_dynamics(mesh, {});
  ASSERT_FALSE(m.hanging_vertices.empty());
  EXPECT_EQ(m.free_vertices.size() + m.hanging_vertices.size(), mesh.n_vertices());
  const Positions x = full_positions(m, free_rows(m, m.rest), pinned_rows(m, m.rest));
  const Layers l = get_layers(mesh);
  for (int v : m.hanging_vertices) {
    const OpenMesh::Vec2i p = mesh.property(l.parents, mesh.vertex_handle(v));
    EXPECT_EQ(x.row(v), 0.5 * (x.row(p[0]) + x.row(p[1]))) << "vertex " << v;
  }
  const Eigen::VectorXd row_sums = m.S * Eigen::VectorXd::Ones(m.S.cols());
  for (Eigen::Index v = 0; v < row_sums.size(); ++v) EXPECT_EQ(row_sums[v], 1.0);
  EXPECT_NEAR(m.free_mass.sum(), m.material.areal_density * garment_area(mesh), 1e-15);
}

TEST(DynamicsModel, PinnedVerticesLeaveTheUnknowns) {
  DynamicsOptions o;
  o.pinned = {0, 4};
  const DynamicsModel m = build_dynamics(test::make_grid(4, 3), o);
  EXPECT_EQ(m.pinned_vertices, (std::vector<int>{0, 4}));
  EXPECT_EQ(m.free_vertices.size(), 20u - 2u);
  EXPECT_EQ(m.P.nonZeros(), 2);
}

TEST(DynamicsModel, BadPinsAreRefused) {
  const QuadMesh mesh = refined_grid();
  DynamicsOptions o;
  o.pinned = {static_cast<int>(mesh.n_vertices())};
  EXPECT_THROW(build_dynamics(mesh, o), ArgumentError);
  const Layers l = get_layers(mesh);
  for (auto v : mesh.vertices())
    if (mesh.property(l.hanging, v)) {
      o.pinned = {v.idx()};
      try {
        build_dynamics(mesh, o);
        FAIL() << "pinning a hanging node must be refused";
      } catch (const ArgumentError& e) {
        EXPECT_NE(std::string(e.what()).find("hanging"), std::string::npos) << e.what();
      }
      break;
    }
}

TEST(DynamicsModel, MostStretchedAndTearOpeningAgreeWithBruteForce) {
  // A 4 x 3 grid (edges 0.1 m) deformed at random, and then with one edge
  // pulled to 2.5x (a tear 0.15 m open) and another to 1.9x (stretched,
  // not doubled): strain and opening against a loop over the springs.
  const DynamicsModel m = build_dynamics(test::make_grid(4, 3, 0.1), {});
  Positions x = m.rest;
  for (Eigen::Index v = 0; v < x.rows(); ++v) x.row(v) += 0.004 * Eigen::RowVector3d(std::sin(3.0 * v), std::cos(5.0 * v), 0.5);
  const auto brute = [&](double& strain, double& opening) {
    strain = 0.0;
    opening = 0.0;
    for (const Spring& s : m.springs) {
      if (s.kind != SpringKind::stretch) continue;
      const double length = (x.row(s.i) - x.row(s.j)).norm();
      strain = std::max(strain, length / s.rest - 1.0);
      if (length >= 2.0 * s.rest) opening = std::max(opening, length - s.rest);
    }
  };
  double strain = 0.0, opening = 0.0;
  brute(strain, opening);
  StretchPeak peak = most_stretched(m, x);
  EXPECT_NEAR(peak.strain, strain, 1e-12);
  EXPECT_EQ(peak.tear_opening, 0.0) << "nothing doubled";
  ASSERT_GT(strain, 0.0);
  EXPECT_NEAR(max_stretch(m, x), strain, 1e-12);
  // The last vertex of the grid's first row pulled out along x: its edge
  // to its neighbour becomes 0.25 m long (2.5x); a vertex of the top row
  // pulled up to make its vertical edge 0.19 m (1.9x).
  x = m.rest;
  x(4, 0) += 0.15;
  x(19, 1) += 0.09;
  brute(strain, opening);
  peak = most_stretched(m, x);
  EXPECT_NEAR(peak.strain, 1.5, 1e-12);
  EXPECT_NEAR(peak.strain, strain, 1e-12);
  EXPECT_NEAR(peak.tear_opening, 0.15, 1e-12);
  EXPECT_NEAR(peak.tear_opening, opening, 1e-12);
  EXPECT_EQ(std::min(peak.i, peak.j), 3);
  EXPECT_EQ(std::max(peak.i, peak.j), 4);
}

TEST(DynamicsModel, AnEdgeExactlyDoubledCountsAsATearAndOneJustShortDoesNot) {
  // Edges of 1/8 m, so positions and lengths are exact binary fractions:
  // the first row's last vertex pulled out by exactly one edge length
  // doubles its edge (strain 1 exactly), which counts; one ulp less does not.
  const DynamicsModel m = build_dynamics(test::make_grid(4, 3, 0.125), {});
  Positions x = m.rest;
  x(4, 0) += 0.125;
  StretchPeak peak = most_stretched(m, x);
  EXPECT_EQ(peak.strain, 1.0);
  EXPECT_EQ(peak.tear_opening, 0.125);
  x(4, 0) = std::nextafter(x(4, 0), 0.0);
  peak = most_stretched(m, x);
  EXPECT_LT(peak.strain, 1.0);
  EXPECT_EQ(peak.tear_opening, 0.0);
}

}  // namespace

// The peak split by who sets a spring's length: a spring between two
// pinned vertices is stretched by what drives the pins (a waistband on the
// skin), one with a free end by the cloth.
TEST(DynamicsModel, MostStretchedSaysWhetherThePinsSetIt) {
  DynamicsOptions o;
  o.pinned = {0, 1, 2, 3, 4};  // the grid's first row
  const DynamicsModel m = build_dynamics(test::make_grid(4, 3, 0.1), o);
  const std::set<int> pinned(o.pinned.begin(), o.pinned.end());
  const auto brute = [&](const Positions& x, double& cloth, double& held) {
    cloth = held = 0.0;
    for (const Spring& s : m.springs) {
      if (s.kind != SpringKind::stretch) continue;
      const double strain = (x.row(s.i) - x.row(s.j)).norm() / s.rest - 1.0;
      double& part = pinned.count(s.i) && pinned.count(s.j) ? held : cloth;
      part = std::max(part, strain);
    }
  };
  // The first row's last edge (pinned at both ends) to 1.5x; the last
  // column's top edge (free) to 1.2x. Moving pin 4 also tilts its edge to
  // free vertex 9: sqrt(0.05^2 + 0.1^2) = 0.1118 m, strain 0.118.
  Positions x = m.rest;
  x(4, 0) += 0.05;
  x(19, 1) += 0.02;
  StretchPeak peak = most_stretched(m, x);
  EXPECT_NEAR(peak.strain, 0.5, 1e-12);
  EXPECT_TRUE(peak.pinned());
  EXPECT_EQ(std::min(peak.i, peak.j), 3);
  EXPECT_EQ(std::max(peak.i, peak.j), 4);
  EXPECT_NEAR(peak.pinned_strain, 0.5, 1e-12);
  EXPECT_NEAR(peak.cloth_strain, 0.2, 1e-12);
  // The free edge pulled farther than the pinned one: the peak is the cloth's.
  x(19, 1) += 0.05;
  peak = most_stretched(m, x);
  EXPECT_NEAR(peak.strain, 0.7, 1e-12);
  EXPECT_FALSE(peak.pinned());
  EXPECT_NEAR(peak.cloth_strain, 0.7, 1e-12);
  EXPECT_NEAR(peak.pinned_strain, 0.5, 1e-12);
  // A spring from a pin to a free vertex is the cloth's: the solver moves
  // its free end.
  x = m.rest;
  x(9, 1) += 0.03;
  peak = most_stretched(m, x);
  EXPECT_NEAR(peak.strain, 0.3, 1e-12);
  EXPECT_FALSE(peak.pinned());
  EXPECT_EQ(std::min(peak.i, peak.j), 4);
  EXPECT_EQ(std::max(peak.i, peak.j), 9);
  EXPECT_NEAR(peak.cloth_strain, 0.3, 1e-12);
  EXPECT_EQ(peak.pinned_strain, 0.0);
  // At random: both parts against the loop, the peak their larger.
  x = m.rest;
  for (Eigen::Index v = 0; v < x.rows(); ++v) x.row(v) += 0.01 * Eigen::RowVector3d(std::sin(7.0 * v), std::cos(2.0 * v), std::sin(v));
  double cloth = 0.0, held = 0.0;
  brute(x, cloth, held);
  peak = most_stretched(m, x);
  EXPECT_NEAR(peak.cloth_strain, cloth, 1e-12);
  EXPECT_NEAR(peak.pinned_strain, held, 1e-12);
  EXPECT_EQ(peak.strain, std::max(peak.cloth_strain, peak.pinned_strain));
  EXPECT_EQ(peak.pinned(), held > cloth);
}

// A T-node whose coarse edge's ends are both pinned follows the pins too:
// with every vertex but the T-nodes pinned, no spring is the cloth's.
TEST(DynamicsModel, TNodesBetweenPinsFollowThePins) {
  const QuadMesh mesh = refined_grid();
  const Layers l = get_layers(mesh);
  DynamicsOptions o;
  int hanging = 0;
  for (auto v : mesh.vertices()) {
    if (mesh.property(l.hanging, v)) ++hanging;
    else o.pinned.push_back(v.idx());
  }
  ASSERT_GT(hanging, 0) << "the refined grid has T-nodes";
  const DynamicsModel m = build_dynamics(mesh, o);
  Positions x = m.rest;
  for (Eigen::Index v = 0; v < x.rows(); ++v) x.row(v) *= 1.0 + 0.1 * std::abs(std::sin(3.0 * v));
  const StretchPeak peak = most_stretched(m, x);
  ASSERT_GT(peak.strain, 0.0);
  EXPECT_TRUE(peak.pinned());
  EXPECT_EQ(peak.cloth_strain, 0.0);
  EXPECT_EQ(peak.pinned_strain, peak.strain);
}

}  // namespace mrcloth
