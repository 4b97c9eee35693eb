// Mode painting beside the computed modes: the geodesic brush against a
// Manhattan-distance oracle on a grid, threshold fills on any layer,
// erasing back to computed modes, and the layers through .om and CSV.
#include "mesh_ops/mode_painting.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/uniform_refine.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() /
                       ("mrcloth_painting_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::create_directories(dir);
  return dir;
}

/// Vertices of a 6 x 6 unit grid (7 x 7 vertices, index 7 y + x) with mode
/// `mode` in `modes`.
std::vector<int> with_mode(const std::vector<int>& modes, int mode) {
  std::vector<int> ids;
  for (std::size_t v = 0; v < modes.size(); ++v)
    if (modes[v] == mode) ids.push_back(static_cast<int>(v));
  return ids;
}

TEST(ModePainting, GeodesicBrushFollowsTheEdges) {
  // On a grid of unit squares the shortest path along edges is the
  // Manhattan distance: the brush must select exactly those within it.
  QuadMesh grid = test::make_grid(6, 6, 1.0);
  for (const double radius : {0.0, 0.99, 1.0, 1.5, 2.0, 3.7}) {
    QuadMesh mesh = copy_mesh(grid);
    const std::vector<int> seeds{7 * 3 + 3, 7 * 0 + 6};  // (3, 3) and the corner (6, 0)
    const std::size_t painted = paint_modes_geodesic(mesh, seeds, radius, 4);
    std::vector<int> expected;
    for (int v = 0; v < 49; ++v) {
      const int x = v % 7, y = v / 7;
      const int d = std::min(std::abs(x - 3) + std::abs(y - 3), std::abs(x - 6) + std::abs(y - 0));
      if (d <= radius + 1e-12) expected.push_back(v);
    }
    EXPECT_EQ(with_mode(get_modes(mesh), 4), expected) << "radius " << radius;
    EXPECT_EQ(painted, expected.size());
  }
  QuadMesh mesh = copy_mesh(grid);
  EXPECT_THROW(paint_modes_geodesic(mesh, {49}, 1.0, 2), ArgumentError);
  EXPECT_THROW(paint_modes_geodesic(mesh, {0}, -1.0, 2), ArgumentError);
  EXPECT_THROW(paint_modes_geodesic(mesh, {0}, 1.0, -2), ArgumentError);
  EXPECT_EQ(paint_modes_geodesic(mesh, {}, 5.0, 2), 0u) << "no seeds, nothing painted";
}

TEST(ModePainting, ThresholdFillOnAnyLayer) {
  QuadMesh mesh = test::make_grid(6, 6, 1.0);
  std::vector<double> x(49);
  for (int v = 0; v < 49; ++v) x[static_cast<std::size_t>(v)] = v % 7;
  set_vertex_layer(mesh, "mean_curvature", x);
  EXPECT_EQ(fill_modes_threshold(mesh, "mean_curvature", 4.0, 3), 21u) << "columns 4, 5, 6";
  EXPECT_EQ(fill_modes_threshold(mesh, "mrcloth:mean_curvature", 0.0, 2, false), 7u) << "column 0; prefixed name";
  const std::vector<int> modes = get_modes(mesh);
  for (int v = 0; v < 49; ++v)
    EXPECT_EQ(modes[static_cast<std::size_t>(v)], v % 7 >= 4 ? 3 : v % 7 == 0 ? 2 : 1) << v;
  // The mode layer itself is a layer: fill where mode >= 3.
  EXPECT_EQ(fill_modes_threshold(mesh, "mode", 3.0, 5), 21u);
  try {
    fill_modes_threshold(mesh, "wrinkles", 1.0, 2);
    ADD_FAILURE() << "an unknown layer";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("'wrinkles'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mean_curvature"), std::string::npos) << "lists the layers: " << e.what();
  }
  EXPECT_THROW(set_vertex_layer(mesh, "mode", x), ArgumentError) << "reserved";
  EXPECT_THROW(set_vertex_layer(mesh, "extra", std::vector<double>(48)), ArgumentError) << "count";
}

TEST(ModePainting, EraseGoesBackToTheComputedModes) {
  QuadMesh mesh = test::make_grid(6, 6, 1.0);
  // Before any analysis, erasing goes back to the default mode.
  set_modes(mesh, {3, 4}, 5);
  EXPECT_EQ(erase_modes(mesh, {3}), 1u);
  EXPECT_EQ(get_modes(mesh)[3], kDefaultMode);
  EXPECT_EQ(get_modes(mesh)[4], 5);

  // The computed-mode layer reads as the default mode before any analysis,
  // what erasing goes back to, as the layers' CSV writes it (getLayer refused it).
  EXPECT_EQ(vertex_layer(mesh, "computed_mode"), std::vector<double>(49, kDefaultMode));
  EXPECT_EQ(computed_modes(mesh), std::vector<int>(49, kDefaultMode));
  EXPECT_EQ(vertex_layer_names(mesh), (std::vector<std::string>{"mode", "computed_mode"}));

  std::vector<int> computed(49);
  for (int v = 0; v < 49; ++v) computed[static_cast<std::size_t>(v)] = 1 + v % 3;
  set_computed_modes(mesh, computed);
  EXPECT_EQ(vertex_layer(mesh, "computed_mode")[5], computed[5]);
  EXPECT_EQ(get_modes(mesh), computed) << "painting starts from the computed modes";
  EXPECT_EQ(computed_modes(mesh), computed);
  paint_modes_geodesic(mesh, {24}, 1.0, 7);  // 5 vertices
  set_modes(mesh, {0}, 9);
  EXPECT_EQ(erase_modes(mesh, {24, 25, 0}), 3u);
  std::vector<int> modes = get_modes(mesh);
  EXPECT_EQ(modes[24], computed[24]);
  EXPECT_EQ(modes[0], computed[0]);
  EXPECT_EQ(modes[17], 7) << "not erased";
  EXPECT_EQ(erase_modes(mesh), 3u) << "the remaining painted vertices: 17, 23, 31";
  EXPECT_EQ(get_modes(mesh), computed);
  EXPECT_EQ(erase_modes(mesh), 0u);
  EXPECT_THROW(erase_modes(mesh, {-1}), ArgumentError);
  EXPECT_THROW(set_computed_modes(mesh, std::vector<int>(49, 0)), ArgumentError);
  EXPECT_THROW(set_computed_modes(mesh, std::vector<int>(3, 1)), ArgumentError);
  // A mode no layer file could hold again (saved, it would be read back as damaged) is refused, nothing changed.
  std::vector<int> beyond(49, kLargestMode);
  beyond[30] = kLargestMode + 1;
  try {
    set_computed_modes(mesh, beyond);
    ADD_FAILURE() << "a mode beyond kLargestMode";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 30 has mode 1001; expected computed modes from 1 to 1000"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(get_modes(mesh), computed);
  set_computed_modes(mesh, std::vector<int>(49, kLargestMode));
  EXPECT_EQ(get_modes(mesh), std::vector<int>(49, kLargestMode));

  // Mode 0 (never refine) is a computed mode like any other, not "none":
  // erasing goes back to it (it went to the default mode).
  std::vector<int> with_zero(49, 2);
  with_zero[10] = 0;
  set_computed_layer(mesh, with_zero);
  set_modes(mesh, {10, 11}, 5);
  EXPECT_EQ(erase_modes(mesh, {10, 11}), 2u);
  EXPECT_EQ(get_modes(mesh)[10], 0);
  EXPECT_EQ(get_modes(mesh)[11], 2);
  EXPECT_EQ(vertex_layer(mesh, "computed_mode")[10], 0.0);
  std::vector<int> negative = with_zero;
  negative[7] = -1;
  try {
    set_computed_layer(mesh, negative);
    ADD_FAILURE() << "a negative computed mode";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 7 has mode -1; expected modes from 0 to 1000"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(computed_modes(mesh), with_zero) << "nothing changed by the refused layer";
}

// New vertices inherit the computed modes as they inherit the modes (the
// rounded mean of their fathers', a computed 0 among them); a mesh without
// computed modes gets none by refining.
TEST(ModePainting, RefinementCarriesTheComputedModes) {
  QuadMesh mesh = test::make_grid(2, 1, 1.0);  // vertices 0 1 2 / 3 4 5
  set_computed_modes(mesh, {1, 2, 3, 2, 3, 3});
  QuadMesh refined = copy_mesh(mesh);
  uniform_refine(refined, 2);
  EXPECT_EQ(computed_modes(refined), get_modes(refined));
  EXPECT_EQ(erase_modes(refined), 0u) << "nothing painted";
  // The midpoint of edge 0-1 (modes 1, 2) rounds half up to 2.
  bool found = false;
  for (const auto v : refined.vertices()) {
    const auto& p = refined.point(v);
    if (std::abs(p[0] - 0.5) < 1e-12 && std::abs(p[1]) < 1e-12) {
      EXPECT_EQ(computed_modes(refined)[static_cast<std::size_t>(v.idx())], 2);
      found = true;
    }
  }
  EXPECT_TRUE(found);
  // Painted, refined, erased: back to the computed modes.
  QuadMesh painted = copy_mesh(mesh);
  set_modes(painted, {4}, 9);
  uniform_refine(painted, 1);
  EXPECT_GT(erase_modes(painted), 1u) << "vertex 4 and the new ones around it";
  EXPECT_EQ(get_modes(painted), computed_modes(painted));
  // A computed 0 (mapped from a painted 0) counts in the mean: the midpoint
  // of 0 and 3 is 2, where it was "none" (and erased to the default mode).
  QuadMesh zero = test::make_grid(2, 1, 1.0);
  set_computed_layer(zero, {0, 3, 3, 3, 3, 3});
  set_modes(zero, {0, 1, 2, 3, 4, 5}, 3);
  set_modes(zero, {0}, 0);
  uniform_refine(zero, 1);
  EXPECT_EQ(computed_modes(zero), get_modes(zero));
  EXPECT_EQ(erase_modes(zero), 0u) << "nothing painted";
  // A mesh with no computed modes gets none by refining.
  QuadMesh plain = test::make_grid(2, 1, 1.0);
  uniform_refine(plain, 1);
  OpenMesh::VPropHandleT<int> handle;
  EXPECT_FALSE(plain.get_property_handle(handle, layer::computed_mode));
}

TEST(ModePainting, LayersRoundTripThroughOmAndCsv) {
  QuadMesh mesh = test::make_grid(4, 3, 0.5);
  const int n = static_cast<int>(mesh.n_vertices());
  std::vector<int> computed(static_cast<std::size_t>(n));
  std::vector<double> mean(static_cast<std::size_t>(n)), deviation(static_cast<std::size_t>(n)), extra(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    computed[static_cast<std::size_t>(v)] = 1 + v % 3;
    mean[static_cast<std::size_t>(v)] = 0.1 * v + 1.0 / 3.0;
    deviation[static_cast<std::size_t>(v)] = std::sqrt(v + 0.5);
    extra[static_cast<std::size_t>(v)] = -1e-300 * v;
  }
  set_computed_modes(mesh, computed);
  set_vertex_layer(mesh, "mean_curvature", mean);
  set_vertex_layer(mesh, "curvature_deviation", deviation);
  set_vertex_layer(mesh, "my_weights", extra);
  set_modes(mesh, {2, 5}, 6);
  const std::vector<int> painted = get_modes(mesh);

  const fs::path dir = temp_dir();
  save_mesh(mesh, (dir / "layers.om").string());
  QuadMesh loaded = load_garment((dir / "layers.om").string()).mesh;
  EXPECT_EQ(get_modes(loaded), painted);
  EXPECT_EQ(computed_modes(loaded), computed);
  EXPECT_EQ(vertex_layer(loaded, "mean_curvature"), mean);
  EXPECT_EQ(vertex_layer(loaded, "curvature_deviation"), deviation);
  EXPECT_EQ(erase_modes(loaded), 2u) << "erasing after a reload still finds the computed modes";

  // CSV: every layer, exact (17 significant digits), readable back.
  write_vertex_layers_csv(mesh, (dir / "layers.csv").string());
  std::ifstream in(dir / "layers.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "vertex,x,y,z,mode,computed_mode,mean_curvature,curvature_deviation,my_weights");
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, n);
  QuadMesh other = test::make_grid(4, 3, 0.5);
  const ModesCsvRead read = read_modes_csv(other, (dir / "layers.csv").string());
  EXPECT_EQ(read.set, static_cast<std::size_t>(n));
  EXPECT_EQ(read.misplaced, 0u) << "the same positions, to the bit";
  EXPECT_EQ(read.farthest_vertex, -1);
  EXPECT_EQ(get_modes(other), painted);
  for (const auto& name : vertex_layer_names(mesh)) EXPECT_NO_THROW(vertex_layer(mesh, name)) << name;
}

// A CSV of a mesh with as many vertices but elsewhere, or of this mesh with
// its vertices renumbered, sets the modes all the same (by vertex number),
// and says how many rows' positions do not fit: exactly those moved beyond
// the tolerance, the farthest named with its line.
TEST(ModePainting, CsvPositionsThatDoNotFitTheMeshAreCounted) {
  QuadMesh mesh = test::make_grid(3, 3, 1.0);  // 16 vertices, 1 m apart
  const fs::path dir = temp_dir();
  write_vertex_layers_csv(mesh, (dir / "grid.csv").string());
  QuadMesh moved = test::make_grid(3, 3, 1.0);
  moved.set_point(moved.vertex_handle(5), moved.point(moved.vertex_handle(5)) + OpenMesh::Vec3d(0, 0, 0.5 * kCsvPositionTolerance));
  moved.set_point(moved.vertex_handle(9), moved.point(moved.vertex_handle(9)) + OpenMesh::Vec3d(0, 0, 2 * kCsvPositionTolerance));
  moved.set_point(moved.vertex_handle(12), moved.point(moved.vertex_handle(12)) + OpenMesh::Vec3d(0.3, 0, 0));
  ModesCsvRead read = read_modes_csv(moved, (dir / "grid.csv").string());
  EXPECT_EQ(read.set, 16u);
  EXPECT_EQ(read.misplaced, 2u) << "vertices 9 and 12; 5 is within the tolerance";
  EXPECT_EQ(read.farthest_vertex, 12);
  EXPECT_EQ(read.farthest_line, 14) << "the header is line 1, vertex v's row line v + 2";
  EXPECT_NEAR(read.farthest, 0.3, 1e-12);
  // The same mesh in decimetres: every row but the origin's is off.
  QuadMesh scaled = test::make_grid(3, 3, 0.1);
  read = read_modes_csv(scaled, (dir / "grid.csv").string());
  EXPECT_EQ(read.misplaced, 15u);
  EXPECT_NEAR(read.farthest, 0.9 * std::sqrt(18.0), 1e-12) << "the far corner, (3, 3) against (0.3, 0.3)";
  // Without x, y, z columns (another tool's file) nothing is compared.
  std::ofstream(dir / "plain.csv") << "vertex,mode\n12,3\n";
  read = read_modes_csv(scaled, (dir / "plain.csv").string());
  EXPECT_EQ(read.set, 1u);
  EXPECT_EQ(read.misplaced, 0u);
}

TEST(ModePainting, MalformedCsvNamesTheLine) {
  const fs::path dir = temp_dir();
  QuadMesh mesh = test::make_grid(2, 2, 1.0);  // 9 vertices
  const auto expect_error = [&](const std::string& text, const std::string& fragment) {
    const fs::path path = dir / "bad.csv";
    std::ofstream(path) << text;
    try {
      read_modes_csv(mesh, path.string());
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.csv"), std::string::npos) << e.what();
    }
    EXPECT_EQ(get_modes(mesh), std::vector<int>(9, kDefaultMode)) << "nothing changes on an error: " << text;
  };
  expect_error("", ":1: the file is empty");
  expect_error("id,mode\n0,2\n", ":1: the header has no 'vertex'");
  expect_error("vertex,mode\n0,2\n1,x\n", ":3: mode \"x\" is not an integer");
  expect_error("vertex,mode\n0,2\n9,1\n", ":3: vertex 9 is out of range");
  expect_error("vertex,mode\n0,-1\n", ":2: mode -1 is out of range; expected a mode from 0 to 1000");
  expect_error("vertex,mode\n0,1\n1,2147483647\n", ":3: mode 2147483647 is out of range");
  expect_error("vertex,mode\n0\n", ":2: 1 fields");
  expect_error("vertex,mode\n1.5,2\n", ":2: vertex \"1.5\" is not an integer");
  expect_error("vertex,mode\n0,99999999999\n", ":2: mode 99999999999 is out of range");
  expect_error("vertex,mode\n4,2\n0,1\n4,3\n", ":4: vertex 4 is given again (first at line 2); expected one row per vertex");
  expect_error("vertex,mode\n0,1\n1,2,3\n", ":3: 3 fields; expected 2 as in the header");
  expect_error("vertex,mode,note\n0,1,size 1,5\n", ":2: 4 fields; expected 3 as in the header");
  expect_error("vertex,mode\n0,\"1\n", ":2: a quote is not closed on this line");
  expect_error("vertex,mode\n0,1\n1,2,3,,\n", ":3: 3 fields; expected 2 as in the header");
  EXPECT_THROW(read_modes_csv(mesh, (dir / "missing.csv").string()), InputError);
  try {
    read_modes_csv(mesh, dir.string());
    ADD_FAILURE() << "a folder was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(": is a folder; expected a CSV file"), std::string::npos) << e.what();
  }
  // Quoted fields as spreadsheets write them (a quoted comma, doubled quotes), and trailing commas.
  std::ofstream(dir / "quoted.csv") << "\"vertex\",\"mode\",\"note\"\n\"2\",\"4\",\"a, \"\"b\"\"\"\n3 , 6 ,,\n";
  EXPECT_EQ(read_modes_csv(mesh, (dir / "quoted.csv").string()).set, 2u);
  EXPECT_EQ(get_modes(mesh)[2], 4);
  EXPECT_EQ(get_modes(mesh)[3], 6);
  // Rows shorter than the header that reach the vertex and mode columns, and blank lines.
  std::ofstream(dir / "short.csv") << "vertex,mode,comment\n2,7\n   \n3,8,ok\n";
  EXPECT_EQ(read_modes_csv(mesh, (dir / "short.csv").string()).set, 2u);
  EXPECT_EQ(get_modes(mesh)[2], 7);
  set_modes(mesh, {2, 3}, kDefaultMode);
  // Extra columns and a header in any order are fine; unlisted vertices keep their modes.
  std::ofstream(dir / "ok.csv") << "mode,note,vertex\n3,a,4\n2,b,0\n";
  EXPECT_EQ(read_modes_csv(mesh, (dir / "ok.csv").string()).set, 2u);
  EXPECT_EQ(get_modes(mesh), (std::vector<int>{2, 1, 1, 1, 3, 1, 1, 1, 1}));
  // A spreadsheet's export: a byte-order mark, capitals, spaces, CRLF.
  std::ofstream(dir / "excel.csv") << "\xEF\xBB\xBFVertex , Mode\r\n1,5\r\n";
  EXPECT_EQ(read_modes_csv(mesh, (dir / "excel.csv").string()).set, 1u);
  EXPECT_EQ(get_modes(mesh)[1], 5);
}

}  // namespace
}  // namespace mrcloth

namespace mrcloth {
namespace {

TEST(ModePainting, CurvatureColoursInAPly) {
  // Vertex colours by mean curvature: viridis from 0 to the largest value,
  // read back from the exported PLY at known vertices.
  EXPECT_EQ(sequential_color(0.0), (std::array<unsigned char, 3>{68, 1, 84}));
  EXPECT_EQ(sequential_color(1.0), (std::array<unsigned char, 3>{253, 231, 37}));
  EXPECT_EQ(sequential_color(0.5), (std::array<unsigned char, 3>{33, 144, 141}));
  EXPECT_EQ(sequential_color(-3.0), sequential_color(0.0));
  EXPECT_EQ(sequential_color(std::nan("")), sequential_color(0.0));
  EXPECT_EQ(sequential_color(7.0), sequential_color(1.0));

  QuadMesh mesh = test::make_grid(2, 2, 1.0);
  std::vector<double> curvature(9, 0.0);
  curvature[4] = 8.0;  // the largest
  curvature[8] = 4.0;  // half of it
  set_vertex_layer(mesh, "mean_curvature", curvature);
  const fs::path path = temp_dir() / "curvature.ply";
  ExportOptions options;
  options.color_by = ColorBy::curvature;
  export_surface(mesh, path.string(), options);
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line != "end_header") {
  }
  std::vector<std::array<int, 3>> colours;
  for (int v = 0; v < 9 && std::getline(in, line); ++v) {
    std::istringstream fields(line);
    double x, y, z;
    std::array<int, 3> rgb{};
    fields >> x >> y >> z >> rgb[0] >> rgb[1] >> rgb[2];
    colours.push_back(rgb);
  }
  ASSERT_EQ(colours.size(), 9u);
  EXPECT_EQ(colours[0], (std::array<int, 3>{68, 1, 84}));
  EXPECT_EQ(colours[4], (std::array<int, 3>{253, 231, 37}));
  EXPECT_EQ(colours[8], (std::array<int, 3>{33, 144, 141}));
  QuadMesh bare = test::make_grid(1, 1, 1.0);
  EXPECT_THROW(export_surface(bare, (temp_dir() / "bare.ply").string(), options), ArgumentError)
      << "no curvature layer: nothing to colour by";
}

}  // namespace
}  // namespace mrcloth
