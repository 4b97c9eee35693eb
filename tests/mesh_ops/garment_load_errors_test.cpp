// What loading a garment refuses (garment_io): missing or unknown files,
// broken OBJ, OFF and PLY text or binary data, non-manifold meshes, damaged
// stored layers; each refusal names the file, and the line or element at fault.
// Fixtures are tiny text meshes written by the tests into a scratch folder
// (garment_io_support.h).
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/quad_refiner.h"

#include "garment_io_support.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using mrcloth::QuadMesh;
using mrcloth::test::binary_off_square;
using mrcloth::test::binary_quad_ply;
using mrcloth::test::grid_obj;
using mrcloth::test::ply_header;
using mrcloth::test::ScratchDir;
using mrcloth::test::write_file;

namespace {

// Three quads sharing the edge 0-1.
const char* const kThreeQuadsOnOneEdgeObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 -1 0\nv 1 -1 0\nv 0 0 1\nv 1 0 1\n"
    "f 1 2 3 4\nf 2 1 5 6\nf 1 2 8 7\n";

}  // namespace

// --- refusing bad files --------------------------------------------------------

TEST(GarmentLoadErrors, MissingFile) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(dir.file("absent.obj"), "cannot open file (it does not exist)");
  // A name decoded from bytes that were not UTF-8 (a Latin-1 "caf\xe9.obj"
  // reaches the loader as "caf\uFFFD.obj"): said so, not only "missing".
  EXPECT_LOAD_ERROR(dir.file("caf\xEF\xBF\xBD.obj"), "its name holds U+FFFD, the mark of bytes that were not UTF-8");
}

TEST(GarmentLoadErrors, FolderInsteadOfFile) {
  ScratchDir dir;
  fs::create_directories(dir.file("folder.obj"));
  EXPECT_LOAD_ERROR(dir.file("folder.obj"), "cannot open file");
}

TEST(GarmentLoadErrors, UnknownExtension) {
  ScratchDir dir;
  const std::string stl = write_file(dir.file("shirt.stl"), "solid x\nendsolid x\n");
  EXPECT_LOAD_ERROR(stl, "unknown mesh format (extension '.stl'); expected one of .obj, .off, .ply, .om");
  const std::string bare = write_file(dir.file("shirt"), grid_obj());
  EXPECT_LOAD_ERROR(bare, "unknown mesh format (extension none)");
}

TEST(GarmentLoadErrors, EmptyFiles) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("empty.obj"), ""), "the file is empty");
  EXPECT_LOAD_ERROR(write_file(dir.file("empty.off"), ""), "the file is empty");
  EXPECT_LOAD_ERROR(write_file(dir.file("comments.obj"), "# nothing here\n"), "the file has no vertices");
  EXPECT_LOAD_ERROR(write_file(dir.file("points.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\n"), "the file has no faces");
  EXPECT_LOAD_ERROR(write_file(dir.file("points.off"), "OFF\n3 0 0\n0 0 0\n1 0 0\n1 1 0\n"), "the file has no faces");
}

TEST(GarmentLoadErrors, NonFiniteCoordinateObj) {
  ScratchDir dir;
  const std::string quad_faces = "v 1 0 0\nv 1 1 0\nf 1 2 3 4\n";
  EXPECT_LOAD_ERROR(write_file(dir.file("nan.obj"), "v nan 0 0\nv 0 1 0\n" + quad_faces),
                    "vertex 0 (line 1) has a non-finite coordinate (nan)");
  EXPECT_LOAD_ERROR(write_file(dir.file("huge.obj"), "# c\nv 0 0 0\nv 0 1 0\nv 1 1e999 0\nv 1 0 0\nf 1 2 3 4\n"),
                    "vertex 2 (line 4) has a non-finite coordinate (1e999)");
  EXPECT_LOAD_ERROR(write_file(dir.file("inf.obj"), "v 0 0 -inf\nv 0 1 0\n" + quad_faces),
                    "vertex 0 (line 1) has a non-finite coordinate (-inf)");
  EXPECT_LOAD_ERROR(write_file(dir.file("word.obj"), "v 0 0 zero\nv 0 1 0\n" + quad_faces),
                    "vertex 0 (line 1) has a coordinate that is not a number ('zero')");
}

TEST(GarmentLoadErrors, NonFiniteCoordinateOffAndPly) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("nan.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 NaN 0\n0 1 0\n4 0 1 2 3\n"),
                    "vertex 2 (line 5) has a non-finite coordinate (NaN)");
  EXPECT_LOAD_ERROR(
      write_file(dir.file("inf.ply"), ply_header(4, 1) + "0 0 0\n1 0 0\n1 1 0\n0 inf 0\n4 0 1 2 3\n"),
      "vertex 3 (line 14) has a non-finite coordinate (inf)");
}

TEST(GarmentLoadErrors, NonManifoldEdge) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("fan.obj"), kThreeQuadsOnOneEdgeObj),
                    "face 2 (line 11) would be a third face on its edge from vertex 0 (line 1) to vertex 1 (line 2); "
                    "expected an oriented 2-manifold quad mesh");
  // With texture coordinates the OBJ reader takes another path after add_face.
  EXPECT_LOAD_ERROR(write_file(dir.file("fan_uv.obj"),
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 -1 0\nv 1 -1 0\nv 0 0 1\nv 1 0 1\nvt 0 0\n"
                               "f 1/1 2/1 3/1 4/1\nf 2/1 1/1 5/1 6/1\nf 1/1 2/1 8/1 7/1\nf 5/1 6/1 8/1\n"),
                    "face 2 (line 12) would be a third face on its edge from vertex 0 (line 1) to vertex 1 (line 2)");
  EXPECT_LOAD_ERROR(write_file(dir.file("fan.off"),
                               "OFF\n8 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 -1 0\n1 -1 0\n0 0 1\n1 0 1\n"
                               "4 0 1 2 3\n4 1 0 4 5\n4 1 0 6 7\n"),
                    "face 2 (line 13) would be a third face on its edge from vertex 1 (line 4) to vertex 0 (line 3)");
}

TEST(GarmentLoadErrors, AFaceWoundTheOtherWayIsNamedWithItsEdge) {
  // Two squares sharing the edge 1-2, the second wound clockwise.
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("flipped.obj"),
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 3 6 5\n"),
                    "face 1 (line 8) runs its edge from vertex 1 (line 2) to vertex 2 (line 3) the way face 0 (line 7) does: "
                    "one of them is wound the other way round");
}

TEST(GarmentLoadErrors, NonManifoldVertex) {
  // Four quads close a disc around vertex 4; a fifth quad then touches that
  // interior vertex from above.
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("spike.off"),
                               "OFF\n12 5 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n0 2 0\n1 2 0\n2 2 0\n"
                               "1 1 1\n2 1 1\n2 2 1\n"
                               "4 0 1 4 3\n4 1 2 5 4\n4 3 4 7 6\n4 4 5 8 7\n4 4 9 10 11\n"),
                    "face 4 (line 19) would join the faces before it only at a vertex (a bow-tie)");
}

TEST(GarmentLoadErrors, RepeatedVertexInFace) {
  ScratchDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n";
  EXPECT_LOAD_ERROR(write_file(dir.file("repeat.obj"), vertices + "f 1 2 3 4\nf 2 5 5 6\n"),
                    "face 1 (line 8) uses vertex 4 (line 5) more than once");
  EXPECT_LOAD_ERROR(write_file(dir.file("repeat.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 1 3\n"),
                    "face 0 (line 7) uses vertex 1 (line 4) more than once");
  EXPECT_LOAD_ERROR(write_file(dir.file("repeat.ply"), ply_header(4, 1) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 3 2 3\n"),
                    "face 0 (line 15) uses vertex 3 (line 14) more than once");
}

TEST(GarmentLoadErrors, VertexIndexOutOfRange) {
  ScratchDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  EXPECT_LOAD_ERROR(write_file(dir.file("range.obj"), vertices + "f 1 2 3 9\n"),
                    "face 0 (line 5) refers to vertex 9, which does not exist (4 vertices are defined before it");
  EXPECT_LOAD_ERROR(write_file(dir.file("zero.obj"), vertices + "f 1 2 3 4\nf 0 1 2 3\n"),
                    "face 1 (line 6) refers to vertex 0, which does not exist");
  EXPECT_LOAD_ERROR(write_file(dir.file("range.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 7\n"),
                    "face 0 (line 7) refers to vertex 7 (counted from 0), which does not exist (the file has 4 vertices)");
  EXPECT_LOAD_ERROR(write_file(dir.file("range.ply"), ply_header(4, 2) + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                                                          "4 0 1 2 3\n3 0 2 12\n"),
                    "face 1 (line 16) refers to vertex 12 (counted from 0), which does not exist (the file has 4 vertices)");
}

/// OpenMesh's OBJ reader aborts the process (an assertion Debian's build
/// keeps) on a face whose first corner has no vertex index: refused first.
TEST(GarmentLoadErrors, ACornerWithoutAVertexIndexIsRefusedBeforeTheReaderAborts) {
  ScratchDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  for (const std::string face : {"f /1 2 3 4", "f /1/1 2 3 4", "f /1", "f 1 2 3 /4"})
    EXPECT_LOAD_ERROR(write_file(dir.file("slash.obj"), vertices + "f 1 2 3 4\n" + face + "\n"),
                      "face 1 (line 6) has a corner that is not a vertex index ('/");
  // An earlier problem the scan sees is still the one named.
  EXPECT_LOAD_ERROR(write_file(dir.file("earlier.obj"), vertices + "f 1 2 3 9\nf /1 2 3 4\n"),
                    "face 0 (line 5) refers to vertex 9");
}

/// OpenMesh's PLY reader crashes on a property before any element and
/// loops for ever on a type it does not know: both refused with the line.
TEST(GarmentLoadErrors, PlyPropertiesOpenMeshCannotReadAreRefusedWithTheirLine) {
  ScratchDir dir;
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  std::string header = ply_header(4, 1);
  const std::string orphan = "ply\nformat ascii 1.0\nproperty float x\n" + header.substr(header.find("element vertex"));
  EXPECT_LOAD_ERROR(write_file(dir.file("orphan.ply"), orphan + body),
                    "the PLY header's property (line 3) comes before any element");
  std::string unknown = header;
  unknown.replace(unknown.find("uchar int"), 9, "uchar intx");
  EXPECT_LOAD_ERROR(write_file(dir.file("unknown.ply"), unknown + body), "is 'property list uchar intx");
}

/// OpenMesh's PLY reader reads its header word by word and loops for ever on
/// a word it cannot convert; it pushes four billion corners for a count of
/// -1: each refused first, naming the line.
TEST(GarmentLoadErrors, PlyHeadersAndDataOpenMeshWouldMisreadNameTheirLine) {
  ScratchDir dir;
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  const std::string header = ply_header(4, 1);
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = header + body;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const auto refused = [&](const std::string& name, const std::string& text, const std::string& problem) {
    EXPECT_LOAD_ERROR(write_file(dir.file(name), text), problem);
  };
  refused("format.ply", with("format ascii 1.0", "format ascii infinity 1.0"),
          "the PLY header's line 2 is 'format ascii infinity 1.0'; expected 'format ascii 1.0'");
  refused("version.ply", with("ascii 1.0", "ascii one"), "line 2 is 'format ascii one'");
  refused("count.ply", with("element vertex 4", "element vertex 9ace"),
          "the PLY header's element (line 4) is 'element vertex 9ace'; expected 'element <name> <count>' with a "
          "count from 0 to 4294967295");
  refused("negative.ply", with("element face 1", "element face -1"), "element (line 8) is 'element face -1'");
  refused("huge.ply", with("element face 1", "element face 4294967296"), "(line 8) is 'element face 4294967296'");
  refused("typo.ply", with("element face", "elemnt face"),
          "the PLY header's line 8 is 'elemnt face 1'; expected comment, obj_info, element, property or end_header");
  refused("end.ply", with("end_header", "end_header 0"), "end (line 10) is 'end_header 0'; expected 'end_header' alone");
  refused("twice.ply", with("element face 1", "element vertex 4"),
          "element (line 8) is a second 'vertex' element (the first is on line 4)");
  refused("list.ply", with("property float z", "property list uchar float z"), "(line 7) makes z a list");
  refused("vertex_list.ply", with("property float z", "property float z\nproperty list uchar int rings"),
          "property (line 8) is a list ('rings' of element 'vertex'); expected lists only for the faces' "
          "vertex_indices");
  refused("length.ply", with("list uchar int", "list float int"),
          "gives its list length as float; expected uchar, uint8, uint16 or int");
  refused("no_y.ply", with("property float y\n", ""), "vertex element (line 4) has 0 properties named y");
  refused("corners.ply", with("4 0 1 2 3", "-1 0 1 2 3"),
          "face 0 (line 15) has '-1' for its number of corners; expected a uchar count");
  refused("many.ply", with("4 0 1 2 3", "200 0 1 2 3"),
          "the PLY data ends at face 0; expected the 1 items the header's element 'face' (line 8) counts");
  refused("short.ply", with("element vertex 4", "element vertex 400"), "the PLY data ends at vertex");
  refused("index.ply", with("4 0 1 2 3", "4 0 1 2 -3"),
          "face 0 (line 15) has '-3' among its vertex indices; expected 4 indices from 0");
  refused("word.ply", with("1 1 0", "1 1 zero"), "vertex 2 (line 13) has a coordinate that is not a number ('zero')");
  refused("magic.ply", with("ply\n", "ply 1\n"), "the first line is not 'ply'; expected a PLY file");
  refused("face_first.ply",
          "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nelement vertex 0\n"
          "property float x\nproperty float y\nproperty float z\nend_header\n",
          "face element (line 3) comes before its vertex element");
}

/// Other scalars of a vertex or face are checked against their type too
/// (OpenMesh reads colours as numbers: a word stops its stream).
TEST(GarmentLoadErrors, PlyScalarsMustBeNumbersOfTheirType) {
  ScratchDir dir;
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_LOAD_ERROR(write_file(dir.file("red.ply"), header + "0 0 0 255\n1 0 0 256\n1 1 0 0\n0 1 0 0\n4 0 1 2 3\n"),
                    "vertex 1 (line 12) has '256' for its red; expected a uchar number");
  EXPECT_LOAD_ERROR(write_file(dir.file("word.ply"), header + "0 0 0 255\n1 0 0 1\n1 1 0 x\n0 1 0 0\n4 0 1 2 3\n"),
                    "vertex 2 (line 13) has 'x' for its red");
  const mrcloth::LoadResult loaded =
      mrcloth::load_garment(write_file(dir.file("fine.ply"), header + "0 0 0 255\n1 0 0 +7\n1 1 0 0\n0 1 0 0\n"
                                                                      "4 0 1 2 3\n"));
  EXPECT_EQ(loaded.mesh.n_faces(), 1u);
}

TEST(GarmentLoadErrors, BinaryPlyCutShortOrWithAHugeCornerCountIsRefused) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("minus.ply"), binary_quad_ply(false, "", -1)),
                    "the PLY binary data's face 0 has 4294967295 corners (as OpenMesh reads its int count), but only "
                    "16 bytes of data remain");
  std::string cut = binary_quad_ply(true, "", 4);
  cut.resize(cut.size() - 20);
  EXPECT_LOAD_ERROR(write_file(dir.file("cut.ply"), cut), "the PLY data ends at face 0");
  cut.resize(cut.size() - 30);  // 38 bytes of data: two 17-byte vertices
  EXPECT_LOAD_ERROR(write_file(dir.file("cut_more.ply"), cut), "the PLY data ends at vertex 2");
  std::string integer = binary_quad_ply(false, "", 4);
  integer.replace(integer.find("float x"), 7, "int x");
  EXPECT_LOAD_ERROR(write_file(dir.file("int.ply"), integer), "stores x as int; expected float or double");
}

/// OpenMesh's OFF reader, given no counts, reserved for whatever its
/// variables held (77 GB under AddressSanitizer, which stops there).
TEST(GarmentLoadErrors, OffWithoutCountsIsRefused) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("bare.off"), "OFF\n"),
                    "the OFF header has no vertex and face counts; expected 'V F E' after OFF");
  EXPECT_LOAD_ERROR(write_file(dir.file("one.off"), "OFF\n# only vertices\n4\n0 0 0\n"),
                    "the OFF header has no vertex and face counts (line 3)");
}

TEST(GarmentLoadErrors, FirstProblemInFileOrderIsReported) {
  ScratchDir dir;
  // Face 1 repeats a vertex (seen by the OBJ scan), face 2 is out of range.
  EXPECT_LOAD_ERROR(write_file(dir.file("two.obj"),
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 1 2 3\nf 1 2 3 7\n"),
                    "face 1 (line 6) uses vertex 0 (line 1) more than once");
  // Face 1 cannot join face 0 (found by the importer) before face 2 repeats a vertex.
  EXPECT_LOAD_ERROR(write_file(dir.file("order.obj"),
                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 -1 0\n"
                               "f 1 2 3 4\nf 1 2 3 5\nf 1 4 4 5\n"),
                    "face 1 (line 7) runs its edge from vertex 0 (line 1) to vertex 1 (line 2) the way face 0 (line 6) does");
}

TEST(GarmentLoadErrors, TextThatIsNotLinesOfUtf8IsNamed) {
  ScratchDir dir;
  EXPECT_LOAD_ERROR(write_file(dir.file("mac.obj"), "v 0 0 0\rv 1 0 0\rv 1 1 0\rv 0 1 0\rf 1 2 3 4\r"),
                    "the file ends its lines with carriage returns alone (classic Mac OS); expected line ends LF or CR LF");
  std::string utf16 = "\xFF\xFE";
  for (const char c : std::string("v 0 0 0\n")) utf16 += std::string{c, '\0'};
  EXPECT_LOAD_ERROR(write_file(dir.file("wide.obj"), utf16), "the file is UTF-16 text");
  EXPECT_LOAD_ERROR(write_file(dir.file("wide.off"), utf16), "the file is UTF-16 text");
  EXPECT_LOAD_ERROR(write_file(dir.file("mac.off"), "OFF\r4 1 0\r0 0 0\r1 0 0\r1 1 0\r0 1 0\r4 0 1 2 3\r"),
                    "the file ends its lines with carriage returns alone");
  // A folder is named as one, whatever its name's suffix.
  std::filesystem::create_directory(dir.file("folder.obj"));
  std::filesystem::create_directory(dir.file("folder"));
  EXPECT_LOAD_ERROR(dir.file("folder.obj"), "cannot open file (it is a folder)");
  EXPECT_LOAD_ERROR(dir.file("folder"), "cannot open file (it is a folder)");
}

TEST(GarmentLoadErrors, OpenMeshDiagnosticsStayQuiet) {
  ScratchDir dir;
  const std::string fan = write_file(dir.file("fan.obj"), kThreeQuadsOnOneEdgeObj);
  const std::string range = write_file(dir.file("range.off"), "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 7\n");
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  EXPECT_THROW(mrcloth::load_garment(fan), mrcloth::InputError);
  EXPECT_THROW(mrcloth::load_garment(range), mrcloth::InputError);
  EXPECT_THROW(mrcloth::load_garment(dir.file("absent.ply")), mrcloth::InputError);
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
  EXPECT_TRUE(::omerr().is_enabled());
  EXPECT_TRUE(::omlog().is_enabled());
}

/// Layers that disagree with the hierarchy (a file of an older mrcloth,
/// without the checksum, damaged; or edited by another program) are refused:
/// a face whose level or polygon is not its record's would simulate with
/// another level's stiffness, and parents naming a later vertex form a
/// cycle the polygon walk recursed along without end.
TEST(GarmentLoadErrors, StoredLayersThatDisagreeWithTheHierarchyAreRefused) {
  ScratchDir dir;
  const auto refined = [&dir] {
    QuadMesh mesh = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj())).mesh;
    mrcloth::QuadRefiner refiner(mesh);
    refiner.split(1);
    EXPECT_TRUE(refiner.finish());
    return mesh;
  };
  QuadMesh level = refined();
  const mrcloth::Layers l = mrcloth::get_layers(level);
  level.property(l.level, QuadMesh::FaceHandle(4)) += 1;
  mrcloth::save_mesh(level, dir.file("level.om"));
  EXPECT_LOAD_ERROR(dir.file("level.om"), "the stored refinement hierarchy is damaged (face 4 is not the polygon or "
                                          "level of its record)");

  QuadMesh twice = refined();
  twice.property(l.quad, QuadMesh::FaceHandle(2)) = twice.property(l.quad, QuadMesh::FaceHandle(3));
  mrcloth::save_mesh(twice, dir.file("twice.om"));
  EXPECT_LOAD_ERROR(dir.file("twice.om"), "(face 3 names no active record, or one an earlier face names)");

  QuadMesh cycle = refined();
  const int last = static_cast<int>(cycle.n_vertices()) - 1;
  // The last vertex the midpoint of coarse edge 0-1, and 1 that of 0-last.
  cycle.property(l.parents, QuadMesh::VertexHandle(last)) = OpenMesh::Vec2i(0, 1);
  cycle.property(l.parents, QuadMesh::VertexHandle(1)) = OpenMesh::Vec2i(0, last);
  mrcloth::save_mesh(cycle, dir.file("cycle.om"));
  EXPECT_LOAD_ERROR(dir.file("cycle.om"), "the stored layers are damaged (vertex 1 names edge ends 0, " +
                                              std::to_string(last) + ")");
}

TEST(GarmentLoadErrors, WhatNoGarmentCanBeIsRefusedAtLoading) {
  ScratchDir dir;
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  // Two quads that share only a corner: a bow-tie vertex.
  EXPECT_LOAD_ERROR(write_file(dir.file("bowtie.obj"),
                               square + "v 2 1 0\nv 2 2 0\nv 1 2 0\nf 1 2 3 4\nf 3 5 6 7\n"),
                    "vertex 2 (line 3) is non-manifold (two fans of faces meet only at it, a bow-tie)");
  EXPECT_LOAD_ERROR(write_file(dir.file("loose.obj"), square + "v 5 5 5\nv 6 6 6\nf 1 2 3 4\n"),
                    "vertex 4 (line 5) belongs to no face (nor do 1 more)");
  EXPECT_LOAD_ERROR(write_file(dir.file("line.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n" + square +
                                                         "f 5 6 7 8\nf 1 2 3 4\n"),
                    "face 1 (line 10) has no area");
  // Crossed as a bow-tie: the halves cancel.
  EXPECT_LOAD_ERROR(write_file(dir.file("twisted.obj"), "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n"),
                    "face 0 (line 5) has no area");
  // Beyond float range OpenMesh's reader would drop the vertex and shift the faces.
  EXPECT_LOAD_ERROR(write_file(dir.file("huge.obj"), "v 0 0 0\nv 1e39 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"),
                    "vertex 1 (line 2) has a coordinate beyond single precision's range (1e39)");
  // OpenMesh's PLY reader never returns from a header without its end.
  EXPECT_LOAD_ERROR(write_file(dir.file("open.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"),
                    "the PLY header has no 'end_header' line");
}

TEST(GarmentLoadErrors, OffHeadersOpenMeshWouldMisreadAreRefused) {
  ScratchDir dir;
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  // More than the data holds: OpenMesh read faces as vertices, or allocated for 1e12.
  EXPECT_LOAD_ERROR(write_file(dir.file("few.off"), "OFF\n5 1 0\n" + body),
                    "the OFF header (line 2) declares 5 vertices and 1 faces, but only 5 lines of data follow");
  EXPECT_LOAD_ERROR(write_file(dir.file("huge.off"), "OFF\n999999999999 1 0\n" + body), "declares 999999999999 vertices");
  EXPECT_LOAD_ERROR(write_file(dir.file("words.off"), "OFF\nabc 1 0\n" + body),
                    "the OFF header's vertex count 'abc' (line 2) is not a count");
  // Not an OFF variant: OpenMesh took "OFFX" for one.
  EXPECT_LOAD_ERROR(write_file(dir.file("offx.off"), "OFFX\n4 1 0\n" + body), "the file starts with 'OFFX'");
  // The counts on the header's line are legal, though OpenMesh reads them only on their own.
  const mrcloth::LoadResult same_line = mrcloth::load_garment(write_file(dir.file("same.off"), "OFF 4 1 0\n" + body));
  EXPECT_EQ(same_line.mesh.n_vertices(), 4u);
  EXPECT_EQ(same_line.mesh.n_faces(), 1u);
}

TEST(GarmentLoadErrors, ADamagedStoredHierarchyIsRefused) {
  ScratchDir dir;
  mrcloth::LoadResult loaded = mrcloth::load_garment(write_file(dir.file("grid.obj"), grid_obj()));
  QuadMesh& mesh = loaded.mesh;
  const mrcloth::Layers l = mrcloth::get_layers(mesh);
  // As a cut-short file reads: a child that is not there, a corner that is no vertex.
  mesh.property(l.quadtree)[2].children = {6, 7, 8, 9};
  mrcloth::save_mesh(mesh, dir.file("child.om"));
  EXPECT_LOAD_ERROR(dir.file("child.om"), "the stored refinement hierarchy is damaged (record 2 has a child out of place)");
  mesh.property(l.quadtree)[2].children = {-1, -1, -1, -1};
  mesh.property(l.quadtree)[3].corners[1] = 12;
  mrcloth::save_mesh(mesh, dir.file("corner.om"));
  EXPECT_LOAD_ERROR(dir.file("corner.om"), "(record 3 has a corner that is not a vertex)");
  mesh.property(l.quadtree)[3].corners[1] = 1;
  mesh.property(l.quadtree)[4].active = 0;
  mrcloth::save_mesh(mesh, dir.file("inactive.om"));
  EXPECT_LOAD_ERROR(dir.file("inactive.om"), "(5 active records for 6 faces)");
}

// OpenMesh's binary OFF reader trusts its counts: a face count of 2^32 - 1
// kept it reading past the end of the file for minutes (found by the
// mutation sweep), a corner count as large pushes billions of corners.
TEST(GarmentLoadErrors, BinaryOffCountsAreCheckedAgainstTheData) {
  ScratchDir dir;
  const mrcloth::LoadResult square = mrcloth::load_garment(write_file(dir.file("square.off"), binary_off_square()));
  ASSERT_EQ(square.mesh.n_vertices(), 4u);
  EXPECT_EQ(square.mesh.point(mrcloth::QuadMesh::VertexHandle(2)), OpenMesh::Vec3d(1, 1, 0));
  EXPECT_LOAD_ERROR(write_file(dir.file("faces.off"), binary_off_square(4, 0xFFFFFFFFu)),
                    "the binary OFF header declares 4 vertices and 4294967295 faces, which need at least 17179869228 "
                    "bytes; 68 follow");
  EXPECT_LOAD_ERROR(write_file(dir.file("vertices.off"), binary_off_square(6)),
                    "the binary OFF header declares 6 vertices and 1 faces, which need at least 76 bytes; 68 follow");
  // One vertex more than written: the face's bytes are read from its last corner on.
  EXPECT_LOAD_ERROR(write_file(dir.file("askew.off"), binary_off_square(5)), "face 0 (byte 83) has corner count 2 and 1 indices' bytes left");
  EXPECT_LOAD_ERROR(write_file(dir.file("corners.off"), binary_off_square(4, 1, 0x7FFFFFFFu)),
                    "face 0 (byte 71) has corner count 2147483647 and 4 indices' bytes left");
  EXPECT_LOAD_ERROR(write_file(dir.file("two.off"), binary_off_square(4, 1, 2)),
                    "face 0 (byte 71) has corner count 2 and 4 indices' bytes left; expected at least 3 corners");
  std::string far = binary_off_square();
  far[far.size() - 4] = 9;  // the last corner names vertex 9
  EXPECT_LOAD_ERROR(write_file(dir.file("far.off"), far), "face 0 names vertex 9; expected an index below 4");
  EXPECT_LOAD_ERROR(write_file(dir.file("one_line.off"), "OFF BINARY " + binary_off_square().substr(11, 20)),
                    "the binary OFF has no line end after 'OFF BINARY'");
  EXPECT_LOAD_ERROR(write_file(dir.file("short.off"), binary_off_square().substr(0, 19)),
                    "the binary OFF ends before its vertex, face and edge counts");
  std::string coloured = binary_off_square();
  coloured.insert(0, "C");
  EXPECT_LOAD_ERROR(write_file(dir.file("coloured.off"), coloured),
                    "binary COFF (with normals, colours or texture coordinates) is not supported");
  EXPECT_LOAD_ERROR(write_file(dir.file("second.off"), "# made by hand\n" + binary_off_square()),
                    "the 'OFF BINARY' line is line 2; expected it first");
}
