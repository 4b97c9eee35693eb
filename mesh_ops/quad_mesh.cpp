#include "quad_mesh.h"

#include "errors.h"
#include "quadtree_forest.h"
#include "texture_coords.h"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>
#include <type_traits>

namespace mrcloth {
namespace {

template <typename Handle, typename Value>
Handle ensure_property(QuadMesh& mesh, const char* name, const Value& initial) {
  Handle handle;
  if (!mesh.get_property_handle(handle, name)) {
    mesh.add_property(handle, name);
    if constexpr (std::is_same_v<Handle, OpenMesh::VPropHandleT<Value>>) {
      for (auto v : mesh.vertices()) mesh.property(handle, v) = initial;
    } else if constexpr (std::is_same_v<Handle, OpenMesh::FPropHandleT<Value>>) {
      for (auto f : mesh.faces()) mesh.property(handle, f) = initial;
    }
  }
  if constexpr (std::is_same_v<Handle, OpenMesh::MPropHandleT<Value>>)
    mesh.mproperty(handle).set_persistent(true);
  else
    mesh.property(handle).set_persistent(true);
  return handle;
}

template <typename Handle>
Handle require_property(const QuadMesh& mesh, const char* name) {
  Handle handle;
  if (!mesh.get_property_handle(handle, name))
    throw ArgumentError(std::string("mesh has no layer '") + name + "'; it was not made refinable");
  return handle;
}

}  // namespace

Layers ensure_layers(QuadMesh& mesh) {
  Layers l;
  l.mode = ensure_property<OpenMesh::VPropHandleT<int>>(mesh, layer::mode, kDefaultMode);
  l.r_value = ensure_property<OpenMesh::VPropHandleT<double>>(mesh, layer::r_value, 0.0);
  l.hanging = ensure_property<OpenMesh::VPropHandleT<bool>>(mesh, layer::hanging, false);
  l.parents = ensure_property<OpenMesh::VPropHandleT<OpenMesh::Vec2i>>(mesh, layer::parents,
                                                                      OpenMesh::Vec2i(-1, -1));
  l.level = ensure_property<OpenMesh::FPropHandleT<int>>(mesh, layer::level, 1);
  l.quad = ensure_property<OpenMesh::FPropHandleT<int>>(mesh, layer::quad, -1);
  // The OM writer stores mesh layers in the order they were made, so the
  // forest, made after the checksum and the UVs, is the file's last chunk:
  // a file cut short anywhere lacks it or holds a damaged one, and its
  // checksum does not match (load_garment refuses all three).
  ensure_property<OpenMesh::MPropHandleT<std::uint64_t>>(mesh, layer::checksum, std::uint64_t{0});
  ensure_record_uvs(mesh);
  l.quadtree = ensure_property<OpenMesh::MPropHandleT<std::vector<QuadRecord>>>(
      mesh, layer::quadtree, std::vector<QuadRecord>{});
  return l;
}

Layers get_layers(const QuadMesh& mesh) {
  Layers l;
  l.mode = require_property<OpenMesh::VPropHandleT<int>>(mesh, layer::mode);
  l.r_value = require_property<OpenMesh::VPropHandleT<double>>(mesh, layer::r_value);
  l.hanging = require_property<OpenMesh::VPropHandleT<bool>>(mesh, layer::hanging);
  l.parents = require_property<OpenMesh::VPropHandleT<OpenMesh::Vec2i>>(mesh, layer::parents);
  l.level = require_property<OpenMesh::FPropHandleT<int>>(mesh, layer::level);
  l.quad = require_property<OpenMesh::FPropHandleT<int>>(mesh, layer::quad);
  l.quadtree = require_property<OpenMesh::MPropHandleT<std::vector<QuadRecord>>>(mesh, layer::quadtree);
  return l;
}

const std::vector<QuadRecord>& quadtree(const QuadMesh& mesh) {
  return mesh.property(get_layers(mesh).quadtree);
}

std::size_t count_roots(const QuadMesh& mesh) {
  const auto& forest = quadtree(mesh);
  return static_cast<std::size_t>(
      std::count_if(forest.begin(), forest.end(), [](const QuadRecord& q) { return q.parent < 0; }));
}

std::vector<std::size_t> faces_per_level(const QuadMesh& mesh) {
  std::vector<std::size_t> counts(1, 0);
  for (const QuadRecord& q : quadtree(mesh)) {
    if (!q.active) continue;
    if (counts.size() <= static_cast<std::size_t>(q.level)) counts.resize(q.level + 1, 0);
    ++counts[q.level];
  }
  return counts;
}

std::vector<std::size_t> vertices_per_level(const QuadMesh& mesh) {
  std::vector<std::size_t> counts(1, 0);
  for (int level : vertex_levels(mesh)) {
    if (level <= 0) continue;  // isolated vertex, not part of any record
    if (counts.size() <= static_cast<std::size_t>(level)) counts.resize(level + 1, 0);
    ++counts[level];
  }
  return counts;
}

std::size_t count_hanging(const QuadMesh& mesh) {
  const auto hanging = get_layers(mesh).hanging;
  std::size_t n = 0;
  for (auto v : mesh.vertices()) n += mesh.property(hanging, v) ? 1 : 0;
  return n;
}

QuadMesh copy_mesh(const QuadMesh& mesh) {
  QuadMesh copy;
  copy = mesh;  // OpenMesh's assignment deep-copies connectivity and all properties
  return copy;
}

std::vector<std::vector<int>> active_face_polygons(const QuadMesh& mesh) {
  std::vector<std::vector<int>> faces;
  faces.reserve(mesh.n_faces());
  for (const auto face : mesh.faces()) {
    std::vector<int> polygon;
    for (const auto vertex : mesh.fv_range(face)) polygon.push_back(vertex.idx());
    faces.push_back(std::move(polygon));
  }
  return faces;
}

}  // namespace mrcloth

namespace OpenMesh::IO {

size_t binary<mrcloth::QuadRecord>::store(std::ostream& os, const value_type& v, bool swap) {
  const std::int32_t ints[kInts] = {v.level,       v.active,      v.parent,      v.children[0],
                                    v.children[1], v.children[2], v.children[3], v.corners[0],
                                    v.corners[1],  v.corners[2],  v.corners[3]};
  size_t bytes = 0;
  for (std::int32_t i : ints) bytes += binary<std::int32_t>::store(os, i, swap);
  return os.good() ? bytes : 0;
}

size_t binary<mrcloth::QuadRecord>::restore(std::istream& is, value_type& v, bool swap) {
  // What a read cut short leaves in place is refused by load_garment's
  // check of the forest: a negative level and corners (a partly read int
  // keeps its high byte, 0x80).
  std::int32_t ints[kInts];
  std::fill(std::begin(ints), std::end(ints), std::numeric_limits<std::int32_t>::min());
  size_t bytes = 0;
  for (std::int32_t& i : ints) bytes += binary<std::int32_t>::restore(is, i, swap);
  v.level = ints[0];
  v.active = ints[1];
  v.parent = ints[2];
  for (int k = 0; k < 4; ++k) v.children[k] = ints[3 + k];
  for (int k = 0; k < 4; ++k) v.corners[k] = ints[7 + k];
  return is.good() ? bytes : 0;
}

}  // namespace OpenMesh::IO
