#include "dynamics_model.h"

#include "mesh_ops/bend_partners.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/lumped_mass.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>
#include <utility>

namespace mrcloth {
namespace {

std::uint64_t pair_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

double level_scale(double alpha, int level) { return std::exp2(alpha * (level - 1)); }

class SpringSet {
 public:
  explicit SpringSet(const Positions& rest) : rest_(rest) {}
  void add(int i, int j, double k, SpringKind kind, int level) {
    if (!seen_.emplace(pair_key(i, j), static_cast<int>(springs_.size())).second) return;
    Spring s;
    s.i = std::min(i, j);
    s.j = std::max(i, j);
    s.rest = (rest_.row(i) - rest_.row(j)).norm();
    s.stiffness = k;
    s.kind = kind;
    s.level = level;
    springs_.push_back(s);
  }
  std::vector<Spring> take() { return std::move(springs_); }

 private:
  const Positions& rest_;
  std::unordered_map<std::uint64_t, int> seen_;
  std::vector<Spring> springs_;
};

// None when `stopped` says so, between the stretch and shear springs, the
// bend pairs (the longest part on a large mesh) and the bend springs.
std::optional<std::vector<Spring>> build_springs(const QuadMesh& mesh, const Positions& rest, const DynamicsOptions& o,
                                                 const std::function<bool()>& stopped) {
  const Material& m = o.material;
  SpringSet set(rest);
  const auto& forest = quadtree(mesh);
  // Stretch first, then shear, then bend: a pair that is both (impossible on
  // a quad mesh without degenerate faces) keeps the stiffer role.
  for (const QuadRecord& q : forest) {
    if (!q.active) continue;
    for (int k = 0; k < 4; ++k)
      set.add(q.corners[k], q.corners[(k + 1) % 4], m.stretch_stiffness * level_scale(o.alpha, q.level),
              SpringKind::stretch, q.level);
  }
  for (const QuadRecord& q : forest) {
    if (!q.active) continue;
    const double k = m.shear_stiffness * level_scale(o.alpha, q.level);
    set.add(q.corners[0], q.corners[2], k, SpringKind::shear, q.level);
    set.add(q.corners[1], q.corners[3], k, SpringKind::shear, q.level);
  }
  if (stopped()) return std::nullopt;
  const std::vector<BendPair> bends = bend_pairs(mesh);
  if (stopped()) return std::nullopt;
  for (const BendPair& b : bends)
    set.add(b.i, b.j, m.bend_stiffness * level_scale(o.alpha_bend, b.level), SpringKind::bend, b.level);
  std::vector<Spring> springs = set.take();
  if (o.bend_model == BendModel::second_difference) {
    // Each pair through the middle bend_pairs gives it (its first record pair's).
    std::unordered_map<std::uint64_t, int> via;
    for (const BendPair& b : bend_pairs(mesh)) via.emplace(pair_key(b.i, b.j), b.via);
    for (Spring& s : springs) {
      if (s.kind != SpringKind::bend) continue;
      s.via = via.at(pair_key(s.i, s.j));
      s.rest = (rest.row(s.i) - 2.0 * rest.row(s.via) + rest.row(s.j)).norm();
    }
  }
  return std::optional<std::vector<Spring>>(std::move(springs));
}

void check_options(const QuadMesh& mesh, const DynamicsOptions& o, const std::vector<char>& hanging) {
  const Material& m = o.material;
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(m.areal_density)) throw ArgumentError("material areal density must be > 0 kg/m^2");
  if (!positive(m.stretch_stiffness) || !positive(m.shear_stiffness) || !(m.bend_stiffness >= 0.0))
    throw ArgumentError("material stiffnesses must be > 0 N/m (bend >= 0)");
  if (!(m.damping >= 0.0)) throw ArgumentError("material damping must be >= 0 1/s");
  if (!(m.stretch_limit > 0.0)) throw ArgumentError("material stretch limit must be > 0");
  if (!std::isfinite(o.alpha) || !std::isfinite(o.alpha_bend)) throw ArgumentError("alpha must be finite");
  const int n = static_cast<int>(mesh.n_vertices());
  for (int v : o.pinned) {
    if (v < 0 || v >= n)
      throw ArgumentError("pinned vertex " + std::to_string(v) + " is out of range; the mesh has " +
                          std::to_string(n) + " vertices");
    if (hanging[v])
      throw ArgumentError("pinned vertex " + std::to_string(v) +
                          " is a hanging node (T-node) whose position its parents decide; pin its parents instead");
  }
}

/// Sorts the vertices into pinned, hanging (T-node) and free, each list in
/// vertex order, and returns each vertex's index in its list (-1 in the
/// others): {free_index, pinned_index}.
std::pair<std::vector<int>, std::vector<int>> classify_vertices(DynamicsModel& model, const std::vector<int>& pins,
                                                                 const std::vector<char>& hanging) {
  const int n = model.num_vertices;
  std::vector<char> pinned(n, 0);
  for (int v : pins) pinned[v] = 1;
  std::vector<int> free_index(n, -1), pinned_index(n, -1);
  for (int v = 0; v < n; ++v) {
    if (pinned[v]) {
      pinned_index[v] = static_cast<int>(model.pinned_vertices.size());
      model.pinned_vertices.push_back(v);
    } else if (hanging[v]) {
      model.hanging_vertices.push_back(v);
    } else {
      free_index[v] = static_cast<int>(model.free_vertices.size());
      model.free_vertices.push_back(v);
    }
  }
  return {std::move(free_index), std::move(pinned_index)};
}

/// Per vertex, its position's weights on the free and on the pinned
/// vertices (column -> weight): a hanging vertex's is the mean of its
/// parents'. Parents have lower indices than the midpoints they made, so
/// one forward sweep composes chains.
struct VertexRows {
  std::vector<std::map<int, double>> free, pinned;
};

VertexRows compose_rows(const QuadMesh& mesh, const Layers& layers, const std::vector<int>& free_index,
                        const std::vector<int>& pinned_index) {
  const int n = static_cast<int>(free_index.size());
  VertexRows rows{std::vector<std::map<int, double>>(n), std::vector<std::map<int, double>>(n)};
  for (int v = 0; v < n; ++v) {
    if (free_index[v] >= 0) {
      rows.free[v][free_index[v]] = 1.0;
    } else if (pinned_index[v] >= 0) {
      rows.pinned[v][pinned_index[v]] = 1.0;
    } else {
      const OpenMesh::Vec2i p = mesh.property(layers.parents, mesh.vertex_handle(v));
      for (int parent : {p[0], p[1]}) {
        for (const auto& [col, w] : rows.free[parent]) rows.free[v][col] += 0.5 * w;
        for (const auto& [col, w] : rows.pinned[parent]) rows.pinned[v][col] += 0.5 * w;
      }
    }
  }
  return rows;
}

/// S, P and the per-vertex stencils from the composed rows.
void set_selection(DynamicsModel& model, const VertexRows& rows) {
  const int n = model.num_vertices;
  std::vector<Eigen::Triplet<double>> s_entries, p_entries;
  model.stencil.resize(n);
  for (int v = 0; v < n; ++v) {
    for (const auto& [col, w] : rows.free[v]) {
      s_entries.emplace_back(v, col, w);
      model.stencil[v].push_back({col, w});
    }
    for (const auto& [col, w] : rows.pinned[v]) p_entries.emplace_back(v, col, w);
  }
  model.S.resize(n, static_cast<int>(model.free_vertices.size()));
  model.S.setFromTriplets(s_entries.begin(), s_entries.end());
  model.P.resize(n, static_cast<int>(model.pinned_vertices.size()));
  model.P.setFromTriplets(p_entries.begin(), p_entries.end());
}

/// The free vertices' masses; throws ArgumentError for a free vertex with
/// none (no face).
void set_free_masses(DynamicsModel& model) {
  model.free_mass.resize(static_cast<int>(model.free_vertices.size()));
  for (std::size_t f = 0; f < model.free_vertices.size(); ++f) model.free_mass[f] = model.mass[model.free_vertices[f]];
  for (std::size_t f = 0; f < model.free_vertices.size(); ++f)
    if (!(model.free_mass[f] > 0.0))
      throw ArgumentError("free vertex " + std::to_string(model.free_vertices[f]) +
                          " has no mass (an isolated vertex?); every simulated vertex needs a face");
}

}  // namespace

DynamicsModel build_dynamics(const QuadMesh& mesh, const DynamicsOptions& options) {
  return std::move(*build_dynamics(mesh, options, {}));
}

std::optional<DynamicsModel> build_dynamics(const QuadMesh& mesh, const DynamicsOptions& options,
                                            const std::function<bool()>& keep_going) {
  const auto stopped = [&] { return keep_going && !keep_going(); };
  const Layers layers = get_layers(mesh);
  const int n = static_cast<int>(mesh.n_vertices());
  std::vector<char> hanging(n, 0);
  for (auto v : mesh.vertices()) hanging[v.idx()] = mesh.property(layers.hanging, v) ? 1 : 0;
  check_options(mesh, options, hanging);

  DynamicsModel model;
  model.num_vertices = n;
  model.material = options.material;
  model.alpha = options.alpha;
  model.alpha_bend = options.alpha_bend;
  model.bend_model = options.bend_model;
  model.rest.resize(n, 3);
  for (auto v : mesh.vertices())
    for (int c = 0; c < 3; ++c) model.rest(v.idx(), c) = mesh.point(v)[c];
  const std::vector<double> mass = lumped_mass(mesh, options.material.areal_density);
  model.mass = Eigen::Map<const Eigen::VectorXd>(mass.data(), n);
  std::optional<std::vector<Spring>> springs = build_springs(mesh, model.rest, options, stopped);
  if (!springs || stopped()) return std::nullopt;
  model.springs = std::move(*springs);
  for (const QuadRecord& q : quadtree(mesh))
    if (q.active) model.corners.push_back(q.corners);

  const auto [free_index, pinned_index] = classify_vertices(model, options.pinned, hanging);
  const VertexRows rows = compose_rows(mesh, layers, free_index, pinned_index);
  if (stopped()) return std::nullopt;
  set_selection(model, rows);
  set_free_masses(model);
  return std::optional<DynamicsModel>(std::move(model));
}

Positions full_positions(const DynamicsModel& model, const Positions& free, const Positions& pinned) {
  Positions x = model.S * free;
  if (model.P.cols() > 0) x += model.P * pinned;
  return x;
}

Positions free_rows(const DynamicsModel& model, const Positions& full) {
  Positions q(static_cast<int>(model.free_vertices.size()), 3);
  for (std::size_t f = 0; f < model.free_vertices.size(); ++f) q.row(f) = full.row(model.free_vertices[f]);
  return q;
}

Positions pinned_rows(const DynamicsModel& model, const Positions& full) {
  Positions p(static_cast<int>(model.pinned_vertices.size()), 3);
  for (std::size_t k = 0; k < model.pinned_vertices.size(); ++k) p.row(k) = full.row(model.pinned_vertices[k]);
  return p;
}

QuadMesh mesh_at_positions(const QuadMesh& mesh, const Positions& x) {
  if (x.rows() != static_cast<Eigen::Index>(mesh.n_vertices()))
    throw ArgumentError("positions have " + std::to_string(x.rows()) + " rows; the mesh has " +
                        std::to_string(mesh.n_vertices()) + " vertices");
  QuadMesh moved = copy_mesh(mesh);
  for (const auto v : moved.vertices()) moved.set_point(v, OpenMesh::Vec3d(x(v.idx(), 0), x(v.idx(), 1), x(v.idx(), 2)));
  return moved;
}

double max_stretch(const DynamicsModel& model, const Positions& full) { return most_stretched(model, full).strain; }

StretchPeak most_stretched(const DynamicsModel& model, const Positions& full) {
  StretchPeak peak;
  // A vertex with no free term in its stencil (S row) follows the pins alone.
  const auto follows_pins = [&](int v) {
    return static_cast<std::size_t>(v) < model.stencil.size() && model.stencil[static_cast<std::size_t>(v)].empty();
  };
  for (const Spring& s : model.springs) {
    if (s.kind != SpringKind::stretch) continue;
    const double excess = (full.row(s.i) - full.row(s.j)).norm() - s.rest;
    const double strain = excess / s.rest;
    const bool pinned = follows_pins(s.i) && follows_pins(s.j);
    double& part = pinned ? peak.pinned_strain : peak.cloth_strain;
    part = std::max(part, strain);
    if (strain > peak.strain) {
      peak.strain = strain;
      peak.i = s.i;
      peak.j = s.j;
    }
    if (strain >= 1.0) peak.tear_opening = std::max(peak.tear_opening, excess);
  }
  return peak;
}

}  // namespace mrcloth
