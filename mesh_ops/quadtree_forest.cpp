#include "quadtree_forest.h"

#include "errors.h"

#include <algorithm>
#include <unordered_map>

namespace mrcloth {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// Midpoint of each split edge, recovered from the parents layer (the forest
// plus that layer are the whole truth; nothing else needs to be saved).
std::unordered_map<std::uint64_t, int> midpoints_from_parents(const QuadMesh& mesh, const Layers& l) {
  std::unordered_map<std::uint64_t, int> map;
  map.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const OpenMesh::Vec2i p = mesh.property(l.parents, v);
    if (p[0] >= 0) map.emplace(edge_key(p[0], p[1]), v.idx());
  }
  return map;
}

// Appends the vertices strictly inside edge (a, b), in order from a to b,
// and, with `params`, each one's place along the edge (ta at a, tb at b).
void append_edge_interior(const std::unordered_map<std::uint64_t, int>& mids, int a, int b, std::vector<int>& out,
                          std::vector<double>* params = nullptr, double ta = 0.0, double tb = 1.0) {
  const auto it = mids.find(edge_key(a, b));
  if (it == mids.end()) return;
  const int m = it->second;
  const double tm = 0.5 * (ta + tb);
  append_edge_interior(mids, a, m, out, params, ta, tm);
  out.push_back(m);
  if (params) params->push_back(tm);
  append_edge_interior(mids, m, b, out, params, tm, tb);
}

// The record's polygon: its corners with the vertices inside its edges;
// with `params`, each one's place along the boundary (k + t on edge k).
std::vector<int> polygon_of(const std::unordered_map<std::uint64_t, int>& mids, const QuadRecord& q,
                            std::vector<double>* params = nullptr) {
  std::vector<int> loop;
  loop.reserve(8);
  for (int k = 0; k < 4; ++k) {
    loop.push_back(q.corners[k]);
    if (params) params->push_back(k);
    append_edge_interior(mids, q.corners[k], q.corners[(k + 1) % 4], loop, params, k, k + 1);
  }
  return loop;
}

void mark_edge_interior(const QuadMesh& mesh, const std::unordered_map<std::uint64_t, int>& mids,
                        int a, int b, std::vector<char>& hanging) {
  const auto it = mids.find(edge_key(a, b));
  if (it == mids.end()) return;
  const int m = it->second;
  hanging[m] = 1;
  mark_edge_interior(mesh, mids, a, m, hanging);
  mark_edge_interior(mesh, mids, m, b, hanging);
}

}  // namespace

void init_forest(QuadMesh& mesh) {
  const Layers l = ensure_layers(mesh);
  std::vector<QuadRecord> forest;
  forest.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    if (mesh.valence(f) != 4)
      throw ArgumentError("face " + std::to_string(f.idx()) + " has " +
                          std::to_string(mesh.valence(f)) + " vertices; a refinable mesh needs quads only");
    QuadRecord q;
    int k = 0;
    for (auto v : mesh.fv_range(f)) q.corners[k++] = v.idx();
    mesh.property(l.level, f) = 1;
    mesh.property(l.quad, f) = static_cast<int>(forest.size());
    forest.push_back(q);
  }
  for (auto v : mesh.vertices()) {
    mesh.property(l.mode, v) = kDefaultMode;
    mesh.property(l.r_value, v) = 0.0;
    mesh.property(l.hanging, v) = false;
    mesh.property(l.parents, v) = OpenMesh::Vec2i(-1, -1);
  }
  mesh.property(l.quadtree) = std::move(forest);
}

std::vector<std::vector<double>> active_face_boundary_params(const QuadMesh& mesh) {
  const Layers l = get_layers(mesh);
  const auto mids = midpoints_from_parents(mesh, l);
  const auto& forest = mesh.property(l.quadtree);
  std::vector<std::vector<double>> all;
  all.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {
    const QuadRecord& record = forest[static_cast<std::size_t>(mesh.property(l.quad, f))];
    std::vector<double> along;
    const std::vector<int> loop = polygon_of(mids, record, &along);
    // In the face's own vertex order, which may start elsewhere on the loop.
    std::vector<double> params;
    for (const auto v : f.vertices())
      params.push_back(along[static_cast<std::size_t>(std::find(loop.begin(), loop.end(), v.idx()) - loop.begin())]);
    all.push_back(std::move(params));
  }
  return all;
}

int first_face_unlike_its_record(const QuadMesh& mesh) {
  const Layers l = get_layers(mesh);
  const auto mids = midpoints_from_parents(mesh, l);
  const auto& forest = mesh.property(l.quadtree);
  std::vector<int> loop;
  for (const auto f : mesh.faces()) {
    const QuadRecord& record = forest[static_cast<std::size_t>(mesh.property(l.quad, f))];
    const std::vector<int> polygon = polygon_of(mids, record);
    loop.clear();
    for (const auto v : f.vertices()) loop.push_back(v.idx());
    const auto start = std::find(polygon.begin(), polygon.end(), loop.front());
    bool same = mesh.property(l.level, f) == record.level && loop.size() == polygon.size() && start != polygon.end();
    if (same) std::rotate(loop.begin(), loop.begin() + (polygon.end() - start) % static_cast<long>(loop.size()), loop.end());
    if (!same || loop != polygon) return f.idx();
  }
  return -1;
}

std::vector<int> active_face_polygon(const QuadMesh& mesh, const QuadRecord& record) {
  const Layers l = get_layers(mesh);
  return polygon_of(midpoints_from_parents(mesh, l), record);
}

bool rebuild_active_faces(QuadMesh& mesh, const std::function<bool(int faces_added)>& progress, int every) {
  const Layers l = get_layers(mesh);
  const auto mids = midpoints_from_parents(mesh, l);

  for (auto f : mesh.faces()) mesh.delete_face(f, /*delete_isolated_vertices=*/false);
  mesh.garbage_collection();  // no vertex was deleted, so vertex indices do not move

  const auto& forest = mesh.property(l.quadtree);
  std::vector<QuadMesh::VertexHandle> handles;
  int added = 0;
  for (std::size_t i = 0; i < forest.size(); ++i) {
    const QuadRecord& q = forest[i];
    if (!q.active) continue;
    if (progress && added > 0 && added % every == 0 && !progress(added)) return false;
    ++added;
    handles.clear();
    for (int v : polygon_of(mids, q)) handles.push_back(mesh.vertex_handle(v));
    const auto f = mesh.add_face(handles);
    if (!f.is_valid())
      throw Error("internal: active quad record " + std::to_string(i) +
                  " could not be added as a face (the forest is inconsistent)");
    mesh.property(l.level, f) = q.level;
    mesh.property(l.quad, f) = static_cast<int>(i);
  }
  update_hanging_nodes(mesh);
  return true;
}

void update_hanging_nodes(QuadMesh& mesh) {
  const Layers l = get_layers(mesh);
  const auto mids = midpoints_from_parents(mesh, l);
  std::vector<char> hanging(mesh.n_vertices(), 0);
  for (const QuadRecord& q : mesh.property(l.quadtree)) {
    if (!q.active) continue;
    for (int k = 0; k < 4; ++k) mark_edge_interior(mesh, mids, q.corners[k], q.corners[(k + 1) % 4], hanging);
  }
  for (auto v : mesh.vertices()) mesh.property(l.hanging, v) = hanging[v.idx()] != 0;
}

std::vector<int> vertex_levels(const QuadMesh& mesh) {
  std::vector<int> level(mesh.n_vertices(), 0);
  for (const QuadRecord& q : quadtree(mesh))
    for (int c : q.corners)
      if (level[c] == 0 || q.level < level[c]) level[c] = q.level;
  return level;
}

}  // namespace mrcloth
