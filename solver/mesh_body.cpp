// MeshBody: collision with a moving closed triangle mesh (the skinned
// body): a bounding-volume hierarchy refit every pose (TriangleTree4),
// closest point and inside/outside, and the response of a cloth point.
// Split from body_skinned_mesh.cpp, which loads, binds and skins the body.
#include "mesh_body.h"

#include "mesh_ops/errors.h"
#include "triangle_tree4.h"

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

struct MeshBody::Impl {
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

  TriangleTree4 tree;                          ///< over the triangles, in this pose; names them in leaf order
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

  static void require_corners_in_range(const std::vector<Eigen::Vector3i>& input, int vertex_count) {
    for (std::size_t t = 0; t < input.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        if (input[t](k) < 0 || input[t](k) >= vertex_count)
          throw ArgumentError("MeshBody: triangle " + std::to_string(t) + " names vertex " + std::to_string(input[t](k)) +
                              "; expected an index below " + std::to_string(vertex_count));
      }
    }
  }

  /// Builds the tree (once, on the first pose) and stores the triangles in
  /// its leaf order.
  void store_in_leaf_order(const std::vector<Eigen::Vector3i>& input) {
    const std::vector<int> order = tree.build(input, x);
    triangles.resize(input.size());
    leaf_of_input.resize(input.size());
    for (std::size_t t = 0; t < order.size(); ++t) {
      triangles[t] = input[static_cast<std::size_t>(order[t])];
      leaf_of_input[static_cast<std::size_t>(order[t])] = static_cast<int>(t);
    }
    ignored.assign(input.size(), 0);
    on_rim.assign(input.size(), 0);
  }

  /// Neighbours across each edge: the mesh must be closed and consistently
  /// oriented (each directed edge once, its reverse once).
  void link_neighbours() {
    std::unordered_map<std::uint64_t, int> directed;
    directed.reserve(3 * triangles.size());
    auto key = [](int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); };
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const int a = triangles[t](k), b = triangles[t]((k + 1) % 3);
        if (!directed.emplace(key(a, b), static_cast<int>(3 * t + static_cast<std::size_t>(k))).second) {
          throw ArgumentError("MeshBody: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                              ") is used twice in the same direction; expected a consistently oriented 2-manifold mesh");
        }
      }
    }
    neighbours.resize(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const int a = triangles[t](k), b = triangles[t]((k + 1) % 3);
        const auto found = directed.find(key(b, a));
        if (found == directed.end()) {
          throw ArgumentError("MeshBody: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                              ") has a triangle on one side only; expected a closed mesh");
        }
        neighbours[t][static_cast<std::size_t>(k)] = found->second / 3;
      }
    }
  }

  /// The (triangle, corner) pairs around each vertex (ring, ring_start).
  void build_rings() {
    ring_start.assign(x.size() + 1, 0);
    for (const Eigen::Vector3i& tri : triangles)
      for (int k = 0; k < 3; ++k) ++ring_start[static_cast<std::size_t>(tri(k)) + 1];
    for (std::size_t v = 0; v < x.size(); ++v) ring_start[v + 1] += ring_start[v];
    ring.resize(3 * triangles.size());
    std::vector<int> fill(ring_start.begin(), ring_start.end() - 1);
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        ring[static_cast<std::size_t>(fill[static_cast<std::size_t>(triangles[t](k))]++)] = {static_cast<int>(t), k};
  }

  void require_outward_orientation() const {
    double volume = 0.0;
    for (const Eigen::Vector3i& tri : triangles)
      volume += x[static_cast<std::size_t>(tri(0))].dot(x[static_cast<std::size_t>(tri(1))].cross(x[static_cast<std::size_t>(tri(2))]));
    if (!(volume > 0.0))
      throw ArgumentError("MeshBody: the triangles enclose a negative volume; expected them ordered counter-clockwise seen from outside");
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

  const Vector3d& corner(int t, int k) const {
    return x[static_cast<std::size_t>(triangles[static_cast<std::size_t>(t)](k))];
  }

  /// Unit normal of triangle t (zero when it is degenerate).
  Vector3d face_normal(int t) const {
    const Vector3d n = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
    const double length = n.norm();
    return length > 0.0 ? Vector3d(n / length) : Vector3d::Zero();
  }

  /// Tests seen triangle t against the closest so far (`best`, its squared
  /// distance, and `out`); its own box first, which rejects most.
  void consider(const Vector3d& p, int t, double& best, Closest& out) const {
    consider(p, t, tree.triangle_box_distance2(p, t), best, out);
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

  /// Closest seen triangle to p closer than sqrt(max_d2); false when none is.
  bool closest(const Vector3d& p, double max_d2, Closest& out) const {
    double best = max_d2;
    tree.leaves_near(p, [&] { return best; }, [&](int first, int count) {
      double box2[4];
      tree.leaf_box_distances(first, p, box2);
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
    tree.leaves_near(p, [&] { return limit2; }, [&](int leaf, int count) {
      double box2[4];
      tree.leaf_box_distances(leaf, p, box2);
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
    if (!deep || !tree.inside_root(p)) return false;
    if (!closest(p, std::numeric_limits<double>::infinity(), c)) return false;
    out = signed_contact(p, c);
    return out.distance < 0.0;
  }

  /// Whether no triangle can have crossed the segment a-b since the last
  /// update but one: no leaf's swept box meets it. A point that moved along
  /// it while the surface moved (straight) between those poses then stayed
  /// on its side. Conservative: a false "no" only costs a query.
  bool segment_clear(const Vector3d& a, const Vector3d& b) const {
    return tree.leaves_on_segment(a, b - a, true, [](int, int) { return false; });
  }

  /// Whether p is inside the closed mesh, every triangle counted (the
  /// ignored ones too): the parity of a ray's crossings, the ray in a
  /// direction no face or edge of a body is likely to be aligned with.
  /// The parity of a closed surface's crossings (self-intersecting too) is
  /// the same along every ray, so the ray leaves by the root box's nearest
  /// face: out of a leg through its front or back, not up through the torso
  /// (a third of the boxes to open on a walking body).
  bool inside_whole_mesh(const Vector3d& p) const {
    if (!tree.inside_root(p)) return false;
    int axis = 0;
    double sign = 1.0, reach = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (p(k) - tree.root_lo()(k) < reach) {
        reach = p(k) - tree.root_lo()(k);
        axis = k;
        sign = -1.0;
      }
      if (tree.root_hi()(k) - p(k) < reach) {
        reach = tree.root_hi()(k) - p(k);
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
    tree.leaves_on_segment(p, d, false, [&](int first, int count) {
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
    tree.leaves_on_segment(a, d, false, [&](int first, int count) {
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
      if (tree.triangle_box_distance2(p, t) < radius2) return true;
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
    if (!tree.inside_root(p)) return false;
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
  Impl::require_corners_in_range(triangles, static_cast<int>(vertices.rows()));
  m.store_in_leaf_order(triangles);
  m.link_neighbours();
  m.number_vertices_by_leaf();  // after the checks above, whose messages name the input's vertices
  m.build_rings();
  m.x_previous = m.x;
  m.tree.refit(m.triangles, m.x, /*first=*/true);
  m.require_outward_orientation();
  const double diagonal = (m.tree.root_hi() - m.tree.root_lo()).norm();
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
  m.tree.refit(m.triangles, m.x);
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
    if (!m.tree.inside_root(p)) return {};
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
