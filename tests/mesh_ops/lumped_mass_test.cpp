#include "mesh_invariants.h"
#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/lumped_mass.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/uniform_refine.h"

#include <gtest/gtest.h>

#include <numeric>
#include <random>

namespace mrcloth {
namespace {

double total(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

TEST(LumpedMass, UnitGridByHand) {
  // 2x1 unit quads, density 2: each quad has mass 2, a quarter (0.5) to each
  // corner; the two shared vertices get 1.
  QuadMesh mesh = test::make_grid(2, 1);
  const auto m = lumped_mass(mesh, 2.0);
  EXPECT_EQ(m, (std::vector<double>{0.5, 1.0, 0.5, 0.5, 1.0, 0.5}));
  EXPECT_EQ(garment_area(mesh), 2.0);
}

TEST(LumpedMass, PlanarLevelKFaceHasAQuarterPowerOfTheCoarseArea) {
  QuadMesh mesh = test::make_grid(3, 2, 0.5);
  set_modes(mesh, {0, 1, 4, 5}, 4);
  adaptive_refine(mesh, {8.0, 4, true});
  const auto areas = rest_face_areas(mesh);
  const auto level = get_layers(mesh).level;
  for (auto f : mesh.faces())
    EXPECT_NEAR(areas[f.idx()], 0.25 * std::ldexp(1.0, -2 * (mesh.property(level, f) - 1)), 1e-15);
}

TEST(LumpedMass, HangingVerticesPassTheirMassToTheirParents) {
  QuadMesh mesh = test::make_grid(2, 1);
  set_modes(mesh, {0, 1, 3, 4}, 3);
  adaptive_refine(mesh, {9.0, 2, false});  // left 12 >= 9, right 8: left split once: one hanging midpoint
  ASSERT_EQ(count_hanging(mesh), 1u);
  const auto m = lumped_mass(mesh, 1.0);
  const auto hanging = get_layers(mesh).hanging;
  for (auto v : mesh.vertices()) {
    if (mesh.property(hanging, v)) {
      EXPECT_EQ(m[v.idx()], 0.0);
    }
  }
  // Vertex 1 (shared, bottom): a quarter of the right quad (0.25) + a quarter
  // of one left child (1/16) + half of the hanging midpoint's two child
  // quarters (0.5 * 2/16).
  EXPECT_DOUBLE_EQ(m[1], 0.25 + 1.0 / 16 + 1.0 / 16);
  EXPECT_NEAR(total(m), 2.0, 1e-15);
}

TEST(LumpedMass, TotalIsDensityTimesAreaOnRandomRefinements) {
  std::mt19937 rng(7);
  const double density = 0.173;
  for (int trial = 0; trial < 20; ++trial) {
    QuadMesh mesh = test::make_tube(9, 6, 0.35, 0.6);  // curved, trapezoid quads
    const double area = garment_area(mesh);
    std::uniform_int_distribution<int> mode(1, 4);
    for (auto v : mesh.vertices()) set_modes(mesh, {v.idx()}, mode(rng));
    const bool balance = trial % 2 == 0;
    adaptive_refine(mesh, {std::uniform_real_distribution<double>(5.0, 11.0)(rng), 4, balance});
    SCOPED_TRACE("trial " + std::to_string(trial));
    EXPECT_NEAR(garment_area(mesh), area, 1e-12 * area) << "refinement moved coarse vertices";
    EXPECT_NEAR(total(lumped_mass(mesh, density)), density * area, 1e-12 * density * area);
    EXPECT_NEAR(total(rest_face_areas(mesh)), area, 1e-12 * area);
  }
}

TEST(LumpedMass, UniformRefinementConservesMassAtExtremeScales) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    QuadMesh mesh = test::make_tube(8, 4, 0.3 * scale, 0.5 * scale);
    const double expected = 0.2 * garment_area(mesh);
    uniform_refine(mesh, 2);
    EXPECT_NEAR(total(lumped_mass(mesh, 0.2)), expected, 1e-12 * expected) << "scale " << scale;
  }
}

TEST(LumpedMass, RefusesNonPositiveDensity) {
  QuadMesh mesh = test::make_grid(1, 1);
  EXPECT_THROW(lumped_mass(mesh, 0.0), ArgumentError);
  EXPECT_THROW(lumped_mass(mesh, -1.0), ArgumentError);
}

}  // namespace
}  // namespace mrcloth
