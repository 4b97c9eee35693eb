// The test that validates eq. 1's exponents and the level convention: a
// multi-resolution sheet must drape like the uniform high-resolution sheet it
// approximates. Both refine the same coarse sheet by midpoints, so every
// vertex of the multi-resolution sheet is a vertex of the high-resolution one
// at bitwise the same rest position; shapes are compared there.
#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/uniform_refine.h"
#include "solver/simulate.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

namespace mrcloth {
namespace {

Positions hang_from_two_corners(const QuadMesh& mesh, const DynamicsOptions& base, int corner_a, int corner_b) {
  DynamicsOptions d = base;
  d.pinned = {corner_a, corner_b};
  d.material.damping = 3.0;  // reach equilibrium within the simulated 2 s
  const DynamicsModel model = build_dynamics(mesh, d);
  SimulationOptions s;
  s.frames = 60;
  s.fps = 30.0;
  s.substeps = 4;
  s.iterations = 10;
  ClothState state = rest_state(model);
  const SimulationReport report = simulate(model, state, s);
  EXPECT_FALSE(report.non_finite);
  return full_positions(model, state.positions, state.pinned);
}

struct Comparison {
  double multi_rms = 0.0;   // multi-resolution vs high resolution, metres
  double coarse_rms = 0.0;  // coarse vs high resolution, metres
};

Comparison compare(const DynamicsOptions& options) {
  const int n = 9;  // 0.5 m sheet, 8 x 8 coarse quads
  const QuadMesh coarse = test::make_sheet(n, 0.5);
  QuadMesh high = copy_mesh(coarse);
  uniform_refine(high, 2);
  QuadMesh multi = copy_mesh(coarse);
  paint_modes_sphere(multi, {0, 0, 0}, 0.3, 2);
  paint_modes_sphere(multi, {0, 0, 0}, 0.18, 3);
  adaptive_refine(multi, {8.0, 3, true});

  std::map<std::array<double, 3>, int> high_index;
  for (auto v : high.vertices()) high_index[{high.point(v)[0], high.point(v)[1], high.point(v)[2]}] = v.idx();
  const auto to_high = [&](const QuadMesh& mesh, int v) {
    const auto p = mesh.point(mesh.vertex_handle(v));
    const auto it = high_index.find({p[0], p[1], p[2]});
    return it == high_index.end() ? -1 : it->second;
  };

  const Positions xh = hang_from_two_corners(high, options, 0, n - 1);
  const Positions xm = hang_from_two_corners(multi, options, 0, n - 1);
  const Positions xc = hang_from_two_corners(coarse, options, 0, n - 1);
  Comparison c;
  for (Eigen::Index v = 0; v < xm.rows(); ++v) {
    const int h = to_high(multi, static_cast<int>(v));
    EXPECT_GE(h, 0) << "multi-resolution vertex " << v << " is not a high-resolution vertex";
    if (h >= 0) c.multi_rms += (xm.row(v) - xh.row(h)).squaredNorm();
  }
  for (Eigen::Index v = 0; v < xc.rows(); ++v) c.coarse_rms += (xc.row(v) - xh.row(v)).squaredNorm();
  c.multi_rms = std::sqrt(c.multi_rms / xm.rows());
  c.coarse_rms = std::sqrt(c.coarse_rms / xc.rows());
  return c;
}

TEST(DrapeConsistency, MultiResolutionDrapesLikeHighResolutionWithTheDefaults) {
  const Comparison c = compare({});
  // Stated tolerance: RMS distance at the shared vertices within 4 mm on a
  // 0.5 m sheet hanging ~0.4 m, and closer than the coarse sheet gets.
  EXPECT_LT(c.multi_rms, 0.004);
  EXPECT_LT(c.multi_rms, c.coarse_rms);
}

TEST(DrapeConsistency, TheDefaultExponentsBeatTheirNeighbours) {
  const double at_default = compare({}).multi_rms;
  DynamicsOptions stiffer_fine_stretch;
  stiffer_fine_stretch.alpha = 0.25;
  DynamicsOptions weaker_fine_bend;
  weaker_fine_bend.alpha_bend = 1.0;
  EXPECT_LT(at_default, compare(stiffer_fine_stretch).multi_rms);
  EXPECT_LT(at_default, compare(weaker_fine_bend).multi_rms);
}

}  // namespace
}  // namespace mrcloth
