#include "quad_refiner.h"

#include "errors.h"
#include "mode_painting.h"
#include "quadtree_forest.h"
#include "texture_coords.h"

namespace mrcloth {

QuadRefiner::QuadRefiner(QuadMesh& mesh) : mesh_(mesh), layers_(get_layers(mesh)) {
  mesh.get_property_handle(computed_, layer::computed_mode);
  midpoints_.reserve(mesh.n_vertices() * 2);
  for (auto v : mesh.vertices()) {
    const OpenMesh::Vec2i p = mesh.property(layers_.parents, v);
    if (p[0] >= 0) midpoints_.emplace(key(p[0], p[1]), v.idx());
  }
}

std::uint64_t QuadRefiner::key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

int QuadRefiner::midpoint(int a, int b) const {
  const auto it = midpoints_.find(key(a, b));
  return it == midpoints_.end() ? -1 : it->second;
}

int QuadRefiner::midpoint_or_new(int a, int b, bool& created) {
  const auto [it, inserted] = midpoints_.try_emplace(key(a, b), -1);
  created = inserted;
  if (!inserted) return it->second;
  const auto pa = mesh_.point(mesh_.vertex_handle(a));
  const auto pb = mesh_.point(mesh_.vertex_handle(b));
  const auto v = mesh_.add_vertex((pa + pb) * 0.5);
  inherit_from_fathers(v.idx(), {a, b});
  mesh_.property(layers_.hanging, v) = false;
  mesh_.property(layers_.parents, v) = OpenMesh::Vec2i(a, b);
  it->second = v.idx();
  return v.idx();
}

QuadSplit QuadRefiner::split(int record) {
  auto& forest = mesh_.property(layers_.quadtree);
  if (record < 0 || static_cast<std::size_t>(record) >= forest.size())
    throw ArgumentError("quad record " + std::to_string(record) + " does not exist (the forest has " +
                        std::to_string(forest.size()) + ")");
  if (!forest[record].active)
    throw ArgumentError("quad record " + std::to_string(record) + " is not active; only active faces split");

  const QuadRecord parent = forest[record];  // copy: the vector grows below
  QuadSplit s;
  s.record = record;
  for (int k = 0; k < 4; ++k) {
    bool created = false;
    s.midpoints[k] = midpoint_or_new(parent.corners[k], parent.corners[(k + 1) % 4], created);
    s.midpoint_is_new[k] = created;
  }
  OpenMesh::Vec3d centre(0, 0, 0);
  for (int c : parent.corners) centre += mesh_.point(mesh_.vertex_handle(c));
  const auto cv = mesh_.add_vertex(centre * 0.25);
  inherit_from_fathers(cv.idx(), {parent.corners[0], parent.corners[1], parent.corners[2], parent.corners[3]});
  mesh_.property(layers_.hanging, cv) = false;
  mesh_.property(layers_.parents, cv) = OpenMesh::Vec2i(-1, -1);
  s.center = cv.idx();

  // Child k holds the parent's corner k at its own position k, so every child
  // keeps the parent's orientation and uniform refinement stays a regular grid.
  const auto& c = parent.corners;
  const auto& m = s.midpoints;
  const std::array<std::array<int, 4>, 4> child_corners = {{
      {c[0], m[0], s.center, m[3]},
      {m[0], c[1], m[1], s.center},
      {s.center, m[1], c[2], m[2]},
      {m[3], s.center, m[2], c[3]},
  }};
  for (int k = 0; k < 4; ++k) {
    QuadRecord child;
    child.level = parent.level + 1;
    child.active = 1;
    child.parent = record;
    child.corners = child_corners[k];
    s.children[k] = static_cast<int>(forest.size());
    forest.push_back(child);
  }
  forest[record].active = 0;
  forest[record].children = s.children;
  split_record_uvs(mesh_, record, s.children);
  return s;
}

void QuadRefiner::inherit_from_fathers(int vertex, std::initializer_list<int> fathers) {
  double r_sum = 0.0;
  int mode_sum = 0;
  for (int f : fathers) {
    const auto fh = mesh_.vertex_handle(f);
    r_sum += mesh_.property(layers_.r_value, fh);
    mode_sum += mesh_.property(layers_.mode, fh);
  }
  const int n = static_cast<int>(fathers.size());
  // Round half up so a midpoint between modes 2 and 3 counts as 3: wrinkle
  // regions should not shrink when a painted mesh is refined.
  const auto rounded_mean = [n](int sum) { return (2 * sum + n) / (2 * n); };
  const auto vh = mesh_.vertex_handle(vertex);
  mesh_.property(layers_.r_value, vh) = r_sum / n;
  mesh_.property(layers_.mode, vh) = rounded_mean(mode_sum);
  // The computed modes alike, where the mesh has them.
  if (!computed_.is_valid()) return;
  int computed_sum = 0;
  for (int f : fathers) computed_sum += mesh_.property(computed_, mesh_.vertex_handle(f));
  mesh_.property(computed_, vh) = rounded_mean(computed_sum);
}

bool QuadRefiner::finish(const std::function<bool(int faces_added)>& progress) {
  return rebuild_active_faces(mesh_, progress);
}

}  // namespace mrcloth
