// MeshBody: collision with a moving closed triangle mesh (the skinned
// body): a bounding-volume hierarchy refit every pose, closest point and
// inside/outside, and the response of a cloth point. Split from
// body_skinned_mesh.cpp, which loads, binds and skins the body.
#include "mesh_body.h"

#include "mesh_ops/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mrcloth {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

/// Which part of a triangle is closest: its interior, a vertex or an edge
/// (edge k runs from corner k to corner k+1).
enum Feature : int { kFace = 0, kVertex0 = 1, kVertex1 = 2, kVertex2 = 3, kEdge0 = 4, kEdge1 = 5, kEdge2 = 6 };

struct TrianglePoint {
  Vector3d point;
  double b0, b1, b2;  ///< barycentric coordinates of point
  int feature;
};

/// Closest point of triangle (a, b, c) to p, with the feature it lies on
/// (Ericson, Real-Time Collision Detection, 5.1.5: Voronoi regions tested
/// by signs of dot products, so the feature is consistent with the point).
TrianglePoint closest_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, 1.0, 0.0, 0.0, kVertex0};
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, 0.0, 1.0, 0.0, kVertex1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, 1.0 - v, v, 0.0, kEdge0};
  }
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, 0.0, 0.0, 1.0, kVertex2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, 1.0 - w, 0.0, w, kEdge2};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), 0.0, 1.0 - w, w, kEdge1};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // A degenerate (zero-area) triangle that no region above claimed: its
    // closest point lies on one of its edges.
    TrianglePoint best{a, 1.0, 0.0, 0.0, kVertex0};
    double best_d2 = std::numeric_limits<double>::infinity();
    const Vector3d corners[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Vector3d& s = corners[k];
      const Vector3d e = corners[(k + 1) % 3] - s;
      const double len2 = e.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((p - s).dot(e) / len2, 0.0, 1.0) : 0.0;
      const Vector3d q = s + t * e;
      const double d2q = (p - q).squaredNorm();
      if (d2q < best_d2) {
        best_d2 = d2q;
        double bary[3] = {0.0, 0.0, 0.0};
        bary[k] = 1.0 - t;
        bary[(k + 1) % 3] = t;
        best = {q, bary[0], bary[1], bary[2], kEdge0 + k};
      }
    }
    return best;
  }
  const double v = vb / sum, w = vc / sum;
  return {a + ab * v + ac * w, 1.0 - v - w, v, w, kFace};
}

}  // namespace

// ---------------------------------------------------------------------------
// MeshBody
//
// Our own BVH, not CGAL's AABB tree: CGAL's tree cannot be refit, so the
// body would be rebuilt every step. Measured on the 26,756-triangle body in
// a walk (Release, one thread of a shared 2-core Xeon VM): CGAL 5.5
// AABB_tree build + accelerate_distance_queries 22 ms (10 ms without the
// kd-tree), ours refit 0.3 ms (build once ~30 ms); closest point for points
// 0-1 cm from the body ~4 us ours vs ~6 us CGAL, 1-5 cm 7 vs 9 us, 5-15 cm
// 8-9 vs 12 us. The surface-area heuristic's splits (instead of medians)
// then took points within 3 mm from 2.7-3.2 to 2.2 us, within 3 cm from 5.0
// to 4.0 us (walk frame 100, 20,000 points, same machine).

struct MeshBody::Impl {
  static constexpr int kLeafSize = 4;
  static constexpr int kStackSize = 96;
  static constexpr int kStackSize4 = 3 * kStackSize;  ///< a 4-wide node pushes up to 3 more than it pops, at half the binary depth
  static constexpr int kMaxSahDepth = 40;  ///< below this the build splits at medians (depth stays < 40 + log2 n < kStackSize)
  static constexpr int kMaxSweeps = 8;
  /// Beyond thickness, how far the bounded search looks (metres): only a
  /// cost trade-off (points farther than this outside are clear, deeper
  /// inside go to the unbounded search), never a change of result.
  static constexpr double kMargin = 0.05;
  /// Beyond this distance from the nearest seen triangle, while some are
  /// left out, the side comes from the whole mesh (inside_whole_mesh),
  /// metres: well outside the thickness layer, where pushes are decided.
  static constexpr double kWholeMeshSideBeyond = 0.01;
  static_assert(kWholeMeshSideBeyond < kMargin, "beyond the bounded search, the side is always the whole mesh's");
  /// A resolve's search looks twice this far (metres) beyond the nearest
  /// surface for triangles the point is behind, so it vouches for the
  /// point's side at most this far (SurfaceNearby::flip).
  static constexpr double kFlipReach = 0.0025;

  /// An internal node holding both children's boxes (one 64-byte line
  /// decides both), stored as floats rounded outwards: a box can only grow,
  /// so pruning stays conservative and results exact, at half the memory.
  struct Node {
    float lo[2][3], hi[2][3];
    int index[2] = {-1, -1};  ///< child k: node index if internal, first triangle if a leaf, -1 if none
    int count[2] = {0, 0};    ///< child k: triangles in the leaf, 0 if internal (or none)
  };

  struct Closest {
    double d2 = std::numeric_limits<double>::infinity();
    int triangle = -1;
    TrianglePoint at{Vector3d::Zero(), 0.0, 0.0, 0.0, kFace};
  };

  struct Contact {
    double distance = 0.0;  ///< signed, negative inside
    Vector3d normal{0, 1, 0};
    int triangle = -1;
    double b0 = 0, b1 = 0, b2 = 0;
  };

  /// Every seen triangle within `radius` of `centre`, as a search found
  /// them: the later searches of the same resolve that stay inside that
  /// ball read them instead of the tree. Empty (radius 0) when there were
  /// more than fit.
  struct Candidates {
    static constexpr int kCapacity = 96;
    int items[kCapacity];
    int count = 0;
    Vector3d centre{0, 0, 0};
    double radius = 0.0;
    /// Whether they hold every triangle within sqrt(search2) of p.
    bool cover(const Vector3d& p, double search2) const {
      return radius > 0.0 && (p - centre).norm() + std::sqrt(search2) <= radius;
    }
  };

  std::vector<Node> nodes;
  /// Per node, its children's boxes over both of the last two poses (what
  /// each subtree swept through between the last two updates, if its
  /// vertices moved in straight lines), rounded outwards as Node's.
  struct SweptBoxes {
    float lo[2][3], hi[2][3];
  };
  std::vector<SweptBoxes> swept;
  /// Four boxes, per axis (an empty one: lo +inf, hi -inf, never near).
  struct Boxes4 {
    float lo[3][4], hi[3][4];
  };
  /// The same tree with every other level skipped, for the proximity
  /// searches: a node holds its grandchildren's boxes (or a child's, where
  /// that child is a leaf), axis by axis, so one pass over four lanes
  /// measures all of them: half the levels and a quarter of the branches.
  /// Segment walks use the binary tree (with its swept boxes).
  struct alignas(64) Node4 {
    Boxes4 boxes;  ///< each child's box
    int index[4];  ///< child k: Node4 index if internal, first triangle if a leaf, -1 if none
    int count[4];  ///< child k: triangles in the leaf, 0 if internal (or none)
  };
  std::vector<Node4> nodes4;
  /// Per leaf, its triangles' boxes in the current pose, rounded outwards,
  /// four side by side, so a visited leaf tests them together (one pass
  /// over four lanes, as a node's children) instead of one after another;
  /// per triangle (leaf order), its box's place there: 4 * block + lane.
  std::vector<Boxes4> leaf_boxes;
  std::vector<int> box_slot;
  /// Per Node4 child, the binary node and side whose child box it copies
  /// at each refit ({-1, 0}: none).
  std::vector<std::array<std::pair<int, int>, 4>> source4;
  std::vector<Eigen::Vector3i> triangles;      ///< in leaf order
  std::vector<int> leaf_of_input;              ///< per triangle in construction order, its leaf-order index
  std::vector<char> ignored;                   ///< per triangle (leaf order): unseen in this pose (turned over)
  std::vector<int> ignored_list;               ///< the ignored triangles (leaf order): a few dozen on a walking body
  std::vector<char> on_rim;                    ///< per triangle (leaf order): seen, with a corner on an ignored one
  std::vector<int> rim_list;                   ///< the triangles on_rim marks
  bool any_ignored = false;
  std::vector<std::array<int, 3>> neighbours;  ///< triangle across edge k
  std::vector<int> ring_start;                 ///< per vertex, its first entry in ring (one past the end: the next vertex's)
  std::vector<std::pair<int, int>> ring;       ///< (triangle, corner) around each vertex
  std::vector<Vector3d> x, x_previous;         ///< vertex positions now and at the previous update (in number_vertices_by_leaf's order)
  std::vector<int> input_vertex;               ///< per vertex, its row in the input (empty: the input's order)
  Vector3d root_lo{0, 0, 0}, root_hi{0, 0, 0};  ///< the whole mesh's box
  double thickness = 0.0, friction = 0.0;
  unsigned long long serial = 0;  ///< counts update() calls: a memo is only good for the pose it was made in
  /// (thickness + kWholeMeshSideBeyond)^2: how far depths() looks for the
  /// nearest triangle. Beyond it the side alone decides (as signed_contact
  /// does beyond kWholeMeshSideBeyond), and a point outside has no depth.
  double depth_reach2 = 0.0;
  double normal_floor = 0.0;  ///< below this distance the pseudo-normal, not p - c, is the normal

  static void require_finite(const Eigen::MatrixX3d& vertices) {
    for (Eigen::Index v = 0; v < vertices.rows(); ++v)
      if (!vertices.row(v).allFinite())
        throw ArgumentError("MeshBody: vertex " + std::to_string(v) + " is not finite; expected finite positions");
  }

  void set_positions(const Eigen::MatrixX3d& vertices) {
    x.resize(static_cast<std::size_t>(vertices.rows()));
    for (std::size_t v = 0; v < x.size(); ++v)
      x[v] = vertices.row(input_vertex.empty() ? static_cast<Eigen::Index>(v) : input_vertex[v]).transpose();
  }

  /// Renumbers the vertices in the order the triangles (in leaf order)
  /// first use them, the unused ones last: a leaf's corners then lie
  /// together in x, not scattered over the input's order.
  void number_vertices_by_leaf() {
    std::vector<int> internal(x.size(), -1);
    input_vertex.clear();
    input_vertex.reserve(x.size());
    for (Eigen::Vector3i& tri : triangles)
      for (int k = 0; k < 3; ++k) {
        int& to = internal[static_cast<std::size_t>(tri(k))];
        if (to < 0) {
          to = static_cast<int>(input_vertex.size());
          input_vertex.push_back(tri(k));
        }
        tri(k) = to;
      }
    for (std::size_t v = 0; v < internal.size(); ++v)
      if (internal[v] < 0) input_vertex.push_back(static_cast<int>(v));
    std::vector<Vector3d> reordered(x.size());
    for (std::size_t v = 0; v < x.size(); ++v) reordered[v] = x[static_cast<std::size_t>(input_vertex[v])];
    x = std::move(reordered);
  }

  /// Builds the subtree of order[begin, end) and returns it as a child
  /// (index, count): a leaf of at most kLeafSize triangles, or a node.
  /// A triangle's box, and the box of a set of them.
  struct Box {
    Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity());
    Vector3d hi = Vector3d::Constant(-std::numeric_limits<double>::infinity());
    void add(const Box& b) {
      lo = lo.cwiseMin(b.lo);
      hi = hi.cwiseMax(b.hi);
    }
    double half_area() const {
      const Vector3d e = (hi - lo).cwiseMax(0.0);
      return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
    }
  };

  /// Builds the subtree of order[begin, end) and returns it as a child
  /// (index, count): a leaf of at most kLeafSize triangles, or a node. The
  /// split is the surface-area heuristic's best of 16 bins per axis (the
  /// expected number of boxes a query opens), falling back to the median
  /// along the widest axis when no bin split separates the triangles or
  /// the tree grows deep (the query's stack is fixed).
  std::pair<int, int> build(std::vector<int>& order, const std::vector<Vector3d>& centroid,
                            const std::vector<Box>& box, int begin, int end, int depth) {
    if (end - begin <= kLeafSize) return {begin, end - begin};
    const auto at = [&](int i) { return static_cast<std::size_t>(order[static_cast<std::size_t>(i)]); };
    Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int i = begin; i < end; ++i) {
      lo = lo.cwiseMin(centroid[at(i)]);
      hi = hi.cwiseMax(centroid[at(i)]);
    }
    constexpr int kBins = 16;
    int best_axis = -1, best_split = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    const auto bin_of = [&](std::size_t t, int axis) {
      const double extent = hi(axis) - lo(axis);
      return std::min(kBins - 1, static_cast<int>(kBins * (centroid[t](axis) - lo(axis)) / extent));
    };
    for (int axis = 0; axis < 3 && depth < kMaxSahDepth; ++axis) {
      if (!(hi(axis) - lo(axis) > 0.0)) continue;
      Box bins[kBins];
      int counts[kBins] = {0};
      for (int i = begin; i < end; ++i) {
        const int b = bin_of(at(i), axis);
        bins[b].add(box[at(i)]);
        ++counts[b];
      }
      // Right-to-left areas and counts, then one left-to-right sweep.
      double right_area[kBins];
      int right_count[kBins];
      Box right;
      int count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        right.add(bins[b]);
        count += counts[b];
        right_area[b] = right.half_area();
        right_count[b] = count;
      }
      Box left;
      count = 0;
      for (int split = 1; split < kBins; ++split) {
        left.add(bins[split - 1]);
        count += counts[split - 1];
        if (count == 0 || right_count[split] == 0) continue;
        const double cost = left.half_area() * count + right_area[split] * right_count[split];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_split = split;
        }
      }
    }
    int mid = 0;
    if (best_axis >= 0) {
      mid = static_cast<int>(std::partition(order.begin() + begin, order.begin() + end,
                                            [&](int t) { return bin_of(static_cast<std::size_t>(t), best_axis) < best_split; }) -
                             order.begin());
    }
    if (best_axis < 0 || mid == begin || mid == end) {
      int axis = 0;
      (hi - lo).maxCoeff(&axis);
      mid = begin + (end - begin) / 2;
      std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](int a, int b) {
        return centroid[static_cast<std::size_t>(a)](axis) < centroid[static_cast<std::size_t>(b)](axis);
      });
    }
    const int index = static_cast<int>(nodes.size());
    nodes.emplace_back();
    const std::pair<int, int> left = build(order, centroid, box, begin, mid, depth + 1);
    const std::pair<int, int> right = build(order, centroid, box, mid, end, depth + 1);
    Node& node = nodes[static_cast<std::size_t>(index)];
    node.index[0] = left.first;
    node.count[0] = left.second;
    node.index[1] = right.first;
    node.count[1] = right.second;
    return {index, 0};
  }

  /// Makes the Node4 of binary node b (and, recursively, of the binary
  /// nodes below it at every other level); returns its index. Called once
  /// the binary tree is built.
  int build4(int b) {
    const int index = static_cast<int>(nodes4.size());
    nodes4.emplace_back();
    source4.emplace_back();
    int slot = 0;
    const auto place = [&](int node, int k) {
      const Node& n = nodes[static_cast<std::size_t>(node)];
      source4[static_cast<std::size_t>(index)][static_cast<std::size_t>(slot)] = {node, k};
      nodes4[static_cast<std::size_t>(index)].count[slot] = n.count[k];
      nodes4[static_cast<std::size_t>(index)].index[slot] = n.index[k];
      const int at = slot++;
      if (n.count[k] > 0) {
        for (int lane = 0; lane < n.count[k]; ++lane)
          box_slot[static_cast<std::size_t>(n.index[k] + lane)] = 4 * static_cast<int>(leaf_boxes.size()) + lane;
        leaf_boxes.push_back(empty_boxes4());
      } else {
        const int child = build4(n.index[k]);  // after this nodes4 may have moved
        nodes4[static_cast<std::size_t>(index)].index[at] = child;
      }
    };
    for (int k = 0; k < 2; ++k) {
      const Node& n = nodes[static_cast<std::size_t>(b)];
      if (n.count[k] == 0 && n.index[k] < 0) continue;
      if (n.count[k] > 0) {
        place(b, k);
        continue;
      }
      const int c = n.index[k];
      for (int k2 = 0; k2 < 2; ++k2) {
        const Node& m = nodes[static_cast<std::size_t>(c)];
        if (m.count[k2] == 0 && m.index[k2] < 0) continue;
        place(c, k2);
      }
    }
    for (; slot < 4; ++slot) {
      source4[static_cast<std::size_t>(index)][static_cast<std::size_t>(slot)] = {-1, 0};
      nodes4[static_cast<std::size_t>(index)].index[slot] = -1;
      nodes4[static_cast<std::size_t>(index)].count[slot] = 0;
    }
    return index;
  }

  static Boxes4 empty_boxes4() {
    Boxes4 b;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 4; ++c) {
        b.lo[a][c] = std::numeric_limits<float>::infinity();
        b.hi[a][c] = -std::numeric_limits<float>::infinity();
      }
    return b;
  }

  /// Copies the binary tree's refit boxes into nodes4.
  void refit4() {
    for (std::size_t i = 0; i < nodes4.size(); ++i) {
      Node4& node = nodes4[i];
      for (int slot = 0; slot < 4; ++slot) {
        const auto [b, k] = source4[i][static_cast<std::size_t>(slot)];
        for (int a = 0; a < 3; ++a) {
          node.boxes.lo[a][slot] = b < 0 ? std::numeric_limits<float>::infinity() : nodes[static_cast<std::size_t>(b)].lo[k][a];
          node.boxes.hi[a][slot] = b < 0 ? -std::numeric_limits<float>::infinity() : nodes[static_cast<std::size_t>(b)].hi[k][a];
        }
      }
    }
  }

  // Outward by 4e-7 relative before the conversion, which rounds by at most
  // 6e-8 relative: the float always lies on the safe side (branch-free; the
  // boxes grow by 0.4 micrometre per metre).
  static float round_down(double v) { return static_cast<float>(v - (std::abs(v) * 4e-7 + 1e-30)); }
  static float round_up(double v) { return static_cast<float>(v + (std::abs(v) * 4e-7 + 1e-30)); }

  /// Children after parents in `nodes`, so one backward pass refits: O(n).
  /// `first`: no earlier pose (x_previous is x), so the swept boxes are
  /// the boxes.
  void refit(bool first = false) {
    swept.resize(nodes.size());
    for (std::size_t i = nodes.size(); i-- > 0;) {
      Node& node = nodes[i];
      SweptBoxes& sweep = swept[i];
      for (int k = 0; k < 2; ++k) {
        if (node.count[k] == 0 && node.index[k] < 0) {
          // No child (a root holding a single leaf): a box nothing is near.
          for (int a = 0; a < 3; ++a) {
            node.lo[k][a] = sweep.lo[k][a] = std::numeric_limits<float>::infinity();
            node.hi[k][a] = sweep.hi[k][a] = -std::numeric_limits<float>::infinity();
          }
          continue;
        }
        Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        if (node.count[k] > 0) {
          for (int t = node.index[k]; t < node.index[k] + node.count[k]; ++t) {
            Vector3d triangle_lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), triangle_hi = -triangle_lo;
            for (int c = 0; c < 3; ++c) {
              const Vector3d& q = corner(t, c);
              triangle_lo = triangle_lo.cwiseMin(q);
              triangle_hi = triangle_hi.cwiseMax(q);
            }
            const int slot = box_slot[static_cast<std::size_t>(t)];
            Boxes4& block = leaf_boxes[static_cast<std::size_t>(slot >> 2)];
            for (int a = 0; a < 3; ++a) {
              block.lo[a][slot & 3] = round_down(triangle_lo(a));
              block.hi[a][slot & 3] = round_up(triangle_hi(a));
            }
            lo = lo.cwiseMin(triangle_lo);
            hi = hi.cwiseMax(triangle_hi);
          }
        } else {
          const Node& child = nodes[static_cast<std::size_t>(node.index[k])];
          for (int a = 0; a < 3; ++a) {
            // Float to double is exact: the union of the child's boxes.
            lo(a) = std::min(child.lo[0][a], child.lo[1][a]);
            hi(a) = std::max(child.hi[0][a], child.hi[1][a]);
          }
        }
        // The box over both poses is the union of this box and the last:
        // rounding outwards is monotonic, so these are the floats that
        // rounding the union of both poses' corners (or of the children's
        // swept boxes) gives.
        for (int a = 0; a < 3; ++a) {
          const float new_lo = round_down(lo(a)), new_hi = round_up(hi(a));
          sweep.lo[k][a] = first ? new_lo : std::min(node.lo[k][a], new_lo);
          sweep.hi[k][a] = first ? new_hi : std::max(node.hi[k][a], new_hi);
          node.lo[k][a] = new_lo;
          node.hi[k][a] = new_hi;
        }
      }
    }
    refit4();
    root_lo = Vector3d::Constant(std::numeric_limits<double>::infinity());
    root_hi = -root_lo;
    for (int k = 0; k < 2; ++k)
      for (int a = 0; a < 3; ++a) {
        root_lo(a) = std::min(root_lo(a), static_cast<double>(nodes[0].lo[k][a]));
        root_hi(a) = std::max(root_hi(a), static_cast<double>(nodes[0].hi[k][a]));
      }
  }

  const Vector3d& corner(int t, int k) const {
    return x[static_cast<std::size_t>(triangles[static_cast<std::size_t>(t)](k))];
  }

  /// Unit normal of triangle t (zero when it is degenerate).
  Vector3d face_normal(int t) const {
    const Vector3d n = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
    const double length = n.norm();
    return length > 0.0 ? Vector3d(n / length) : Vector3d::Zero();
  }

  double root_distance2(const Vector3d& p) const {
    const Vector3d e = (root_lo - p).cwiseMax(p - root_hi).cwiseMax(0.0);
    return e.squaredNorm();
  }

  bool inside_root(const Vector3d& p) const {
    return (p.array() >= root_lo.array()).all() && (p.array() <= root_hi.array()).all();
  }

  /// Tests seen triangle t against the closest so far (`best`, its squared
  /// distance, and `out`); its own box first, which rejects most.
  void consider(const Vector3d& p, int t, double& best, Closest& out) const {
    consider(p, t, triangle_box_distance2(p, t), best, out);
  }
  /// The same with t's box distance `box2` already known.
  void consider(const Vector3d& p, int t, double box2, double& best, Closest& out) const {
    if (!(box2 < best)) return;
    const TrianglePoint at = closest_on_triangle(p, corner(t, 0), corner(t, 1), corner(t, 2));
    const double d2 = (p - at.point).squaredNorm();
    if (d2 < best) {
      best = d2;
      out.d2 = d2;
      out.triangle = t;
      out.at = at;
    }
  }

  /// The four children's squared distances from p (0 inside), in double
  /// (the boxes' floats are exact in it): per axis the gap below or above
  /// the box, squared and summed in axis order, two lanes at a time.
  static void box_distances4(const Boxes4& node, const Vector3d& p, double d[4]) {
#if defined(__SSE2__)
    const __m128d zero = _mm_setzero_pd();
    for (int h = 0; h < 4; h += 2) {
      __m128d sum = zero;
      for (int a = 0; a < 3; ++a) {
        const __m128d at = _mm_set1_pd(p(a));
        const __m128d lo = _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&node.lo[a][h]))));
        const __m128d hi = _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&node.hi[a][h]))));
        const __m128d e = _mm_max_pd(zero, _mm_max_pd(_mm_sub_pd(lo, at), _mm_sub_pd(at, hi)));
        sum = _mm_add_pd(sum, _mm_mul_pd(e, e));
      }
      _mm_storeu_pd(d + h, sum);
    }
#else
    for (int c = 0; c < 4; ++c) d[c] = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 4; ++c) {
        const double below = static_cast<double>(node.lo[a][c]) - p(a);
        const double above = p(a) - static_cast<double>(node.hi[a][c]);
        const double e = std::max(0.0, std::max(below, above));
        d[c] += e * e;
      }
#endif
  }

  /// triangle_box_distance2(p, t) of the leaf's triangles, t from `first`
  /// (the leaf's first triangle) on, together.
  void leaf_box_distances(int first, const Vector3d& p, double d[4]) const {
    box_distances4(leaf_boxes[static_cast<std::size_t>(box_slot[static_cast<std::size_t>(first)] >> 2)], p, d);
  }

  /// Visits the leaves whose box lies nearer to p than sqrt(limit()) (a
  /// bound that may shrink as they are visited), nearer child first, each
  /// leaf as visit(first, count), walking the 4-wide tree; inner nodes wait
  /// on a fixed stack, the nearer on top. No allocation. (Against the
  /// binary tree: the shared skirt refined twice on 07_06, 1.3 million
  /// first-round resolves replayed from a recorded run, 0.87 us each
  /// against 1.23, the same answers but for which of two triangles meeting
  /// at a closest point is named, in 1,752 of them.)
  template <typename Limit, typename Visit>
  void leaves_near(const Vector3d& p, Limit limit, Visit visit) const {
    struct Item {
      int node;
      double d2;
    };
    Item stack[kStackSize4];
    int top = 0;
    const double root_d2 = root_distance2(p);
    if (!(root_d2 < limit())) return;
    stack[top++] = {0, root_d2};
    while (top > 0) {
      const Item item = stack[--top];
      if (!(item.d2 < limit())) continue;
      const Node4& node = nodes4[static_cast<std::size_t>(item.node)];
      double d[4];
      box_distances4(node.boxes, p, d);
      // The children within the bound, nearest first (insertion: few are):
      // leaves visited in that order (the bound may shrink as they are),
      // inner nodes pushed farthest first.
      const double bound = limit();
      int order[4], n = 0;
      for (int c = 0; c < 4; ++c) {
        if (!(d[c] < bound)) continue;
        int k = n++;
        for (; k > 0 && d[c] < d[order[k - 1]]; --k) order[k] = order[k - 1];
        order[k] = c;
      }
      for (int i = 0; i < n; ++i) {
        const int c = order[i];
        if (node.count[c] > 0 && d[c] < limit()) visit(node.index[c], node.count[c]);
      }
      for (int i = n; i-- > 0;) {
        const int c = order[i];
        if (node.count[c] == 0 && node.index[c] >= 0 && d[c] < limit()) stack[top++] = {node.index[c], d[c]};
      }
    }
  }

  /// Closest seen triangle to p closer than sqrt(max_d2); false when none is.
  bool closest(const Vector3d& p, double max_d2, Closest& out) const {
    double best = max_d2;
    leaves_near(p, [&] { return best; }, [&](int first, int count) {
      double box2[4];
      leaf_box_distances(first, p, box2);
      for (int t = first; t < first + count; ++t)
        if (!(any_ignored && ignored[static_cast<std::size_t>(t)])) consider(p, t, box2[t - first], best, out);
    });
    return out.triangle >= 0;
  }

  /// closest(p, max_d2, out), and also the distance to the nearest other
  /// triangle whose plane p is behind, where that is within `margin` of
  /// the nearest's distance (`behind`: that distance, or the nearest's plus
  /// margin when none is; unchanged when there is no nearest). A point
  /// inside by a triangle's closest feature is behind the plane of a
  /// triangle through that feature, no farther away; where skinning drives
  /// one part of the body into another (the thighs, a hand into the hip) p
  /// can be in front of its nearest triangle and inside the other part,
  /// and moving a little then makes the other part's surface the nearest:
  /// its side flips. `out` may hold a first candidate (its d2 the bound).
  bool closest_and_behind(const Vector3d& p, double max_d2, double margin, Closest& out, double& behind,
                          Candidates* candidates = nullptr) const {
    struct Behind {
      double d2 = std::numeric_limits<double>::infinity();
      int triangle = -1;
    } first, second;  // the two nearest triangles p is behind (one may be the nearest itself)
    double best = out.triangle >= 0 ? out.d2 : max_d2;
    const auto limit_of = [&](double b) {
      const double r = std::sqrt(b) + margin;
      return r * r;
    };
    double limit2 = limit_of(best);
    bool overflow = false;
    if (candidates) candidates->count = 0;
    const auto visit = [&](int t, double box2) {
      if (any_ignored && ignored[static_cast<std::size_t>(t)]) return;
      if (!(box2 < limit2)) return;
      if (candidates) {
        if (candidates->count < Candidates::kCapacity) candidates->items[candidates->count++] = t;
        else overflow = true;
      }
      const Vector3d a = corner(t, 0);
      const bool is_behind = (p - a).dot((corner(t, 1) - a).cross(corner(t, 2) - a)) < 0.0;
      if (!(box2 < best) && !is_behind) return;
      const TrianglePoint at = closest_on_triangle(p, a, corner(t, 1), corner(t, 2));
      const double d2 = (p - at.point).squaredNorm();
      if (is_behind && d2 < second.d2 && t != first.triangle) {
        if (d2 < first.d2) {
          second = first;
          first = {d2, t};
        } else {
          second = {d2, t};
        }
      }
      if (d2 < best) {
        best = d2;
        limit2 = limit_of(best);
        out.d2 = d2;
        out.triangle = t;
        out.at = at;
      }
    };
    leaves_near(p, [&] { return limit2; }, [&](int leaf, int count) {
      double box2[4];
      leaf_box_distances(leaf, p, box2);
      for (int t = leaf; t < leaf + count; ++t) visit(t, box2[t - leaf]);
    });
    if (candidates) {
      // Everything pruned lay beyond the limit when it was pruned, and the
      // limit only shrank: the list holds every triangle within it.
      candidates->centre = p;
      candidates->radius = overflow ? 0.0 : std::sqrt(limit2);
    }
    if (out.triangle < 0) return false;
    const Behind& other = first.triangle != out.triangle ? first : second;
    behind = std::min(std::sqrt(other.d2), std::sqrt(best) + margin);
    return true;
  }

  /// The angle-weighted pseudo-normal (Baerentzen and Aanaes 2005) of the
  /// feature of triangle t a closest point lies on, not normalised: the face
  /// normal, the sum of the two face normals at an edge, the sum of the
  /// incident face normals weighted by their angles at a vertex. Formed here
  /// from the current positions rather than stored per update: refits stay
  /// O(n) bounding boxes only, and vertex features are a small share of the
  /// queries.
  Vector3d pseudo_normal(int t, int feature) const {
    const auto ti = static_cast<std::size_t>(t);
    if (feature == kFace) return face_normal(t);
    if (feature >= kEdge0) {
      const int across = neighbours[ti][static_cast<std::size_t>(feature - kEdge0)];
      if (any_ignored && ignored[static_cast<std::size_t>(across)]) return face_normal(t);
      return face_normal(t) + face_normal(across);
    }
    const auto v = static_cast<std::size_t>(triangles[ti](feature - kVertex0));
    Vector3d sum = Vector3d::Zero();
    for (int r = ring_start[v]; r < ring_start[v + 1]; ++r) {
      const auto [u, k] = ring[static_cast<std::size_t>(r)];
      if (any_ignored && ignored[static_cast<std::size_t>(u)]) continue;
      const Vector3d e1 = corner(u, (k + 1) % 3) - corner(u, k);
      const Vector3d e2 = corner(u, (k + 2) % 3) - corner(u, k);
      const Vector3d n = e1.cross(e2);
      const double length = n.norm();
      if (length > 0.0) sum += std::atan2(length, e1.dot(e2)) * (n / length);
    }
    return sum;
  }

  Contact signed_contact(const Vector3d& p, const Closest& c) const {
    Contact contact;
    const Vector3d diff = p - c.at.point;
    const double distance = std::sqrt(c.d2);
    Vector3d pseudo = pseudo_normal(c.triangle, c.at.feature);
    if (!(pseudo.squaredNorm() > 0.0)) pseudo = face_normal(c.triangle);
    bool inside = diff.dot(pseudo) < 0.0;
    // With turned triangles left out the seen surface is open, and a point
    // a few centimetres from it can be nearest to a triangle whose side is
    // the wrong one (on 08_03 a point 29 mm inside the leg was called 22
    // mm outside): there the whole closed mesh decides. Nearer in, it
    // vetoes "inside" where the nearest is on the rim of the hole they
    // leave: above the hole a point outside is behind the rim's side (the
    // shared skirt refined twice on 07_03: a point outside the body,
    // winding number 0, was called 7 mm inside the groin's fold). Not the
    // other way: in the pocket a fold leaves (behind a bent knee) the
    // parity says inside where the seen surface, which the turned skin was
    // left out of so as not to push cloth into the leg, says outside (the
    // walk table's trousers on 02_01: 3 runs then ended 4 mm "inside").
    if (any_ignored && (distance > kWholeMeshSideBeyond || (inside && on_rim[static_cast<std::size_t>(c.triangle)])))
      inside = inside_whole_mesh(p);
    contact.distance = inside ? -distance : distance;
    // The outward normal is the distance field's gradient, (p - c) / |p - c|
    // (signed), so a push along it lands exactly at the new distance; on the
    // surface itself that direction is noise, and the pseudo-normal serves.
    if (distance > normal_floor) contact.normal = (inside ? -diff : diff) / distance;
    else contact.normal = pseudo.squaredNorm() > 0.0 ? pseudo.normalized() : Vector3d::UnitY();
    contact.triangle = c.triangle;
    contact.b0 = c.at.b0;
    contact.b1 = c.at.b1;
    contact.b2 = c.at.b2;
    return contact;
  }

  /// The contact of p if a triangle is closer than sqrt(search2), or, with
  /// `deep`, if p is inside: false means p is outside and at least that far.
  bool contact(const Vector3d& p, double search2, bool deep, Contact& out) const {
    Closest c;
    if (closest(p, search2, c)) {
      out = signed_contact(p, c);
      return true;
    }
    // Nothing within reach: outside (no contact), or deep inside. Only a
    // point inside the root box can be inside; search without bound.
    if (!deep || !inside_root(p)) return false;
    if (!closest(p, std::numeric_limits<double>::infinity(), c)) return false;
    out = signed_contact(p, c);
    return out.distance < 0.0;
  }

  /// Squared distance from p to the bounding box of triangle t (0 inside):
  /// branch-free, and a fraction of the exact test's cost.
  double triangle_box_distance2(const Vector3d& p, int t) const {
    const int slot = box_slot[static_cast<std::size_t>(t)];
    const Boxes4& block = leaf_boxes[static_cast<std::size_t>(slot >> 2)];
    double box2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double below = static_cast<double>(block.lo[k][slot & 3]) - p(k);
      const double above = p(k) - static_cast<double>(block.hi[k][slot & 3]);
      const double e = std::max(0.0, std::max(below, above));
      box2 += e * e;
    }
    return box2;
  }

  /// Whether segment a-b meets the box [lo, hi] (slab test).
  static bool segment_meets_box(const Vector3d& a, const Vector3d& d, const float lo[3], const float hi[3]) {
    double enter = 0.0, leave = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double l = lo[k], h = hi[k];
      if (d(k) == 0.0) {
        if (a(k) < l || a(k) > h) return false;
        continue;
      }
      double t0 = (l - a(k)) / d(k), t1 = (h - a(k)) / d(k);
      if (t0 > t1) std::swap(t0, t1);
      enter = std::max(enter, t0);
      leave = std::min(leave, t1);
      if (enter > leave) return false;
    }
    return true;
  }

  /// Visits the leaves whose box meets the segment a + t d, t in [0, 1]:
  /// their current boxes, or with `over_last_two` their boxes over the last
  /// two poses. `visit(first, count)` (the leaf's triangles) returns false
  /// to stop; the result is false when it stopped.
  template <typename Visit>
  bool leaves_on_segment(const Vector3d& a, const Vector3d& d, bool over_last_two, Visit visit) const {
    int stack[kStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const auto i = static_cast<std::size_t>(stack[--top]);
      const Node& node = nodes[i];
      for (int k = 0; k < 2; ++k) {
        if (node.count[k] == 0 && node.index[k] < 0) continue;
        const float* lo = over_last_two ? swept[i].lo[k] : node.lo[k];
        const float* hi = over_last_two ? swept[i].hi[k] : node.hi[k];
        if (!segment_meets_box(a, d, lo, hi)) continue;
        if (node.count[k] == 0) stack[top++] = node.index[k];
        else if (!visit(node.index[k], node.count[k])) return false;
      }
    }
    return true;
  }

  /// Whether no triangle can have crossed the segment a-b since the last
  /// update but one: no leaf's swept box meets it. A point that moved along
  /// it while the surface moved (straight) between those poses then stayed
  /// on its side. Conservative: a false "no" only costs a query.
  bool segment_clear(const Vector3d& a, const Vector3d& b) const {
    return leaves_on_segment(a, b - a, true, [](int, int) { return false; });
  }

  /// Whether p is inside the closed mesh, every triangle counted (the
  /// ignored ones too): the parity of a ray's crossings, the ray in a
  /// direction no face or edge of a body is likely to be aligned with.
  /// The parity of a closed surface's crossings (self-intersecting too) is
  /// the same along every ray, so the ray leaves by the root box's nearest
  /// face: out of a leg through its front or back, not up through the torso
  /// (a third of the boxes to open on a walking body).
  bool inside_whole_mesh(const Vector3d& p) const {
    if (!inside_root(p)) return false;
    int axis = 0;
    double sign = 1.0, reach = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (p(k) - root_lo(k) < reach) {
        reach = p(k) - root_lo(k);
        axis = k;
        sign = -1.0;
      }
      if (root_hi(k) - p(k) < reach) {
        reach = root_hi(k) - p(k);
        axis = k;
        sign = 1.0;
      }
    }
    // Skewed off the axis (fixed, irrational-looking slopes); the axis part
    // ends a millimetre beyond the face, outside the box.
    Vector3d d(0.3170, 0.5918, 0.7412);
    d(axis) = sign;
    d *= reach + 1e-3;
    int crossings = 0;
    leaves_on_segment(p, d, false, [&](int first, int count) {
      for (int t = first; t < first + count; ++t) {
        SegmentHit hit;
        if (segment_meets_triangle(p, d, t, hit) && hit.s > 0.0) ++crossings;
      }
      return true;
    });
    return crossings % 2 == 1;
  }

  /// Where the segment a + s d, s in [0, 1], meets triangle t (Moller-
  /// Trumbore): its parameter s and barycentrics u, v (of corners 1 and 2).
  struct SegmentHit {
    double s = 0.0, u = 0.0, v = 0.0;
  };
  bool segment_meets_triangle(const Vector3d& a, const Vector3d& d, int t, SegmentHit& hit) const {
    const Vector3d e1 = corner(t, 1) - corner(t, 0), e2 = corner(t, 2) - corner(t, 0);
    const Vector3d pv = d.cross(e2);
    const double det = e1.dot(pv);
    if (det == 0.0) return false;
    const Vector3d tv = a - corner(t, 0);
    hit.u = tv.dot(pv) / det;
    if (hit.u < 0.0 || hit.u > 1.0) return false;
    const Vector3d qv = tv.cross(e1);
    hit.v = d.dot(qv) / det;
    if (hit.v < 0.0 || hit.u + hit.v > 1.0) return false;
    hit.s = e2.dot(qv) / det;
    return hit.s >= 0.0 && hit.s <= 1.0;
  }

  /// Where segment a-b first enters the surface (in the current pose),
  /// coming from a: the first triangle it crosses against that triangle's
  /// outward normal. `out`: that triangle, the crossing's barycentrics and
  /// the triangle's unit normal (distance 0). False when the segment
  /// enters nowhere.
  bool first_entry(const Vector3d& a, const Vector3d& b, Contact& out) const {
    const Vector3d d = b - a;
    double best = std::numeric_limits<double>::infinity();
    // One-sided: only crossings into the body.
    leaves_on_segment(a, d, false, [&](int first, int count) {
      for (int t = first; t < first + count; ++t) {
        if (any_ignored && ignored[static_cast<std::size_t>(t)]) continue;
        const Vector3d n = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
        SegmentHit hit;
        if (!(d.dot(n) < 0.0) || !segment_meets_triangle(a, d, t, hit) || hit.s >= best) continue;
        best = hit.s;
        out.triangle = t;
        out.b0 = 1.0 - hit.u - hit.v;
        out.b1 = hit.u;
        out.b2 = hit.v;
        out.normal = n.normalized();
      }
      return true;
    });
    if (!(best <= 1.0)) return false;
    out.distance = 0.0;
    return true;
  }

  /// The point of a contact's triangle at its barycentrics.
  Vector3d surface_point(const Contact& c) const {
    return c.b0 * corner(c.triangle, 0) + c.b1 * corner(c.triangle, 1) + c.b2 * corner(c.triangle, 2);
  }

  /// Whether an ignored (turned) triangle lies within sqrt(radius2) of p:
  /// there the seen surface is open, and a side read off it may be wrong.
  bool near_fold(const Vector3d& p, double radius2) const {
    for (int t : ignored_list)
      if (triangle_box_distance2(p, t) < radius2) return true;
    return false;
  }

  /// Whether memo says its point was left outside in this pose or the one
  /// before, with a side that may be carried: then that side still holds at
  /// a point the way to which no surface crossed (segment_clear).
  bool recently_outside(const ContactMemo* memo) const {
    return memo && memo->owner == this && memo->radius > 0.0 && memo->outside && memo->sided &&
           (memo->serial == serial || memo->serial + 1 == serial);
  }

  /// The contact of p with the seen triangle nearest to it within `reach`
  /// beyond the thickness, or, with nothing that near, the contact of p
  /// deep inside; false when p is outside and nothing is that near. The
  /// same answer as contact(p, (thickness + reach)^2, true, out); the memo
  /// only makes it cheaper: its nearest triangle starts the search with a
  /// bound, and with nothing within reach its carried side (a way no
  /// surface crossed) stands for the unbounded search. `behind`, if
  /// given, receives closest_and_behind's distance for a contact found
  /// within reach (the depth for one deep inside).
  bool nearest_contact(const Vector3d& p, double reach, const ContactMemo* memo, Contact& out,
                       double* behind = nullptr, Candidates* candidates = nullptr) const {
    const double near2 = (thickness + reach) * (thickness + reach);
    Closest c;
    if (memo && memo->owner == this && memo->nearest >= 0 &&
        static_cast<std::size_t>(memo->nearest) < triangles.size() &&
        !(any_ignored && ignored[static_cast<std::size_t>(memo->nearest)])) {
      const int t = memo->nearest;
      const TrianglePoint at = closest_on_triangle(p, corner(t, 0), corner(t, 1), corner(t, 2));
      const double d2 = (p - at.point).squaredNorm();
      if (d2 < near2) {
        c.d2 = d2;
        c.triangle = t;
        c.at = at;
      }
    }
    // The search finds any triangle nearer than the memo's, which stays
    // the answer when none is.
    double behind_distance = 0.0;
    const bool found = behind ? closest_and_behind(p, near2, 2.0 * kFlipReach, c, behind_distance, candidates)
                              : (closest(p, c.triangle >= 0 ? c.d2 : near2, c) || c.triangle >= 0);
    if (found) {
      out = signed_contact(p, c);
      if (behind) *behind = behind_distance;
      return true;
    }
    if (recently_outside(memo) && segment_clear(memo->centre, p)) return false;
    if (!inside_root(p)) return false;
    // Beyond reach, with triangles left out, the side is the whole mesh's
    // parity (signed_contact's rule): outside needs no nearest search.
    if (any_ignored && !inside_whole_mesh(p)) return false;
    if (!closest(p, std::numeric_limits<double>::infinity(), c)) return false;
    out = signed_contact(p, c);
    if (behind) *behind = -out.distance;  // inside: no side to vouch for
    return out.distance < 0.0;
  }

  /// What the memo keeps of a point left at p with nearest seen triangle
  /// `nearest` (-1: none within reach), outside or not.
  void remember(const Vector3d& p, int nearest, bool outside, double reach, ContactMemo* memo) const {
    if (!memo) return;
    memo->items.clear();
    memo->nearest = nearest;
    memo->centre = p;
    memo->radius = thickness + reach;
    memo->outside = outside;
    // A side is carried only from where nothing seen was near (so it came
    // from the tree's whole search or a carried side, not from one nearby
    // triangle, which where skinning drives one part into another can be
    // the wrong part's) and no fold is near (the seen surface is open there).
    memo->sided = nearest < 0 && !(any_ignored && near_fold(p, memo->radius * memo->radius));
    memo->owner = this;
    memo->serial = serial;
  }

  /// Pushes p out to thickness along the distance's gradient, searching
  /// within sqrt(search2). A push out of one side of a crease (armpit,
  /// crotch) can land within thickness of the other, so it repeats, as
  /// resolve_point does between colliders; after a push p is exactly
  /// thickness outside its closest point, so later sweeps only search that
  /// far. In a gap narrower than twice the thickness (between toes or
  /// fingers) no place is clear of both sides and the pushes alternate: then
  /// the place seen farthest out is kept. `largest` takes the largest push;
  /// `last` (if given) the contact of the last push kept.
  /// contact(p, search2, false, out), from `candidates` when they cover
  /// that ball.
  bool contact_near(const Vector3d& p, double search2, const Candidates* candidates, Contact& out) const {
    if (!candidates || !candidates->cover(p, search2)) return contact(p, search2, false, out);
    Closest c;
    double best = search2;
    for (int k = 0; k < candidates->count; ++k) consider(p, candidates->items[k], best, c);
    if (c.triangle < 0) return false;
    out = signed_contact(p, c);
    return true;
  }

  void project(Vector3d& p, double search2, double& largest, Contact* last = nullptr,
               const Candidates* candidates = nullptr) const {
    Vector3d best_p = p;
    double best_distance = -std::numeric_limits<double>::infinity();
    Contact best_contact;
    const double near2 = thickness * thickness;
    for (int sweep = 0; sweep <= kMaxSweeps; ++sweep) {
      Contact c;
      if (!contact_near(p, sweep == 0 ? search2 : near2, candidates, c)) return;
      const double gap = c.distance - thickness;
      if (!(gap < -1e-12)) return;  // round-off short of thickness is clear: no endless re-pushes
      if (c.distance > best_distance) {
        best_distance = c.distance;
        best_p = p;
        best_contact = c;
      }
      if (sweep == kMaxSweeps) break;
      p += -gap * c.normal;
      largest = std::max(largest, -gap);
      if (last) *last = c;
    }
    p = best_p;
    if (last) *last = best_contact;
  }

  Vector3d surface_motion(const Contact& c) const {
    const Eigen::Vector3i& tri = triangles[static_cast<std::size_t>(c.triangle)];
    Vector3d motion = Vector3d::Zero();
    const double b[3] = {c.b0, c.b1, c.b2};
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(tri(k));
      motion += b[k] * (x[v] - x_previous[v]);
    }
    return motion;
  }
};

MeshBody::MeshBody(const Eigen::MatrixX3d& vertices, std::vector<Eigen::Vector3i> triangles, double thickness,
                   double friction)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (!(thickness >= 0.0 && thickness <= kMostContactThickness))
    throw ArgumentError("MeshBody: thickness must be from 0 to " + number_text(kMostContactThickness) + " m (got " +
                        number_text(thickness) + ")");
  if (!(std::isfinite(friction) && friction >= 0.0))
    throw ArgumentError("MeshBody: friction must be a finite number >= 0 (got " + number_text(friction) + ")");
  if (triangles.empty()) throw ArgumentError("MeshBody: no triangles; expected a closed triangle mesh");
  m.thickness = thickness;
  m.friction = friction;
  m.depth_reach2 = (thickness + Impl::kWholeMeshSideBeyond) * (thickness + Impl::kWholeMeshSideBeyond);
  Impl::require_finite(vertices);
  m.set_positions(vertices);
  const int vertex_count = static_cast<int>(vertices.rows());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (triangles[t](k) < 0 || triangles[t](k) >= vertex_count)
        throw ArgumentError("MeshBody: triangle " + std::to_string(t) + " names vertex " + std::to_string(triangles[t](k)) +
                            "; expected an index below " + std::to_string(vertex_count));
    }
  }

  // The tree: surface-area-heuristic splits (built once, on the first
  // pose), depth-first node order (left child next, parents before
  // children, so a reverse pass refits), triangles stored in leaf order.
  std::vector<Vector3d> centroid(triangles.size());
  std::vector<Impl::Box> boxes(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    centroid[t] = (m.x[static_cast<std::size_t>(triangles[t](0))] + m.x[static_cast<std::size_t>(triangles[t](1))] +
                   m.x[static_cast<std::size_t>(triangles[t](2))]) / 3.0;
    for (int k = 0; k < 3; ++k) boxes[t].add({m.x[static_cast<std::size_t>(triangles[t](k))], m.x[static_cast<std::size_t>(triangles[t](k))]});
  }
  std::vector<int> order(triangles.size());
  for (std::size_t t = 0; t < order.size(); ++t) order[t] = static_cast<int>(t);
  m.nodes.reserve(2 * triangles.size() / Impl::kLeafSize + 2);
  const std::pair<int, int> top = m.build(order, centroid, boxes, 0, static_cast<int>(order.size()), 0);
  if (top.second > 0) {
    // Few enough triangles for one leaf: a root node holding it alone.
    m.nodes.emplace_back();
    m.nodes[0].index[0] = top.first;
    m.nodes[0].count[0] = top.second;
  }
  m.triangles.resize(triangles.size());
  m.leaf_of_input.resize(triangles.size());
  for (std::size_t t = 0; t < order.size(); ++t) {
    m.triangles[t] = triangles[static_cast<std::size_t>(order[t])];
    m.leaf_of_input[static_cast<std::size_t>(order[t])] = static_cast<int>(t);
  }
  m.ignored.assign(triangles.size(), 0);
  m.on_rim.assign(triangles.size(), 0);

  // Neighbours across each edge: the mesh must be closed and consistently
  // oriented (each directed edge once, its reverse once).
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(3 * m.triangles.size());
  auto key = [](int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); };
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[t](k), b = m.triangles[t]((k + 1) % 3);
      if (!directed.emplace(key(a, b), static_cast<int>(3 * t + static_cast<std::size_t>(k))).second) {
        throw ArgumentError("MeshBody: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                            ") is used twice in the same direction; expected a consistently oriented 2-manifold mesh");
      }
    }
  }
  m.neighbours.resize(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[t](k), b = m.triangles[t]((k + 1) % 3);
      const auto found = directed.find(key(b, a));
      if (found == directed.end()) {
        throw ArgumentError("MeshBody: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                            ") has a triangle on one side only; expected a closed mesh");
      }
      m.neighbours[t][static_cast<std::size_t>(k)] = found->second / 3;
    }
  }
  m.number_vertices_by_leaf();  // after the checks above, whose messages name the input's vertices

  m.ring_start.assign(m.x.size() + 1, 0);
  for (const Eigen::Vector3i& tri : m.triangles)
    for (int k = 0; k < 3; ++k) ++m.ring_start[static_cast<std::size_t>(tri(k)) + 1];
  for (std::size_t v = 0; v < m.x.size(); ++v) m.ring_start[v + 1] += m.ring_start[v];
  m.ring.resize(3 * m.triangles.size());
  std::vector<int> fill(m.ring_start.begin(), m.ring_start.end() - 1);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      m.ring[static_cast<std::size_t>(fill[static_cast<std::size_t>(m.triangles[t](k))]++)] = {static_cast<int>(t), k};

  m.nodes4.reserve(m.nodes.size());
  m.box_slot.assign(m.triangles.size(), -1);
  m.build4(0);
  m.x_previous = m.x;
  m.refit(/*first=*/true);
  double volume = 0.0;
  for (const Eigen::Vector3i& tri : m.triangles)
    volume += m.x[static_cast<std::size_t>(tri(0))].dot(m.x[static_cast<std::size_t>(tri(1))].cross(m.x[static_cast<std::size_t>(tri(2))]));
  if (!(volume > 0.0))
    throw ArgumentError("MeshBody: the triangles enclose a negative volume; expected them ordered counter-clockwise seen from outside");
  const double diagonal = (m.root_hi - m.root_lo).norm();
  m.normal_floor = 1e-10 * std::max(1.0, diagonal);
}

MeshBody::~MeshBody() = default;

void MeshBody::update(const Eigen::MatrixX3d& vertices, const std::vector<char>& ignored) {
  Impl& m = *impl_;
  if (vertices.rows() != static_cast<Eigen::Index>(m.x.size())) {
    throw ArgumentError("MeshBody::update: " + std::to_string(vertices.rows()) + " vertices; expected " +
                        std::to_string(m.x.size()) + " (the count the body was built with)");
  }
  if (!ignored.empty() && ignored.size() != m.triangles.size())
    throw ArgumentError("MeshBody::update: " + std::to_string(ignored.size()) + " ignore flags; expected one per triangle (" +
                        std::to_string(m.triangles.size()) + ")");
  m.any_ignored = false;
  std::fill(m.ignored.begin(), m.ignored.end(), 0);
  m.ignored_list.clear();
  for (std::size_t t = 0; t < ignored.size(); ++t)
    if (ignored[t]) {
      m.ignored[static_cast<std::size_t>(m.leaf_of_input[t])] = 1;
      m.ignored_list.push_back(m.leaf_of_input[t]);
      m.any_ignored = true;
    }
  for (int t : m.rim_list) m.on_rim[static_cast<std::size_t>(t)] = 0;
  m.rim_list.clear();
  for (int t : m.ignored_list)
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(m.triangles[static_cast<std::size_t>(t)](k));
      for (int r = m.ring_start[v]; r < m.ring_start[v + 1]; ++r) {
        const auto u = static_cast<std::size_t>(m.ring[static_cast<std::size_t>(r)].first);
        if (m.ignored[u] || m.on_rim[u]) continue;
        m.on_rim[u] = 1;
        m.rim_list.push_back(static_cast<int>(u));
      }
    }
  Impl::require_finite(vertices);
  ++m.serial;
  std::swap(m.x, m.x_previous);
  m.set_positions(vertices);
  m.refit();
}

double MeshBody::resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction,
                         ContactMemo* memo, SurfaceNearby* nearby) const {
  const Impl& m = *impl_;
  // The nearest seen triangle within reach (the memo's from the last
  // resolve starts the search), or the contact deep inside.
  Impl::Contact c;
  double behind = 0.0;  // how far the nearest triangle p is behind is (when near)
  const Vector3d searched = position;
  Impl::Candidates candidates;  // what that search saw, for the searches after a push
  const bool near = m.nearest_contact(position, kNearbyReach, memo, c, nearby ? &behind : nullptr, &candidates);
  if (!near || !(c.distance - m.thickness < 0.0)) {
    if (nearby) {
      nearby->clearance = near ? c.distance - m.thickness : kNearbyReach;
      nearby->has_plane = near;
      nearby->normal = c.normal;
      nearby->point = position - nearby->clearance * c.normal;
      // Its side holds while the nearest triangle it is behind stays farther.
      nearby->flip = near ? 0.5 * (behind - c.distance) : std::numeric_limits<double>::infinity();
    }
    m.remember(position, near ? c.triangle : -1, true, kNearbyReach, memo);
    return 0.0;
  }
  // Where the point ends: thickness off its last push's surface.
  const auto finish = [&](const Impl::Contact& last, double largest) {
    if (nearby) {
      nearby->clearance = 0.0;
      nearby->has_plane = true;
      nearby->normal = last.normal;
      nearby->point = position;
      // Now thickness off its surface, and the triangles it was behind at
      // most as much nearer as it moved.
      nearby->flip = std::max(0.0, 0.5 * (behind - (position - searched).norm() - m.thickness));
    }
    m.remember(position, last.triangle, true, kNearbyReach, memo);
    return largest;
  };
  // Inside, the nearest surface may be the far side of a limb that moved
  // more than half its width through the point this step (a shin swinging
  // at 3 m/s moves 25 mm per 1/120 s step): pushed there, cloth ends on
  // both sides of the limb and tears. The point's way relative to the
  // surface (from where it started, carried along by the surface, to here)
  // says where it entered, and it goes back out there: the limb carries it
  // from where it met it. Not when that place is inside another part of
  // the body (where the skin passes into itself, as the thighs do), nor
  // when the way enters nowhere (the point started inside): then the
  // nearest surface, as below.
  if (c.distance < 0.0) {
    Impl::Contact entry, there;
    if (m.first_entry(start + m.surface_motion(c), position, entry)) {
      const Vector3d out = m.surface_point(entry) + m.thickness * entry.normal;
      // The entry triangle lies within thickness of `out`, so the closest
      // one does too: searching no farther finds the same one, sooner.
      const double within = m.thickness + 1e-9;
      if (!(m.contact(out, within * within, true, there) && there.distance < 0.0)) {
        double largest = (out - position).norm();
        position = out;
        m.project(position, m.thickness * m.thickness, largest, &entry);
        return finish(entry, largest);
      }
    }
  }
  const double gap = c.distance - m.thickness;
  // As resolve_point: out to thickness along the normal, then Coulomb
  // friction on the step's tangential displacement, here relative to the
  // surface (which moved by its vertices' displacement since the last
  // update).
  const double correction = -gap;
  position += correction * c.normal;
  double largest = correction;
  if (!friction) {
    m.project(position, m.thickness * m.thickness, largest, &c, &candidates);
    return finish(c, largest);
  }
  const Vector3d step = position - start - m.surface_motion(c);
  const Vector3d tangential = step - c.normal * c.normal.dot(step);
  const double slide = tangential.norm();
  const double grip = m.friction * correction;
  const Vector3d move = slide <= grip ? Vector3d(-tangential) : Vector3d(-tangential * (grip / slide));
  position += move;
  // The point is now thickness outside its closest point, moved along the
  // surface by `move`: only a triangle nearer than thickness plus the move
  // can still hold it (the other side of a crease, or the surface it slid
  // along); pushes from there on are frictionless.
  const double reach = m.thickness + move.norm();
  m.project(position, reach * reach, largest, &c, &candidates);
  return finish(c, largest);
}

double MeshBody::penetration(const Eigen::Vector3d& p) const { return depths(p).penetration; }

double MeshBody::depth(const Eigen::Vector3d& p) const { return depths(p).depth; }

PointDepths MeshBody::depths(const Eigen::Vector3d& p, int* hint) const {
  // The nearest triangle within reach (thickness + kWholeMeshSideBeyond),
  // else, inside the root box, the nearest of all, which counts where p is
  // inside. The hint's triangle bounds whichever search runs, as a memo's
  // does in resolve. (Searching out to thickness + kMargin, 5.4 cm, gave
  // the same numbers: beyond kWholeMeshSideBeyond the side is the whole
  // mesh's parity either way, or the nearest of all's, and a point found
  // outside there has no depth; it only cost a search per point in the
  // band, a third of the measuring of the shared skirt refined twice.)
  const Impl& m = *impl_;
  Impl::Closest seed;
  if (hint && *hint >= 0 && static_cast<std::size_t>(*hint) < m.triangles.size() &&
      !(m.any_ignored && m.ignored[static_cast<std::size_t>(*hint)])) {
    const int t = *hint;
    seed.triangle = t;
    seed.at = closest_on_triangle(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2));
    seed.d2 = (p - seed.at.point).squaredNorm();
  }
  Impl::Closest nearest = seed.d2 < m.depth_reach2 ? seed : Impl::Closest{};
  bool within = m.closest(p, nearest.triangle >= 0 ? nearest.d2 : m.depth_reach2, nearest);
  if (!within) {
    if (!m.inside_root(p)) return {};
    // Beyond reach, with triangles left out, the side is the whole mesh's
    // parity (signed_contact's rule beyond kWholeMeshSideBeyond): a point
    // outside needs no search for its nearest triangle.
    if (m.any_ignored && !m.inside_whole_mesh(p)) return {};
    nearest = seed;
    if (!m.closest(p, nearest.triangle >= 0 ? nearest.d2 : std::numeric_limits<double>::infinity(), nearest))
      return {};
  }
  if (hint) *hint = nearest.triangle;
  const Impl::Contact c = m.signed_contact(p, nearest);
  if (!within && !(c.distance < 0.0)) return {};  // outside, beyond reach
  return {std::max(0.0, m.thickness - c.distance), std::max(0.0, -c.distance)};
}

MeshBody::SurfacePoint MeshBody::nearest_point(const Eigen::Vector3d& p) const {
  const Impl& m = *impl_;
  Impl::Closest c;
  m.closest(p, std::numeric_limits<double>::infinity(), c);
  SurfacePoint out;
  if (c.triangle < 0) return out;
  const double b[3] = {c.at.b0, c.at.b1, c.at.b2};
  for (int k = 0; k < 3; ++k) {
    const int v = m.triangles[static_cast<std::size_t>(c.triangle)](k);
    out.vertices[static_cast<std::size_t>(k)] = m.input_vertex.empty() ? v : m.input_vertex[static_cast<std::size_t>(v)];
    out.weights[static_cast<std::size_t>(k)] = b[k];
  }
  out.distance = std::sqrt(c.d2);
  return out;
}

SurfaceQuery MeshBody::query(const Eigen::Vector3d& p) const {
  Impl::Closest c;
  impl_->closest(p, std::numeric_limits<double>::infinity(), c);
  const Impl::Contact contact = impl_->signed_contact(p, c);
  SurfaceQuery out;
  out.distance = contact.distance;
  out.normal = contact.normal;
  return out;
}

}  // namespace mrcloth
