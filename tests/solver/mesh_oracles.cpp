#include "mesh_oracles.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace mrcloth::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

using Eigen::Vector3d;
using Eigen::Vector3i;

// ---- independent brute force -----------------------------------------------

double segment_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double triangle_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a);
  if (n.squaredNorm() > 0) {
    const Vector3d unit = n.normalized();
    const Vector3d q = p - unit * unit.dot(p - a);
    const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 && (a - c).cross(q - c).dot(n) >= 0;
    if (inside) return std::abs(unit.dot(p - a));
  }
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

double brute_distance(const Mesh& mesh, const Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vector3i& t : mesh.triangles) best = std::min(best, triangle_distance(p, mesh.vertex(t(0)), mesh.vertex(t(1)), mesh.vertex(t(2))));
  return best;
}

double winding_number(const Mesh& mesh, const Vector3d& p) {
  double total = 0.0;
  for (const Vector3i& t : mesh.triangles) {
    const Vector3d a = mesh.vertex(t(0)) - p, b = mesh.vertex(t(1)) - p, c = mesh.vertex(t(2)) - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    total += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  return total / (4.0 * kPi);
}

// ---- meshes ------------------------------------------------------------------

Mesh icosphere(int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vector3d> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                             {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (Vector3d& p : v) p.normalize();
  std::vector<Vector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoint.find(key);
      if (found != midpoint.end()) return found->second;
      v.push_back((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]).normalized());
      return midpoint[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<Vector3i> next;
    for (const Vector3i& t : f) {
      const int ab = mid(t(0), t(1)), bc = mid(t(1), t(2)), ca = mid(t(2), t(0));
      next.emplace_back(t(0), ab, ca);
      next.emplace_back(t(1), bc, ab);
      next.emplace_back(t(2), ca, bc);
      next.emplace_back(ab, bc, ca);
    }
    f = next;
  }
  Mesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) mesh.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  mesh.triangles = f;
  return mesh;
}

Mesh subdivided_cube(int n) {
  std::map<std::array<int, 3>, int> index;
  std::vector<Vector3d> v;
  auto vertex = [&](std::array<int, 3> lattice) {
    const auto found = index.find(lattice);
    if (found != index.end()) return found->second;
    v.emplace_back(2.0 * lattice[0] / n - 1.0, 2.0 * lattice[1] / n - 1.0, 2.0 * lattice[2] / n - 1.0);
    return index[lattice] = static_cast<int>(v.size()) - 1;
  };
  std::vector<Vector3i> f;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) is right-handed
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          auto at = [&](int di, int dj) {
            std::array<int, 3> l{};
            l[static_cast<std::size_t>(axis)] = side * n;
            l[static_cast<std::size_t>(u)] = i + di;
            l[static_cast<std::size_t>(w)] = j + dj;
            return vertex(l);
          };
          const int a = at(0, 0), b = at(1, 0), c = at(1, 1), d = at(0, 1);
          // Counter-clockwise seen from outside: +axis side uses (u, w) order.
          if (side == 1) {
            f.emplace_back(a, b, c);
            f.emplace_back(a, c, d);
          } else {
            f.emplace_back(a, c, b);
            f.emplace_back(a, d, c);
          }
        }
      }
    }
  }
  Mesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) mesh.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  mesh.triangles = f;
  return mesh;
}

namespace {

/// A point uniform in the box with corners lo and hi.
Vector3d random_in_box(std::mt19937& rng, const Vector3d& lo, const Vector3d& hi) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  return lo + Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(hi - lo);
}

/// A direction uniform on the unit sphere (length 1).
Vector3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  for (;;) {
    const Vector3d v(gauss(rng), gauss(rng), gauss(rng));
    if (v.norm() > 1e-3) return v.normalized();
  }
}

}  // namespace

std::vector<Vector3d> sample_points(const Mesh& mesh, std::mt19937& rng, int count, double spread) {
  const Vector3d lo = mesh.vertices.colwise().minCoeff().transpose(), hi = mesh.vertices.colwise().maxCoeff().transpose();
  const Vector3d pad = Vector3d::Constant(spread);
  std::vector<Vector3d> points;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(mesh.triangles.size()) - 1);
  for (int i = 0; i < count; ++i) {
    if (i % 4 == 0) {
      points.push_back(random_in_box(rng, lo - pad, hi + pad));
      continue;
    }
    const Vector3i& t = mesh.triangles[static_cast<std::size_t>(pick(rng))];
    Vector3d s;
    if (i % 4 == 1) {
      double r1 = unit(rng), r2 = unit(rng);
      if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
      s = mesh.vertex(t(0)) + r1 * (mesh.vertex(t(1)) - mesh.vertex(t(0))) + r2 * (mesh.vertex(t(2)) - mesh.vertex(t(0)));
    } else if (i % 4 == 2) {
      s = mesh.vertex(t(i % 3));
    } else {
      s = 0.5 * (mesh.vertex(t(0)) + mesh.vertex(t(1)));
    }
    points.push_back(s + spread * unit(rng) * random_unit(rng));
  }
  return points;
}

void expect_matches_brute_force(const MeshBody& body, const Mesh& mesh, const std::vector<Vector3d>& points,
                                const std::string& label) {
  int inside = 0, outside = 0;
  for (const Vector3d& p : points) {
    const SurfaceQuery q = body.query(p);
    const double expected = brute_distance(mesh, p);
    ASSERT_NEAR(std::abs(q.distance), expected, 1e-12) << label << " at (" << p.transpose() << ")";
    if (expected < 1e-9) continue;
    const bool is_inside = winding_number(mesh, p) > 0.5;
    ASSERT_EQ(q.distance < 0, is_inside) << label << " at (" << p.transpose() << "), distance " << q.distance;
    ASSERT_NEAR(q.normal.norm(), 1.0, 1e-12);
    // The normal is the distance's gradient: one step along it gains the step.
    (is_inside ? inside : outside)++;
  }
  EXPECT_GT(inside, static_cast<int>(points.size()) / 10) << label << ": too few points inside to mean anything";
  EXPECT_GT(outside, static_cast<int>(points.size()) / 10) << label;
}

Eigen::MatrixX3d transformed(const Mesh& mesh, const Eigen::Matrix3d& a, const Vector3d& t) {
  Eigen::MatrixX3d out(mesh.vertices.rows(), 3);
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) out.row(i) = (a * mesh.vertex(static_cast<int>(i)) + t).transpose();
  return out;
}

}  // namespace mrcloth::test
