#include "mesh_invariants.h"
#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/mode_painting.h"
#include "mesh_ops/texture_coords.h"
#include "mesh_ops/uniform_refine.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const char* env = std::getenv("MRCLOTH_TEST_TMP");
  fs::path dir = fs::path(env ? env : fs::temp_directory_path().string()) / "save_load_test";
  fs::create_directories(dir);
  return dir;
}

bool same_record(const QuadRecord& a, const QuadRecord& b) {
  return a.level == b.level && a.active == b.active && a.parent == b.parent && a.children == b.children &&
         a.corners == b.corners;
}

QuadMesh refined_tube() {
  QuadMesh mesh = test::make_tube(10, 5, 0.3, 0.5);
  paint_modes_sphere(mesh, {0.3, 0.25, 0.0}, 0.2, 3);
  set_modes(mesh, {0, 1, 2}, 2);
  adaptive_refine(mesh, {8.0, 3, true});
  return mesh;
}

TEST(SaveLoad, OmRoundTripKeepsHierarchyAndEveryLayer) {
  const QuadMesh saved = refined_tube();
  ASSERT_GT(count_hanging(saved), 0u) << "the fixture should have T-nodes";
  const fs::path path = temp_dir() / "refined.om";
  save_mesh(saved, path.string());
  const QuadMesh loaded = load_garment(path.string()).mesh;

  ASSERT_EQ(loaded.n_vertices(), saved.n_vertices());
  ASSERT_EQ(loaded.n_faces(), saved.n_faces());
  const Layers a = get_layers(saved), b = get_layers(loaded);
  for (auto v : saved.vertices()) {
    const auto w = loaded.vertex_handle(v.idx());
    EXPECT_EQ(saved.point(v), loaded.point(w)) << "vertex " << v.idx();
    EXPECT_EQ(saved.property(a.mode, v), loaded.property(b.mode, w));
    EXPECT_EQ(saved.property(a.r_value, v), loaded.property(b.r_value, w));
    EXPECT_EQ(saved.property(a.hanging, v), loaded.property(b.hanging, w));
    EXPECT_EQ(saved.property(a.parents, v), loaded.property(b.parents, w));
  }
  for (auto f : saved.faces()) {
    const auto g = loaded.face_handle(f.idx());
    EXPECT_EQ(saved.property(a.level, f), loaded.property(b.level, g));
    EXPECT_EQ(saved.property(a.quad, f), loaded.property(b.quad, g));
  }
  const auto& fa = quadtree(saved);
  const auto& fb = quadtree(loaded);
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t i = 0; i < fa.size(); ++i) EXPECT_TRUE(same_record(fa[i], fb[i])) << "record " << i;
  EXPECT_TRUE(test::face_forest_violations(loaded).empty());
}

TEST(SaveLoad, ALoadedRefinedMeshRefinesLikeTheOriginal) {
  // The midpoints are recovered from the parents layer: refining after a
  // round trip must reuse them exactly as refining the original does.
  QuadMesh original = refined_tube();
  const fs::path path = temp_dir() / "refine_again.om";
  save_mesh(original, path.string());
  QuadMesh loaded = load_garment(path.string()).mesh;
  uniform_refine(original, 1);
  uniform_refine(loaded, 1);
  ASSERT_EQ(loaded.n_vertices(), original.n_vertices());
  for (auto v : original.vertices()) EXPECT_EQ(original.point(v), loaded.point(loaded.vertex_handle(v.idx())));
  EXPECT_TRUE(test::face_forest_violations(loaded).empty());
  EXPECT_TRUE(test::hanging_midpoint_violations(loaded).empty());
}

TEST(SaveLoad, ActiveSurfaceExportKeepsTheActivePolygons) {
  const QuadMesh mesh = refined_tube();
  ASSERT_GT(count_hanging(mesh), 0u);
  const fs::path path = temp_dir() / "surface.obj";
  export_surface(mesh, path.string(), {ColorBy::level, false});
  // Faces with T-nodes are polygons, so loading splits every face into quads
  // once: one centre per face and one midpoint per edge are added.
  const LoadResult back = load_garment(path.string());
  EXPECT_EQ(back.warnings.size(), 1u);
  EXPECT_EQ(back.mesh.n_vertices(), mesh.n_vertices() + mesh.n_faces() + mesh.n_edges());
  for (auto v : mesh.vertices()) EXPECT_EQ(mesh.point(v), back.mesh.point(back.mesh.vertex_handle(v.idx())));
}

// A file cut short anywhere (a copy or disk that stopped midway) is refused:
// before, a cut after the vertex and face layers loaded as a coarse garment
// without its hierarchy, and one in the UVs with zeros for the lost ones.
TEST(SaveLoad, AnOmFileCutShortAnywhereIsRefused) {
  QuadMesh mesh = refined_tube();
  std::vector<RecordUV> uvs(quadtree(mesh).size());
  for (std::size_t r = 0; r < uvs.size(); ++r)
    for (int k = 0; k < 4; ++k) uvs[r].corner[static_cast<std::size_t>(k)] = OpenMesh::Vec2d(0.01 * r, 0.25 * k);
  set_record_uvs(mesh, uvs);
  const fs::path whole = temp_dir() / "whole.om", cut = temp_dir() / "cut.om";
  save_mesh(mesh, whole.string());
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1000u);
  ASSERT_TRUE(has_texture_coords(load_garment(whole.string()).mesh));

  // Every byte of the first and last 300 (the header, the forest's last
  // records) and every 37th between (every layer's chunk).
  std::vector<std::size_t> lengths;
  for (std::size_t n = 0; n < bytes.size(); n += (n < 300 || n + 300 > bytes.size()) ? 1 : 37) lengths.push_back(n);
  std::size_t refused = 0;
  for (const std::size_t n : lengths) {
    std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(n));
    try {
      load_garment(cut.string());
      ADD_FAILURE() << "the first " << n << " of " << bytes.size() << " bytes loaded";
    } catch (const InputError& error) {
      ++refused;
      EXPECT_NE(std::string(error.what()).find(cut.string()), std::string::npos) << error.what();
    }
  }
  EXPECT_EQ(refused, lengths.size());
}

// A byte changed anywhere (one at a time, each flipped) is refused by the
// checksum save_mesh writes, before OpenMesh's reader sees the file (it
// asserted, aborting the host, on some; others loaded as another mesh).
// Only a flip inside the checksum layer's own name hides it: the mesh then
// loads whole. A file saved without the checksum layer (before it was
// made) still loads.
TEST(SaveLoad, AnOmFileWithAnyByteChangedIsRefused) {
  const QuadMesh mesh = refined_tube();
  const fs::path whole = temp_dir() / "checked.om", flipped = temp_dir() / "flipped.om";
  save_mesh(mesh, whole.string());
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t name = bytes.find(layer::checksum);
  ASSERT_NE(name, std::string::npos);
  std::size_t refused = 0;
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    std::string changed = bytes;
    changed[k] = static_cast<char>(changed[k] ^ 0xff);
    std::ofstream(flipped, std::ios::binary | std::ios::trunc).write(changed.data(), static_cast<std::streamsize>(changed.size()));
    try {
      const QuadMesh back = load_garment(flipped.string()).mesh;
      const bool in_name = k >= name && k < name + std::string(layer::checksum).size();
      EXPECT_TRUE(in_name) << "byte " << k << " of " << bytes.size() << " flipped loaded";
      EXPECT_EQ(back.n_vertices(), mesh.n_vertices());
    } catch (const InputError& error) {
      ++refused;
    }
  }
  EXPECT_GE(refused + std::string(layer::checksum).size(), bytes.size());

  QuadMesh unchecked = copy_mesh(mesh);
  OpenMesh::MPropHandleT<std::uint64_t> handle;
  ASSERT_TRUE(unchecked.get_property_handle(handle, layer::checksum));
  unchecked.remove_property(handle);
  const fs::path old = temp_dir() / "without_checksum.om";
  save_mesh(unchecked, old.string());
  EXPECT_EQ(load_garment(old.string()).mesh.n_vertices(), mesh.n_vertices());

  // Such a file damaged in the layers later steps index by is refused by
  // name (a parents pair out of range crashed objectInfo).
  const Layers layers = get_layers(unchecked);
  const auto vertex = unchecked.vertex_handle(3);
  const auto expect_refused = [&](const std::string& said) {
    save_mesh(unchecked, old.string());
    try {
      load_garment(old.string());
      ADD_FAILURE() << "loaded; expected: " << said;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(said), std::string::npos) << error.what();
    }
  };
  unchecked.property(layers.parents, vertex) = OpenMesh::Vec2i(5, 99999);
  expect_refused("vertex 3 names edge ends 5, 99999");
  unchecked.property(layers.parents, vertex) = OpenMesh::Vec2i(-1, -1);
  unchecked.property(layers.mode, vertex) = 5000;
  expect_refused("vertex 3 has mode 5000");
  unchecked.property(layers.mode, vertex) = 2;
  set_computed_layer(unchecked, std::vector<int>(unchecked.n_vertices(), 1));
  // set_computed_layer refuses -2: written into the layer directly.
  OpenMesh::VPropHandleT<int> computed_layer;
  ASSERT_TRUE(unchecked.get_property_handle(computed_layer, layer::computed_mode));
  unchecked.property(computed_layer, vertex) = -2;
  expect_refused("vertex 3 has computed mode -2");
}

/// Every proper prefix of `bytes` written to `cut` and loaded: the lengths that were not refused.
std::vector<std::size_t> prefixes_loaded(const std::string& bytes, const fs::path& cut) {
  std::vector<std::size_t> loaded;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(n));
    try {
      load_garment(cut.string());
      loaded.push_back(n);
    } catch (const InputError&) {
    }
  }
  return loaded;
}

/// `bytes` written to `path`.
void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// The InputError loading `bytes` (written to `path`) gives, or "loaded".
std::string load_error(const fs::path& path, const std::string& bytes) {
  write_bytes(path, bytes);
  try {
    load_garment(path.string());
  } catch (const InputError& error) {
    return error.what();
  }
  return "loaded";
}

/// A 3 x 2 quad grid in the OM format before 2.0 (OpenMesh 7 and older
/// wrote it: faces as vertex indices, the edges made while reading), as
/// bytes: the header counting `header_edges` edges (the grid has 17), the
/// positions, the faces (with `one_face_reversed`, face 1 wound the other
/// way), and with `layers` a face and an edge layer of ints.
std::string old_format_om_file(std::uint32_t header_edges, bool layers, bool one_face_reversed = false) {
  std::string bytes = "OMQ";
  const auto put = [&](auto value) { bytes.append(reinterpret_cast<const char*>(&value), sizeof(value)); };
  put(static_cast<std::uint8_t>((1 << 5) | 2));  // version 1.2
  put(std::uint32_t{12});
  put(std::uint32_t{6});
  put(header_edges);
  put(std::uint16_t{0x1400});  // vertex positions: 3 floats
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      put(0.1f * static_cast<float>(x));
      put(0.1f * static_cast<float>(y));
      put(0.0f);
    }
  put(std::uint16_t{0x80e8});  // face topology: 32-bit vertex indices
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      const std::int32_t a = 4 * y + x;
      if (one_face_reversed && y == 0 && x == 1)
        for (const std::int32_t corner : {a, a + 4, a + 5, a + 1}) put(corner);
      else
        for (const std::int32_t corner : {a, a + 1, a + 5, a + 4}) put(corner);
    }
  if (layers) {
    // Named custom chunks: bit 1 named, bits 2-4 the element kind, 5-8 the type.
    for (const auto& [entity, name, count] : {std::tuple{2, "f:int", 6u}, std::tuple{4, "e:int", header_edges}}) {
      put(static_cast<std::uint16_t>((1 << 1) | (entity << 2) | (6 << 5)));
      bytes += static_cast<char>(std::string(name).size());
      bytes += name;
      put(static_cast<std::uint32_t>(4 * count));
      for (std::uint32_t k = 0; k < count; ++k) put(static_cast<std::int32_t>(k));
    }
  }
  return bytes;
}

// Files of the format before 2.0 load; their layers are sized by the
// header's counts, which the reader does not check against the edges the
// faces make (it asserted): a header that disagrees is refused.
TEST(SaveLoad, AnOldFormatOmFileLoadsAndItsEdgeCountIsChecked) {
  const fs::path path = temp_dir() / "old_format.om";
  for (const bool layers : {false, true}) {
    write_bytes(path, old_format_om_file(17, layers));
    const QuadMesh mesh = load_garment(path.string()).mesh;
    EXPECT_EQ(mesh.n_vertices(), 12u);
    EXPECT_EQ(mesh.n_faces(), 6u);
    EXPECT_EQ(mesh.n_edges(), 17u);
  }
  EXPECT_EQ(load_error(path, old_format_om_file(20, true)),
            path.string() + ": the file is damaged (its faces make 17 edges, its header counts 20 for the layers "
                            "stored with them); expected a whole .om file");
  // A face that cannot join the others: loading skips the faces from it
  // on, and the reader asserted on the face layer sized for all of them.
  EXPECT_EQ(load_error(path, old_format_om_file(17, true, true)),
            path.string() + ": the file is damaged (face 1 cannot join the faces before it, and the layers stored "
                            "with the faces count it); expected a whole .om file");
}

// Another program's .om (no mrcloth layers, no hierarchy: loaded as a coarse
// garment) cut short at any byte is refused too: OpenMesh 9's files end
// with a sentinel; and where the format is older, by the header's counts or
// the halfedge links, which OM files store as they are.
/// A tube written by OpenMesh's own writer, as another program would: no
/// mrcloth layers; with `rich`, also normals, colours, texture coordinates,
/// flags and a layer of each element kind.
std::string other_programs_om_file(bool rich) {
  const QuadMesh tube = test::make_tube(6, 3, 0.3, 0.5);
  OpenMesh::PolyMesh_ArrayKernelT<> plain;
  plain.request_vertex_normals();
  plain.request_vertex_colors();
  plain.request_vertex_texcoords2D();
  plain.request_face_normals();
  plain.request_face_colors();
  plain.request_vertex_status();
  plain.request_face_status();
  plain.request_edge_status();
  plain.request_halfedge_status();
  for (const auto v : tube.vertices()) {
    const auto& p = tube.point(v);
    plain.add_vertex(OpenMesh::Vec3f(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])));
  }
  for (const auto f : tube.faces()) {
    std::vector<OpenMesh::VertexHandle> corners;
    for (const auto v : tube.fv_range(f)) corners.emplace_back(v.idx());
    plain.add_face(corners);
  }
  OpenMesh::IO::Options options = OpenMesh::IO::Options::Binary;
  if (rich) {
    plain.update_normals();
    OpenMesh::VPropHandleT<int> vertex_layer;
    OpenMesh::FPropHandleT<double> face_layer;
    OpenMesh::EPropHandleT<float> edge_layer;
    OpenMesh::HPropHandleT<bool> halfedge_layer;
    OpenMesh::MPropHandleT<int> mesh_layer;
    plain.add_property(vertex_layer, "v:int");
    plain.add_property(face_layer, "f:double");
    plain.add_property(edge_layer, "e:float");
    plain.add_property(halfedge_layer, "h:bool");
    plain.add_property(mesh_layer, "m:int");
    plain.property(vertex_layer).set_persistent(true);
    plain.property(face_layer).set_persistent(true);
    plain.property(edge_layer).set_persistent(true);
    plain.property(halfedge_layer).set_persistent(true);
    plain.mproperty(mesh_layer).set_persistent(true);
    for (const auto v : plain.vertices()) plain.property(vertex_layer, v) = v.idx();
    for (const auto h : plain.halfedges()) plain.property(halfedge_layer, h) = h.idx() % 3 == 0;
    options += OpenMesh::IO::Options::VertexNormal;
    options += OpenMesh::IO::Options::VertexColor;
    options += OpenMesh::IO::Options::VertexTexCoord;
    options += OpenMesh::IO::Options::FaceNormal;
    options += OpenMesh::IO::Options::FaceColor;
    options += OpenMesh::IO::Options::Status;
  }
  const fs::path path = temp_dir() / (rich ? "other_rich.om" : "other_plain.om");
  EXPECT_TRUE(OpenMesh::IO::write_mesh(plain, path.string(), options));
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.find("mrcloth:"), std::string::npos);
  EXPECT_EQ(load_garment(path.string()).mesh.n_faces(), tube.n_faces());
  return bytes;
}

// Another program's .om (no mrcloth layers, no hierarchy: loaded as a coarse
// garment) cut short at any byte is refused too: OpenMesh 9's files end
// with a sentinel; and where the format is older, by the header's counts or
// the halfedge links, which OM files store as they are.
TEST(SaveLoad, AnotherProgramsOmFileCutShortIsRefused) {
  for (const bool rich : {false, true}) {
    const std::string bytes = other_programs_om_file(rich);
    const std::vector<std::size_t> loaded = prefixes_loaded(bytes, temp_dir() / "other_cut.om");
    for (const std::size_t n : loaded) ADD_FAILURE() << "the first " << n << " of " << bytes.size() << " bytes loaded";
  }
}

// The first damage the walk meets is named by its chunk's byte offset.
TEST(SaveLoad, AnOmFileDamagedInsideNamesTheChunk) {
  const std::string bytes = other_programs_om_file(false);
  const fs::path path = temp_dir() / "named.om";
  const auto message = [&](const std::string& changed) { return load_error(path, changed); };
  // The positions' chunk follows the 16-byte header; its dimensions are
  // bits 11-13 of its 16-bit header (OpenMesh's reader asserted on 2).
  std::string two_dimensional = bytes;
  two_dimensional[17] = static_cast<char>((static_cast<unsigned char>(bytes[17]) & ~0x38u) | 0x08u);
  EXPECT_EQ(message(two_dimensional), path.string() + ": the file is cut short or damaged (the chunk at byte 16 stores "
                                                      "vertex positions of 2 components; expected 3); expected a whole "
                                                      ".om file");
  // Face corners' texture coordinates (a halfedge chunk) of one
  // dimension: OpenMesh 9 asserts two, and reads two floats each whatever
  // the header says.
  const std::size_t edges = *reinterpret_cast<const std::uint32_t*>(bytes.data() + 12);
  const std::uint16_t corner_uvs = (6 << 2) | (2 << 5) | (1 << 10);
  std::string one_dimensional = bytes.substr(0, bytes.size() - 2);
  one_dimensional.append(reinterpret_cast<const char*>(&corner_uvs), 2);
  one_dimensional.append(std::string(2 * edges * 8, '\0'));
  one_dimensional += bytes.substr(bytes.size() - 2);
  EXPECT_EQ(message(one_dimensional), path.string() + ": the file is cut short or damaged (the chunk at byte " +
                                          std::to_string(bytes.size() - 2) + " stores halfedge texture coordinates "
                                          "of 1 components; expected 2); expected a whole .om file");
  // Bytes after the closing chunk.
  EXPECT_EQ(message(bytes + "xyz"), path.string() + ": the file is cut short or damaged (the chunk at byte " +
                                        std::to_string(bytes.size() - 2) +
                                        " closes the file, but 3 bytes follow it); expected a whole .om file");
}

// A .om file without the checksum (another program's, or one save_mesh
// wrote before it had one) with any byte changed loads as some mesh or is
// refused with an InputError naming the file: OpenMesh's reader asserted
// (aborting the host), wrote out of bounds, or read billions of halfedges
// past the end on 1-2 % of such files (check_om_structure now walks the
// chunks first). Each byte is changed three ways: all bits, the lowest, the
// highest.
TEST(SaveLoad, AnOmFileWithoutChecksumWithAnyByteChangedLoadsOrIsRefused) {
  QuadMesh unchecked = refined_tube();
  OpenMesh::MPropHandleT<std::uint64_t> handle;
  ASSERT_TRUE(unchecked.get_property_handle(handle, layer::checksum));
  unchecked.remove_property(handle);
  const fs::path saved = temp_dir() / "unchecked.om";
  save_mesh(unchecked, saved.string());
  std::ifstream in(saved, std::ios::binary);
  const std::string ours((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  const fs::path changed_path = temp_dir() / "changed.om";
  for (const std::string& bytes : {other_programs_om_file(false), other_programs_om_file(true), ours,
                                   old_format_om_file(17, true)}) {
    std::size_t refused = 0, loaded = 0;
    for (std::size_t k = 0; k < bytes.size(); ++k) {
      for (const unsigned mask : {0xffu, 0x01u, 0x80u}) {
        std::string changed = bytes;
        changed[k] = static_cast<char>(static_cast<unsigned char>(changed[k]) ^ mask);
        std::ofstream(changed_path, std::ios::binary | std::ios::trunc)
            .write(changed.data(), static_cast<std::streamsize>(changed.size()));
        try {
          load_garment(changed_path.string());
          ++loaded;
        } catch (const InputError& error) {
          ++refused;
          EXPECT_EQ(std::string(error.what()).rfind(changed_path.string(), 0), 0u) << error.what();
        }
      }
    }
    EXPECT_EQ(loaded + refused, 3 * bytes.size());
    EXPECT_GT(refused, bytes.size() / 4) << "the chunk frames and links should refuse many";
  }
}

}  // namespace
}  // namespace mrcloth
