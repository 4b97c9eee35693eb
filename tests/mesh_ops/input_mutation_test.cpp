// The OBJ, ASCII OFF and PLY (ASCII and binary) garment readers given thousands of seeded edits of valid
// files (tests/input_mutations.h): each either reads the file, and what it
// returns holds the reader's promises (finite coordinates, quads only, a
// consistent forest), or throws InputError naming the file. Anything else (another exception, a crash, a
// hang under ctest's timeout) fails, with the offending input kept beside
// the test's folder for replay.
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/mode_painting.h"
#include "mesh_ops/uniform_refine.h"
#include "input_mutations.h"
#include "mesh_invariants.h"
#include "test_meshes.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

/// What a garment read must hold when it succeeds.
void expect_sound_garment(const QuadMesh& mesh, const std::string& input) {
  ASSERT_GT(mesh.n_faces(), 0u) << input;
  for (const auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    ASSERT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) << "vertex " << v.idx() << "\n" << input;
  }
  for (const auto f : mesh.faces()) ASSERT_EQ(mesh.valence(f), 4u) << "face " << f.idx() << "\n" << input;
  const auto violations = test::face_forest_violations(mesh);
  ASSERT_TRUE(violations.empty()) << violations.front() << "\n" << input;
}

using Tally = test::SweepTally;
using test::write_bytes;

/// Loads each of `count` mutations of `valid` as a garment (test::sweep_reader).
template <class Mutator>
Tally load_mutations(const fs::path& dir, const std::string& suffix, const std::string& valid, Mutator mutate,
                     int count) {
  return test::sweep_reader(dir, suffix, valid, std::move(mutate), count, test::Naming::file,
                            [](const std::string& path, const std::string& input) {
                              expect_sound_garment(load_garment(path).mesh, input);
                            });
}

const std::string kObjAlphabet = "vtfgo/ #\n\t-.0123456789e";

/// The grid's faces as corner indices.
std::vector<std::array<int, 4>> grid_faces() {
  std::vector<std::array<int, 4>> faces;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) faces.push_back({j * 4 + i, j * 4 + i + 1, j * 4 + i + 5, j * 4 + i + 4});
  return faces;
}

/// A 3 x 2 grid with texture coordinates, a group, a comment and a material.
std::string grid_obj() {
  std::string text = "# a 3 x 2 grid\nmtllib none.mtl\no sheet\ng skirt\n";
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) text += "v " + std::to_string(0.1 * i) + " " + std::to_string(0.1 * j) + " 0\n";
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) text += "vt " + std::to_string(i / 3.0) + " " + std::to_string(j / 2.0) + "\n";
  text += "usemtl cotton\n";
  for (const auto& face : grid_faces()) {
    text += "f";
    for (const int corner : face) text += " " + std::to_string(corner + 1) + "/" + std::to_string(corner + 1);
    text += "\n";
  }
  return text;
}

std::string grid_off() {
  std::string text = "OFF\n12 6 0\n";
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) text += std::to_string(0.1 * i) + " " + std::to_string(0.1 * j) + " 0\n";
  for (const auto& f : grid_faces())
    text += "4 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + " " +
            std::to_string(f[3]) + "\n";
  return text;
}

std::string grid_ply_header(const std::string& format) {
  return "ply\nformat " + format + " 1.0\ncomment a 3 x 2 grid\nelement vertex 12\nproperty float x\n"
         "property float y\nproperty float z\nproperty uchar red\nelement face 6\n"
         "property list uchar int vertex_indices\nobj_info made by hand\nend_header\n";
}

std::string grid_ply_text() {
  std::string text = grid_ply_header("ascii");
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) text += std::to_string(0.1 * i) + " " + std::to_string(0.1 * j) + " 0 200\n";
  for (const auto& f : grid_faces())
    text += "4 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + " " +
            std::to_string(f[3]) + "\n";
  return text;
}

/// Little-endian, as x86 holds it in memory.
template <typename T>
void append_bytes(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

std::string grid_ply_binary() {
  std::string bytes = grid_ply_header("binary_little_endian");
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) {
      append_bytes(bytes, 0.1f * static_cast<float>(i));
      append_bytes(bytes, 0.1f * static_cast<float>(j));
      append_bytes(bytes, 0.0f);
      append_bytes(bytes, std::uint8_t{200});
    }
  for (const auto& f : grid_faces()) {
    append_bytes(bytes, std::uint8_t{4});
    for (const int corner : f) append_bytes(bytes, std::int32_t{corner});
  }
  return bytes;
}

TEST(GarmentMutations, PlyTextEditsLoadSoundOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("input_mutation_test", "ply");
  const std::string valid = grid_ply_text();
  write_bytes(dir / "valid.ply", valid);
  expect_sound_garment(load_garment((dir / "valid.ply").string()).mesh, valid);
  const Tally tally = load_mutations(dir, ".ply", valid,
                                     test::TextMutator(13, "plyelementvrxfcstuchar \n-.0123456789"), 1500);
  EXPECT_GT(tally.read, 50);
  EXPECT_GT(tally.refused, 100);
}

TEST(GarmentMutations, PlyBinaryEditsLoadSoundOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("input_mutation_test", "ply_binary");
  const std::string valid = grid_ply_binary();
  write_bytes(dir / "valid.ply", valid);
  const LoadResult loaded = load_garment((dir / "valid.ply").string());
  expect_sound_garment(loaded.mesh, "(binary)");
  ASSERT_EQ(loaded.mesh.n_vertices(), 12u);
  EXPECT_EQ(loaded.mesh.point(QuadMesh::VertexHandle(7)), OpenMesh::Vec3d(0.1f * 3, 0.1f, 0.0));
  // Edits anywhere, and edits of the data alone (most header edits are refused).
  const std::size_t header = grid_ply_header("binary_little_endian").size();
  const Tally whole = load_mutations(dir, ".ply", valid, test::ByteMutator(14), 750);
  const Tally data = load_mutations(dir, ".ply", valid, test::ByteMutator(15, header), 750);
  EXPECT_GT(whole.read + data.read, 50);
  EXPECT_GT(whole.refused + data.refused, 100);
}

/// save_mesh's checksum makes almost every byte edit of its .om a refusal
/// by checksum; stamping the edited bytes with a fresh one (FNV-1a, 64 bits,
/// its own eight bytes taken as zero, as save_mesh writes it) lets the edits
/// reach the chunk, layer and forest checks behind it.
std::string with_fresh_checksum(std::string bytes) {
  const std::string name = layer::checksum;
  const std::size_t at = bytes.find(name);
  if (at == std::string::npos || at + name.size() >= bytes.size()) return bytes;
  const std::size_t value_at = at + name.size() + 1 + static_cast<unsigned char>(bytes[at + name.size()]) + 4;
  if (value_at + 8 > bytes.size()) return bytes;
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    const unsigned char byte = (k >= value_at && k < value_at + 8) ? 0 : static_cast<unsigned char>(bytes[k]);
    hash = (hash ^ byte) * 1099511628211ull;
  }
  for (std::size_t k = 0; k < 8; ++k) bytes[value_at + k] = static_cast<char>((hash >> (8 * k)) & 0xFF);
  return bytes;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(GarmentMutations, OmEditsLoadSoundOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("input_mutation_test", "om");
  QuadMesh refined = test::make_grid(3, 2, 0.1);
  uniform_refine(refined, 1);
  set_modes(refined, {0, 1, 2}, 3);
  save_mesh(refined, (dir / "valid.om").string());
  const std::string valid = read_bytes(dir / "valid.om");
  ASSERT_EQ(with_fresh_checksum(valid), valid) << "the test's checksum is save_mesh's";
  expect_sound_garment(load_garment((dir / "valid.om").string()).mesh, "(valid .om)");

  const Tally stamped = load_mutations(
      dir, ".om", valid, [mutate = test::ByteMutator(16)](const std::string& bytes) mutable {
        return with_fresh_checksum(mutate(bytes));
      },
      750);
  const Tally plain = load_mutations(dir, ".om", valid, test::ByteMutator(17), 750);
  EXPECT_GT(stamped.read, 20);
  EXPECT_GT(stamped.refused, 100);
  EXPECT_GT(plain.refused, 700) << "the checksum refuses nearly every edit";
}

/// The grid as a plain OpenMesh mesh, for OpenMesh's own writers.
OpenMesh::PolyMesh_ArrayKernelT<> plain_grid() {
  OpenMesh::PolyMesh_ArrayKernelT<> plain;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) plain.add_vertex({0.1f * static_cast<float>(i), 0.1f * static_cast<float>(j), 0.f});
  for (const auto& f : grid_faces())
    plain.add_face({plain.vertex_handle(static_cast<unsigned>(f[0])), plain.vertex_handle(static_cast<unsigned>(f[1])),
                    plain.vertex_handle(static_cast<unsigned>(f[2])), plain.vertex_handle(static_cast<unsigned>(f[3]))});
  return plain;
}

/// A plain OpenMesh .om (no mrcloth layers, no checksum): OpenMesh's own
/// reader behind check_om_structure.
TEST(GarmentMutations, PlainOpenMeshOmEditsLoadSoundOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("input_mutation_test", "plain_om");
  const OpenMesh::PolyMesh_ArrayKernelT<> plain = plain_grid();
  ASSERT_TRUE(OpenMesh::IO::write_mesh(plain, (dir / "valid.om").string()));
  const std::string valid = read_bytes(dir / "valid.om");
  expect_sound_garment(load_garment((dir / "valid.om").string()).mesh, "(valid .om)");
  const Tally tally = load_mutations(dir, ".om", valid, test::ByteMutator(18), 1500);
  EXPECT_GT(tally.read, 50);
  EXPECT_GT(tally.refused, 100);
}

/// Mode CSV files: a refused file changes no mode; an accepted one sets
/// modes within 0..kLargestMode.
TEST(ModeCsvMutations, EditsSetValidModesOrAreRefusedChangingNothing) {
  const fs::path dir = test::fresh_folder("input_mutation_test", "csv");
  std::string valid = "vertex,x,y,z,mode\n";
  for (int v = 0; v < 12; ++v) valid += std::to_string(v) + ",0.1,0.2,0," + std::to_string(1 + v % 4) + "\n";
  test::TextMutator mutate(19, "vertexmod,\n\t -.0123456789\"");
  const fs::path path = dir / "modes.csv";
  int read = 0, refused = 0;
  for (int k = 0; k < 1500; ++k) {
    const std::string input = mutate(valid);
    write_bytes(path, input);
    QuadMesh mesh = test::make_grid(3, 2, 0.1);
    const std::vector<int> before = get_modes(mesh);
    try {
      read_modes_csv(mesh, path.string());
      for (const int mode : get_modes(mesh)) ASSERT_TRUE(mode >= 0 && mode <= kLargestMode) << mode << "\n" << input;
      ++read;
    } catch (const InputError& error) {
      ASSERT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
      ASSERT_EQ(get_modes(mesh), before) << "a refused file changed modes:\n" << input;
      ++refused;
    }
  }
  EXPECT_GT(read, 100);
  EXPECT_GT(refused, 100);
}

TEST(GarmentMutations, ObjEditsLoadSoundOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("input_mutation_test", "obj");
  const std::string valid = grid_obj();
  write_bytes(dir / "valid.obj", valid);
  expect_sound_garment(load_garment((dir / "valid.obj").string()).mesh, valid);
  const Tally tally = load_mutations(dir, ".obj", valid, test::TextMutator(11, kObjAlphabet), 1500);
  EXPECT_GT(tally.read, 100);
  EXPECT_GT(tally.refused, 100);
}

TEST(GarmentMutations, OffEditsLoadSoundOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("input_mutation_test", "off");
  const std::string valid = grid_off();
  write_bytes(dir / "valid.off", valid);
  expect_sound_garment(load_garment((dir / "valid.off").string()).mesh, valid);
  const Tally tally = load_mutations(dir, ".off", valid, test::TextMutator(12, "OFF \n\t-.0123456789e#"), 1500);
  EXPECT_GT(tally.read, 100);
  EXPECT_GT(tally.refused, 100);
}

/// Binary OFF as OpenMesh writes it ("OFF BINARY", then little-endian
/// counts, float coordinates and int face lists), read by OpenMesh's reader.
TEST(GarmentMutations, BinaryOffEditsLoadSoundOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("input_mutation_test", "off_binary");
  const OpenMesh::PolyMesh_ArrayKernelT<> plain = plain_grid();
  ASSERT_TRUE(OpenMesh::IO::write_mesh(plain, (dir / "valid.off").string(), OpenMesh::IO::Options::Binary));
  const std::string valid = read_bytes(dir / "valid.off");
  const LoadResult loaded = load_garment((dir / "valid.off").string());
  expect_sound_garment(loaded.mesh, "(binary OFF)");
  ASSERT_EQ(loaded.mesh.n_vertices(), 12u);
  ASSERT_EQ(loaded.mesh.n_faces(), 6u);
  const std::size_t header = valid.find('\n') + 1;
  const Tally whole = load_mutations(dir, ".off", valid, test::ByteMutator(31), 750);
  const Tally data = load_mutations(dir, ".off", valid, test::ByteMutator(32, header), 750);
  EXPECT_GT(whole.read + data.read, 50);
  EXPECT_GT(whole.refused + data.refused, 100);
}

/// The material library an OBJ names (OpenMesh's OBJ reader parses it) has
/// no say in the garment: every edit of it loads the same mesh.
TEST(GarmentMutations, MaterialFileEditsLeaveTheGarmentAsItIs) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("input_mutation_test", "mtl");
  std::string obj = grid_obj();
  obj.replace(obj.find("mtllib none.mtl"), 15, "mtllib grid.mtl");
  write_bytes(dir / "grid.obj", obj);
  const std::string valid =
      "# made by hand\nnewmtl cotton\nKa 0.2 0.2 0.2\nKd 0.8 0.7 0.6\nKs 0 0 0\nNs 10\nd 1\nTr 0\nillum 2\n"
      "map_Kd cotton.png\n\nnewmtl other\nKd 1 0 0\n";
  write_bytes(dir / "grid.mtl", valid);
  const LoadResult reference = load_garment((dir / "grid.obj").string());
  test::TextMutator mutate(41, "newmtlKadsNTrilumap_ \n.-0123456789");
  int loaded = 0;
  for (int k = 0; k < 1500; ++k) {
    const std::string input = mutate(valid);
    write_bytes(dir / "grid.mtl", input);
    try {
      const LoadResult result = load_garment((dir / "grid.obj").string());
      ASSERT_EQ(result.mesh.n_vertices(), reference.mesh.n_vertices()) << input;
      ASSERT_EQ(result.mesh.n_faces(), reference.mesh.n_faces()) << input;
      for (const auto v : result.mesh.vertices()) ASSERT_EQ(result.mesh.point(v), reference.mesh.point(v)) << input;
      ++loaded;
    } catch (const std::exception& e) {
      ADD_FAILURE() << k << ": " << e.what() << "\n" << input;
    }
  }
  EXPECT_EQ(loaded, 1500);
}

}  // namespace
}  // namespace mrcloth
