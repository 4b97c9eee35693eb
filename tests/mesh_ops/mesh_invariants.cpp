#include "mesh_invariants.h"

#include "mesh_ops/quadtree_forest.h"

#include <algorithm>
#include <cmath>

namespace mrcloth::test {
namespace {

bool cyclic_equal(const std::vector<int>& a, const std::vector<int>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t shift = 0; shift < a.size(); ++shift) {
    bool same = true;
    for (std::size_t i = 0; i < a.size() && same; ++i) same = a[i] == b[(i + shift) % b.size()];
    if (same) return true;
  }
  return false;
}

// Length of the overlap of two collinear segments, 0 if not collinear.
double overlap(const OpenMesh::Vec3d& a0, const OpenMesh::Vec3d& a1, const OpenMesh::Vec3d& b0,
               const OpenMesh::Vec3d& b1) {
  const OpenMesh::Vec3d d = a1 - a0;
  const double len = d.norm();
  const OpenMesh::Vec3d u = d / len;
  const double tol = 1e-9 * len;
  for (const auto& p : {b0, b1}) {
    const OpenMesh::Vec3d w = p - a0;
    if ((w - u * OpenMesh::dot(w, u)).norm() > tol) return 0.0;
  }
  double s0 = OpenMesh::dot(b0 - a0, u), s1 = OpenMesh::dot(b1 - a0, u);
  if (s0 > s1) std::swap(s0, s1);
  return std::min(len, s1) - std::max(0.0, s0);
}

}  // namespace

std::vector<std::string> face_forest_violations(const QuadMesh& mesh) {
  std::vector<std::string> out;
  const Layers l = get_layers(mesh);
  const auto& forest = mesh.property(l.quadtree);
  std::vector<int> faces_of_record(forest.size(), 0);
  for (auto f : mesh.faces()) {
    const int q = mesh.property(l.quad, f);
    if (q < 0 || q >= static_cast<int>(forest.size())) {
      out.push_back("face " + std::to_string(f.idx()) + " links to no record");
      continue;
    }
    ++faces_of_record[q];
    if (!forest[q].active) out.push_back("face " + std::to_string(f.idx()) + " has an inactive record");
    if (mesh.property(l.level, f) != forest[q].level)
      out.push_back("face " + std::to_string(f.idx()) + " level differs from its record");
    std::vector<int> loop;
    for (auto v : mesh.fv_range(f)) loop.push_back(v.idx());
    if (!cyclic_equal(loop, active_face_polygon(mesh, forest[q])))
      out.push_back("face " + std::to_string(f.idx()) + " polygon differs from record " + std::to_string(q));
  }
  for (std::size_t q = 0; q < forest.size(); ++q)
    if (faces_of_record[q] != (forest[q].active ? 1 : 0))
      out.push_back("record " + std::to_string(q) + " has " + std::to_string(faces_of_record[q]) + " faces");
  for (auto v : mesh.vertices())
    if (mesh.is_isolated(v)) out.push_back("vertex " + std::to_string(v.idx()) + " is isolated");
  return out;
}

std::vector<std::string> hanging_midpoint_violations(const QuadMesh& mesh) {
  std::vector<std::string> out;
  const Layers l = get_layers(mesh);
  for (auto v : mesh.vertices()) {
    if (!mesh.property(l.hanging, v)) continue;
    const OpenMesh::Vec2i p = mesh.property(l.parents, v);
    if (p[0] < 0 || p[1] < 0 || p[0] >= static_cast<int>(mesh.n_vertices()) ||
        p[1] >= static_cast<int>(mesh.n_vertices())) {
      out.push_back("hanging vertex " + std::to_string(v.idx()) + " has invalid parents");
      continue;
    }
    const auto mid = (mesh.point(mesh.vertex_handle(p[0])) + mesh.point(mesh.vertex_handle(p[1]))) * 0.5;
    if (mesh.point(v) != mid) out.push_back("hanging vertex " + std::to_string(v.idx()) + " is off its parents' midpoint");
  }
  return out;
}

int max_neighbour_level_difference(const QuadMesh& mesh) {
  const Layers l = get_layers(mesh);
  int worst = 0;
  for (auto e : mesh.edges()) {
    if (e.is_boundary()) continue;
    const int a = mesh.property(l.level, e.h0().face());
    const int b = mesh.property(l.level, e.h1().face());
    worst = std::max(worst, std::abs(a - b));
  }
  return worst;
}

int brute_force_max_level_difference(const QuadMesh& mesh) {
  const Layers l = get_layers(mesh);
  // Only the active records' four corners: independent of how the mesh
  // inserted hanging vertices into its polygons.
  std::vector<std::vector<OpenMesh::Vec3d>> polys;
  std::vector<int> levels;
  for (const QuadRecord& q : mesh.property(l.quadtree)) {
    if (!q.active) continue;
    std::vector<OpenMesh::Vec3d> corners;
    for (int c : q.corners) corners.push_back(mesh.point(mesh.vertex_handle(c)));
    polys.push_back(corners);
    levels.push_back(q.level);
  }
  int worst = 0;
  for (std::size_t i = 0; i < polys.size(); ++i)
    for (std::size_t j = i + 1; j < polys.size(); ++j) {
      if (std::abs(levels[i] - levels[j]) <= worst) continue;
      bool neighbours = false;
      const auto& a = polys[i];
      const auto& b = polys[j];
      for (std::size_t s = 0; s < a.size() && !neighbours; ++s)
        for (std::size_t t = 0; t < b.size() && !neighbours; ++t)
          neighbours = overlap(a[s], a[(s + 1) % a.size()], b[t], b[(t + 1) % b.size()]) > 1e-9;
      if (neighbours) worst = std::abs(levels[i] - levels[j]);
    }
  return worst;
}

int euler_characteristic(const QuadMesh& mesh) {
  return static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) + static_cast<int>(mesh.n_faces());
}

}  // namespace mrcloth::test
