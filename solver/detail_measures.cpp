#include "detail_measures.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/mode_layer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace mrcloth {
namespace {

// Offset of child k's corner 0 (and of corner k of a record) in units of the
// side, in the record's (u, v): child k holds corner k, so the quadrants go
// round the square in corner order.
constexpr int kOffsetU[4] = {0, 1, 1, 0};
constexpr int kOffsetV[4] = {0, 0, 1, 1};

const std::vector<QuadRecord>& checked_forest(const QuadMesh& mesh) {
  const std::vector<QuadRecord>& forest = quadtree(mesh);  // throws for a mesh never made refinable
  if (forest.empty()) throw ArgumentError("mesh has an empty quadtree forest; material coordinates need one");
  for (std::size_t i = 0; i < forest.size(); ++i) {
    const int p = forest[i].parent;
    // Children are appended after their parent; relying on it lets every pass
    // below go once through the records in order.
    if (p >= static_cast<int>(i))
      throw ArgumentError("quad record " + std::to_string(i) + " has parent " + std::to_string(p) +
                          " stored after it; the forest is corrupt");
  }
  return forest;
}

std::string point_name(std::size_t k, const MaterialPoint& p) {
  return "material point " + std::to_string(k) + " (root " + std::to_string(p.root) + ", u " +
         std::to_string(p.u) + ", v " + std::to_string(p.v) + ")";
}

void check_rows(const char* what, Eigen::Index rows, int expected) {
  if (rows != expected)
    throw ArgumentError(std::string(what) + " has " + std::to_string(rows) + " rows; the mesh has " +
                        std::to_string(expected) + " vertices");
}

}  // namespace

std::vector<MaterialPoint> material_points(const QuadMesh& mesh) {
  const std::vector<QuadRecord>& forest = checked_forest(mesh);
  const std::size_t n = forest.size();
  std::vector<int> root(n);
  std::vector<double> u0(n, 0.0), v0(n, 0.0), side(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const QuadRecord& q = forest[i];
    if (q.parent < 0) root[i] = static_cast<int>(i);
    for (int k = 0; k < 4; ++k) {
      const int c = q.children[k];
      if (c < 0) continue;
      if (c <= static_cast<int>(i) || c >= static_cast<int>(n))
        throw ArgumentError("quad record " + std::to_string(i) + " has child " + std::to_string(c) +
                            " out of order or range; the forest is corrupt");
      root[c] = root[i];
      side[c] = 0.5 * side[i];
      u0[c] = u0[i] + kOffsetU[k] * side[c];
      v0[c] = v0[i] + kOffsetV[k] * side[c];
    }
  }

  std::vector<MaterialPoint> points(mesh.n_vertices());
  const int nv = static_cast<int>(mesh.n_vertices());
  for (std::size_t i = 0; i < n; ++i) {
    const QuadRecord& q = forest[i];
    for (int k = 0; k < 4; ++k) {
      const int c = q.corners[k];
      if (c < 0 || c >= nv)
        throw ArgumentError("quad record " + std::to_string(i) + " has corner vertex " + std::to_string(c) +
                            "; the mesh has " + std::to_string(nv) + " vertices");
      MaterialPoint& p = points[c];
      // Lowest root wins, so every mesh refined from one coarse mesh names a
      // shared boundary vertex the same way.
      if (p.root < 0 || root[i] < p.root) p = {root[i], u0[i] + kOffsetU[k] * side[i], v0[i] + kOffsetV[k] * side[i]};
    }
  }
  for (int vtx = 0; vtx < nv; ++vtx)
    if (points[vtx].root < 0)
      throw ArgumentError("vertex " + std::to_string(vtx) +
                          " is no corner of any quad record (isolated); it has no material coordinates");
  return points;
}

MaterialEvaluator::MaterialEvaluator(const QuadMesh& mesh)
    : forest_(checked_forest(mesh)), num_vertices_(static_cast<int>(mesh.n_vertices())) {
  num_roots_ = static_cast<int>(count_roots(mesh));
}

MaterialBinding MaterialEvaluator::bind(const std::vector<MaterialPoint>& points) const {
  MaterialBinding b;
  b.num_vertices = num_vertices_;
  b.leaf.resize(points.size());
  b.corners.resize(points.size());
  b.weights.resize(points.size());
  // Child index of the quadrant (upper u?, upper v?), from kOffsetU/V.
  constexpr int kChild[2][2] = {{0, 3}, {1, 2}};
  for (std::size_t k = 0; k < points.size(); ++k) {
    const MaterialPoint& p = points[k];
    if (p.root < 0 || p.root >= num_roots_ || forest_[p.root].parent >= 0)
      throw ArgumentError(point_name(k, p) + ": root out of range; the mesh has " + std::to_string(num_roots_) +
                          " coarse faces");
    if (!std::isfinite(p.u) || !std::isfinite(p.v) || p.u < 0.0 || p.u > 1.0 || p.v < 0.0 || p.v > 1.0)
      throw ArgumentError(point_name(k, p) + ": u and v must be finite and in [0, 1]");
    int rec = p.root;
    // Local parameters in the current record. 2a - 1 for a in [0.5, 1] is
    // exact (Sterbenz), so dyadic coordinates stay exact all the way down.
    double a = p.u, c = p.v;
    for (std::size_t depth = 0; !forest_[rec].active; ++depth) {
      const QuadRecord& q = forest_[rec];
      if (q.children[0] < 0 || depth > forest_.size())
        throw ArgumentError("quad record " + std::to_string(rec) + " is neither active nor split (reached from " +
                            point_name(k, p) + "); the forest is corrupt");
      const int iu = a >= 0.5 ? 1 : 0;
      const int iv = c >= 0.5 ? 1 : 0;
      a = 2.0 * a - iu;
      c = 2.0 * c - iv;
      rec = q.children[kChild[iu][iv]];
    }
    const QuadRecord& leaf = forest_[rec];
    b.leaf[k] = rec;
    for (int j = 0; j < 4; ++j) {
      if (leaf.corners[j] < 0 || leaf.corners[j] >= num_vertices_)
        throw ArgumentError("quad record " + std::to_string(rec) + " has corner vertex " +
                            std::to_string(leaf.corners[j]) + " out of range");
      b.corners[k][j] = leaf.corners[j];
    }
    b.weights[k] = {(1.0 - a) * (1.0 - c), a * (1.0 - c), a * c, (1.0 - a) * c};
  }
  return b;
}

Eigen::MatrixX3d MaterialEvaluator::evaluate(const MaterialBinding& binding, const FramePositions& positions) const {
  if (binding.num_vertices != num_vertices_)
    throw ArgumentError("binding was made for a mesh of " + std::to_string(binding.num_vertices) +
                        " vertices; this evaluator's mesh has " + std::to_string(num_vertices_));
  check_rows("positions", positions.rows(), num_vertices_);
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(binding.size()), 3);
  for (std::size_t k = 0; k < binding.size(); ++k) {
    const auto& c = binding.corners[k];
    const auto& w = binding.weights[k];
    out.row(static_cast<Eigen::Index>(k)) = w[0] * positions.row(c[0]) + w[1] * positions.row(c[1]) +
                                            w[2] * positions.row(c[2]) + w[3] * positions.row(c[3]);
  }
  return out;
}

Eigen::MatrixX3d MaterialEvaluator::evaluate(const std::vector<MaterialPoint>& points,
                                             const FramePositions& positions) const {
  check_rows("positions", positions.rows(), num_vertices_);  // before the binding work
  return evaluate(bind(points), positions);
}

FramePositions mesh_positions(const QuadMesh& mesh) {
  FramePositions x(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    x.row(v.idx()) << p[0], p[1], p[2];
  }
  return x;
}

DistanceStats point_distances(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  if (a.rows() != b.rows())
    throw ArgumentError("point_distances: a has " + std::to_string(a.rows()) + " rows, b has " +
                        std::to_string(b.rows()) + " rows");
  const Eigen::Index n = a.rows();
  if (n == 0) throw ArgumentError("point_distances: no points to compare");
  std::vector<double> d(static_cast<std::size_t>(n));
  double sum_sq = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!a.row(i).allFinite() || !b.row(i).allFinite())
      throw ArgumentError("point_distances: row " + std::to_string(i) + " has a non-finite coordinate");
    d[static_cast<std::size_t>(i)] = (a.row(i) - b.row(i)).norm();
    sum_sq += d[static_cast<std::size_t>(i)] * d[static_cast<std::size_t>(i)];
  }
  DistanceStats s;
  s.rms = std::sqrt(sum_sq / static_cast<double>(n));
  // Nearest rank: the ceil(0.95 n)-th smallest, in integers so 0.95 * 100 is
  // not at the mercy of rounding.
  const std::size_t rank = (95 * static_cast<std::size_t>(n) + 99) / 100;  // 1-based, >= 1
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(rank - 1), d.end());
  s.p95 = d[rank - 1];
  s.max = *std::max_element(d.begin(), d.end());
  return s;
}

WrinkleEnergy::WrinkleEnergy(const QuadMesh& mesh) {
  const int n = static_cast<int>(mesh.n_vertices());
  offsets_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (auto v : mesh.vertices()) {
    for (auto w : mesh.vv_range(v)) neighbours_.push_back(w.idx());
    offsets_[static_cast<std::size_t>(v.idx()) + 1] = static_cast<int>(neighbours_.size());
    if (!mesh.is_boundary(v) && !mesh.is_isolated(v)) interior_.push_back(v.idx());
  }
}

double WrinkleEnergy::energy(const Eigen::MatrixX3d& positions, const std::vector<int>& vertices) const {
  const int n = num_vertices();
  check_rows("positions", positions.rows(), n);
  const std::vector<int>& subset = vertices.empty() ? interior_ : vertices;
  double e = 0.0;
  for (std::size_t k = 0; k < subset.size(); ++k) {
    const int i = subset[k];
    if (i < 0 || i >= n)
      throw ArgumentError("wrinkle energy: vertex " + std::to_string(i) + " (entry " + std::to_string(k) +
                          ") is out of range; the mesh has " + std::to_string(n) + " vertices");
    const int begin = offsets_[static_cast<std::size_t>(i)];
    const int end = offsets_[static_cast<std::size_t>(i) + 1];
    Eigen::RowVector3d lap = -static_cast<double>(end - begin) * positions.row(i);
    for (int j = begin; j < end; ++j) lap += positions.row(neighbours_[static_cast<std::size_t>(j)]);
    e += lap.squaredNorm();
  }
  return e;
}

double WrinkleEnergy::ratio(const Eigen::MatrixX3d& model, const Eigen::MatrixX3d& reference,
                            const std::vector<int>& vertices) const {
  const double kept = energy(model, vertices);
  const double full = energy(reference, vertices);
  if (full == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return kept / full;
}

std::vector<int> vertices_with_mode(const QuadMesh& mesh, int mode, bool interior_only) {
  const std::vector<int> modes = get_modes(mesh);
  std::vector<int> out;
  for (auto v : mesh.vertices()) {
    if (modes[static_cast<std::size_t>(v.idx())] != mode) continue;
    if (interior_only && (mesh.is_boundary(v) || mesh.is_isolated(v))) continue;
    out.push_back(v.idx());
  }
  return out;
}

}  // namespace mrcloth
