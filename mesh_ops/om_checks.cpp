#include "om_checks.h"

#include "errors.h"
#include "garment_formats.h"
#include "little_endian.h"
#include "mode_layer.h"
#include "mode_painting.h"
#include "quadtree_forest.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mrcloth {

void check_stored_forest(const std::string& path, const QuadMesh& mesh) {
  const std::vector<QuadRecord>& forest = quadtree(mesh);
  const auto n = static_cast<std::int32_t>(forest.size());
  const auto n_vertices = static_cast<std::int32_t>(mesh.n_vertices());
  std::size_t active = 0;
  const auto corrupt = [&](std::size_t r, const std::string& what) {
    throw InputError(with_path(path, "the stored refinement hierarchy is damaged (record " + std::to_string(r) + " " +
                                         what + "); expected a .om file as mrcloth writes it, whole"));
  };
  for (std::size_t r = 0; r < forest.size(); ++r) {
    const QuadRecord& record = forest[r];
    if (record.level < 1 || (record.active != 0 && record.active != 1)) corrupt(r, "has level or state out of range");
    if ((record.parent < 0) != (record.level == 1) || record.parent >= n ||
        (record.parent >= 0 && forest[static_cast<std::size_t>(record.parent)].level != record.level - 1))
      corrupt(r, "has a parent out of place");
    const bool leaf = record.children[0] < 0;
    for (const std::int32_t child : record.children) {
      if ((child < 0) != leaf || child >= n ||
          (child >= 0 && forest[static_cast<std::size_t>(child)].parent != static_cast<std::int32_t>(r)))
        corrupt(r, "has a child out of place");
    }
    for (const std::int32_t corner : record.corners)
      if (corner < 0 || corner >= n_vertices) corrupt(r, "has a corner that is not a vertex");
    active += record.active ? 1 : 0;
  }
  if (active != mesh.n_faces())
    throw InputError(with_path(path, "the stored refinement hierarchy is damaged (" + std::to_string(active) +
                                         " active records for " + std::to_string(mesh.n_faces()) +
                                         " faces); expected a .om file as mrcloth writes it, whole"));
  const Layers layers = get_layers(mesh);
  std::vector<char> named(forest.size(), 0);
  for (const auto f : mesh.faces()) {
    const int r = mesh.property(layers.quad, f);
    if (r < 0 || r >= n || !forest[static_cast<std::size_t>(r)].active || named[static_cast<std::size_t>(r)]++)
      throw InputError(with_path(path, "the stored refinement hierarchy is damaged (" + face_label(f.idx()) +
                                           " names no active record, or one an earlier face names); expected a .om "
                                           "file as mrcloth writes it, whole"));
  }
  // The vertex layers later steps index by (a file saved before the
  // checksum, damaged inside, crashed objectInfo through them); eraseModes
  // copies the computed modes into the mode layer.
  OpenMesh::VPropHandleT<int> computed;
  const bool has_computed = mesh.get_property_handle(computed, layer::computed_mode);
  for (const auto v : mesh.vertices()) {
    const OpenMesh::Vec2i ends = mesh.property(layers.parents, v);
    const bool none = ends[0] == -1 && ends[1] == -1;
    // Refinement appends each midpoint after the ends of its edge: parents
    // with a larger index would be a cycle, which the polygons recurse along.
    const bool valid = ends[0] >= 0 && ends[0] < v.idx() && ends[1] >= 0 && ends[1] < v.idx() && ends[0] != ends[1];
    const int mode = mesh.property(layers.mode, v);
    const int computed_mode = has_computed ? mesh.property(computed, v) : 0;
    if (computed_mode < 0 || computed_mode > kLargestMode)
      throw InputError(with_path(path, "the stored layers are damaged (vertex " + std::to_string(v.idx()) +
                                           " has computed mode " + std::to_string(computed_mode) +
                                           "); expected a .om file as mrcloth writes it, whole"));
    if ((!none && !valid) || mode < 0 || mode > kLargestMode)
      throw InputError(with_path(path, "the stored layers are damaged (vertex " + std::to_string(v.idx()) +
                                           (none || valid ? " has mode " + std::to_string(mode)
                                                          : " names edge ends " + std::to_string(ends[0]) + ", " +
                                                                std::to_string(ends[1])) +
                                           "); expected a .om file as mrcloth writes it, whole"));
  }
  if (const int face = first_face_unlike_its_record(mesh); face >= 0)
    throw InputError(with_path(path, "the stored refinement hierarchy is damaged (" + face_label(face) +
                                         " is not the polygon or level of its record); expected a .om file as "
                                         "mrcloth writes it, whole"));
}

ChecksumPlace checksum_place(const std::string& bytes) {
  const std::string name = layer::checksum;
  const std::size_t at = bytes.find(name);
  if (at == std::string::npos) return {};
  const ChecksumPlace damaged{true, true, 0};
  if (at == 0 || static_cast<unsigned char>(bytes[at - 1]) != name.size()) return damaged;
  const std::size_t type_at = at + name.size();
  if (type_at >= bytes.size()) return damaged;
  const std::size_t size_at = type_at + 1 + static_cast<unsigned char>(bytes[type_at]);
  if (size_at + 4 + 8 > bytes.size()) return damaged;
  return little_endian_at(bytes, size_at, 4) == 8 ? ChecksumPlace{true, false, size_at + 4} : damaged;
}

std::uint64_t file_checksum(const std::string& bytes, std::size_t skip) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    const unsigned char byte = (k >= skip && k < skip + 8) ? 0 : static_cast<unsigned char>(bytes[k]);
    hash = (hash ^ byte) * 1099511628211ull;
  }
  return hash;
}

void check_om_checksum(const std::string& path, const std::string& bytes) {
  const ChecksumPlace place = checksum_place(bytes);
  if (!place.present) return;
  const std::uint64_t stored = place.damaged ? 0 : little_endian_at(bytes, place.offset, 8);
  if (place.damaged || stored != file_checksum(bytes, place.offset))
    throw InputError(with_path(path, "the file is damaged or cut short (its bytes do not match the checksum mrcloth "
                                     "wrote into it); expected a .om file as mrcloth writes it, whole"));
}

void check_om_counts(const std::string& path, const std::string& bytes, const QuadMesh& mesh) {
  if (bytes.size() < 16 || bytes.compare(0, 2, "OM") != 0) return;  // the reader refused it already
  const auto count = [&](std::size_t at) { return static_cast<std::uint32_t>(little_endian_at(bytes, at, 4)); };
  const std::uint32_t vertices = count(4), faces = count(8);
  if (mesh.n_vertices() != vertices || mesh.n_faces() != faces)
    throw InputError(with_path(path, "the file is cut short or damaged (its header counts " + std::to_string(vertices) +
                                         " vertices and " + std::to_string(faces) + " faces; " +
                                         std::to_string(mesh.n_vertices()) + " and " + std::to_string(mesh.n_faces()) +
                                         " could be read); expected a whole .om file"));
  // OM files store the halfedge connectivity itself: one cut short (or
  // damaged) inside it reads as links that do not close up.
  const auto damaged = [&](const std::string& what) {
    throw InputError(with_path(path, "the file is cut short or damaged (" + what + "); expected a whole .om file"));
  };
  const auto valid = [](int index, std::size_t size) { return index >= 0 && static_cast<std::size_t>(index) < size; };
  for (const auto h : mesh.halfedges()) {
    const auto next = mesh.next_halfedge_handle(h), opposite = mesh.opposite_halfedge_handle(h);
    const auto to = mesh.to_vertex_handle(h);
    if (!valid(next.idx(), mesh.n_halfedges()) || !valid(to.idx(), mesh.n_vertices()) ||
        mesh.prev_halfedge_handle(next) != h || mesh.from_vertex_handle(opposite) != to ||
        mesh.face_handle(next) != mesh.face_handle(h) ||
        (!mesh.is_boundary(h) && !valid(mesh.face_handle(h).idx(), mesh.n_faces())))
      damaged("halfedge " + std::to_string(h.idx()) + " is not linked to its neighbours");
  }
  for (const auto f : mesh.faces()) {
    const auto first = mesh.halfedge_handle(f);
    if (!valid(first.idx(), mesh.n_halfedges()) || mesh.face_handle(first) != f)
      damaged("face " + std::to_string(f.idx()) + " names a halfedge not its own");
  }
  for (const auto v : mesh.vertices()) {
    const auto out = mesh.halfedge_handle(v);
    if (out.is_valid() && (!valid(out.idx(), mesh.n_halfedges()) || mesh.from_vertex_handle(out) != v))
      damaged("vertex " + std::to_string(v.idx()) + " names a halfedge not its own");
  }
}

void drop_analysis_layers_not_stored(const std::string& bytes, QuadMesh& mesh) {
  const auto stored = [&](const char* name) { return bytes.find(name) != std::string::npos; };
  if (OpenMesh::VPropHandleT<int> handle; !stored(layer::computed_mode) && mesh.get_property_handle(handle, layer::computed_mode))
    mesh.remove_property(handle);
  for (const char* name : {layer::mean_curvature, layer::curvature_deviation})
    if (OpenMesh::VPropHandleT<double> handle; !stored(name) && mesh.get_property_handle(handle, name))
      mesh.remove_property(handle);
}

}  // namespace mrcloth
