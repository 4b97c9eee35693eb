// Bend partners (bend_pairs / bend_partners) against brute-force oracles on
// regular grids and tubes, and hand-worked sets at refinement interfaces and
// irregular vertices.
#include "mesh_invariants.h"
#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/bend_partners.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/uniform_refine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

namespace mrcloth {
namespace {

/// A pair as compared in these tests: (i, j, via, diagonal), i < j.
using Pair = std::tuple<int, int, int, bool>;
using PairSet = std::set<Pair>;

Pair line(int a, int b, int via) { return {std::min(a, b), std::max(a, b), via, false}; }
Pair diag(int a, int b, int via) { return {std::min(a, b), std::max(a, b), via, true}; }

PairSet as_set(const std::vector<BendPair>& pairs) {
  PairSet set;
  for (const BendPair& p : pairs) set.insert({p.i, p.j, p.via, p.diagonal});
  return set;
}

/// Brute force over every vertex pair of an nx x ny grid, by grid coordinates
/// only: two steps along a row or column, or two diagonal steps whose middle
/// vertex is interior. Vertex (i, j) is j * (nx + 1) + i as in make_grid.
PairSet grid_oracle(int nx, int ny) {
  const int n = (nx + 1) * (ny + 1);
  const auto vid = [&](int i, int j) { return j * (nx + 1) + i; };
  PairSet set;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const int ai = a % (nx + 1), aj = a / (nx + 1), bi = b % (nx + 1), bj = b / (nx + 1);
      const int di = bi - ai, dj = bj - aj;
      const int mi = (ai + bi) / 2, mj = (aj + bj) / 2;
      const bool straight = (std::abs(di) == 2 && dj == 0) || (di == 0 && std::abs(dj) == 2);
      const bool diagonal = std::abs(di) == 2 && std::abs(dj) == 2;
      const bool interior_middle = mi > 0 && mi < nx && mj > 0 && mj < ny;
      if (straight) set.insert(line(a, b, vid(mi, mj)));
      if (diagonal && interior_middle) set.insert(diag(a, b, vid(mi, mj)));
    }
  return set;
}

/// Vertex of `mesh` at exactly (x, y, z), or -1.
int vertex_at(const QuadMesh& mesh, double x, double y, double z = 0.0) {
  for (auto v : mesh.vertices())
    if (mesh.point(v) == QuadMesh::Point(x, y, z)) return v.idx();
  return -1;
}

/// A disc of `valence` quads around vertex 0: spokes e_k = 1 + k, rim corners
/// f_k = 1 + valence + k, quad k = (0, e_k, f_k, e_{k+1}).
QuadMesh make_fan(int valence) {
  QuadMesh mesh;
  mesh.add_vertex(QuadMesh::Point(0, 0, 0));
  for (int k = 0; k < valence; ++k) {
    const double a = 2.0 * M_PI * k / valence;
    mesh.add_vertex(QuadMesh::Point(std::cos(a), std::sin(a), 0));
  }
  for (int k = 0; k < valence; ++k) {
    const double a = 2.0 * M_PI * (k + 0.5) / valence;
    mesh.add_vertex(QuadMesh::Point(1.5 * std::cos(a), 1.5 * std::sin(a), 0));
  }
  const auto e = [&](int k) { return mesh.vertex_handle(1 + (k % valence)); };
  const auto f = [&](int k) { return mesh.vertex_handle(1 + valence + k); };
  for (int k = 0; k < valence; ++k) mesh.add_face(mesh.vertex_handle(0), e(k), f(k), e(k + 1));
  init_forest(mesh);
  return mesh;
}

/// The hand-worked pairs of make_fan: across spoke k, (e_{k-1}, e_{k+1})
/// through the centre and (f_{k-1}, f_k) through e_k; with valence 4 also the
/// two diagonals (f_k, f_{k+2}) through the centre.
PairSet fan_expected(int valence) {
  const auto e = [&](int k) { return 1 + ((k + valence) % valence); };
  const auto f = [&](int k) { return 1 + valence + ((k + valence) % valence); };
  PairSet set;
  for (int k = 0; k < valence; ++k) {
    if (e(k - 1) != e(k + 1)) set.insert(line(e(k - 1), e(k + 1), 0));
    set.insert(line(f(k - 1), f(k), e(k)));
  }
  if (valence == 4) {
    set.insert(diag(f(0), f(2), 0));
    set.insert(diag(f(1), f(3), 0));
  }
  return set;
}

TEST(BendPairs, RegularGridsMatchTheBruteForceOracle) {
  const std::array<std::array<int, 2>, 7> sizes = {{{1, 1}, {2, 2}, {3, 4}, {5, 5}, {4, 1}, {1, 3}, {6, 3}}};
  for (const auto& [nx, ny] : sizes) {
    SCOPED_TRACE("grid " + std::to_string(nx) + "x" + std::to_string(ny));
    const QuadMesh mesh = test::make_grid(nx, ny);
    const std::vector<BendPair> pairs = bend_pairs(mesh);
    EXPECT_EQ(as_set(pairs), grid_oracle(nx, ny));
    // Rows, columns and two diagonals per interior vertex, counted independently.
    const std::size_t expected = static_cast<std::size_t>(
        std::max(0, nx - 1) * (ny + 1) + std::max(0, ny - 1) * (nx + 1) + 2 * std::max(0, nx - 1) * std::max(0, ny - 1));
    EXPECT_EQ(pairs.size(), expected);
    for (const BendPair& p : pairs) EXPECT_EQ(p.level, 1);
  }
}

TEST(BendPairs, ExactCountsOnSmallGrids) {
  EXPECT_EQ(bend_pairs(test::make_grid(1, 1)).size(), 0u);
  EXPECT_EQ(bend_pairs(test::make_grid(2, 2)).size(), 8u);   // 3 rows + 3 columns + 2 diagonals
  EXPECT_EQ(bend_pairs(test::make_grid(3, 4)).size(), 34u);  // 10 + 12 + 12
  EXPECT_EQ(bend_pairs(test::make_grid(5, 5)).size(), 80u);  // 24 + 24 + 32
}

TEST(BendPairs, OutputIsSortedUniqueAndViaIsTheMiddleVertex) {
  const QuadMesh mesh = test::make_grid(5, 4);
  const std::vector<BendPair> pairs = bend_pairs(mesh);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const BendPair& p = pairs[k];
    EXPECT_LT(p.i, p.j);
    if (k > 0) {
      EXPECT_LT(std::make_pair(pairs[k - 1].i, pairs[k - 1].j), std::make_pair(p.i, p.j));
    }
    const auto mid = (mesh.point(mesh.vertex_handle(p.i)) + mesh.point(mesh.vertex_handle(p.j))) * 0.5;
    EXPECT_EQ(mesh.point(mesh.vertex_handle(p.via)), mid) << "pair " << p.i << "-" << p.j;
  }
}

TEST(BendPairs, InteriorVerticesFarFromTheBoundaryHaveEightPartners) {
  const int nx = 6, ny = 5;
  const QuadMesh mesh = test::make_grid(nx, ny);
  const auto partners = bend_partners(mesh);
  const auto vid = [&](int i, int j) { return j * (nx + 1) + i; };
  int checked = 0;
  for (int j = 2; j <= ny - 2; ++j)
    for (int i = 2; i <= nx - 2; ++i) {
      const std::vector<int> expected = {vid(i - 2, j - 2), vid(i, j - 2),     vid(i + 2, j - 2),
                                         vid(i - 2, j),     vid(i + 2, j),     vid(i - 2, j + 2),
                                         vid(i, j + 2),     vid(i + 2, j + 2)};
      EXPECT_EQ(partners[static_cast<std::size_t>(vid(i, j))], expected) << "vertex (" << i << "," << j << ")";
      ++checked;
    }
  EXPECT_EQ(checked, 6);
  // A corner only reaches along its two boundary lines and one diagonal.
  EXPECT_EQ(partners[0], (std::vector<int>{2, vid(0, 2), vid(2, 2)}));
}

TEST(BendPairs, UniformRefinementEqualsTheFinerGrid) {
  QuadMesh refined = test::make_grid(2, 2);
  uniform_refine(refined, 1);
  const QuadMesh fine = test::make_grid(4, 4, 0.5);
  ASSERT_EQ(refined.n_vertices(), fine.n_vertices());
  // Vertex numbering differs; positions are exact multiples of 0.5 in both.
  std::vector<int> to_fine(refined.n_vertices(), -1);
  for (auto v : refined.vertices()) {
    const auto p = refined.point(v);
    to_fine[static_cast<std::size_t>(v.idx())] = vertex_at(fine, p[0], p[1], p[2]);
    ASSERT_GE(to_fine[static_cast<std::size_t>(v.idx())], 0) << "refined vertex " << v.idx();
  }
  PairSet mapped;
  for (const BendPair& p : bend_pairs(refined)) {
    EXPECT_EQ(p.level, 2) << "level-1 records are all refined, so only level 2 bends";
    const int a = to_fine[static_cast<std::size_t>(p.i)], b = to_fine[static_cast<std::size_t>(p.j)];
    mapped.insert({std::min(a, b), std::max(a, b), to_fine[static_cast<std::size_t>(p.via)], p.diagonal});
  }
  EXPECT_EQ(mapped, as_set(bend_pairs(fine)));
  EXPECT_EQ(mapped.size(), 48u);
}

TEST(BendPairs, TubeClosesAroundEveryRing) {
  const int around = 6, rings = 4;
  const QuadMesh mesh = test::make_tube(around, rings, 0.3, 0.5);
  const auto vid = [&](int i, int j) { return j * around + ((i + around) % around); };
  PairSet expected;
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      expected.insert(line(vid(i - 1, j), vid(i + 1, j), vid(i, j)));  // every ring, boundary rings too
      if (j + 2 < rings) expected.insert(line(vid(i, j), vid(i, j + 2), vid(i, j + 1)));
      if (j >= 1 && j + 1 < rings) {
        expected.insert(diag(vid(i - 1, j - 1), vid(i + 1, j + 1), vid(i, j)));
        expected.insert(diag(vid(i + 1, j - 1), vid(i - 1, j + 1), vid(i, j)));
      }
    }
  const std::vector<BendPair> pairs = bend_pairs(mesh);
  EXPECT_EQ(as_set(pairs), expected);
  // around * rings ring pairs + around * (rings - 2) columns + 2 diagonals per interior vertex.
  EXPECT_EQ(pairs.size(), 24u + 12u + 24u);
  const auto partners = bend_partners(mesh);
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const auto& list = partners[static_cast<std::size_t>(vid(i, j))];
      EXPECT_TRUE(std::binary_search(list.begin(), list.end(), vid(i - 2, j))) << "vertex " << vid(i, j);
      EXPECT_TRUE(std::binary_search(list.begin(), list.end(), vid(i + 2, j))) << "vertex " << vid(i, j);
    }
}

TEST(BendPairs, DuplicatePairsKeepTheFirstRecordPairInForestOrder) {
  // Four quads around: (i-1, i+1) is reached through i and through i+2, and
  // each diagonal through two different vertices. Faces f = 4j + i have
  // corners (i,j), (i,j+1), (i+1,j+1), (i+1,j); vertex (i,j) = 4j + i.
  // Worked by hand: the winner is the candidate whose (lower, higher) record
  // pair is lexicographically smallest.
  const QuadMesh mesh = test::make_tube(4, 3, 0.3, 0.5);
  const PairSet expected = {
      line(0, 2, 1),   // faces (0,1) via 1 beats faces (2,3) via 3
      line(1, 3, 0),   // faces (0,3) via 0 beats faces (1,2) via 2
      line(4, 6, 5),   // faces (0,1) via 5 beats (2,3), (4,5), (6,7)
      line(5, 7, 4),   // faces (0,3) via 4 beats (1,2), (4,7), (5,6)
      line(8, 10, 9),  // faces (4,5) via 9 beats (6,7) via 11
      line(9, 11, 8),  // faces (4,7) via 8 beats (5,6) via 10
      line(0, 8, 4),   line(1, 9, 5), line(2, 10, 6), line(3, 11, 7),
      diag(0, 10, 5),  // faces (0,5) at 5 beat faces (3,6) at 7
      diag(2, 8, 5),   // faces (1,4) at 5 beat faces (2,7) at 7
      diag(1, 11, 4),  // faces (0,7) at 4 beat faces (1,6) at 6
      diag(3, 9, 6),   // faces (2,5) at 6 beat faces (3,4) at 4
  };
  EXPECT_EQ(as_set(bend_pairs(mesh)), expected);
}

// 3x3 grid, only the centre quad (corners 5, 6, 10, 9) refined once:
// modes 3 on those four make its R sum 12 >= 10 while each side quad sums 8.
class RefinedCentre : public ::testing::Test {
 protected:
  void SetUp() override {
    mesh = test::make_grid(3, 3);
    set_modes(mesh, {5, 6, 9, 10}, 3);
    const AdaptiveRefineReport report = adaptive_refine(mesh, {10.0, 2, true});
    ASSERT_EQ(report.faces_refined_per_pass, (std::vector<std::size_t>{1}));
    ASSERT_EQ(report.faces_refined_for_balance, 0u);
    ASSERT_TRUE(test::face_forest_violations(mesh).empty());
    m56 = vertex_at(mesh, 1.5, 1.0);
    m610 = vertex_at(mesh, 2.0, 1.5);
    m109 = vertex_at(mesh, 1.5, 2.0);
    m95 = vertex_at(mesh, 1.0, 1.5);
    centre = vertex_at(mesh, 1.5, 1.5);
    ASSERT_EQ(mesh.n_vertices(), 21u);
    ASSERT_EQ(count_hanging(mesh), 4u);
  }
  QuadMesh mesh;
  int m56 = -1, m610 = -1, m109 = -1, m95 = -1, centre = -1;
};

TEST_F(RefinedCentre, CoarseAndFinePairsAreExactlyTheHandWorkedSet) {
  // Level 1: only the centre record is inactive, so every record pair and
  // every fan has an active member: all 24 pairs of the plain 3x3 grid stay.
  PairSet expected = grid_oracle(3, 3);
  ASSERT_EQ(expected.size(), 24u);
  // Level 2: the centre's four children form a 2x2 grid.
  const PairSet fine = {
      line(5, 6, m56),    line(m95, m610, centre), line(9, 10, m109),
      line(5, 9, m95),    line(m56, m109, centre), line(6, 10, m610),
      diag(5, 10, centre), diag(6, 9, centre),
  };
  expected.insert(fine.begin(), fine.end());
  const std::vector<BendPair> pairs = bend_pairs(mesh);
  EXPECT_EQ(as_set(pairs), expected);
  EXPECT_EQ(pairs.size(), 32u);
  for (const BendPair& p : pairs) EXPECT_EQ(p.level, fine.count({p.i, p.j, p.via, p.diagonal}) ? 2 : 1);
}

TEST_F(RefinedCentre, CoarseNeighbourKeepsItsBendingAcrossTheInterface) {
  // The left quad (4, 5, 9, 8) is active; its level-1 neighbour across edge
  // 5-9 is the refined centre record, which still counts.
  const PairSet pairs = as_set(bend_pairs(mesh));
  EXPECT_EQ(pairs.count(line(4, 6, 5)), 1u);
  EXPECT_EQ(pairs.count(line(8, 10, 9)), 1u);
  // ...and so does every diagonal through a corner of the refined quad.
  EXPECT_EQ(pairs.count(diag(0, 10, 5)), 1u);
  EXPECT_EQ(pairs.count(diag(3, 9, 6)), 1u);
}

TEST(BendPairs, ActiveFaceBesideARefinedOneKeepsPairsOnlyThatRecordPairGives) {
  // 2x1 grid (0 1 2 / 3 4 5), the right quad refined (modes 4 on 2 and 5:
  // right sum 10 >= 8, left sum 4). The level-1 pairs (0,2) and (3,5) come
  // from the one record pair (left active, right refined) and nothing else.
  QuadMesh mesh = test::make_grid(2, 1);
  set_modes(mesh, {2, 5}, 4);
  ASSERT_EQ(adaptive_refine(mesh, {8.0, 2, true}).faces_refined_per_pass, (std::vector<std::size_t>{1}));
  const int m12 = vertex_at(mesh, 1.5, 0.0), m25 = vertex_at(mesh, 2.0, 0.5), m54 = vertex_at(mesh, 1.5, 1.0);
  const int m41 = vertex_at(mesh, 1.0, 0.5), centre = vertex_at(mesh, 1.5, 0.5);
  const PairSet expected = {
      line(0, 2, 1),          line(3, 5, 4),  // level 1, across the interface
      line(1, 2, m12),        line(m41, m25, centre), line(4, 5, m54),
      line(1, 4, m41),        line(m12, m54, centre), line(2, 5, m25),
      diag(1, 5, centre),     diag(2, 4, centre),
  };
  const std::vector<BendPair> pairs = bend_pairs(mesh);
  EXPECT_EQ(as_set(pairs), expected);
  for (const BendPair& p : pairs) EXPECT_EQ(p.level, p.via == 1 || p.via == 4 ? 1 : 2);
}

TEST(BendPairs, IrregularVerticesHaveLinePairsAcrossEveryEdgeAndNoDiagonals) {
  for (int valence : {3, 4, 5, 6}) {
    SCOPED_TRACE("valence " + std::to_string(valence));
    const QuadMesh mesh = make_fan(valence);
    const std::vector<BendPair> pairs = bend_pairs(mesh);
    EXPECT_EQ(as_set(pairs), fan_expected(valence));
    const std::size_t diagonals = static_cast<std::size_t>(
        std::count_if(pairs.begin(), pairs.end(), [](const BendPair& p) { return p.diagonal; }));
    EXPECT_EQ(diagonals, valence == 4 ? 2u : 0u);
  }
  // Hand counts: valence 3 bends (1,2), (1,3), (2,3) through the centre.
  EXPECT_EQ(bend_pairs(make_fan(3)).size(), 6u);
  EXPECT_EQ(bend_pairs(make_fan(4)).size(), 8u);
  EXPECT_EQ(bend_pairs(make_fan(5)).size(), 10u);
}

TEST(BendPairs, FullyRefinedLevelsDoNotBend) {
  // Both records of a pair refined: only their children bend there.
  QuadMesh mesh = test::make_grid(2, 1);
  uniform_refine(mesh, 2);
  for (const BendPair& p : bend_pairs(mesh)) EXPECT_EQ(p.level, 3);
}

TEST(BendPartners, SymmetricAndMatchingBendPairsOnRandomRefinements) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    QuadMesh mesh = test::make_grid(5, 4, 0.5);
    std::uniform_int_distribution<int> mode(1, 4);
    for (auto v : mesh.vertices()) set_modes(mesh, {v.idx()}, mode(rng));
    adaptive_refine(mesh, {8.0, 3, trial % 2 == 0});
    const std::vector<BendPair> pairs = bend_pairs(mesh);
    const auto partners = bend_partners(mesh);
    ASSERT_EQ(partners.size(), mesh.n_vertices());
    std::size_t total = 0;
    for (std::size_t v = 0; v < partners.size(); ++v) {
      const auto& list = partners[v];
      total += list.size();
      EXPECT_TRUE(std::is_sorted(list.begin(), list.end()));
      EXPECT_EQ(std::adjacent_find(list.begin(), list.end()), list.end());
      for (int w : list) {
        const auto& back = partners[static_cast<std::size_t>(w)];
        EXPECT_TRUE(std::binary_search(back.begin(), back.end(), static_cast<int>(v))) << v << " -> " << w;
      }
    }
    EXPECT_EQ(total, 2 * pairs.size());
    for (const BendPair& p : pairs) {
      const auto& list = partners[static_cast<std::size_t>(p.i)];
      EXPECT_TRUE(std::binary_search(list.begin(), list.end(), p.j));
      // A flat grid refined by midpoints: via is exactly halfway, and the
      // pair spans two steps of its level (spacing 0.5 / 2^(level-1)).
      const auto a = mesh.point(mesh.vertex_handle(p.i)), b = mesh.point(mesh.vertex_handle(p.j));
      EXPECT_EQ(mesh.point(mesh.vertex_handle(p.via)), (a + b) * 0.5);
      const double step = 0.5 / std::pow(2.0, p.level - 1);
      EXPECT_DOUBLE_EQ((b - a).norm(), 2.0 * step * (p.diagonal ? std::sqrt(2.0) : 1.0));
    }
  }
}

TEST(BendPairs, MeshWithoutForestOrBadRecordsThrows) {
  QuadMesh plain;
  plain.add_vertex(QuadMesh::Point(0, 0, 0));
  EXPECT_THROW(bend_pairs(plain), ArgumentError);

  QuadMesh mesh = test::make_grid(1, 1);
  mesh.property(get_layers(mesh).quadtree)[0].corners[2] = 99;
  try {
    bend_pairs(mesh);
    FAIL() << "a corner outside the mesh must throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("quad record 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("99"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mrcloth
