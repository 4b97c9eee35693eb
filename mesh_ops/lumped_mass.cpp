#include "lumped_mass.h"

#include "errors.h"

#include <cmath>

namespace mrcloth {
namespace {

// Magnitude of the quad's vector area, 0.5 |(p2 - p0) x (p3 - p1)|: exact for
// planar quads, and a well-defined area for slightly warped ones.
double quad_area(const QuadMesh& mesh, const std::array<std::int32_t, 4>& c) {
  const auto p = [&](int k) { return mesh.point(mesh.vertex_handle(c[k])); };
  return 0.5 * OpenMesh::cross(p(2) - p(0), p(3) - p(1)).norm();
}

// Root (coarse record) of every record; parents precede children in the forest.
std::vector<int> root_of_records(const std::vector<QuadRecord>& forest) {
  std::vector<int> root(forest.size());
  for (std::size_t i = 0; i < forest.size(); ++i)
    root[i] = forest[i].parent < 0 ? static_cast<int>(i) : root[forest[i].parent];
  return root;
}

}  // namespace

std::vector<double> rest_face_areas(const QuadMesh& mesh) {
  const Layers l = get_layers(mesh);
  const auto& forest = mesh.property(l.quadtree);
  const std::vector<int> root = root_of_records(forest);

  std::vector<double> own(forest.size(), 0.0);
  std::vector<double> active_sum(forest.size(), 0.0);  // per root
  for (std::size_t i = 0; i < forest.size(); ++i) {
    if (!forest[i].active) continue;
    own[i] = quad_area(mesh, forest[i].corners);
    active_sum[root[i]] += own[i];
  }
  std::vector<double> areas(mesh.n_faces(), 0.0);
  for (auto f : mesh.faces()) {
    const int q = mesh.property(l.quad, f);
    const int r = root[q];
    const double root_area = quad_area(mesh, forest[r].corners);
    // A lone active root keeps its own area exactly; otherwise share it.
    areas[f.idx()] = (q == r) ? root_area
                     : active_sum[r] > 0.0 ? root_area * (own[q] / active_sum[r])
                                           : root_area * std::ldexp(1.0, -2 * (forest[q].level - 1));
  }
  return areas;
}

double garment_area(const QuadMesh& mesh) {
  double area = 0.0;
  for (const QuadRecord& q : quadtree(mesh))
    if (q.parent < 0) area += quad_area(mesh, q.corners);
  return area;
}

std::vector<double> lumped_mass(const QuadMesh& mesh, double areal_density) {
  if (!(areal_density > 0.0) || !std::isfinite(areal_density))
    throw ArgumentError("areal density must be a positive number of kg/m^2");
  const Layers l = get_layers(mesh);
  const auto& forest = mesh.property(l.quadtree);
  const std::vector<double> areas = rest_face_areas(mesh);

  std::vector<double> mass(mesh.n_vertices(), 0.0);
  for (auto f : mesh.faces()) {
    const double quarter = 0.25 * areal_density * areas[f.idx()];
    for (int c : forest[mesh.property(l.quad, f)].corners) mass[c] += quarter;
  }
  // A hanging vertex is not simulated: its mass moves to its parents. Parents
  // always have lower indices than the midpoint they made, so one backward
  // sweep also carries mass along chains of hanging vertices.
  for (int v = static_cast<int>(mesh.n_vertices()) - 1; v >= 0; --v) {
    const auto vh = mesh.vertex_handle(v);
    if (!mesh.property(l.hanging, vh)) continue;
    const OpenMesh::Vec2i p = mesh.property(l.parents, vh);
    mass[p[0]] += 0.5 * mass[v];
    mass[p[1]] += 0.5 * mass[v];
    mass[v] = 0.0;
  }
  return mass;
}

}  // namespace mrcloth
