#include "bend_partners.h"

#include "errors.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <tuple>
#include <unordered_map>

namespace mrcloth {
namespace {

// A record corner (or the corner edge starting there): record index, corner k.
struct Corner {
  int record = -1;
  int k = 0;
};

// A directed corner edge of one level, or (with to = -1) a corner vertex of one level.
struct LevelKey {
  int level;
  int from;
  int to;
  bool operator==(const LevelKey& o) const { return level == o.level && from == o.from && to == o.to; }
};

struct LevelKeyHash {
  std::size_t operator()(const LevelKey& key) const {
    std::uint64_t h = static_cast<std::uint32_t>(key.level);
    h = h * 0x9E3779B97F4A7C15ull + static_cast<std::uint32_t>(key.from);
    h = h * 0x9E3779B97F4A7C15ull + static_cast<std::uint32_t>(key.to);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// A pair before deduplication, with the two records that produced it: when a
// vertex pair is produced more than once, the lowest (first, second) wins,
// which is "the first record pair in forest order".
struct Candidate {
  BendPair pair;
  int first = -1;
  int second = -1;
};

// What the pass over the forest needs: who sits on the other side of every
// directed corner edge, and how many records of a level share a corner vertex.
struct ForestIndex {
  std::unordered_map<LevelKey, Corner, LevelKeyHash> edge;  ///< (level, p, q) -> record whose corner edge k is p->q
  std::unordered_map<LevelKey, int, LevelKeyHash> corner_count;  ///< (level, p, -1) -> records with corner p
};

int corner(const QuadRecord& q, int k) { return q.corners[static_cast<std::size_t>(k & 3)]; }

void validate_forest(const std::vector<QuadRecord>& forest, std::size_t n_vertices) {
  for (std::size_t r = 0; r < forest.size(); ++r) {
    const QuadRecord& q = forest[r];
    if (q.level < 1)
      throw ArgumentError("quad record " + std::to_string(r) + " has level " + std::to_string(q.level) +
                          "; levels start at 1");
    for (int c : q.corners)
      if (c < 0 || static_cast<std::size_t>(c) >= n_vertices)
        throw ArgumentError("quad record " + std::to_string(r) + " names corner vertex " + std::to_string(c) +
                            ", outside [0, " + std::to_string(n_vertices) + ")");
  }
}

ForestIndex index_forest(const std::vector<QuadRecord>& forest) {
  ForestIndex index;
  index.edge.reserve(forest.size() * 4);
  index.corner_count.reserve(forest.size() * 2);
  for (std::size_t r = 0; r < forest.size(); ++r) {
    const QuadRecord& q = forest[r];
    for (int k = 0; k < 4; ++k) {
      // try_emplace keeps the first record of a (never expected) duplicate directed edge.
      index.edge.try_emplace({q.level, corner(q, k), corner(q, k + 1)}, Corner{static_cast<int>(r), k});
      ++index.corner_count[{q.level, corner(q, k), -1}];
    }
  }
  return index;
}

// The record of the same level across corner edge k of `record` (which runs
// p -> q there): the one whose corner edge runs q -> p. Its `k` is the corner
// holding q. Returns record -1 when there is none.
Corner across_edge(const ForestIndex& index, const std::vector<QuadRecord>& forest, int record, int k) {
  const QuadRecord& q = forest[static_cast<std::size_t>(record)];
  const auto it = index.edge.find({q.level, corner(q, k + 1), corner(q, k)});
  return it == index.edge.end() ? Corner{} : it->second;
}

void add_candidate(std::vector<Candidate>& out, int a, int b, int via, int level, bool diagonal, int r1, int r2) {
  if (a == b) return;  // only on degenerate closed strips; a vertex is not its own partner
  Candidate c;
  c.pair = BendPair{std::min(a, b), std::max(a, b), via, level, diagonal};
  c.first = std::min(r1, r2);
  c.second = std::max(r1, r2);
  out.push_back(c);
}

// F = (p, q, r, s) from its corner k, G = (q, p, t, u) from its corner holding
// q: s and t are the neighbours of p off the shared edge, r and u those of q,
// so (s, t) and (r, u) run straight across the edge along the grid lines.
void grid_line_pairs(const std::vector<QuadRecord>& forest, Corner f, Corner g, std::vector<Candidate>& out) {
  const QuadRecord& F = forest[static_cast<std::size_t>(f.record)];
  const QuadRecord& G = forest[static_cast<std::size_t>(g.record)];
  const int p = corner(F, f.k), q = corner(F, f.k + 1), r = corner(F, f.k + 2), s = corner(F, f.k + 3);
  const int t = corner(G, g.k + 2), u = corner(G, g.k + 3);
  add_candidate(out, s, t, p, F.level, false, f.record, g.record);
  add_candidate(out, r, u, q, F.level, false, f.record, g.record);
}

// Walks the fan of same-level records around corner `start.k` of `start.record`
// by crossing the edge from that corner to the next one, four times. Returns
// the four corners in fan order, or record -1 in slot 0 when the walk does not
// close after exactly four distinct records.
std::array<Corner, 4> closed_fan(const ForestIndex& index, const std::vector<QuadRecord>& forest, Corner start) {
  std::array<Corner, 4> fan{};
  Corner at = start;
  for (int step = 0; step < 4; ++step) {
    fan[static_cast<std::size_t>(step)] = at;
    const Corner next = across_edge(index, forest, at.record, at.k);
    if (next.record < 0) return {};
    at = Corner{next.record, (next.k + 1) & 3};  // the next record's corner holding the same vertex
  }
  const bool closes = at.record == start.record && at.k == start.k;
  const bool distinct = fan[0].record != fan[2].record && fan[1].record != fan[3].record;
  if (!closes || !distinct) return {};
  return fan;
}

void diagonal_pairs(const ForestIndex& index, const std::vector<QuadRecord>& forest, std::vector<Candidate>& out) {
  for (std::size_t r = 0; r < forest.size(); ++r) {
    const QuadRecord& q = forest[r];
    for (int k = 0; k < 4; ++k) {
      const int p = corner(q, k);
      if (index.corner_count.at({q.level, p, -1}) != 4) continue;
      const auto fan = closed_fan(index, forest, Corner{static_cast<int>(r), k});
      if (fan[0].record < 0) continue;
      // Each fan is seen from all four records: emit it once, from its lowest one.
      bool lowest = true, any_active = false;
      for (const Corner& c : fan) {
        lowest = lowest && c.record >= static_cast<int>(r);
        any_active = any_active || forest[static_cast<std::size_t>(c.record)].active != 0;
      }
      if (!lowest || !any_active) continue;
      for (int d = 0; d < 2; ++d) {
        const Corner a = fan[static_cast<std::size_t>(d)], b = fan[static_cast<std::size_t>(d + 2)];
        const int opposite_a = corner(forest[static_cast<std::size_t>(a.record)], a.k + 2);
        const int opposite_b = corner(forest[static_cast<std::size_t>(b.record)], b.k + 2);
        add_candidate(out, opposite_a, opposite_b, p, q.level, true, a.record, b.record);
      }
    }
  }
}

void all_grid_line_pairs(const ForestIndex& index, const std::vector<QuadRecord>& forest, std::vector<Candidate>& out) {
  for (std::size_t r = 0; r < forest.size(); ++r)
    for (int k = 0; k < 4; ++k) {
      const Corner g = across_edge(index, forest, static_cast<int>(r), k);
      // Each record pair is found from both sides: take it from the lower one.
      if (g.record <= static_cast<int>(r)) continue;
      if (!forest[r].active && !forest[static_cast<std::size_t>(g.record)].active) continue;
      grid_line_pairs(forest, Corner{static_cast<int>(r), k}, g, out);
    }
}

// Sorts by (i, j), then by the defining record pair in forest order, and keeps
// the first candidate of each vertex pair. The sort is stable so a record pair
// that yields one vertex pair twice keeps its first.
std::vector<BendPair> first_of_each_pair(std::vector<Candidate> candidates) {
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.pair.i, a.pair.j, a.first, a.second) < std::tie(b.pair.i, b.pair.j, b.first, b.second);
  });
  std::vector<BendPair> pairs;
  pairs.reserve(candidates.size());
  for (const Candidate& c : candidates)
    if (pairs.empty() || pairs.back().i != c.pair.i || pairs.back().j != c.pair.j) pairs.push_back(c.pair);
  return pairs;
}

}  // namespace

std::vector<BendPair> bend_pairs(const QuadMesh& mesh) {
  const std::vector<QuadRecord>& forest = quadtree(mesh);
  validate_forest(forest, mesh.n_vertices());
  const ForestIndex index = index_forest(forest);
  std::vector<Candidate> candidates;
  candidates.reserve(forest.size() * 4);
  all_grid_line_pairs(index, forest, candidates);
  diagonal_pairs(index, forest, candidates);
  return first_of_each_pair(std::move(candidates));
}

std::vector<std::vector<int>> bend_partners(const QuadMesh& mesh) {
  std::vector<std::vector<int>> partners(mesh.n_vertices());
  for (const BendPair& p : bend_pairs(mesh)) {
    partners[static_cast<std::size_t>(p.i)].push_back(p.j);
    partners[static_cast<std::size_t>(p.j)].push_back(p.i);
  }
  for (auto& list : partners) std::sort(list.begin(), list.end());
  return partners;
}

}  // namespace mrcloth
