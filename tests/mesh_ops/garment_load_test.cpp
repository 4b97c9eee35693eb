// Loading good garments (garment_io) in each format, and the unit table
// (units) they load in; the real MakeHuman skirt helper when the shared data
// is there. Fixtures are tiny text meshes written by the tests into a scratch
// folder (garment_io_support.h).
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/quadtree_forest.h"
#include "mesh_ops/units.h"

#include "garment_io_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <clocale>
#include <filesystem>
#include <limits>
#include <string>

namespace fs = std::filesystem;
using mrcloth::QuadMesh;
using mrcloth::test::binary_off_square;
using mrcloth::test::binary_quad_ply;
using mrcloth::test::expect_grid_as_read;
using mrcloth::test::grid_obj;
using mrcloth::test::grid_off;
using mrcloth::test::grid_ply;
using mrcloth::test::ply_header;
using mrcloth::test::ScratchDir;
using mrcloth::test::write_file;

// --- units -------------------------------------------------------------------

TEST(Units, TableOfAcceptedUnits) {
  EXPECT_EQ(mrcloth::metres_per_unit("m"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("metres"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("meters"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("metre"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("meter"), 1.0);
  EXPECT_EQ(mrcloth::metres_per_unit("dm"), 0.1);
  EXPECT_EQ(mrcloth::metres_per_unit("cm"), 0.01);
  EXPECT_EQ(mrcloth::metres_per_unit("mm"), 0.001);
  EXPECT_EQ(mrcloth::metres_per_unit("inch"), 0.0254);
  EXPECT_EQ(mrcloth::metres_per_unit("in"), 0.0254);
}

TEST(Units, NamesAreCaseInsensitive) {
  EXPECT_EQ(mrcloth::metres_per_unit("DM"), 0.1);
  EXPECT_EQ(mrcloth::metres_per_unit("Cm"), 0.01);
  EXPECT_EQ(mrcloth::metres_per_unit("INCH"), 0.0254);
  EXPECT_EQ(mrcloth::metres_per_unit("Metres"), 1.0);
}

// In the process's locale (Qt sets the user's): a Turkish one lowered
// "INCH" to "Inch" (std::tolower's I), refusing it, and ".OBJ" likewise.
TEST(Units, NamesAreCaseInsensitiveInATurkishLocale) {
  const std::string before = std::setlocale(LC_ALL, nullptr);
  if (!std::setlocale(LC_ALL, "tr_TR.UTF-8") && !std::setlocale(LC_ALL, "tr_TR.utf8"))
    GTEST_SKIP() << "no Turkish locale on this machine (locale-gen tr_TR.UTF-8 makes one)";
  const bool turkish_lowering = std::tolower('I') != 'i';
  const double inch = mrcloth::metres_per_unit("INCH");
  std::setlocale(LC_ALL, before.c_str());
  EXPECT_TRUE(turkish_lowering) << "the locale should lower I otherwise, or this test shows nothing";
  EXPECT_EQ(inch, 0.0254);
  EXPECT_EQ(mrcloth::ascii_lower("INCH.OBJ \xC4\xB0"), "inch.obj \xC4\xB0");
}

TEST(Units, UnknownUnitIsRefusedWithTheAcceptedList) {
  for (const std::string unit : {"furlong", "", "km", "m "}) {
    try {
      mrcloth::metres_per_unit(unit);
      ADD_FAILURE() << "unit '" << unit << "' was accepted";
    } catch (const mrcloth::ArgumentError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("unknown unit '" + unit + "'"), std::string::npos) << message;
      EXPECT_NE(message.find("m, dm, cm, mm, inch"), std::string::npos) << message;
    }
  }
}

TEST(Units, LoadWithUnknownUnitIsAnArgumentError) {
  ScratchDir dir;
  const std::string path = write_file(dir.file("grid.obj"), grid_obj());
  EXPECT_THROW(mrcloth::load_garment(path, {"yards"}), mrcloth::ArgumentError);
}

// --- loading good files ------------------------------------------------------

TEST(GarmentLoad, ObjQuadGridInDecimetres) {
  ScratchDir dir;
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()), {"dm"}), 0.1);
}

TEST(GarmentLoad, OffQuadGridInDecimetres) {
  ScratchDir dir;
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("grid.off"), grid_off()), {"dm"}), 0.1);
}

TEST(GarmentLoad, PlyQuadGridInDecimetres) {
  ScratchDir dir;
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("grid.ply"), grid_ply()), {"dm"}), 0.1);
}

TEST(GarmentLoad, PlyWithMoreVertexPropertiesKeepsDoubles) {
  // x, y, z are picked out by name, in any order, among other properties.
  ScratchDir dir;
  const std::string path = write_file(dir.file("rich.ply"),
                                      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double z\n"
                                      "property uchar red\nproperty float x\nproperty float confidence\n"
                                      "property float y\nelement face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n0.1 7 0.3 0 -0.7\n0.1 7 1.7 0.5 -0.7\n0.2 7 1.7 1 0.45\n"
                                      "0.2 7 0.3 0 0.45\n4 0 1 2 3\n");
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path, {"mm"});
  ASSERT_EQ(loaded.mesh.n_vertices(), 4u);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  EXPECT_EQ(loaded.mesh.point(QuadMesh::VertexHandle(1)), OpenMesh::Vec3d(1.7 * 0.001, -0.7 * 0.001, 0.1 * 0.001));
  EXPECT_EQ(loaded.mesh.point(QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(1.7 * 0.001, 0.45 * 0.001, 0.2 * 0.001));
}

TEST(GarmentLoad, DefaultUnitIsMetresAndExtensionCaseDoesNotMatter) {
  ScratchDir dir;
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("GRID.OBJ"), grid_obj())), 1.0);
  expect_grid_as_read(mrcloth::load_garment(write_file(dir.file("grid.Off"), grid_off()), {"cm"}), 0.01);
}

TEST(GarmentLoad, TrianglesAndPentagonsAreSplitIntoQuads) {
  // A pentagon 0-4, a triangle on its edge 4-0 and a quad on its edge 1-2:
  // 8 vertices, 10 edges, 3 faces -> 8 + 10 + 3 vertices and 5 + 3 + 4 quads.
  ScratchDir dir;
  const std::string path = write_file(dir.file("mixed.obj"),
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 1.5 0\nv 0 1 0\n"
                                      "v -1 0.5 0\nv 2 0 0\nv 2 1 0\n"
                                      "f 1 2 3 4 5\nf 1 5 6\nf 2 7 8 3\n");
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path);
  const QuadMesh& mesh = loaded.mesh;
  EXPECT_EQ(mesh.n_vertices(), 21u);
  EXPECT_EQ(mesh.n_faces(), 12u);
  EXPECT_EQ(mesh.n_edges(), 32u);  // Euler: V - E + F = 1 for a disc
  for (const auto f : mesh.faces()) EXPECT_EQ(mesh.valence(f), 4u) << "face " << f.idx();
  EXPECT_EQ(mrcloth::quadtree(mesh).size(), 12u);
  // The file's vertices keep their indices; then edge midpoints, then centres.
  EXPECT_EQ(mesh.point(QuadMesh::VertexHandle(3)), OpenMesh::Vec3d(0.5, 1.5, 0));
  EXPECT_EQ(mesh.point(QuadMesh::VertexHandle(7)), OpenMesh::Vec3d(2, 1, 0));
  const OpenMesh::Vec3d triangle_centre = mesh.point(QuadMesh::VertexHandle(19));
  EXPECT_NEAR(triangle_centre[0], -1.0 / 3.0, 1e-15);
  EXPECT_NEAR(triangle_centre[1], 0.5, 1e-15);
  EXPECT_EQ(mesh.point(QuadMesh::VertexHandle(20)), OpenMesh::Vec3d(1.5, 0.5, 0));
  // Every edge midpoint exists once: the boundary has 2 * 8 edges, all halves.
  std::size_t boundary = 0;
  for (const auto e : mesh.edges()) boundary += mesh.is_boundary(e) ? 1 : 0;
  EXPECT_EQ(boundary, 16u);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  const std::string& warning = loaded.warnings[0];
  EXPECT_EQ(warning.rfind(path + ": ", 0), 0u) << warning;
  EXPECT_NE(warning.find("1 triangle and 1 n-gon"), std::string::npos) << warning;
  EXPECT_NE(warning.find("split into quads"), std::string::npos) << warning;
  EXPECT_NE(warning.find("21 vertices instead of 8"), std::string::npos) << warning;
}

TEST(GarmentLoad, AllTriangleOffIsSplitWithPluralWarning) {
  ScratchDir dir;
  const std::string path =
      write_file(dir.file("two.off"), "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path);
  EXPECT_EQ(loaded.mesh.n_vertices(), 4u + 5u + 2u);
  EXPECT_EQ(loaded.mesh.n_faces(), 6u);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("2 triangles and 0 n-gons"), std::string::npos) << loaded.warnings[0];
}

/// OpenMesh's reader starts binary data 12 bytes after the header's last
/// word: a comment before end_header shifted it; the reader now gets a
/// header without comments.
TEST(GarmentLoad, BinaryPlyReadsInEitherByteOrderWhateverItsHeaderComments) {
  ScratchDir dir;
  for (const bool big : {false, true}) {
    for (const std::string extra : {"", "comment made by hand\n", "obj_info x\ncomment two\n\n"}) {
      const std::string name = std::string(big ? "big" : "little") + std::to_string(extra.size()) + ".ply";
      const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file(name), binary_quad_ply(big, extra, 4)));
      ASSERT_EQ(loaded.mesh.n_vertices(), 4u) << name;
      ASSERT_EQ(loaded.mesh.n_faces(), 1u) << name;
      EXPECT_EQ(loaded.mesh.point(QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(1.25, 0.1f, 0.5)) << name;
    }
  }
}

TEST(GarmentLoad, UpperCaseMagicPlyReads) {
  ScratchDir dir;
  const std::string text = "PLY" + ply_header(4, 1).substr(3) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  EXPECT_EQ(mrcloth::load_garment(write_file(dir.file("upper.ply"), text)).mesh.n_faces(), 1u);
}

TEST(GarmentLoad, UnweldedSeamsAreNamedInAWarning) {
  ScratchDir dir;
  // Two squares side by side, their shared side written twice (as panels are exported).
  const std::string panels = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\n"
                             "f 1 2 3 4\nf 5 6 7 8\n";
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("panels.obj"), panels));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("2 pairs of boundary vertices lie on one another, the first vertex 1 (line 2) on vertex 4 (line 5): "),
            std::string::npos)
      << loaded.warnings[0];
  // Welded, nothing to say.
  const std::string welded = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 5 6 3\n";
  EXPECT_TRUE(mrcloth::load_garment(write_file(dir.file("welded.obj"), welded)).warnings.empty());
  // The two ends of one very short edge are no seam: welding them would collapse the face.
  const std::string sliver = "v 0 0 0\nv 1 0 0\nv 1 1e-9 0\nv 0 1e-9 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\nf 4 3 6 5\n";
  EXPECT_TRUE(mrcloth::load_garment(write_file(dir.file("sliver.obj"), sliver)).warnings.empty());
}

TEST(GarmentLoad, AConcaveFaceIsNamedInAWarning) {
  // A dart: corner 2 of (0,0) (2,0) (0.5,0.5) (0,2) turns inwards, and the
  // bilinear split folds a child over another.
  ScratchDir dir;
  const std::string dart = "v 0 0 0\nv 2 0 0\nv 0.5 0.5 0\nv 0 2 0\nf 1 2 3 4\n";
  const mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("dart.obj"), dart));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("dart.obj: face 0 (line 5) is concave at its corner 2: refining it folds a child face over another"),
            std::string::npos)
      << loaded.warnings[0];
  // The same turned the other way (clockwise) is as concave; a kite is not.
  EXPECT_EQ(mrcloth::load_garment(write_file(dir.file("dart_cw.obj"), "v 0 0 0\nv 0 2 0\nv 0.5 0.5 0\nv 2 0 0\nf 1 2 3 4\n"))
                .warnings.size(), 1u);
  EXPECT_TRUE(mrcloth::load_garment(write_file(dir.file("kite.obj"), "v 0 0 0\nv 2 0 0\nv 1.5 1.5 0\nv 0 2 0\nf 1 2 3 4\n"))
                  .warnings.empty());
}

TEST(GarmentLoad, LinesContinuedByABackslashAreJoinedAndLaterLinesKeepTheirNumbers) {
  ScratchDir dir;
  const std::string square = "v 0 0 0\nv 1 0 \\\n0\nv 1 1 0\nv 0 1 0\n";
  const mrcloth::LoadResult joined = mrcloth::load_garment(write_file(dir.file("joined.obj"), square + "f 1 2 \\\n3 4\n"));
  EXPECT_EQ(joined.mesh.n_vertices(), 4u);
  EXPECT_EQ(joined.mesh.n_faces(), 1u);
  EXPECT_EQ(joined.mesh.point(QuadMesh::VertexHandle(1)), OpenMesh::Vec3d(1, 0, 0));
  // Line 6 (after the continued line 2-3) is named as line 6.
  EXPECT_LOAD_ERROR(write_file(dir.file("bad.obj"), square + "f 1 2 3 9\n"), "face 0 (line 6) refers to vertex 9");
}

TEST(GarmentLoad, AByteOrderMarkBeforeTheFirstVertexIsSkipped) {
  ScratchDir dir;
  const mrcloth::LoadResult marked =
      mrcloth::load_garment(write_file(dir.file("marked.obj"), "\xEF\xBB\xBF" + grid_obj().substr(std::string("# grid\no grid\n").size())));
  expect_grid_as_read(marked, 1.0);
}

// OpenMesh's OFF reader keeps what the last file it checked by name said
// of itself (binary, colours, normals) and applies it to text it is handed
// as a stream: the ASCII OFF read after a binary one was read as binary.
TEST(GarmentLoad, OffReadsDoNotInheritTheLastFilesLayout) {
  ScratchDir dir;
  const mrcloth::LoadResult binary = mrcloth::load_garment(write_file(dir.file("square.off"), binary_off_square()));
  EXPECT_EQ(binary.mesh.n_faces(), 1u);
  // A comment makes the loader hand OpenMesh a cleaned copy as a stream.
  const std::string text = "OFF\n# a comment\n4 1 0\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n4 0 1 2 3\n";
  const mrcloth::LoadResult ascii = mrcloth::load_garment(write_file(dir.file("commented.off"), text));
  ASSERT_EQ(ascii.mesh.n_vertices(), 4u);
  EXPECT_EQ(ascii.mesh.point(mrcloth::QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(2, 2, 0));
  // And a coloured OFF's layout does not carry over either.
  const std::string coloured = "COFF\n4 1 0\n0 0 0 255 0 0\n3 0 0 0 255 0\n3 3 0 0 0 255\n0 3 0 9 9 9\n4 0 1 2 3\n";
  EXPECT_EQ(mrcloth::load_garment(write_file(dir.file("coloured.off"), coloured)).mesh.n_vertices(), 4u);
  const mrcloth::LoadResult again = mrcloth::load_garment(write_file(dir.file("again.off"), text));
  EXPECT_EQ(again.mesh.point(mrcloth::QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(2, 2, 0));
}

// --- real data -----------------------------------------------------------------

TEST(GarmentRealData, MakeHumanSkirtHelperInDecimetres) {
  const std::string path = std::string(MRCLOTH_SHARED_DATA) + "/garments/makehuman/skirthelper.obj";
  if (!fs::exists(path)) GTEST_SKIP() << "shared data not found at " << path;
  const mrcloth::LoadResult loaded = mrcloth::load_garment(path, {"dm"});
  const QuadMesh& mesh = loaded.mesh;
  EXPECT_EQ(mesh.n_vertices(), 720u);
  EXPECT_EQ(mesh.n_faces(), 684u);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const auto v : mesh.vertices()) {
    low = std::min(low, mesh.point(v)[1]);
    high = std::max(high, mesh.point(v)[1]);
  }
  // The file's y spans -7.2846 .. 1.8385 decimetres.
  EXPECT_NEAR(low, -0.72846, 1e-12);
  EXPECT_NEAR(high, 0.18385, 1e-12);
  EXPECT_EQ(mrcloth::quadtree(mesh).size(), 684u);
}
