// Mapping modes from a refined mesh to its coarse mesh: stable indices, the
// cells of coarse vertices (exact members on a grid), highest / most
// frequent in the cell, agreement counts, and refusal of unrelated meshes.
#include "mesh_ops/mode_mapping.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/mode_painting.h"
#include "mesh_ops/uniform_refine.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

/// Refined vertices within the square of half-width `half` around p (the
/// oracle for a cell on a regular grid), by position.
std::vector<int> within_square(const QuadMesh& mesh, const QuadMesh::Point& p, double half) {
  std::vector<int> inside;
  for (const auto v : mesh.vertices()) {
    const auto d = mesh.point(v) - p;
    if (std::abs(d[0]) <= half + 1e-12 && std::abs(d[1]) <= half + 1e-12) inside.push_back(v.idx());
  }
  return inside;
}

TEST(ModeMapping, CellsAreTheDualSquaresOfTheCoarseVertices) {
  // A 3 x 3 grid of unit quads refined twice: a coarse vertex's cell is the
  // square half a coarse edge around it, clipped to the sheet: 5 x 5 fine
  // vertices inside, 3 x 5 on an edge, 3 x 3 at a corner.
  const QuadMesh coarse = test::make_grid(3, 3, 1.0);
  QuadMesh refined = copy_mesh(coarse);
  uniform_refine(refined, 2);
  const std::vector<std::vector<int>> cells = coarse_vertex_cells(refined, 16);
  for (int v = 0; v < 16; ++v) {
    const std::vector<int>& cell = cells[static_cast<std::size_t>(v)];
    EXPECT_EQ(cell, within_square(refined, coarse.point(coarse.vertex_handle(static_cast<unsigned>(v))), 0.5))
        << "coarse vertex " << v;
    const int x = v % 4, y = v / 4;
    const bool x_edge = x == 0 || x == 3, y_edge = y == 0 || y == 3;
    EXPECT_EQ(cell.size(), static_cast<std::size_t>((x_edge ? 3 : 5) * (y_edge ? 3 : 5))) << v;
  }
  // Unrefined: each cell is the vertex alone.
  const std::vector<std::vector<int>> alone = coarse_vertex_cells(coarse, 16);
  for (int v = 0; v < 16; ++v) EXPECT_EQ(alone[static_cast<std::size_t>(v)], std::vector<int>{v});
}

TEST(ModeMapping, IndexHighestAndFrequent) {
  QuadMesh coarse = test::make_grid(3, 3, 1.0);
  QuadMesh refined = copy_mesh(coarse);
  uniform_refine(refined, 2);
  // Interior coarse vertex 5 at (1, 1): its own fine vertex mode 2, 3 others
  // of its cell mode 4, 14 mode 3, 7 left at 1 -> highest 4, most frequent 3.
  std::vector<int> cell5 = within_square(refined, QuadMesh::Point(1, 1, 0), 0.5);
  ASSERT_EQ(cell5.size(), 25u);
  std::vector<int> threes, fours;
  for (const int u : cell5) {
    if (u == 5) continue;
    if (fours.size() < 3) fours.push_back(u);
    else if (threes.size() < 14) threes.push_back(u);
  }
  set_modes(refined, threes, 3);
  set_modes(refined, fours, 4);
  set_modes(refined, {5}, 2);
  // Corner vertex 15 at (3, 3), far from those: its 9 fine vertices mode 1
  // except itself, mode 3.
  set_modes(refined, {15}, 3);

  ModeMapReport index = map_modes(refined, coarse, ModeMapping::stable_index);
  EXPECT_EQ(get_modes(coarse), index.modes);
  EXPECT_EQ(index.modes[5], 2);
  EXPECT_EQ(index.modes[15], 3);
  EXPECT_EQ(index.changed, 2) << "vertices 5 and 15 left mode 1";
  const ModeMapReport highest = map_modes(refined, coarse, ModeMapping::cell_highest);
  EXPECT_EQ(highest.modes[5], 4);
  EXPECT_EQ(highest.modes[15], 3);
  const ModeMapReport frequent = map_modes(refined, coarse, ModeMapping::cell_frequent);
  EXPECT_EQ(frequent.modes[5], 3) << "14 threes, 7 ones, 3 fours, 1 two";
  EXPECT_EQ(frequent.modes[15], 1) << "8 ones, 1 three";
  EXPECT_EQ(get_modes(coarse), frequent.modes);
  // Vertices whose cells other painted vertices reach differ too; count by brute force.
  const std::vector<std::vector<int>> cells = coarse_vertex_cells(refined, 16);
  const std::vector<int> fine = get_modes(refined);
  int agree_highest = 0;
  for (int v = 0; v < 16; ++v) {
    int h = 0;
    for (const int u : cells[static_cast<std::size_t>(v)]) h = std::max(h, fine[static_cast<std::size_t>(u)]);
    agree_highest += h == fine[static_cast<std::size_t>(v)];
  }
  EXPECT_EQ(index.agree_highest, agree_highest);
  EXPECT_EQ(highest.agree_highest, agree_highest) << "the counts do not depend on the mapping chosen";
  EXPECT_LT(index.agree_highest, 16);
  for (int v = 0; v < 16; ++v) EXPECT_EQ(index.cell_sizes[static_cast<std::size_t>(v)], static_cast<int>(cells[static_cast<std::size_t>(v)].size()));
}

// The mapped modes are the coarse mesh's computed ones: a brush stroke on
// the coarse mesh afterwards is erased back to them, not to the default.
TEST(ModeMapping, ErasingAfterMappingGoesBackToTheMappedModes) {
  QuadMesh coarse = test::make_grid(3, 3, 1.0);
  QuadMesh refined = copy_mesh(coarse);
  uniform_refine(refined, 1);
  set_modes(refined, {5, 6}, 3);
  const ModeMapReport mapped = map_modes(refined, coarse, ModeMapping::stable_index);
  EXPECT_EQ(computed_modes(coarse), mapped.modes);
  set_modes(coarse, {5}, 2);
  EXPECT_EQ(erase_modes(coarse, {5}), 1u);
  EXPECT_EQ(get_modes(coarse)[5], 3);
  EXPECT_EQ(erase_modes(coarse), 0u);
  EXPECT_EQ(get_modes(coarse), mapped.modes);
  // A painted 0 (never refine) maps as a mode: erased back to 0, not to the default.
  set_modes(refined, {7}, 0);
  const ModeMapReport zero = map_modes(refined, coarse, ModeMapping::stable_index);
  ASSERT_EQ(zero.modes[7], 0);
  set_modes(coarse, {7}, 4);
  EXPECT_EQ(erase_modes(coarse, {7}), 1u);
  EXPECT_EQ(get_modes(coarse)[7], 0);
}

TEST(ModeMapping, TiesGoToTheHigherMode) {
  // Corner vertex 0 of a single quad refined once: cell of 4 fine vertices,
  // two of mode 2 and two of mode 5.
  QuadMesh coarse = test::make_grid(1, 1, 1.0);
  QuadMesh refined = copy_mesh(coarse);
  uniform_refine(refined, 1);
  const std::vector<int> cell = coarse_vertex_cells(refined, 4)[0];
  ASSERT_EQ(cell.size(), 4u);
  set_modes(refined, {cell[0], cell[1]}, 2);
  set_modes(refined, {cell[2], cell[3]}, 5);
  EXPECT_EQ(map_modes(refined, coarse, ModeMapping::cell_frequent).modes[0], 5);
}

TEST(ModeMapping, AdaptiveRefinementsMapToo) {
  // Refined only around one vertex: other cells are the coarse vertex plus
  // whatever fine vertices its quarters hold, and stable indices still hold.
  QuadMesh coarse = test::make_grid(3, 3, 1.0);
  set_modes(coarse, {5}, 3);
  QuadMesh refined = copy_mesh(coarse);
  adaptive_refine(refined, {4.0, 3, true});
  ASSERT_GT(refined.n_vertices(), coarse.n_vertices());
  const std::vector<std::vector<int>> cells = coarse_vertex_cells(refined, 16);
  std::set<int> covered;
  for (const auto& cell : cells) covered.insert(cell.begin(), cell.end());
  EXPECT_EQ(covered.size(), refined.n_vertices()) << "every refined vertex lies in some cell";
  const ModeMapReport report = map_modes(refined, coarse, ModeMapping::stable_index);
  const std::vector<int> fine = get_modes(refined);
  EXPECT_EQ(report.modes, std::vector<int>(fine.begin(), fine.begin() + 16));
}

TEST(ModeMapping, RefusesUnrelatedMeshesAndNames) {
  QuadMesh coarse = test::make_grid(3, 3, 1.0);
  QuadMesh other = test::make_grid(2, 2, 1.0);
  QuadMesh refined = copy_mesh(coarse);
  uniform_refine(refined, 1);
  EXPECT_THROW(map_modes(other, coarse, ModeMapping::stable_index), ArgumentError) << "fewer vertices";
  QuadMesh bigger = test::make_grid(4, 4, 1.0);
  EXPECT_THROW(map_modes(bigger, coarse, ModeMapping::stable_index), ArgumentError) << "other faces";
  QuadMesh moved = copy_mesh(refined);
  moved.point(moved.vertex_handle(7)) += QuadMesh::Point(0, 0, 0.01);
  try {
    map_modes(moved, coarse, ModeMapping::stable_index);
    ADD_FAILURE() << "a refined mesh not at rest";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("coarse vertex 7"), std::string::npos) << e.what();
  }
  EXPECT_EQ(get_modes(coarse), std::vector<int>(16, kDefaultMode)) << "refusals change nothing";
  for (const ModeMapping m : {ModeMapping::stable_index, ModeMapping::cell_highest, ModeMapping::cell_frequent})
    EXPECT_EQ(mode_mapping_from_name(mode_mapping_name(m)), m);
  EXPECT_THROW(mode_mapping_from_name("mean"), ArgumentError);
}

}  // namespace
}  // namespace mrcloth
