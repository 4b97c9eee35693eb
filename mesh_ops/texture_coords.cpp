#include "texture_coords.h"

#include "errors.h"
#include "quadtree_forest.h"

#include <cmath>
#include <string>

namespace mrcloth {
namespace {

OpenMesh::MPropHandleT<std::vector<RecordUV>> handle_of(const QuadMesh& mesh) {
  OpenMesh::MPropHandleT<std::vector<RecordUV>> handle;
  mesh.get_property_handle(handle, layer::record_uvs);
  return handle;
}

const std::vector<RecordUV>& no_uvs() {
  static const std::vector<RecordUV> empty;
  return empty;
}

OpenMesh::Vec2d mix(const OpenMesh::Vec2d& a, const OpenMesh::Vec2d& b, double t) { return a + (b - a) * t; }

}  // namespace

bool has_texture_coords(const QuadMesh& mesh) {
  const auto handle = handle_of(mesh);
  return handle.is_valid() && !mesh.property(handle).empty() && mesh.property(handle).size() == quadtree(mesh).size();
}

const std::vector<RecordUV>& record_uvs(const QuadMesh& mesh) {
  const auto handle = handle_of(mesh);
  return handle.is_valid() ? mesh.property(handle) : no_uvs();
}

void ensure_record_uvs(QuadMesh& mesh) {
  auto handle = handle_of(mesh);
  if (handle.is_valid()) return;
  mesh.add_property(handle, layer::record_uvs);
  mesh.mproperty(handle).set_persistent(true);
}

void set_record_uvs(QuadMesh& mesh, std::vector<RecordUV> uvs) {
  if (!uvs.empty() && uvs.size() != quadtree(mesh).size())
    throw ArgumentError("set_record_uvs: " + std::to_string(uvs.size()) + " records' UVs; expected one per quadtree "
                        "record (" + std::to_string(quadtree(mesh).size()) + ") or none");
  ensure_record_uvs(mesh);
  mesh.property(handle_of(mesh)) = std::move(uvs);
}

void split_record_uvs(QuadMesh& mesh, int parent, const std::array<int, 4>& children) {
  const auto handle = handle_of(mesh);
  if (!handle.is_valid()) return;
  std::vector<RecordUV>& uvs = mesh.property(handle);
  // Only a mesh whose every record has UVs gains its children's (the
  // children are the forest's last four records).
  if (uvs.empty() || uvs.size() + 4 != quadtree(mesh).size()) return;
  const auto& c = uvs[static_cast<std::size_t>(parent)].corner;
  const OpenMesh::Vec2d m[4] = {mix(c[0], c[1], 0.5), mix(c[1], c[2], 0.5), mix(c[2], c[3], 0.5), mix(c[3], c[0], 0.5)};
  const OpenMesh::Vec2d centre = (c[0] + c[1] + c[2] + c[3]) * 0.25;
  // The corners of QuadRefiner::split's children, in its order.
  const RecordUV child[4] = {{{c[0], m[0], centre, m[3]}},
                             {{m[0], c[1], m[1], centre}},
                             {{centre, m[1], c[2], m[2]}},
                             {{m[3], centre, m[2], c[3]}}};
  for (int k = 0; k < 4; ++k) {
    if (children[static_cast<std::size_t>(k)] != static_cast<int>(uvs.size()))
      throw Error("internal: split_record_uvs expects the children appended in order");
    uvs.push_back(child[k]);
  }
}

std::vector<std::vector<OpenMesh::Vec2d>> active_face_uvs(const QuadMesh& mesh) {
  std::vector<std::vector<OpenMesh::Vec2d>> all;
  if (!has_texture_coords(mesh)) return all;
  const std::vector<RecordUV>& uvs = record_uvs(mesh);
  const Layers l = get_layers(mesh);
  const std::vector<std::vector<double>> params = active_face_boundary_params(mesh);
  all.reserve(params.size());
  std::size_t face = 0;
  for (const auto f : mesh.faces()) {
    const auto& c = uvs[static_cast<std::size_t>(mesh.property(l.quad, f))].corner;
    std::vector<OpenMesh::Vec2d> polygon;
    for (const double s : params[face]) {
      const int k = static_cast<int>(std::floor(s));
      polygon.push_back(mix(c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>((k + 1) % 4)], s - k));
    }
    all.push_back(std::move(polygon));
    ++face;
  }
  return all;
}

}  // namespace mrcloth

namespace OpenMesh::IO {

size_t binary<mrcloth::RecordUV>::store(std::ostream& os, const value_type& v, bool swap) {
  size_t bytes = 0;
  for (const auto& uv : v.corner)
    for (int c = 0; c < 2; ++c) bytes += binary<double>::store(os, uv[c], swap);
  return os.good() ? bytes : 0;
}

size_t binary<mrcloth::RecordUV>::restore(std::istream& is, value_type& v, bool swap) {
  size_t bytes = 0;
  for (auto& uv : v.corner)
    for (int c = 0; c < 2; ++c) bytes += binary<double>::restore(is, uv[c], swap);
  return is.good() ? bytes : 0;
}

}  // namespace OpenMesh::IO
