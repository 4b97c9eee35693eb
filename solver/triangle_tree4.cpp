// TriangleTree4: building the tree (surface-area heuristic) and refitting
// its boxes to each pose; the searches are in the header.
#include "triangle_tree4.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

using Eigen::Vector3d;
using Node = TriangleTree4::Node;
using Boxes4 = TriangleTree4::Boxes4;

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

/// Builds the subtree of order[begin, end) into `nodes` and returns it as
/// a child (index, count): a leaf of at most kLeafSize triangles, or a
/// node. The split is the surface-area heuristic's best of 16 bins per axis
/// (the expected number of boxes a query opens), falling back to the median
/// along the widest axis when no bin split separates the triangles or the
/// tree grows deep (the query's stack is fixed).
std::pair<int, int> build_subtree(std::vector<Node>& nodes, std::vector<int>& order, const std::vector<Vector3d>& centroid,
                                  const std::vector<Box>& box, int begin, int end, int depth) {
  if (end - begin <= TriangleTree4::kLeafSize) return {begin, end - begin};
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
  for (int axis = 0; axis < 3 && depth < TriangleTree4::kMaxSahDepth; ++axis) {
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
  const std::pair<int, int> left = build_subtree(nodes, order, centroid, box, begin, mid, depth + 1);
  const std::pair<int, int> right = build_subtree(nodes, order, centroid, box, mid, end, depth + 1);
  Node& node = nodes[static_cast<std::size_t>(index)];
  node.index[0] = left.first;
  node.count[0] = left.second;
  node.index[1] = right.first;
  node.count[1] = right.second;
  return {index, 0};
}

Boxes4 empty_boxes4() {
  Boxes4 b;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 4; ++c) {
      b.lo[a][c] = std::numeric_limits<float>::infinity();
      b.hi[a][c] = -std::numeric_limits<float>::infinity();
    }
  return b;
}

// Outward by 4e-7 relative before the conversion, which rounds by at most
// 6e-8 relative: the float always lies on the safe side (branch-free; the
// boxes grow by 0.4 micrometre per metre).
float round_down(double v) { return static_cast<float>(v - (std::abs(v) * 4e-7 + 1e-30)); }
float round_up(double v) { return static_cast<float>(v + (std::abs(v) * 4e-7 + 1e-30)); }

}  // namespace

std::vector<int> TriangleTree4::build(const std::vector<Eigen::Vector3i>& triangles, const std::vector<Vector3d>& x) {
  // Surface-area-heuristic splits (built once, on the first pose),
  // depth-first node order (left child next, parents before children, so a
  // reverse pass refits).
  std::vector<Vector3d> centroid(triangles.size());
  std::vector<Box> boxes(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    centroid[t] = (x[static_cast<std::size_t>(triangles[t](0))] + x[static_cast<std::size_t>(triangles[t](1))] +
                   x[static_cast<std::size_t>(triangles[t](2))]) / 3.0;
    for (int k = 0; k < 3; ++k) boxes[t].add({x[static_cast<std::size_t>(triangles[t](k))], x[static_cast<std::size_t>(triangles[t](k))]});
  }
  std::vector<int> order(triangles.size());
  for (std::size_t t = 0; t < order.size(); ++t) order[t] = static_cast<int>(t);
  nodes_.clear();
  nodes_.reserve(2 * triangles.size() / kLeafSize + 2);
  const std::pair<int, int> top = build_subtree(nodes_, order, centroid, boxes, 0, static_cast<int>(order.size()), 0);
  if (top.second > 0) {
    // Few enough triangles for one leaf: a root node holding it alone.
    nodes_.emplace_back();
    nodes_[0].index[0] = top.first;
    nodes_[0].count[0] = top.second;
  }
  nodes4_.clear();
  source4_.clear();
  leaf_boxes_.clear();
  nodes4_.reserve(nodes_.size());
  box_slot_.assign(triangles.size(), -1);
  build4(0);
  return order;
}

/// Makes the Node4 of binary node b (and, recursively, of the binary
/// nodes below it at every other level); returns its index. Called once
/// the binary tree is built.
int TriangleTree4::build4(int b) {
  const int index = static_cast<int>(nodes4_.size());
  nodes4_.emplace_back();
  source4_.emplace_back();
  int slot = 0;
  const auto place = [&](int node, int k) {
    const Node& n = nodes_[static_cast<std::size_t>(node)];
    source4_[static_cast<std::size_t>(index)][static_cast<std::size_t>(slot)] = {node, k};
    nodes4_[static_cast<std::size_t>(index)].count[slot] = n.count[k];
    nodes4_[static_cast<std::size_t>(index)].index[slot] = n.index[k];
    const int at = slot++;
    if (n.count[k] > 0) {
      for (int lane = 0; lane < n.count[k]; ++lane)
        box_slot_[static_cast<std::size_t>(n.index[k] + lane)] = 4 * static_cast<int>(leaf_boxes_.size()) + lane;
      leaf_boxes_.push_back(empty_boxes4());
    } else {
      const int child = build4(n.index[k]);  // after this nodes4_ may have moved
      nodes4_[static_cast<std::size_t>(index)].index[at] = child;
    }
  };
  for (int k = 0; k < 2; ++k) {
    const Node& n = nodes_[static_cast<std::size_t>(b)];
    if (n.count[k] == 0 && n.index[k] < 0) continue;
    if (n.count[k] > 0) {
      place(b, k);
      continue;
    }
    const int c = n.index[k];
    for (int k2 = 0; k2 < 2; ++k2) {
      const Node& m = nodes_[static_cast<std::size_t>(c)];
      if (m.count[k2] == 0 && m.index[k2] < 0) continue;
      place(c, k2);
    }
  }
  for (; slot < 4; ++slot) {
    source4_[static_cast<std::size_t>(index)][static_cast<std::size_t>(slot)] = {-1, 0};
    nodes4_[static_cast<std::size_t>(index)].index[slot] = -1;
    nodes4_[static_cast<std::size_t>(index)].count[slot] = 0;
  }
  return index;
}

/// Copies the binary tree's refit boxes into nodes4_.
void TriangleTree4::refit4() {
  for (std::size_t i = 0; i < nodes4_.size(); ++i) {
    Node4& node = nodes4_[i];
    for (int slot = 0; slot < 4; ++slot) {
      const auto [b, k] = source4_[i][static_cast<std::size_t>(slot)];
      for (int a = 0; a < 3; ++a) {
        node.boxes.lo[a][slot] = b < 0 ? std::numeric_limits<float>::infinity() : nodes_[static_cast<std::size_t>(b)].lo[k][a];
        node.boxes.hi[a][slot] = b < 0 ? -std::numeric_limits<float>::infinity() : nodes_[static_cast<std::size_t>(b)].hi[k][a];
      }
    }
  }
}

/// Children after parents in `nodes_`, so one backward pass refits: O(n).
void TriangleTree4::refit(const std::vector<Eigen::Vector3i>& triangles, const std::vector<Vector3d>& x, bool first) {
  const auto corner = [&](int t, int k) -> const Vector3d& {
    return x[static_cast<std::size_t>(triangles[static_cast<std::size_t>(t)](k))];
  };
  swept_.resize(nodes_.size());
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    Node& node = nodes_[i];
    SweptBoxes& sweep = swept_[i];
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
          const int slot = box_slot_[static_cast<std::size_t>(t)];
          Boxes4& block = leaf_boxes_[static_cast<std::size_t>(slot >> 2)];
          for (int a = 0; a < 3; ++a) {
            block.lo[a][slot & 3] = round_down(triangle_lo(a));
            block.hi[a][slot & 3] = round_up(triangle_hi(a));
          }
          lo = lo.cwiseMin(triangle_lo);
          hi = hi.cwiseMax(triangle_hi);
        }
      } else {
        const Node& child = nodes_[static_cast<std::size_t>(node.index[k])];
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
  root_lo_ = Vector3d::Constant(std::numeric_limits<double>::infinity());
  root_hi_ = -root_lo_;
  for (int k = 0; k < 2; ++k)
    for (int a = 0; a < 3; ++a) {
      root_lo_(a) = std::min(root_lo_(a), static_cast<double>(nodes_[0].lo[k][a]));
      root_hi_(a) = std::max(root_hi_(a), static_cast<double>(nodes_[0].hi[k][a]));
    }
}

}  // namespace mrcloth
