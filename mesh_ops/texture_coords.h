#pragma once
// Texture coordinates (UVs) carried from a garment's file through every
// refinement to every surface written, so a simulated garment exported to a
// DCC tool keeps its textures. They are stored per quadtree record corner,
// not per vertex: a vertex on a UV seam has one UV per side, and a record's
// corners are always on one side. A child record's corner UVs are the
// parent's bilinear interpolation at the child's corners (corners, edge
// midpoints, the centre), as its positions were at rest, so any level of
// refinement and any T-node (the midpoint of its coarse edge) reads the
// texture exactly where the coarse garment had it.
#include "quad_mesh.h"

#include <array>
#include <vector>

namespace mrcloth {

/// The UVs of one quadtree record's four corners, in its corner order.
struct RecordUV {
  std::array<OpenMesh::Vec2d, 4> corner;
};

namespace layer {
inline constexpr const char* record_uvs = "mrcloth:record_uvs";  ///< mesh std::vector<RecordUV>: per record, or empty
}  // namespace layer

/// Whether the mesh has texture coordinates: one RecordUV per quadtree record.
bool has_texture_coords(const QuadMesh& mesh);

/// The per-record UVs (empty when the mesh has none).
const std::vector<RecordUV>& record_uvs(const QuadMesh& mesh);

/// Sets the per-record UVs (one per record of the forest; empty removes
/// them), persistent so they are saved in `.om` files. Throws
/// ArgumentError for a count that is neither 0 nor the forest's size.
void set_record_uvs(QuadMesh& mesh, std::vector<RecordUV> uvs);

/// Creates the (empty) property if missing: the `.om` reader fills only
/// properties that exist before it reads.
void ensure_record_uvs(QuadMesh& mesh);

/// After record `parent` split into `children` (child k holds the parent's
/// corner k, QuadRefiner::split): appends the children's UVs, each the
/// parent's bilinear interpolation at the child's corners. No-op for a mesh
/// without texture coordinates.
void split_record_uvs(QuadMesh& mesh, int parent, const std::array<int, 4>& children);

/// Per active face (face order), the UVs at its vertices (in the face's own
/// order, as f.vertices() visits them and active_face_polygons lists them),
/// each T-node at its place along its record's edge. Empty when the mesh
/// has no texture coordinates.
std::vector<std::vector<OpenMesh::Vec2d>> active_face_uvs(const QuadMesh& mesh);

}  // namespace mrcloth

// Storing RecordUV in .om files.
#include <OpenMesh/Core/IO/SR_store.hh>
namespace OpenMesh::IO {
template <>
struct binary<mrcloth::RecordUV> {
  using value_type = mrcloth::RecordUV;
  static const bool is_streamable = true;
  static constexpr std::size_t kDoubles = 8;
  static size_t size_of() { return kDoubles * sizeof(double); }
  static size_t size_of(const value_type&) { return size_of(); }
  static std::string type_identifier() { return "mrcloth::RecordUV"; }
  static size_t store(std::ostream& os, const value_type& v, bool swap = false);
  static size_t restore(std::istream& is, value_type& v, bool swap = false);
};
}  // namespace OpenMesh::IO
