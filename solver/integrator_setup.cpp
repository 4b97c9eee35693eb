#include "integrator_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iterator>
#include <limits>
#include <queue>

namespace mrcloth {
namespace {

void add_spring(std::vector<Eigen::Triplet<double>>& t, int i, int j, double k) {
  t.emplace_back(i, i, k);
  t.emplace_back(j, j, k);
  t.emplace_back(i, j, -k);
  t.emplace_back(j, i, -k);
}

// Spring Laplacian entries in full coordinates; see implicit_integrator.h for bend.
Eigen::SparseMatrix<double> full_stiffness_laplacian(const DynamicsModel& model,
                                                     const std::vector<int>& bend_middle) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(model.springs.size() * 8);
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    const Spring& sp = model.springs[s];
    // A second-difference spring's |xi - 2 xvia + xj|^2 is bounded the same way.
    const int middle = sp.via >= 0 ? sp.via : bend_middle[s];
    if (sp.kind != SpringKind::bend || middle < 0) {
      add_spring(t, sp.i, sp.j, sp.stiffness);
    } else {
      add_spring(t, sp.i, middle, 2.0 * sp.stiffness);
      add_spring(t, middle, sp.j, 2.0 * sp.stiffness);
    }
  }
  Eigen::SparseMatrix<double> L(model.num_vertices, model.num_vertices);
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

// The vertex between a bend spring's ends: the common neighbour along the
// stretch/shear springs closest to their midpoint at rest.
std::vector<int> bend_middles(const DynamicsModel& model) {
  std::vector<std::vector<int>> neighbours(model.num_vertices);
  for (const Spring& s : model.springs) {
    if (s.kind == SpringKind::bend) continue;
    neighbours[s.i].push_back(s.j);
    neighbours[s.j].push_back(s.i);
  }
  for (auto& n : neighbours) std::sort(n.begin(), n.end());
  std::vector<int> middle(model.springs.size(), -1);
  for (std::size_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
    if (s.kind != SpringKind::bend) continue;
    const Eigen::RowVector3d mid = 0.5 * (model.rest.row(s.i) + model.rest.row(s.j));
    double best = std::numeric_limits<double>::infinity();
    const auto& a = neighbours[s.i];
    const auto& b = neighbours[s.j];
    std::vector<int> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    for (int c : common) {
      const double d = (model.rest.row(c) - mid).squaredNorm();
      if (d < best) {
        best = d;
        middle[k] = c;
      }
    }
  }
  return middle;
}

// Per vertex, the vertices joined to it by stretch springs, in spring order.
std::vector<std::vector<int>> stretch_neighbours(const DynamicsModel& model) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(model.num_vertices));
  for (const Spring& s : model.springs)
    if (s.kind == SpringKind::stretch) {
      neighbours[static_cast<std::size_t>(s.i)].push_back(s.j);
      neighbours[static_cast<std::size_t>(s.j)].push_back(s.i);
    }
  return neighbours;
}

}  // namespace

Eigen::SparseMatrix<double> system_matrix(const DynamicsModel& model, double h) {
  const Eigen::SparseMatrix<double> L = full_stiffness_laplacian(model, bend_middles(model));
  Eigen::SparseMatrix<double> Q = model.S.transpose() * L * model.S;
  Eigen::SparseMatrix<double> M(Q.rows(), Q.cols());
  std::vector<Eigen::Triplet<double>> diag;
  for (int f = 0; f < Q.rows(); ++f) diag.emplace_back(f, f, model.free_mass[f] / (h * h));
  M.setFromTriplets(diag.begin(), diag.end());
  Q += M;
  return Q;
}

std::vector<int> direct_free_indices(const DynamicsModel& model) {
  std::vector<char> has_pinned_part(model.num_vertices, 0);
  for (int col = 0; col < model.P.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(model.P, col); it; ++it) has_pinned_part[it.row()] = 1;
  std::vector<int> direct_free(model.num_vertices, -1);
  for (int v = 0; v < model.num_vertices; ++v) {
    const auto& st = model.stencil[v];
    if (st.size() == 1 && st[0].weight == 1.0 && !has_pinned_part[v]) direct_free[v] = st[0].free;
  }
  return direct_free;
}

// Mass-weighted projections (exponent 1) conserve momentum, but on a
// multi-resolution mesh a coarse vertex is up to 16 times as heavy as a
// finest one, takes a sixteenth of each correction, and the sweeps then
// converge so slowly that the finest cloth between coarse vertices tears
// (the shared skirt's adaptive meshes on the real walks: see README,
// Limiter weights); on a uniform mesh the masses, and so the weights, are
// nearly equal whatever the exponent.
Eigen::VectorXd projection_weights(const Eigen::VectorXd& free_mass, double mass_exponent) {
  Eigen::VectorXd weight(free_mass.size());
  for (Eigen::Index f = 0; f < weight.size(); ++f) weight[f] = 1.0 / std::pow(free_mass[f], mass_exponent);
  return weight;
}

// Stretch springs in breadth-first order over the spring graph from vertex
// 0: Gauss-Seidel then carries a correction across the cloth in a sweep or
// two, whatever order refinement created the vertices in.
std::vector<int> wavefront_order(const DynamicsModel& model) {
  std::vector<std::vector<int>> incident(model.num_vertices);
  std::vector<int> stretch;
  for (std::size_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
    if (s.kind != SpringKind::stretch) continue;
    incident[s.i].push_back(static_cast<int>(k));
    incident[s.j].push_back(static_cast<int>(k));
    stretch.push_back(static_cast<int>(k));
  }
  std::vector<int> rank(model.num_vertices, -1);
  std::vector<int> queue;
  queue.reserve(model.num_vertices);
  for (int seed = 0; seed < model.num_vertices; ++seed) {  // every connected piece
    if (rank[seed] >= 0) continue;
    rank[seed] = static_cast<int>(queue.size());
    queue.push_back(seed);
    for (std::size_t head = queue.size() - 1; head < queue.size(); ++head)
      for (int k : incident[queue[head]]) {
        const Spring& s = model.springs[k];
        const int other = s.i == queue[head] ? s.j : s.i;
        if (rank[other] >= 0) continue;
        rank[other] = static_cast<int>(queue.size());
        queue.push_back(other);
      }
  }
  const auto key = [&](int k) {
    const Spring& s = model.springs[k];
    return std::make_pair(std::min(rank[s.i], rank[s.j]), std::max(rank[s.i], rank[s.j]));
  };
  std::sort(stretch.begin(), stretch.end(), [&](int a, int b) { return key(a) < key(b); });
  return stretch;
}

// Merged per free vertex: the projection's denominator is the squared norm
// of the constraint's gradient, which counts a shared vertex once with its
// net weight (a T-node to its parent: 1/2 - 1, not 1/4 + 1).
std::vector<std::pair<int, double>> merged_stencil_terms(const DynamicsModel& model, const Spring& s) {
  std::vector<std::pair<int, double>> merged;
  const auto add = [&](int free, double weight) {
    for (auto& term : merged)
      if (term.first == free) {
        term.second += weight;
        return;
      }
    merged.emplace_back(free, weight);
  };
  for (const StencilTerm& t : model.stencil[s.i]) add(t.free, t.weight);
  for (const StencilTerm& t : model.stencil[s.j]) add(t.free, -t.weight);
  return merged;
}

double chain_spectral_radius(const DynamicsModel& model) {
  if (model.pinned_vertices.empty()) return 0.0;
  const std::vector<std::vector<int>> neighbours = stretch_neighbours(model);
  std::vector<int> links(model.num_vertices, -1), queue;
  for (int v : model.pinned_vertices) {
    links[v] = 0;
    queue.push_back(v);
  }
  int longest = 0;
  for (std::size_t head = 0; head < queue.size(); ++head)
    for (int w : neighbours[queue[head]])
      if (links[w] < 0) {
        links[w] = links[queue[head]] + 1;
        longest = std::max(longest, links[w]);
        queue.push_back(w);
      }
  const double c = std::cos(M_PI / (longest + 1));
  return c * c;
}

// A spring from T-node h (halfway between parents a and b) to c on the
// finer side, and c's neighbours ca and cb along the row beside the coarse
// edge (joined by stretch springs to c and to a or b): the row whose bulge
// says where the fine cloth would put h.
std::vector<FineRow> t_node_fine_rows(const DynamicsModel& model) {
  const std::vector<std::vector<int>> neighbours = stretch_neighbours(model);
  const auto joined = [&](int u, int v) {
    const std::vector<int>& n = neighbours[static_cast<std::size_t>(u)];
    return std::find(n.begin(), n.end(), v) != n.end();
  };
  std::vector<FineRow> rows;
  for (std::size_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
    if (s.kind != SpringKind::stretch) continue;
    for (const auto& [h, c] : {std::make_pair(s.i, s.j), std::make_pair(s.j, s.i)}) {
      const std::vector<StencilTerm>& parents = model.stencil[static_cast<std::size_t>(h)];
      // Halfway between two free parents (not a T-node on a T-node's edge).
      if (parents.size() != 2 || parents[0].weight != 0.5 || parents[1].weight != 0.5) continue;
      const int a = model.free_vertices[static_cast<std::size_t>(parents[0].free)];
      const int b = model.free_vertices[static_cast<std::size_t>(parents[1].free)];
      if (c == a || c == b) continue;  // along the coarse edge: its own spring's constraint
      // The row's ends: c's neighbours joined to a and to b. Where the fine
      // side turns a corner they are T-nodes on the next coarse edge (two
      // thirds of the shared skirt's across springs).
      int ca = -1, cb = -1;
      for (const int w : neighbours[static_cast<std::size_t>(c)]) {
        if (w == h || w == a || w == b) continue;
        if (joined(w, a)) ca = w;
        if (joined(w, b)) cb = w;
      }
      if (ca >= 0 && cb >= 0 && ca != cb) {
        rows.push_back({static_cast<int>(k), h, c, ca, cb});
        break;
      }
    }
  }
  return rows;
}

// Each free vertex's tether to its nearest pinned vertex over the cloth
// (Dijkstra along the stretch and shear springs' rest lengths, which is at
// least the geodesic distance, so the tether never binds cloth that is
// within its stretch limit).
std::vector<ImplicitIntegrator::Tether> tethers_to_pins(const DynamicsModel& model, const std::vector<int>& direct_free) {
  std::vector<ImplicitIntegrator::Tether> tethers;
  if (model.pinned_vertices.empty()) return tethers;
  std::vector<std::vector<std::pair<int, double>>> edges(model.num_vertices);
  for (const Spring& s : model.springs) {
    if (s.kind == SpringKind::bend) continue;
    edges[s.i].emplace_back(s.j, s.rest);
    edges[s.j].emplace_back(s.i, s.rest);
  }
  std::vector<double> distance(model.num_vertices, std::numeric_limits<double>::infinity());
  std::vector<int> source(model.num_vertices, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int v : model.pinned_vertices) {
    distance[v] = 0.0;
    source[v] = v;
    queue.emplace(0.0, v);
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    for (const auto& [w, length] : edges[v])
      if (d + length < distance[w]) {
        distance[w] = d + length;
        source[w] = source[v];
        queue.emplace(distance[w], w);
      }
  }
  const double limit = 1.0 + model.material.stretch_limit;
  for (int v = 0; v < model.num_vertices; ++v)
    if (direct_free[v] >= 0 && source[v] >= 0 && distance[v] > 0.0)
      tethers.push_back({direct_free[v], source[v], limit * distance[v]});
  return tethers;
}

// The rows of `points` (#P x 3) in Morton order of their positions: points
// checked one after another then meet the same part of the scene, whose
// tree stays in cache (the refined skirt's first check on the skinned body:
// 101-103 ms per frame against 106-108 in index order, alternating runs).
std::vector<int> spatial_order(const Positions& points) {
  std::vector<int> order(static_cast<std::size_t>(points.rows()));
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  if (points.rows() == 0) return order;
  const Eigen::RowVector3d lo = points.colwise().minCoeff(), hi = points.colwise().maxCoeff();
  const Eigen::RowVector3d extent = (hi - lo).cwiseMax(1e-12);
  const auto spread = [](std::uint64_t v) {  // 21 bits to every third of 63
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  std::vector<std::uint64_t> code(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    std::uint64_t key = 0;
    for (int c = 0; c < 3; ++c) {
      const double unit = (points(static_cast<Eigen::Index>(k), c) - lo(c)) / extent(c);
      key |= spread(static_cast<std::uint64_t>(std::clamp(unit, 0.0, 1.0) * 2097151.0)) << c;
    }
    code[k] = key;
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return code[static_cast<std::size_t>(a)] < code[static_cast<std::size_t>(b)]; });
  return order;
}

}  // namespace mrcloth
