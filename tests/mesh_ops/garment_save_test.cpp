// Saving garments (garment_io: .om with every layer, text formats exactly)
// and exporting surfaces for viewing (colours by mode or level, triangulated
// frames). Fixtures are tiny text meshes written by the tests into a scratch
// folder (garment_io_support.h).
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/mode_painting.h"
#include "mesh_ops/quad_refiner.h"
#include "mesh_ops/quadtree_forest.h"

#include "garment_io_support.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using mrcloth::QuadMesh;
using mrcloth::test::canonical_loop;
using mrcloth::test::expect_grid_as_read;
using mrcloth::test::grid_faces;
using mrcloth::test::grid_obj;
using mrcloth::test::grid_off;
using mrcloth::test::grid_ply;
using mrcloth::test::kGridFaces;
using mrcloth::test::kGridVertices;
using mrcloth::test::ScratchDir;
using mrcloth::test::write_file;

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

// --- saving --------------------------------------------------------------------

TEST(GarmentSave, OmKeepsPointsBitwiseAndEveryLayer) {
  ScratchDir dir;
  mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()), {"inch"});
  QuadMesh& mesh = loaded.mesh;
  // A hierarchy of three levels with hanging vertices, as refinement makes
  // it (the loader checks faces against their records).
  mrcloth::QuadRefiner refiner(mesh);
  const mrcloth::QuadSplit split = refiner.split(1);
  refiner.split(split.children[2]);
  ASSERT_TRUE(refiner.finish());
  const mrcloth::Layers l = mrcloth::get_layers(mesh);
  for (const auto v : mesh.vertices()) {
    const int i = v.idx();
    mesh.property(l.mode, v) = i % 4 + 1;
    mesh.property(l.r_value, v) = i / 3.0 + 1e-300;
  }
  const auto& forest = mesh.property(l.quadtree);
  ASSERT_GT(mrcloth::count_hanging(mesh), 0u);
  ASSERT_EQ(mrcloth::faces_per_level(mesh), (std::vector<std::size_t>{0, 5, 3, 4}));

  const std::string path = dir.file("saved.om");
  mrcloth::save_mesh(mesh, path);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"grid.obj", "saved.om"}));

  const mrcloth::LoadResult back = mrcloth::load_garment(path);
  const QuadMesh& copy = back.mesh;
  EXPECT_TRUE(back.warnings.empty());
  ASSERT_EQ(copy.n_vertices(), mesh.n_vertices());
  ASSERT_EQ(copy.n_faces(), mesh.n_faces());
  const mrcloth::Layers c = mrcloth::get_layers(copy);
  for (const auto v : mesh.vertices()) {
    const auto w = QuadMesh::VertexHandle(v.idx());
    EXPECT_EQ(std::memcmp(mesh.point(v).data(), copy.point(w).data(), 3 * sizeof(double)), 0) << v.idx();
    EXPECT_EQ(copy.property(c.mode, w), mesh.property(l.mode, v));
    EXPECT_EQ(std::memcmp(&copy.property(c.r_value, w), &mesh.property(l.r_value, v), sizeof(double)), 0);
    EXPECT_EQ(copy.property(c.hanging, w), mesh.property(l.hanging, v)) << v.idx();
    EXPECT_EQ(copy.property(c.parents, w), mesh.property(l.parents, v));
  }
  for (const auto f : mesh.faces()) {
    const auto g = QuadMesh::FaceHandle(f.idx());
    EXPECT_EQ(copy.property(c.level, g), mesh.property(l.level, f));
    EXPECT_EQ(copy.property(c.quad, g), mesh.property(l.quad, f));
    EXPECT_EQ(canonical_loop(copy, g), canonical_loop(mesh, f));
  }
  const auto& restored = copy.property(c.quadtree);
  ASSERT_EQ(restored.size(), forest.size());
  for (std::size_t i = 0; i < forest.size(); ++i) {
    EXPECT_EQ(restored[i].level, forest[i].level) << i;
    EXPECT_EQ(restored[i].active, forest[i].active) << i;
    EXPECT_EQ(restored[i].parent, forest[i].parent) << i;
    EXPECT_EQ(restored[i].children, forest[i].children) << i;
    EXPECT_EQ(restored[i].corners, forest[i].corners) << i;
  }
}

TEST(GarmentSave, OmWithoutForestIsMadeRefinable) {
  // A .om written by plain OpenMesh has no mrcloth layers: it loads like any mesh.
  ScratchDir dir;
  QuadMesh plain;
  const mrcloth::LoadResult grid = mrcloth::load_garment(write_file(dir.file("grid.off"), grid_off()));
  for (const auto v : grid.mesh.vertices()) plain.add_vertex(grid.mesh.point(v));
  for (const auto& f : grid_faces())
    plain.add_face({QuadMesh::VertexHandle(f[0]), QuadMesh::VertexHandle(f[1]), QuadMesh::VertexHandle(f[2]),
                    QuadMesh::VertexHandle(f[3])});
  const std::string path = dir.file("plain.om");
  ::omlog().disable();  // the OM writer reports its byte count there
  const bool written = OpenMesh::IO::write_mesh(plain, path, OpenMesh::IO::Options::Binary);
  ::omlog().enable();
  ASSERT_TRUE(written);
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path, {"dm"});
  expect_grid_as_read(loaded, 0.1);
}

TEST(GarmentSave, TextFormatsRoundTripDoublesExactly) {
  ScratchDir dir;
  mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.ply"), grid_ply()));
  QuadMesh& mesh = loaded.mesh;
  // Values no decimal short form or float would keep.
  mesh.point(QuadMesh::VertexHandle(0)) = OpenMesh::Vec3d(1.0 / 3.0, -2.0 / 7.0, 1e-310);
  mesh.point(QuadMesh::VertexHandle(5)) = OpenMesh::Vec3d(std::nextafter(1.0, 2.0), 123456.789e10, -0.0);
  for (const std::string name : {"out.obj", "out.off", "out.ply", "OUT.OBJ"}) {
    const std::string path = dir.file(name);
    mrcloth::save_mesh(mesh, path);
    const mrcloth::LoadResult back = mrcloth::load_garment(path);
    // Vertex 5 so far off turns faces around it inside out (concave), and
    // only that is said: every coordinate was read back exactly.
    for (const std::string& warning : back.warnings)
      EXPECT_NE(warning.find("is concave"), std::string::npos) << name << ": " << warning;
    ASSERT_EQ(back.mesh.n_vertices(), mesh.n_vertices()) << name;
    ASSERT_EQ(back.mesh.n_faces(), mesh.n_faces()) << name;
    for (const auto v : mesh.vertices()) {
      EXPECT_EQ(std::memcmp(mesh.point(v).data(), back.mesh.point(v).data(), 3 * sizeof(double)), 0)
          << name << " vertex " << v.idx();
    }
    for (const auto f : mesh.faces()) EXPECT_EQ(canonical_loop(back.mesh, f), canonical_loop(mesh, f)) << name;
  }
}

TEST(GarmentSave, FailedSavesLeaveNoFileBehind) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::vector<std::string> before = dir.entries();

  const std::string nowhere = dir.file("no_such_folder/out.om");
  try {
    mrcloth::save_mesh(loaded.mesh, nowhere);
    ADD_FAILURE() << "saved into a missing folder";
  } catch (const mrcloth::OutputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(nowhere + ": cannot write file", 0), 0u) << e.what();
  }
  EXPECT_THROW(mrcloth::save_mesh(loaded.mesh, dir.file("out.stl")), mrcloth::ArgumentError);
  EXPECT_THROW(mrcloth::save_mesh(loaded.mesh, dir.file("out")), mrcloth::ArgumentError);
  EXPECT_THROW(mrcloth::export_surface(loaded.mesh, dir.file("out.off")), mrcloth::ArgumentError);
  EXPECT_THROW(mrcloth::export_surface(loaded.mesh, dir.file("no_such_folder/out.ply")), mrcloth::OutputError);
  EXPECT_EQ(dir.entries(), before);

  fs::create_directories(dir.file("taken.om"));
  EXPECT_THROW(mrcloth::save_mesh(loaded.mesh, dir.file("taken.om")), mrcloth::OutputError);
  std::vector<std::string> expected = before;
  expected.push_back("taken.om");
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(dir.entries(), expected);
  EXPECT_TRUE(fs::is_empty(dir.file("taken.om")));
}

TEST(GarmentSave, TheLongestLegalNamesAreWritten) {
  // The temporary file beside the target adds ~20 bytes to its name; a
  // target name of 255 bytes (NAME_MAX), ASCII or multi-byte, still saves.
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::string ascii = std::string(252, 'a') + ".om";
  std::string wide;
  while (wide.size() + 3 + 4 <= 255) wide += "\xe6\x97\xa5";  // U+65E5, three bytes each
  wide += ".obj";
  for (const std::string& name : {ascii, wide}) {
    ASSERT_LE(name.size(), 255u);
    mrcloth::save_mesh(loaded.mesh, dir.file(name));
    EXPECT_EQ(mrcloth::load_garment(dir.file(name)).mesh.n_faces(), static_cast<std::size_t>(kGridFaces)) << name.size();
  }
  std::vector<std::string> expected{"grid.obj", ascii, wide};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(dir.entries(), expected);
}

TEST(GarmentSave, AFileWhereTheFolderShouldBeIsNamedAsSuch) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::string path = dir.file("grid.obj/out.om");
  try {
    mrcloth::save_mesh(loaded.mesh, path);
    ADD_FAILURE() << "saved below a file";
  } catch (const mrcloth::OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("grid.obj' is a file, not a folder"), std::string::npos) << e.what();
  }
}

TEST(GarmentSave, OmBytesAreOpenMeshsOwn) {
  // write_om encodes in memory (OpenMesh's writer asserts on a failed
  // write: a full disk aborted the host); the bytes are the ones OpenMesh
  // writes to a file itself, but for the checksum layer's eight, which
  // hold the FNV-1a hash of all the others.
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  mrcloth::save_mesh(loaded.mesh, dir.file("ours.om"));
  ASSERT_TRUE(OpenMesh::IO::write_mesh(loaded.mesh, dir.file("openmesh.om"), OpenMesh::IO::Options::Binary));
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  std::string ours = bytes(dir.file("ours.om"));
  const std::string theirs = bytes(dir.file("openmesh.om"));
  EXPECT_GT(ours.size(), 100u);
  const std::size_t name = ours.find(mrcloth::layer::checksum);
  ASSERT_NE(name, std::string::npos);
  const std::size_t type = name + std::string(mrcloth::layer::checksum).size();
  const std::size_t value = type + 1 + static_cast<unsigned char>(ours[type]) + 4;
  ASSERT_LE(value + 8, ours.size());
  std::uint64_t hash = 14695981039346656037ull, stored = 0;
  for (std::size_t k = 0; k < ours.size(); ++k)
    hash = (hash ^ ((k >= value && k < value + 8) ? 0u : static_cast<unsigned char>(ours[k]))) * 1099511628211ull;
  for (std::size_t k = 0; k < 8; ++k) stored |= std::uint64_t{static_cast<unsigned char>(ours[value + k])} << (8 * k);
  EXPECT_EQ(stored, hash);
  ours.replace(value, 8, std::string(8, '\0'));
  EXPECT_EQ(ours, theirs);
}

TEST(GarmentSave, AnOmRoundTripAddsNoLayers) {
  // A mesh never analysed has no curvature or computed-mode layers; saved
  // as .om and loaded it still has none (the reader needs them made first),
  // and saving it again gives the same bytes. One analysed keeps its own.
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const auto has = [](const mrcloth::QuadMesh& mesh, const char* name) {
    OpenMesh::VPropHandleT<double> real;
    OpenMesh::VPropHandleT<int> whole;
    return mesh.get_property_handle(real, name) || mesh.get_property_handle(whole, name);
  };
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  mrcloth::save_mesh(loaded.mesh, dir.file("first.om"));
  const mrcloth::LoadResult again = mrcloth::load_garment(dir.file("first.om"));
  for (const char* name : {mrcloth::layer::mean_curvature, mrcloth::layer::curvature_deviation, mrcloth::layer::computed_mode})
    EXPECT_FALSE(has(again.mesh, name)) << name;
  mrcloth::save_mesh(again.mesh, dir.file("second.om"));
  EXPECT_EQ(bytes(dir.file("second.om")), bytes(dir.file("first.om")));

  mrcloth::QuadMesh analysed = mrcloth::copy_mesh(loaded.mesh);
  mrcloth::set_vertex_layer(analysed, mrcloth::layer::mean_curvature, std::vector<double>(analysed.n_vertices(), 2.5));
  mrcloth::save_mesh(analysed, dir.file("analysed.om"));
  const mrcloth::LoadResult kept = mrcloth::load_garment(dir.file("analysed.om"));
  EXPECT_TRUE(has(kept.mesh, mrcloth::layer::mean_curvature));
  EXPECT_FALSE(has(kept.mesh, mrcloth::layer::curvature_deviation));
  EXPECT_EQ(mrcloth::vertex_layer(kept.mesh, mrcloth::layer::mean_curvature),
            std::vector<double>(analysed.n_vertices(), 2.5));
}

TEST(GarmentSave, AnOmOfMrclothLoadedInOtherUnitsIsWarnedOf) {
  // save_mesh writes metres: a units option scales the mesh (as the option
  // says) but not its layers in metres, so the load says so; in metres,
  // nothing is said.
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  mrcloth::save_mesh(loaded.mesh, dir.file("saved.om"));
  EXPECT_TRUE(mrcloth::load_garment(dir.file("saved.om")).warnings.empty());
  mrcloth::LoadOptions centimetres;
  centimetres.units = "cm";
  const mrcloth::LoadResult scaled = mrcloth::load_garment(dir.file("saved.om"), centimetres);
  ASSERT_EQ(scaled.warnings.size(), 1u);
  EXPECT_EQ(scaled.warnings[0], dir.file("saved.om") +
                                    ": mrcloth saved this mesh in metres; units 'cm' scale it by 0.01 (its curvature "
                                    "layers, in 1/m, are not rescaled): give units 'm' to load it as saved");
  EXPECT_EQ(scaled.mesh.point(scaled.mesh.vertex_handle(5)), loaded.mesh.point(loaded.mesh.vertex_handle(5)) * 0.01);
}

TEST(GarmentSave, SaveReplacesAnExistingFile) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::string path = write_file(dir.file("out.obj"), "old contents\n");
  mrcloth::save_mesh(loaded.mesh, path);
  EXPECT_EQ(mrcloth::load_garment(path).mesh.n_faces(), static_cast<std::size_t>(kGridFaces));
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"grid.obj", "out.obj"}));
}

// --- exporting -----------------------------------------------------------------

/// The `f` lines of an OBJ, as written.
std::vector<std::string> obj_faces(const std::string& text) {
  std::vector<std::string> faces;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("f ", 0) == 0) faces.push_back(line);
  return faces;
}

// A simulated frame exported triangulated keeps the rest shape's triangles:
// a square fans along its diagonal 1-3; in a frame where corner 2 has moved
// next to that diagonal the frame alone would fan along 2-4 (the DCC tool
// reading a sequence saw the diagonals flip from frame to frame).
TEST(GarmentExport, FramesTriangulateAsTheirRestShape) {
  ScratchDir dir;
  const QuadMesh rest =
      mrcloth::load_garment(write_file(dir.file("square.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")).mesh;
  QuadMesh frame = rest;
  frame.set_point(QuadMesh::VertexHandle(1), OpenMesh::Vec3d(0.45, 0.55, 0.2));
  mrcloth::ExportOptions options;
  options.triangulate = true;
  mrcloth::export_surface(rest, dir.file("rest.obj"), options);
  mrcloth::export_surface(frame, dir.file("alone.obj"), options);
  options.triangles_of = &rest;
  mrcloth::export_surface(frame, dir.file("frame.obj"), options);
  const std::vector<std::string> rest_faces = obj_faces(read_file(dir.file("rest.obj")));
  ASSERT_EQ(rest_faces.size(), 2u);
  EXPECT_NE(obj_faces(read_file(dir.file("alone.obj"))), rest_faces) << "the frame alone fans the other way";
  EXPECT_EQ(obj_faces(read_file(dir.file("frame.obj"))), rest_faces);
  EXPECT_NE(read_file(dir.file("frame.obj")).find("v 0.45 0.55 0.2"), std::string::npos) << "the frame's positions";
  // Another mesh to triangulate as is refused.
  const QuadMesh other = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj())).mesh;
  options.triangles_of = &other;
  try {
    mrcloth::export_surface(frame, dir.file("wrong.obj"), options);
    ADD_FAILURE() << "another mesh to triangulate as was taken";
  } catch (const mrcloth::ArgumentError& error) {
    EXPECT_EQ(std::string(error.what()), dir.file("wrong.obj") + ": the mesh to triangulate as has " +
                                             std::to_string(other.n_vertices()) + " vertices and " +
                                             std::to_string(other.n_faces()) +
                                             " faces, the mesh exported 4 and 1; expected the same mesh at other positions");
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("wrong.obj")));
}

TEST(GarmentExport, PaletteHasDistinctColoursAndGreyForUnset) {
  const auto grey = mrcloth::palette_color(0);
  EXPECT_EQ(mrcloth::palette_color(-4), grey);
  std::vector<std::array<unsigned char, 3>> colours;
  for (int value = 1; value <= 9; ++value) {
    const auto colour = mrcloth::palette_color(value);
    EXPECT_NE(colour, grey) << value;
    EXPECT_EQ(std::count(colours.begin(), colours.end(), colour), 0) << "value " << value << " repeats a colour";
    colours.push_back(colour);
  }
  EXPECT_EQ(mrcloth::palette_color(1), (std::array<unsigned char, 3>{31, 119, 180}));
  // Every mode a mesh may hold has its own colour (10 drew as 1 before).
  std::set<std::array<unsigned char, 3>> all{grey};
  for (int value = 1; value <= mrcloth::kLargestMode; ++value)
    EXPECT_TRUE(all.insert(mrcloth::palette_color(value)).second) << "value " << value << " repeats a colour";
}

TEST(GarmentExport, PlyWithModeColoursReadsBackInOpenMesh) {
  ScratchDir dir;
  mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()), {"dm"});
  QuadMesh& mesh = loaded.mesh;
  const auto mode = mrcloth::get_layers(mesh).mode;
  for (const auto v : mesh.vertices()) mesh.property(mode, v) = v.idx() % 5;  // includes 0 (grey)
  const std::string path = dir.file("modes.ply");
  mrcloth::export_surface(mesh, path, {mrcloth::ColorBy::mode, false});

  OpenMesh::PolyMesh_ArrayKernelT<> back;
  back.request_vertex_colors();
  OpenMesh::IO::Options options(OpenMesh::IO::Options::VertexColor);
  ASSERT_TRUE(OpenMesh::IO::read_mesh(back, path, options));
  EXPECT_TRUE(options.check(OpenMesh::IO::Options::VertexColor));
  ASSERT_EQ(back.n_vertices(), static_cast<std::size_t>(kGridVertices));
  ASSERT_EQ(back.n_faces(), static_cast<std::size_t>(kGridFaces));
  for (const auto v : back.vertices()) {
    const auto expected = mrcloth::palette_color(v.idx() % 5);
    const auto colour = back.color(v);
    EXPECT_EQ((std::array<unsigned char, 3>{colour[0], colour[1], colour[2]}), expected) << "vertex " << v.idx();
    const OpenMesh::Vec3d& p = mesh.point(QuadMesh::VertexHandle(v.idx()));
    EXPECT_NEAR(back.point(v)[0], p[0], 1e-6);
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"grid.obj", "modes.ply"}));
}

TEST(GarmentExport, ObjTriangulatedWithLevelColours) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.off"), grid_off()));
  const std::string path = dir.file("levels.obj");
  mrcloth::export_surface(loaded.mesh, path, {mrcloth::ColorBy::level, true});
  std::istringstream text(read_file(path));
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  const auto level1 = mrcloth::palette_color(1);
  for (std::string line; std::getline(text, line);) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    std::vector<double> numbers;
    for (double x; words >> x;) numbers.push_back(x);
    if (key == "v") {
      ASSERT_EQ(numbers.size(), 6u) << line;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(std::lround(numbers[3 + k] * 255.0), level1[k]) << line;
      ++vertices;
    } else if (key == "f") {
      EXPECT_EQ(numbers.size(), 3u) << line;
      ++triangles;
    }
  }
  EXPECT_EQ(vertices, static_cast<std::size_t>(kGridVertices));
  EXPECT_EQ(triangles, 2u * kGridFaces);
}

// Level colours follow the faces, as the previews show them: a vertex takes
// the finest level of its faces. Two quads side by side, the left one split:
// every vertex but the right quad's two far corners is level 2 (its corners
// and the shared edge's ends were level 1, coarse specks in the refined quad).
TEST(GarmentExport, LevelColoursAreTheFinestOfEachVertexsFaces) {
  ScratchDir dir;
  QuadMesh mesh = mrcloth::load_garment(write_file(dir.file("two.obj"),
                                                   "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
                                                   "f 1 2 5 4\nf 2 3 6 5\n")).mesh;
  mrcloth::QuadRefiner refiner(mesh);
  refiner.split(0);
  ASSERT_TRUE(refiner.finish());
  const std::string path = dir.file("levels.obj");
  mrcloth::export_surface(mesh, path, {mrcloth::ColorBy::level, false});
  std::istringstream text(read_file(path));
  std::vector<std::array<long, 3>> colours;
  for (std::string line; std::getline(text, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream words(line.substr(2));
    std::vector<double> numbers;
    for (double x; words >> x;) numbers.push_back(x);
    ASSERT_EQ(numbers.size(), 6u) << line;
    colours.push_back({std::lround(numbers[3] * 255.0), std::lround(numbers[4] * 255.0), std::lround(numbers[5] * 255.0)});
  }
  ASSERT_EQ(colours.size(), mesh.n_vertices());
  const auto as_long = [](const std::array<unsigned char, 3>& c) { return std::array<long, 3>{c[0], c[1], c[2]}; };
  const auto level1 = as_long(mrcloth::palette_color(1)), level2 = as_long(mrcloth::palette_color(2));
  for (std::size_t v = 0; v < colours.size(); ++v)
    EXPECT_EQ(colours[v], v == 2 || v == 5 ? level1 : level2) << "vertex " << v;
}

TEST(GarmentExport, UncolouredPlyHasNoColourProperties) {
  ScratchDir dir;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  const std::string path = dir.file("plain.ply");
  mrcloth::export_surface(loaded.mesh, path);
  const std::string text = read_file(path);
  EXPECT_EQ(text.find("red"), std::string::npos);
  EXPECT_NE(text.find("element face 6\n"), std::string::npos);
  const mrcloth::LoadResult back = mrcloth::load_garment(path);
  EXPECT_EQ(back.mesh.n_faces(), static_cast<std::size_t>(kGridFaces));
}
