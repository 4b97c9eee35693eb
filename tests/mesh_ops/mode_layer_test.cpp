#include "test_meshes.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/uniform_refine.h"

#include <gtest/gtest.h>

namespace mrcloth {
namespace {

TEST(ModeLayer, DefaultIsTheLowestMode) {
  const QuadMesh mesh = test::make_grid(2, 2);
  EXPECT_EQ(get_modes(mesh), std::vector<int>(9, kDefaultMode));
}

TEST(ModeLayer, SetModesOnAVertexSet) {
  QuadMesh mesh = test::make_grid(2, 2);
  set_modes(mesh, {0, 4, 8}, 3);
  EXPECT_EQ(get_modes(mesh), (std::vector<int>{3, 1, 1, 1, 3, 1, 1, 1, 3}));
}

TEST(ModeLayer, BadIdsChangeNothing) {
  QuadMesh mesh = test::make_grid(2, 2);
  try {
    set_modes(mesh, {0, 9}, 3);
    FAIL() << "expected ArgumentError";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex id 9"), std::string::npos) << e.what();
  }
  EXPECT_EQ(get_modes(mesh), std::vector<int>(9, 1));
  EXPECT_THROW(set_modes(mesh, {0}, -1), ArgumentError);
  EXPECT_THROW(set_modes(mesh, {0}, kLargestMode + 1), ArgumentError) << "lists per mode are as long as the largest";
  EXPECT_NO_THROW(set_modes(mesh, {0}, kLargestMode));
}

TEST(ModeLayer, SphereBrushSelectsExactlyTheVerticesWithinRadius) {
  QuadMesh mesh = test::make_grid(4, 4);  // unit spacing, vertex (i,j) = j*5+i
  // Centre (2,2): radius 1 takes the centre and its four axis neighbours
  // (distance exactly 1 counts), not the diagonals at sqrt(2).
  EXPECT_EQ(paint_modes_sphere(mesh, {2, 2, 0}, 1.0, 2), 5u);
  std::vector<int> expected(25, 1);
  for (int v : {12, 7, 11, 13, 17}) expected[v] = 2;
  EXPECT_EQ(get_modes(mesh), expected);
  EXPECT_THROW(paint_modes_sphere(mesh, {0, 0, 0}, -1.0, 2), ArgumentError);
}

TEST(ModeLayer, NewVerticesInheritTheRoundedMeanOfTheirFathers) {
  QuadMesh mesh = test::make_grid(1, 1);
  // The quad's corners in order are vertices 0, 1, 3, 2 (see make_grid).
  set_modes(mesh, {1, 3}, 3);
  uniform_refine(mesh, 1);
  // Midpoints of 0-1, 1-3, 3-2, 2-0: (1+3)/2 = 2, 3, 2, 1; centre 8/4 = 2.
  EXPECT_EQ(get_modes(mesh), (std::vector<int>{1, 3, 1, 3, 2, 3, 2, 1, 2}));
}

}  // namespace
}  // namespace mrcloth
