#include "om_structure.h"
#include "errors.h"
#include "little_endian.h"
#include "quad_mesh.h"
#include "texture_coords.h"
#include <OpenMesh/Core/IO/OMFormat.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <cstdint>
#include <set>
#include <vector>

namespace mrcloth {
namespace {

namespace om = OpenMesh::IO::OMFormat;
using Chunk = om::Chunk;

/// Reads the file's bytes in the reader's order (little-endian, as OpenMesh
/// writes on every machine mrcloth runs on) and refuses, by byte offset,
/// what the reader could not read safely.
class OmWalk {
 public:
  OmWalk(const std::string& path, const std::string& bytes) : path_(path), bytes_(bytes) {}

  [[noreturn]] void refuse(const std::string& what) const {
    throw InputError(path_ + ": the file is cut short or damaged (the chunk at byte " + std::to_string(chunk_at_) +
                     " " + what + "); expected a whole .om file");
  }

  void start_chunk() { chunk_at_ = at_; }
  std::size_t left() const { return bytes_.size() - at_; }

  /// Moves past `count` elements of `size` bytes each, all of which must be in the file.
  void skip(std::uint64_t count, std::uint64_t size, const char* what) {
    if (size != 0 && count > left() / size)
      refuse(std::string("needs ") + std::to_string(count) + " " + what + " of " + std::to_string(size) +
             " bytes, past the file's end");
    at_ += static_cast<std::size_t>(count * size);
  }

  std::uint64_t read_unsigned(std::size_t width, const char* what) {
    if (left() < width) refuse(std::string("is cut off in its ") + what);
    const std::uint64_t value = little_endian_at(bytes_, at_, width);
    at_ += width;
    return value;
  }

  /// A signed integer of `width` bytes as the reader restores one into an int.
  std::int64_t read_signed(std::size_t width, const char* what) {
    const std::uint64_t raw = read_unsigned(width, what);
    const int shift = static_cast<int>(64 - 8 * width);
    const auto extended = static_cast<std::int64_t>(raw << shift) >> shift;
    return static_cast<std::int32_t>(extended);  // the reader's int keeps the low 32 bits
  }

  /// A property or type name: a length byte, then the text.
  std::string read_name(const char* what) {
    const std::size_t length = read_unsigned(1, what);
    if (left() < length) refuse(std::string("is cut off in its ") + what);
    std::string name = bytes_.substr(at_, length);
    at_ += length;
    return name;
  }

 private:
  const std::string& path_;
  const std::string& bytes_;
  std::size_t at_ = 0;
  std::size_t chunk_at_ = 0;
};

/// Bytes in one stored integer of a topology chunk (its header's bits field).
std::size_t integer_width(const Chunk::Header& header) { return std::size_t{1} << header.bits_; }

const char* entity_name(unsigned entity) {
  switch (entity) {
    case Chunk::Entity_Vertex: return "vertex";
    case Chunk::Entity_Face: return "face";
    case Chunk::Entity_Edge: return "edge";
    case Chunk::Entity_Halfedge: return "halfedge";
    default: return "mesh";
  }
}

/// What the walk has seen so far.
struct Made {
  bool vertices = false;  ///< the position chunk (adds the vertices)
  bool faces = false;     ///< the face topology chunk (adds the faces)
  bool edges = false;     ///< the halfedge topology chunk, or the faces of an older format
  bool element_layers = false;  ///< a stored face, edge or halfedge layer
  std::vector<std::vector<std::uint64_t>> old_faces;  ///< an older format's faces, by vertex index
};

/// mrcloth's list layers (a count, then the records): OpenMesh's reader
/// asserts when their stored size does not match what they hold.
std::size_t list_record_size(const std::string& name) {
  if (name == layer::quadtree) return OpenMesh::IO::binary<QuadRecord>::size_of();
  if (name == layer::record_uvs) return OpenMesh::IO::binary<RecordUV>::size_of();
  return 0;
}

/// A stored layer: (in formats from 2.2) its type's name, its block size,
/// then the block. `name` is the chunk's property name (the reader keeps the
/// last one read for an unnamed chunk).
void walk_layer(OmWalk& walk, const om::Header& header, const Chunk::Header& chunk, const std::string& name) {
  if (header.version_ > om::mk_version(2, 1)) walk.read_name("layer type name");
  const std::uint64_t block = walk.read_unsigned(4, "layer size");
  if (chunk.entity_ == Chunk::Entity_Mesh) {
    if (const std::size_t record = list_record_size(name); record != 0) {
      if (block < 4) walk.refuse("holds the layer '" + name + "' without its record count");
      const std::uint64_t count = walk.read_unsigned(4, "layer's record count");
      if (block != 4 + count * record)
        walk.refuse("holds the layer '" + name + "' with " + std::to_string(count) + " records in " +
                    std::to_string(block) + " bytes; expected " + std::to_string(4 + count * record));
      walk.skip(count, record, "records");
      return;
    }
  }
  walk.skip(1, block, "bytes of a layer");
}

/// A chunk of vertex, face, edge or halfedge data of a built-in kind whose
/// shape the reader asserts.
void require_dimensions(OmWalk& walk, const Chunk::Header& chunk, std::size_t dimensions, const char* kind) {
  if (om::dimensions(chunk) != dimensions)
    walk.refuse(std::string("stores ") + entity_name(chunk.entity_) + " " + kind + " of " +
                std::to_string(om::dimensions(chunk)) + " components; expected " + std::to_string(dimensions));
}

/// Positions and normals: floats or doubles, three each.
void walk_vectors(OmWalk& walk, const Chunk::Header& chunk, std::uint64_t count, const char* kind) {
  const bool floats = chunk.bits_ == om::bits(0.0f), doubles = chunk.bits_ == om::bits(0.0);
  if (!floats && !doubles)
    walk.refuse(std::string("stores ") + entity_name(chunk.entity_) + " " + kind +
                " that are neither floats nor doubles");
  require_dimensions(walk, chunk, 3, kind);
  walk.skip(count, floats ? 12 : 24, kind);
}

void walk_vertex_chunk(OmWalk& walk, const om::Header& header, const Chunk::Header& chunk, const std::string& name,
                       Made& made) {
  const std::uint64_t n = header.n_vertices_;
  if (chunk.type_ == Chunk::Type_Pos) {
    if (made.vertices) walk.refuse("adds the vertices a second time");
    walk_vectors(walk, chunk, n, "positions");
    made.vertices = true;
    return;
  }
  if (!made.vertices) walk.refuse("fills vertices before the chunk that adds them");
  switch (chunk.type_) {
    case Chunk::Type_Normal: walk_vectors(walk, chunk, n, "normals"); return;
    case Chunk::Type_Texcoord: require_dimensions(walk, chunk, 2, "texture coordinates"); walk.skip(n, 8, "texture coordinates"); return;
    case Chunk::Type_Color: require_dimensions(walk, chunk, 3, "colours"); walk.skip(n, 3, "colours"); return;
    case Chunk::Type_Status: require_dimensions(walk, chunk, 1, "flags"); walk.skip(n, 4, "flags"); return;
    case Chunk::Type_Custom: walk_layer(walk, header, chunk, name); return;
    case Chunk::Type_Topology: walk.skip(n, integer_width(chunk), "halfedge indices"); return;
    default: walk.skip(n, om::vector_size(chunk), "values of an unknown kind"); return;
  }
}

/// The faces of a format before 2.0, stored as vertex indices (a 16-bit
/// corner count first in a polygon mesh).
void walk_old_faces(OmWalk& walk, const om::Header& header, const Chunk::Header& chunk, Made& made) {
  const std::size_t width = integer_width(chunk);
  const std::size_t corners = header.mesh_ == 'T' ? 3 : header.mesh_ == 'Q' ? 4 : 0;
  for (std::uint64_t f = 0; f < header.n_faces_; ++f) {
    const std::size_t n = header.mesh_ == 'P' ? walk.read_unsigned(2, "face's corner count") : corners;
    if (n > walk.left()) walk.refuse("needs more face corners than the file holds");
    std::vector<std::uint64_t>& face = made.old_faces.emplace_back();
    for (std::size_t k = 0; k < n; ++k) face.push_back(walk.read_unsigned(width, "face corners"));
  }
}

void walk_face_chunk(OmWalk& walk, const om::Header& header, const Chunk::Header& chunk, const std::string& name,
                     Made& made) {
  const std::uint64_t n = header.n_faces_;
  if (chunk.type_ == Chunk::Type_Topology) {
    if (!made.vertices) walk.refuse("adds faces before the chunk that adds the vertices");
    if (made.faces) walk.refuse("adds the faces a second time");
    if (header.version_ < om::mk_version(2, 0)) {
      if (made.edges) walk.refuse("adds faces, whose corners make the edges, after a chunk added edges");
      walk_old_faces(walk, header, chunk, made);
      made.edges = true;  // the faces make them
    } else {
      walk.skip(n, integer_width(chunk), "halfedge indices");
    }
    made.faces = true;
    return;
  }
  if (!made.faces) walk.refuse("fills faces before the chunk that adds them");
  made.element_layers = made.element_layers || chunk.type_ == Chunk::Type_Custom;
  switch (chunk.type_) {
    case Chunk::Type_Normal: walk_vectors(walk, chunk, n, "normals"); return;
    case Chunk::Type_Color: require_dimensions(walk, chunk, 3, "colours"); walk.skip(n, 3, "colours"); return;
    case Chunk::Type_Status: require_dimensions(walk, chunk, 1, "flags"); walk.skip(n, 4, "flags"); return;
    case Chunk::Type_Custom: walk_layer(walk, header, chunk, name); return;
    default: walk.skip(n, om::vector_size(chunk), "values of an unknown kind"); return;
  }
}

/// Edges and halfedges: the halfedge topology chunk adds the edges, then
/// links each halfedge to its next one (the reader writes the next one's
/// previous link through the stored index, so it must be in range).
void walk_edge_chunk(OmWalk& walk, const om::Header& header, const Chunk::Header& chunk, const std::string& name,
                     Made& made) {
  const bool halfedges = chunk.entity_ == Chunk::Entity_Halfedge;
  const std::uint64_t edges = header.n_edges_, n = halfedges ? 2 * edges : edges;
  if (halfedges && chunk.type_ == Chunk::Type_Topology) {
    if (made.edges) walk.refuse("adds the edges a second time");
    const std::size_t width = integer_width(chunk);
    if (edges > walk.left() / (6 * width)) walk.refuse("needs more halfedges than the file holds");
    for (std::uint64_t e = 0; e < 2 * edges; ++e) {
      const std::int64_t next = walk.read_signed(width, "halfedge links");
      walk.read_signed(width, "halfedge links");  // the vertex it points to
      walk.read_signed(width, "halfedge links");  // its face
      if (next < 0 || static_cast<std::uint64_t>(next) >= 2 * edges)
        walk.refuse("links halfedge " + std::to_string(e) + " to halfedge " + std::to_string(next) + "; the file has " +
                    std::to_string(2 * edges));
    }
    made.edges = true;
    return;
  }
  if (!made.edges) walk.refuse(std::string("fills ") + entity_name(chunk.entity_) + "s before the chunk that adds them");
  made.element_layers = made.element_layers || chunk.type_ == Chunk::Type_Custom;
  // OpenMesh 9 reads a halfedge's (a face corner's) texture coordinates as
  // two floats whatever the header says, and asserts two dimensions.
  if (halfedges && chunk.type_ == Chunk::Type_Texcoord) {
    require_dimensions(walk, chunk, 2, "texture coordinates");
    walk.skip(n, 8, "texture coordinates");
    return;
  }
  switch (chunk.type_) {
    case Chunk::Type_Status: require_dimensions(walk, chunk, 1, "flags"); walk.skip(n, 4, "flags"); return;
    case Chunk::Type_Custom: walk_layer(walk, header, chunk, name); return;
    default: walk.skip(n, om::vector_size(chunk), "values of an unknown kind"); return;
  }
}

/// In a format before 2.0 the faces make the edges while OpenMesh reads;
/// its stored layers are sized by the header's counts, and the reader
/// asserts where the mesh it made differs: a face that cannot join the
/// others (loading skips the faces from it on), or other edges. Checked by
/// making the faces here, as the loader will.
void check_old_counts(const std::string& path, const om::Header& header, const Made& made) {
  const auto damaged = [&](const std::string& what) {
    throw InputError(path + ": the file is damaged (" + what + "); expected a whole .om file");
  };
  OpenMesh::PolyMesh_ArrayKernelT<> mesh;
  for (std::uint32_t v = 0; v < header.n_vertices_; ++v) mesh.add_vertex(OpenMesh::Vec3f(0.0f, 0.0f, 0.0f));
  for (std::size_t f = 0; f < made.old_faces.size(); ++f) {
    const auto& face = made.old_faces[f];
    std::vector<OpenMesh::VertexHandle> corners;
    for (const std::uint64_t corner : face) {
      if (corner >= header.n_vertices_) break;
      corners.emplace_back(static_cast<int>(corner));
    }
    const std::set<OpenMesh::VertexHandle> distinct(corners.begin(), corners.end());
    if (corners.size() != face.size() || corners.size() < 3 || distinct.size() != corners.size() ||
        !mesh.add_face(corners).is_valid())
      damaged("face " + std::to_string(f) + " cannot join the faces before it, and the layers stored with the faces "
              "count it");
  }
  if (mesh.n_edges() != header.n_edges_)
    damaged("its faces make " + std::to_string(mesh.n_edges()) + " edges, its header counts " +
            std::to_string(header.n_edges_) + " for the layers stored with them");
}

}  // namespace

void check_om_structure(const std::string& path, const std::string& bytes) {
  if (bytes.size() < 16 || bytes.compare(0, 2, "OM") != 0) return;  // the reader refuses it
  OmWalk walk(path, bytes);
  om::Header header;
  header.magic_[0] = 'O';
  header.magic_[1] = 'M';
  walk.read_unsigned(2, "magic");
  header.mesh_ = static_cast<unsigned char>(walk.read_unsigned(1, "mesh kind"));
  header.version_ = static_cast<om::uint8>(walk.read_unsigned(1, "version"));
  header.n_vertices_ = static_cast<om::uint32>(walk.read_unsigned(4, "vertex count"));
  header.n_faces_ = static_cast<om::uint32>(walk.read_unsigned(4, "face count"));
  header.n_edges_ = static_cast<om::uint32>(walk.read_unsigned(4, "edge count"));
  if (header.version_ > om::mk_version(2, 2)) return;  // newer than OpenMesh 9: its reader refuses it

  const bool needs_closing_chunk =
      header.version_ >= om::mk_version(2, 2) || bytes.find("mrcloth:") != std::string::npos;
  Made made;
  std::string name;  // the reader's last property name
  while (walk.left() > 0) {
    walk.start_chunk();
    Chunk::Header chunk;
    chunk << static_cast<om::uint16>(walk.read_unsigned(2, "header"));
    if (chunk.name_) name = walk.read_name("property name");
    switch (chunk.entity_) {
      case Chunk::Entity_Sentinel:
        if (walk.left() != 0) walk.refuse("closes the file, but " + std::to_string(walk.left()) + " bytes follow it");
        if (!made.element_layers || header.version_ >= om::mk_version(2, 0)) return;
        check_old_counts(path, header, made);
        return;
      case Chunk::Entity_Vertex: walk_vertex_chunk(walk, header, chunk, name, made); break;
      case Chunk::Entity_Face: walk_face_chunk(walk, header, chunk, name, made); break;
      case Chunk::Entity_Edge:
      case Chunk::Entity_Halfedge: walk_edge_chunk(walk, header, chunk, name, made); break;
      case Chunk::Entity_Mesh:
        if (chunk.type_ == Chunk::Type_Custom) walk_layer(walk, header, chunk, name);
        else walk.skip(1, om::vector_size(chunk), "values of an unknown kind");
        break;
      default: walk.refuse("is of no element kind the format knows (" + std::to_string(chunk.entity_) + ")");
    }
  }
  walk.start_chunk();
  if (needs_closing_chunk) walk.refuse("should close the file, as OpenMesh's writer closes one, but the file ends there");
  if (made.element_layers && header.version_ < om::mk_version(2, 0)) check_old_counts(path, header, made);
}

}  // namespace mrcloth
