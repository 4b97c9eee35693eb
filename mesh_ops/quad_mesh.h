#pragma once
// The refinable quad mesh: an OpenMesh polygon mesh in double precision whose
// faces are the *active* surface, plus the quadtree records that remember how
// it was refined. All per-element data lives in named, persistent OpenMesh
// properties with the `mrcloth:` prefix, so a `.om` file keeps all of it.
//
// Invariants (checked by tests):
//  - every face is an active quadtree record; its polygon is the record's four
//    corners with any hanging vertices inserted on its edges, so the surface
//    is watertight;
//  - vertices are never deleted or reordered: the coarse vertices keep
//    indices 0..N-1 through every refinement;
//  - a hanging vertex lies exactly at the midpoint of its two parents.
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <array>
#include <cstdint>
#include <vector>

namespace mrcloth {

struct QuadMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
  FaceAttributes(OpenMesh::Attributes::Status);
};

/// Positions in metres, double precision.
using QuadMesh = OpenMesh::PolyMesh_ArrayKernelT<QuadMeshTraits>;

/// One node of the quadtree forest (one tree per coarse face). All fields are
/// 32-bit integers so the record stores densely in `.om` files.
struct QuadRecord {
  std::int32_t level = 1;                   ///< refinement level, coarse = 1
  std::int32_t active = 1;                  ///< 1 if the record is a face of the mesh now
  std::int32_t parent = -1;                 ///< parent record index, -1 for a root
  std::array<std::int32_t, 4> children{-1, -1, -1, -1};  ///< child i holds corner i
  std::array<std::int32_t, 4> corners{-1, -1, -1, -1};   ///< vertex indices, face orientation
};

/// Property names; every one is created persistent by `ensure_layers`.
namespace layer {
inline constexpr const char* mode = "mrcloth:mode";          ///< vertex int: deformation mode (1 = least)
inline constexpr const char* r_value = "mrcloth:r";          ///< vertex double: R of Algorithms 2-3
inline constexpr const char* hanging = "mrcloth:hanging";    ///< vertex bool: T-node on an active edge
inline constexpr const char* parents = "mrcloth:parents";    ///< vertex Vec2i: edge end points of a midpoint, else (-1,-1)
inline constexpr const char* level = "mrcloth:level";        ///< face int: refinement level, coarse = 1
inline constexpr const char* quad = "mrcloth:quad";          ///< face int: index of the face's quadtree record
inline constexpr const char* quadtree = "mrcloth:quadtree";  ///< mesh std::vector<QuadRecord>: the forest
/// mesh std::uint64_t: in a .om file save_mesh wrote, the FNV-1a hash of the
/// file's bytes with these eight taken as zero (load_garment checks it)
inline constexpr const char* checksum = "mrcloth:checksum";
}  // namespace layer

/// The default mode of a vertex nobody has painted: the lowest mode.
inline constexpr int kDefaultMode = 1;

/// Handles to every mrcloth layer of one mesh.
struct Layers {
  OpenMesh::VPropHandleT<int> mode;
  OpenMesh::VPropHandleT<double> r_value;
  OpenMesh::VPropHandleT<bool> hanging;
  OpenMesh::VPropHandleT<OpenMesh::Vec2i> parents;
  OpenMesh::FPropHandleT<int> level;
  OpenMesh::FPropHandleT<int> quad;
  OpenMesh::MPropHandleT<std::vector<QuadRecord>> quadtree;
};

/// Creates any missing mrcloth layer (persistent, with defaults for existing
/// vertices: mode 1, r 0, not hanging, no parents) and returns all handles.
Layers ensure_layers(QuadMesh& mesh);

/// The handles of a mesh that already has every layer; throws ArgumentError otherwise.
Layers get_layers(const QuadMesh& mesh);

/// The quadtree forest of a mesh (read access).
const std::vector<QuadRecord>& quadtree(const QuadMesh& mesh);

/// Number of coarse (level-1) records: the vertices 0..n-1 of those roots are the coarse mesh.
std::size_t count_roots(const QuadMesh& mesh);

/// Active faces per level: element L is the number of active faces of level L (element 0 unused).
std::vector<std::size_t> faces_per_level(const QuadMesh& mesh);

/// Vertices per level: element L counts vertices created at level L (coarse vertices at 1).
/// A vertex's level is that of the face whose refinement created it.
std::vector<std::size_t> vertices_per_level(const QuadMesh& mesh);

/// Number of vertices flagged hanging.
std::size_t count_hanging(const QuadMesh& mesh);

/// Every active face as its polygon of vertex indices (hanging vertices
/// included), in face order: for OBJ sequences and previews.
std::vector<std::vector<int>> active_face_polygons(const QuadMesh& mesh);

/// A deep copy including every property (OpenMesh's assignment copies properties).
QuadMesh copy_mesh(const QuadMesh& mesh);

}  // namespace mrcloth

// Storing QuadRecord in .om files.
#include <OpenMesh/Core/IO/SR_store.hh>
namespace OpenMesh::IO {
template <>
struct binary<mrcloth::QuadRecord> {
  using value_type = mrcloth::QuadRecord;
  static const bool is_streamable = true;
  static constexpr std::size_t kInts = 11;
  static size_t size_of() { return kInts * sizeof(std::int32_t); }
  static size_t size_of(const value_type&) { return size_of(); }
  static std::string type_identifier() { return "mrcloth::QuadRecord"; }
  static size_t store(std::ostream& os, const value_type& v, bool swap = false);
  static size_t restore(std::istream& is, value_type& v, bool swap = false);
};
}  // namespace OpenMesh::IO
