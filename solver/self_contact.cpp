#include "self_contact.h"

#include "mesh_ops/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

namespace mrcloth {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kMinSine = 0.05;
// A crossing found this close outside an element (in barycentric or edge
// parameter) still counts: a point passing exactly over an edge between two
// triangles must be caught by one of them.
constexpr double kCrossingSlack = 1e-3;

// Pairs farther beside each other than this (in barycentric or edge
// parameter) at both ends of a step are not gathered: in one step a point
// does not pass half a triangle sideways and through it.
constexpr double kBeside = 0.5;

signed char sign_of(double v) { return v > 0.0 ? 1 : v < 0.0 ? -1 : 0; }
constexpr std::uint64_t kEdgeEdge = std::uint64_t{1} << 63;

std::uint64_t pair_key(bool edge_edge, int a, int b) {
  return (edge_edge ? kEdgeEdge : 0) | (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}
int first_of(std::uint64_t key) { return static_cast<int>((key & ~kEdgeEdge) >> 32); }
int second_of(std::uint64_t key) { return static_cast<int>(key & 0xffffffffu); }

bool share_support(const std::vector<int>& a, const std::vector<int>& b) {
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i == *j) return true;
    if (*i < *j) ++i; else ++j;
  }
  return false;
}

std::vector<int> merged(std::initializer_list<const std::vector<int>*> sets) {
  std::vector<int> out;
  for (const auto* s : sets) out.insert(out.end(), s->begin(), s->end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// A vertex over a triangle: the barycentric coordinates of its projection
// onto the triangle's plane, the unit normal and the signed distance.
struct OverTriangle {
  double u = 0, v = 0, w = 0;  // weights of a, b, c
  Vec3 normal{0, 0, 0};
  double distance = 0.0;
  bool valid = false;  // false for a degenerate triangle
  bool inside() const { return u >= 0.0 && v >= 0.0 && w >= 0.0; }
  bool near_over() const { return u >= -kBeside && v >= -kBeside && w >= -kBeside; }
};

OverTriangle over_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  OverTriangle o;
  const Vec3 ab = b - a, ac = c - a, n = ab.cross(ac);
  const double area2 = n.squaredNorm();
  if (!(area2 > 0.0)) return o;
  const Vec3 ap = p - a;
  o.v = ap.cross(ac).dot(n) / area2;
  o.w = ab.cross(ap).dot(n) / area2;
  o.u = 1.0 - o.v - o.w;
  o.normal = n / std::sqrt(area2);
  o.distance = ap.dot(o.normal);
  o.valid = true;
  return o;
}

// Two edges p0-p1 and q0-q1: the parameters of their closest points on the
// infinite lines, and the unit common normal (from the first to the second).
struct EdgeEdge {
  double s = 0, t = 0;
  Vec3 normal{0, 0, 0};
  double distance = 0.0;  // (q(t) - p(s)) . normal
  bool valid = false;     // false for (nearly) parallel edges
  bool inside() const { return s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0; }
  bool near_over() const { return s > -kBeside && s < 1.0 + kBeside && t > -kBeside && t < 1.0 + kBeside; }
};

EdgeEdge edge_edge(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  EdgeEdge e;
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const Vec3 n = d1.cross(d2);
  const double n2 = n.squaredNorm();
  // Within 3 degrees of parallel the common normal turns over under small
  // motions (a pair of nearly parallel edges a few centimetres apart would
  // seem to swap sides); the edges' end points meet the triangles instead.
  if (!(n2 > kMinSine * kMinSine * d1.squaredNorm() * d2.squaredNorm())) return e;
  const double a = d1.dot(d1), b = d1.dot(d2), c = d2.dot(d2), d = d1.dot(r), f = d2.dot(r);
  const double denominator = a * c - b * b;
  e.s = (b * f - c * d) / denominator;
  e.t = (a * f - b * d) / denominator;
  e.normal = n / std::sqrt(n2);
  e.distance = (q0 - p0).dot(e.normal);
  e.valid = true;
  return e;
}

struct Box {
  Vec3 lo, hi;
};

Box box_of(const Positions& x0, const Positions& x1, std::initializer_list<int> vertices, double pad) {
  Box b{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  for (int v : vertices) {
    const Vec3 a = x0.row(v).transpose(), c = x1.row(v).transpose();
    b.lo = b.lo.cwiseMin(a).cwiseMin(c);
    b.hi = b.hi.cwiseMax(a).cwiseMax(c);
  }
  b.lo.array() -= pad;
  b.hi.array() += pad;
  return b;
}

bool overlap(const Box& a, const Box& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

// A uniform grid over boxes: cell keys pack three 21-bit signed indices.
struct CellRange {
  Eigen::Array3i lo, hi;
};
CellRange cells_of(const Box& b, double cell) {
  CellRange r;
  for (int c = 0; c < 3; ++c) {
    r.lo[c] = static_cast<int>(std::floor(b.lo[c] / cell));
    r.hi[c] = static_cast<int>(std::floor(b.hi[c] / cell));
  }
  return r;
}
std::uint64_t cell_key(int i, int j, int k) {
  const auto part = [](int v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffffu; };
  return (part(i) << 42) | (part(j) << 21) | part(k);
}

// Boxes filed by cell; `candidates` calls back each pair (query, item) once:
// in the lowest cell both boxes cover. The cells the boxes span are indexed
// densely (an array of runs, filled in item order) when they are few, as on
// any garment; else by a hash of their keys. Either visits the same pairs in
// the same order.
class BoxGrid {
 public:
  BoxGrid(const std::vector<Box>& items, double cell) : items_(items), cell_(cell) {
    ranges_.reserve(items.size());
    Eigen::Array3i lo = Eigen::Array3i::Constant(std::numeric_limits<int>::max());
    Eigen::Array3i hi = Eigen::Array3i::Constant(std::numeric_limits<int>::min());
    for (std::size_t i = 0; i < items.size(); ++i) {
      const CellRange r = cells_of(items[i], cell);
      ranges_.push_back(r);
      if (!filed(r)) continue;
      lo = lo.min(r.lo);
      hi = hi.max(r.hi);
    }
    if ((lo <= hi).all() && ((hi - lo + 1).cast<double>().prod() <= kMaxDenseCells)) {
      build_dense(lo, hi);
      return;
    }
    std::vector<std::pair<std::uint64_t, int>> entries;  // (cell, item), sorted
    each_filed_cell([&](int x, int y, int z, int item) { entries.emplace_back(cell_key(x, y, z), item); });
    std::sort(entries.begin(), entries.end());
    hashed_items_.reserve(entries.size());
    for (const auto& entry : entries) hashed_items_.push_back(entry.second);
    cells_.reserve(entries.size());
    for (std::size_t i = 0; i < entries.size();) {
      std::size_t j = i;
      while (j < entries.size() && entries[j].first == entries[i].first) ++j;
      cells_.emplace(entries[i].first, std::make_pair(static_cast<int>(i), static_cast<int>(j)));
      i = j;
    }
  }
  /// Visits every item after `after` whose box overlaps `query`.
  template <class F>
  void candidates(const Box& query, F&& visit, int after = -1) const {
    const CellRange r = cells_of(query, cell_);
    if (!filed(r)) return;
    const auto visit_run = [&](int x, int y, int z, const int* first, const int* last) {
      for (const int* it = first; it != last; ++it) {
        if (*it <= after) continue;
        const Box& item = items_[static_cast<std::size_t>(*it)];
        if (!overlap(query, item)) continue;
        // Only in the lowest cell common to both, so each pair once.
        const CellRange& ir = ranges_[static_cast<std::size_t>(*it)];
        if (std::max(r.lo[0], ir.lo[0]) != x || std::max(r.lo[1], ir.lo[1]) != y || std::max(r.lo[2], ir.lo[2]) != z)
          continue;
        visit(*it);
      }
    };
    if (dense_) {
      // Cells outside the indexed block hold nothing.
      const Eigen::Array3i from = r.lo.max(lo_), to = r.hi.min(lo_ + dims_ - 1);
      for (int x = from[0]; x <= to[0]; ++x)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int z = from[2]; z <= to[2]; ++z) {
            const std::size_t c = dense_index(x, y, z);
            visit_run(x, y, z, dense_items_.data() + dense_start_[c], dense_items_.data() + dense_start_[c + 1]);
          }
      return;
    }
    for (int x = r.lo[0]; x <= r.hi[0]; ++x)
      for (int y = r.lo[1]; y <= r.hi[1]; ++y)
        for (int z = r.lo[2]; z <= r.hi[2]; ++z) {
          const auto cell = cells_.find(cell_key(x, y, z));
          if (cell == cells_.end()) continue;
          visit_run(x, y, z, hashed_items_.data() + cell->second.first, hashed_items_.data() + cell->second.second);
        }
  }

 private:
  /// At most this many cells are indexed densely (4 bytes each).
  static constexpr double kMaxDenseCells = 1 << 21;
  /// A runaway element (non-finite or huge) is not filed.
  static bool filed(const CellRange& r) { return !((r.hi - r.lo) > 64).any(); }
  std::size_t dense_index(int x, int y, int z) const {
    return (static_cast<std::size_t>(x - lo_[0]) * static_cast<std::size_t>(dims_[1]) +
            static_cast<std::size_t>(y - lo_[1])) * static_cast<std::size_t>(dims_[2]) +
           static_cast<std::size_t>(z - lo_[2]);
  }
  /// A counting sort of (cell, item) by cell, items in order within a cell.
  void build_dense(const Eigen::Array3i& lo, const Eigen::Array3i& hi) {
    dense_ = true;
    lo_ = lo;
    dims_ = hi - lo + 1;
    const std::size_t count = static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(dims_[1]) *
                              static_cast<std::size_t>(dims_[2]);
    dense_start_.assign(count + 1, 0);
    each_filed_cell([&](int x, int y, int z, int) { ++dense_start_[dense_index(x, y, z) + 1]; });
    for (std::size_t c = 0; c < count; ++c) dense_start_[c + 1] += dense_start_[c];
    dense_items_.resize(static_cast<std::size_t>(dense_start_[count]));
    std::vector<int> next(dense_start_.begin(), dense_start_.end() - 1);
    each_filed_cell([&](int x, int y, int z, int item) {
      dense_items_[static_cast<std::size_t>(next[dense_index(x, y, z)]++)] = item;
    });
  }
  /// f(x, y, z, item) for every cell of every filed item, items in order.
  template <class F>
  void each_filed_cell(F&& f) const {
    for (std::size_t i = 0; i < ranges_.size(); ++i) {
      const CellRange& r = ranges_[i];
      if (!filed(r)) continue;
      for (int x = r.lo[0]; x <= r.hi[0]; ++x)
        for (int y = r.lo[1]; y <= r.hi[1]; ++y)
          for (int z = r.lo[2]; z <= r.hi[2]; ++z) f(x, y, z, static_cast<int>(i));
    }
  }

  const std::vector<Box>& items_;
  double cell_;
  std::vector<CellRange> ranges_;  // per item
  // Dense: per cell of the block lo_ .. lo_ + dims_ - 1, its run of items.
  bool dense_ = false;
  Eigen::Array3i lo_{0, 0, 0}, dims_{0, 0, 0};
  std::vector<int> dense_start_, dense_items_;
  // Hashed: the items sorted by cell, and per cell its run in them.
  std::vector<int> hashed_items_;
  std::unordered_map<std::uint64_t, std::pair<int, int>> cells_;
};

double mean_edge_length(const ContactSurface& s, const Positions& x) {
  double sum = 0.0;
  for (const auto& e : s.edges) sum += (x.row(e[0]) - x.row(e[1])).norm();
  return s.edges.empty() ? 0.0 : sum / static_cast<double>(s.edges.size());
}

// One contact as a linear constraint: sum_k weight_k x_k along `normal` at
// least `gap`, over up to four full vertices.
struct Constraint {
  int vertex[4];
  double weight[4];
  int count;
};

}  // namespace

ContactSurface contact_surface(const DynamicsModel& model) {
  ContactSurface s;
  const int n = model.num_vertices;
  for (const auto& q : model.corners) {
    if (q[3] < 0) {
      s.triangles.push_back({q[0], q[1], q[2]});
    } else {
      s.triangles.push_back({q[0], q[1], q[2]});
      s.triangles.push_back({q[0], q[2], q[3]});
    }
  }
  std::set<std::pair<int, int>> edges;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      edges.emplace(std::min(a, b), std::max(a, b));
    }
  for (const auto& [a, b] : edges) s.edges.push_back({a, b});
  // Supports: free and pinned vertices are their own; a T-node's are the
  // vertices its stencil (free) and pinned part reach.
  s.support.assign(static_cast<std::size_t>(n), {});
  for (int v = 0; v < n; ++v) {
    auto& sup = s.support[static_cast<std::size_t>(v)];
    for (const StencilTerm& t : model.stencil[static_cast<std::size_t>(v)])
      sup.push_back(model.free_vertices[static_cast<std::size_t>(t.free)]);
  }
  for (int col = 0; col < model.P.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(model.P, col); it; ++it)
      s.support[static_cast<std::size_t>(it.row())].push_back(model.pinned_vertices[static_cast<std::size_t>(col)]);
  for (auto& sup : s.support) {
    std::sort(sup.begin(), sup.end());
    sup.erase(std::unique(sup.begin(), sup.end()), sup.end());
  }
  s.edge_support.reserve(s.edges.size());
  for (const auto& e : s.edges) s.edge_support.push_back(merged({&s.support[e[0]], &s.support[e[1]]}));
  return s;
}

int count_self_crossings(const ContactSurface& s, const Positions& x, WorkerPool* pool) {
  std::vector<Box> triangles;
  triangles.reserve(s.triangles.size());
  for (const auto& t : s.triangles) triangles.push_back(box_of(x, x, {t[0], t[1], t[2]}, 0.0));
  // Cells twice an edge: the shared skirt refined twice was counted about
  // a quarter sooner than with cells one edge wide (the same count).
  const double cell = std::max(2.0 * mean_edge_length(s, x), 1e-6);
  const BoxGrid grid(triangles, cell);
  std::vector<int> part_crossings(pool ? static_cast<std::size_t>(pool->workers()) : 1, 0);
  const auto count_edges = [&](int part, std::size_t begin, std::size_t end) {
    int& crossings = part_crossings[static_cast<std::size_t>(part)];
    for (std::size_t edge = begin; edge < end; ++edge) {
      const auto& e = s.edges[edge];
      const std::vector<int>& edge_support = s.edge_support[edge];
      const Vec3 p = x.row(e[0]).transpose(), q = x.row(e[1]).transpose();
      grid.candidates(box_of(x, x, {e[0], e[1]}, 0.0), [&](int ti) {
        const auto& t = s.triangles[static_cast<std::size_t>(ti)];
        // The plane test first: it rejects most candidates, and costs less
        // than comparing supports.
        const Vec3 a = x.row(t[0]).transpose(), b = x.row(t[1]).transpose(), c = x.row(t[2]).transpose();
        const Vec3 n = (b - a).cross(c - a);
        const double dp = (p - a).dot(n), dq = (q - a).dot(n);
        if (!(dp * dq < 0.0)) return;
        for (int k = 0; k < 3; ++k)
          if (share_support(edge_support, s.support[t[k]])) return;
        const Vec3 hit = p + (q - p) * (dp / (dp - dq));
        const OverTriangle o = over_triangle(hit, a, b, c);
        if (o.valid && o.u > 0.0 && o.v > 0.0 && o.w > 0.0) ++crossings;
      });
    }
  };
  if (pool) pool->run(s.edges.size(), count_edges);
  else count_edges(0, 0, s.edges.size());
  int crossings = 0;
  for (const int part : part_crossings) crossings += part;
  return crossings;
}

double sheet_neighbourhood(const SelfContactOptions& options) {
  return options.neighbourhood < 0.0 ? 2.0 * (options.thickness + options.reach) : options.neighbourhood;
}

std::vector<std::vector<int>> sheet_supports(const DynamicsModel& model, const ContactSurface& surface,
                                             double radius) {
  const auto n = static_cast<std::size_t>(model.num_vertices);
  std::vector<std::vector<int>> adjacent(n);
  for (const auto& e : surface.edges) {
    adjacent[static_cast<std::size_t>(e[0])].push_back(e[1]);
    adjacent[static_cast<std::size_t>(e[1])].push_back(e[0]);
  }
  std::vector<std::vector<int>> near(n);
  std::vector<int> seen(n, -1), reached;
  for (std::size_t v = 0; v < n; ++v) {
    if (surface.support[v].empty()) continue;
    // Breadth first from v, through vertices within radius of it.
    reached.assign(1, static_cast<int>(v));
    seen[v] = static_cast<int>(v);
    for (std::size_t k = 0; k < reached.size(); ++k)
      for (const int w : adjacent[static_cast<std::size_t>(reached[k])]) {
        const auto wi = static_cast<std::size_t>(w);
        if (seen[wi] == static_cast<int>(v) || !((model.rest.row(w) - model.rest.row(static_cast<Eigen::Index>(v))).norm() < radius))
          continue;
        seen[wi] = static_cast<int>(v);
        reached.push_back(w);
      }
    std::vector<int>& supports = near[v];
    for (const int u : reached)
      supports.insert(supports.end(), surface.support[static_cast<std::size_t>(u)].begin(),
                      surface.support[static_cast<std::size_t>(u)].end());
    std::sort(supports.begin(), supports.end());
    supports.erase(std::unique(supports.begin(), supports.end()), supports.end());
  }
  return near;
}

void SelfContact::precompute(const DynamicsModel& model, const SelfContactOptions& options) {
  if (!(options.thickness >= 0.0) || !std::isfinite(options.thickness))
    throw ArgumentError("self-contact thickness must be >= 0 metres");
  if (!(options.reach >= 0.0) || !std::isfinite(options.reach))
    throw ArgumentError("self-contact reach must be >= 0 metres");
  if (!std::isfinite(options.neighbourhood))
    throw ArgumentError("self-contact neighbourhood must be a finite number of metres (< 0: the default)");
  if (options.passes < 1) throw ArgumentError("self-contact passes must be >= 1");
  model_ = &model;
  options_ = options;
  pairs_.clear();
  memory_.clear();
  if (options.thickness <= 0.0) return;
  surface_ = contact_surface(model);
  // Twice a widened element: of 0.5x, 1x and 2x this was fastest on the
  // MakeHuman trousers (the same pairs, fewer cells visited per query).
  cell_ = 2.0 * (mean_edge_length(surface_, model.rest) + options.thickness + options.reach);
  near_support_ = sheet_supports(model, surface_, sheet_neighbourhood(options));
}

void SelfContact::gather(const Positions& x0, const Positions& x1) {
  memory_.swap(pairs_);  // the last step's pairs, with the sides its projections settled on
  pairs_.clear();
  if (!enabled()) return;
  start_ = x0;
  const ContactSurface& s = surface_;
  const double near = options_.thickness + options_.reach;
  // Swept boxes; only the querying element's is widened by `near`.
  std::vector<Box> triangle_boxes, edge_boxes;
  triangle_boxes.reserve(s.triangles.size());
  edge_boxes.reserve(s.edges.size());
  for (const auto& t : s.triangles) triangle_boxes.push_back(box_of(x0, x1, {t[0], t[1], t[2]}, 0.0));
  for (const auto& e : s.edges) edge_boxes.push_back(box_of(x0, x1, {e[0], e[1]}, 0.0));
  const std::vector<std::vector<int>>& edge_support = s.edge_support;

  // A pair is kept when it is near at either end of the step: over (or
  // beside by at most kBeside of) the element, and within `near` of it or
  // on the other side of it at the end.
  const auto keep = [&](std::uint64_t key, bool overlapping, bool beside, double d0, double d1) {
    const signed char raw = sign_of(d0);
    if (raw == 0 || !beside) return;
    if (sign_of(d1) == raw && std::min(std::abs(d0), std::abs(d1)) > near) return;
    signed char side = raw;
    if (overlapping) {  // a side it overlapped with at the last step's end holds
      const auto it = std::lower_bound(memory_.begin(), memory_.end(), key,
                                       [](const Pair& p, std::uint64_t k) { return p.key < k; });
      if (it != memory_.end() && it->key == key) side = it->side;
    }
    pairs_.push_back({key, side, raw});
  };
  const auto corner = [](const Positions& x, int v) -> Vec3 { return x.row(v).transpose(); };

  // The query's sheet neighbourhood (its own support included) marked with
  // a tag of its own, so a candidate's supports are looked up, not merged
  // (on the skirt refined twice a neighbourhood holds about 90 vertices).
  int tag = 0;
  std::vector<int> near_mark(static_cast<std::size_t>(model_->num_vertices), -1);  // per vertex: the last query near it
  const auto mark_near = [&](int v) {
    for (const int u : near_support_[static_cast<std::size_t>(v)]) near_mark[static_cast<std::size_t>(u)] = tag;
  };
  const auto near_query = [&](const std::vector<int>& support) {
    return std::any_of(support.begin(), support.end(),
                       [&](int u) { return near_mark[static_cast<std::size_t>(u)] == tag; });
  };

  const BoxGrid triangles(triangle_boxes, cell_);
  for (int v = 0; v < model_->num_vertices; ++v) {
    if (near_support_[static_cast<std::size_t>(v)].empty()) continue;
    ++tag;
    mark_near(v);
    triangles.candidates(box_of(x0, x1, {v}, near), [&](int ti) {
      const auto& t = s.triangles[static_cast<std::size_t>(ti)];
      for (int k = 0; k < 3; ++k)
        if (near_query(s.support[t[k]])) return;
      const OverTriangle o0 = over_triangle(corner(x0, v), corner(x0, t[0]), corner(x0, t[1]), corner(x0, t[2]));
      const OverTriangle o1 = over_triangle(corner(x1, v), corner(x1, t[0]), corner(x1, t[1]), corner(x1, t[2]));
      if (!o0.valid || !o1.valid) return;
      keep(pair_key(false, v, ti), o0.inside(), o0.near_over() || o1.near_over(), o0.distance, o1.distance);
    });
  }
  const BoxGrid edges(edge_boxes, cell_);
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const auto& first = s.edges[e];
    Box query = edge_boxes[e];
    query.lo.array() -= near;
    query.hi.array() += near;
    ++tag;
    mark_near(first[0]);
    mark_near(first[1]);
    edges.candidates(query, [&](int other) {  // each pair once, from its lower edge (the widening is symmetric)
      if (near_query(edge_support[static_cast<std::size_t>(other)])) return;
      const auto& second = s.edges[static_cast<std::size_t>(other)];
      const EdgeEdge e0 = edge_edge(corner(x0, first[0]), corner(x0, first[1]), corner(x0, second[0]), corner(x0, second[1]));
      const EdgeEdge e1 = edge_edge(corner(x1, first[0]), corner(x1, first[1]), corner(x1, second[0]), corner(x1, second[1]));
      if (!e0.valid || !e1.valid) return;
      keep(pair_key(true, static_cast<int>(e), other), e0.inside(), e0.near_over() || e1.near_over(), e0.distance,
           e1.distance);
    }, static_cast<int>(e));
  }
  std::sort(pairs_.begin(), pairs_.end(), [](const Pair& a, const Pair& b) { return a.key < b.key; });
}

namespace {

/// Projects one step's gathered pairs, one at a time, on free positions
/// `q` (#free x 3): each pair that overlaps is pushed `gap` metres apart on
/// its side, through the stencils of the model's vertices. `start` holds the
/// full positions at the step's start (#V x 3), `pinned_part` P p (#V x 3).
class PairProjector {
 public:
  PairProjector(const DynamicsModel& model, Positions& q, const Positions& pinned_part, const Positions& start,
                double gap)
      : m_(model), q_(q), pinned_part_(pinned_part), start_(start), gap_(gap) {}

  /// A vertex over a triangle (full ids); `side` is the pair's side to
  /// keep, which a pair that went round the triangle takes anew; `raw` its
  /// sign at the step's start.
  void project_vertex_triangle(int a, const std::array<int, 3>& t, signed char& side, signed char raw) {
    const int ids[4] = {a, t[0], t[1], t[2]};
    for (int k = 0; k < 4; ++k) now_[k] = position(ids[k]);
    const OverTriangle o = over_triangle(now_[0], now_[1], now_[2], now_[3]);
    if (!o.valid || !o.near_over()) return;
    OverTriangle c;
    Vec3 x[4];  // at the sign change, when there was one
    const Use use_as = decide(side, raw, sign_of(o.distance), o.inside(), [&] {
      at_sign_change(ids, [](const Vec3* y) { return (y[2] - y[1]).cross(y[3] - y[1]).dot(y[0] - y[1]); }, raw, x);
      c = over_triangle(x[0], x[1], x[2], x[3]);
      return c.valid && c.u >= -kCrossingSlack && c.v >= -kCrossingSlack && c.w >= -kCrossingSlack;
    });
    if (use_as == Use::skip) return;
    OverTriangle use = o;
    if (use_as == Use::at_crossing) {  // pull it back through where it passed
      use.u = std::max(c.u, 0.0);
      use.v = std::max(c.v, 0.0);
      use.w = std::max(c.w, 0.0);
      const double sum = use.u + use.v + use.w;
      use.u /= sum;
      use.v /= sum;
      use.w /= sum;
      use.distance = (now_[0] - (use.u * now_[1] + use.v * now_[2] + use.w * now_[3])).dot(o.normal);
    }
    const double violation = gap_ - side * use.distance;
    if (violation <= 0.0) return;
    // side * normal . (p - (u a + v b + w c)) >= gap
    apply({{a, t[0], t[1], t[2]}, {1.0, -use.u, -use.v, -use.w}, 4}, side * o.normal, violation);
  }

  /// Two edges (full ids); `side` and `raw` as for project_vertex_triangle.
  void project_edge_edge(const std::array<int, 2>& e1, const std::array<int, 2>& e2, signed char& side, signed char raw) {
    const int ids[4] = {e1[0], e1[1], e2[0], e2[1]};
    for (int k = 0; k < 4; ++k) now_[k] = position(ids[k]);
    const EdgeEdge ee = edge_edge(now_[0], now_[1], now_[2], now_[3]);
    if (!ee.valid || !ee.near_over()) return;
    EdgeEdge c;
    Vec3 x[4];  // at the sign change, when there was one
    const Use use_as = decide(side, raw, sign_of(ee.distance), ee.inside(), [&] {
      at_sign_change(ids, [](const Vec3* y) { return (y[2] - y[0]).dot((y[1] - y[0]).cross(y[3] - y[2])); }, raw, x);
      c = edge_edge(x[0], x[1], x[2], x[3]);
      return c.valid && c.s > -kCrossingSlack && c.s < 1.0 + kCrossingSlack && c.t > -kCrossingSlack &&
             c.t < 1.0 + kCrossingSlack;
    });
    if (use_as == Use::skip) return;
    EdgeEdge use = ee;
    if (use_as == Use::at_crossing) {  // pull it back through where it passed
      use.s = std::clamp(c.s, 0.0, 1.0);
      use.t = std::clamp(c.t, 0.0, 1.0);
    }
    const Vec3 between = (now_[2] + use.t * (now_[3] - now_[2])) - (now_[0] + use.s * (now_[1] - now_[0]));
    const double violation = gap_ - side * between.dot(ee.normal);
    if (violation <= 0.0) return;
    // side * normal . (q(t) - p(s)) >= gap
    apply({{e2[0], e2[1], e1[0], e1[1]}, {1.0 - use.t, use.t, -(1.0 - use.s), -use.s}, 4}, side * ee.normal,
          violation);
  }

  /// The largest single correction so far, metres.
  double largest() const { return largest_; }

 private:
  // How a pair is projected: not at all, as it is now, or where it passed
  // through. A pair whose sign changed this step passed through the other
  // element (it keeps its side, pulled back where it passed when it no
  // longer overlaps) or round it (it takes the new side); any other pair
  // is projected only while it overlaps.
  enum class Use { skip, as_is, at_crossing };
  template <typename PassedThrough>
  static Use decide(signed char& side, signed char raw, signed char sign_now, bool overlapping,
                    PassedThrough&& passed_through) {
    if (sign_now == 0 || sign_now == raw) return overlapping ? Use::as_is : Use::skip;
    if (passed_through()) return overlapping ? Use::as_is : Use::at_crossing;
    if (!overlapping) return Use::skip;
    side = sign_now;
    return Use::as_is;
  }

  Vec3 position(int v) const {
    Vec3 x = pinned_part_.row(v).transpose();
    for (const StencilTerm& t : m_.stencil[static_cast<std::size_t>(v)]) x += t.weight * q_.row(t.free).transpose();
    return x;
  }

  // The four points of a pair at fraction t of the way from the step's start.
  void at(double t, Vec3* out) const {
    for (int k = 0; k < 4; ++k) out[k] = then_[k] + t * (now_[k] - then_[k]);
  }

  // The four points when the pair's sign changed this step (bisection: the
  // sign is continuous along the straight paths, and 30 halvings put it
  // within 1e-9 of the step).
  template <typename SignedVolume>
  void at_sign_change(const int* ids, SignedVolume&& signed_volume, signed char start_sign, Vec3* x) {
    for (int k = 0; k < 4; ++k) then_[k] = start_.row(ids[k]).transpose();
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 30; ++k) {
      const double mid = 0.5 * (lo + hi);
      at(mid, x);
      if (sign_of(signed_volume(x)) == start_sign) lo = mid; else hi = mid;
    }
    at(0.5 * (lo + hi), x);
  }

  // Moves the constraint's free vertices along `normal` (terms merged per
  // free vertex), inverse-mass weighted.
  void apply(const Constraint& c, const Vec3& normal, double violation) {
    terms_.clear();
    for (int k = 0; k < c.count; ++k)
      for (const StencilTerm& t : m_.stencil[static_cast<std::size_t>(c.vertex[k])]) {
        const double w = c.weight[k] * t.weight;
        auto it = std::find_if(terms_.begin(), terms_.end(), [&](const auto& term) { return term.first == t.free; });
        if (it == terms_.end()) terms_.emplace_back(t.free, w);
        else it->second += w;
      }
    const auto inverse_mass = [&](int f) { return 1.0 / m_.free_mass[f]; };
    double denominator = 0.0;
    for (const auto& [f, w] : terms_) denominator += w * w * inverse_mass(f);
    if (!(denominator > 0.0)) return;
    // At most a thickness per projection: a pinch the body will undo (cloth
    // between two limbs) then costs a little each round instead of pushes
    // that become velocity (uncapped, pushes grew to 8 cm and the skirt flew
    // apart within 30 steps).
    // No vertex moves more than that either (a held triangle whose only free
    // corner carries a small weight would otherwise throw it far).
    violation = std::min(violation, gap_);
    double lambda = violation / denominator, farthest = 0.0;
    for (const auto& [f, w] : terms_) farthest = std::max(farthest, std::abs(lambda * w * inverse_mass(f)));
    if (farthest > gap_) lambda *= gap_ / farthest;
    for (const auto& [f, w] : terms_) q_.row(f) += (lambda * w * inverse_mass(f)) * normal.transpose();
    largest_ = std::max(largest_, violation);
  }

  const DynamicsModel& m_;
  Positions& q_;
  const Positions& pinned_part_;
  const Positions& start_;
  const double gap_;
  double largest_ = 0.0;
  std::vector<std::pair<int, double>> terms_;  // one constraint's, in free coordinates
  Vec3 now_[4], then_[4];
};

}  // namespace

double SelfContact::project(Positions& q, const Positions& pinned_part) {
  if (!enabled() || pairs_.empty()) return 0.0;
  PairProjector projector(*model_, q, pinned_part, start_, options_.thickness);
  for (int pass = 0; pass < options_.passes; ++pass) {
    for (Pair& pair : pairs_) {
      const int a = first_of(pair.key), b = second_of(pair.key);
      if (!(pair.key & kEdgeEdge))
        projector.project_vertex_triangle(a, surface_.triangles[static_cast<std::size_t>(b)], pair.side, pair.raw);
      else
        projector.project_edge_edge(surface_.edges[static_cast<std::size_t>(a)], surface_.edges[static_cast<std::size_t>(b)],
                            pair.side, pair.raw);
    }
  }
  return projector.largest();
}

}  // namespace mrcloth
