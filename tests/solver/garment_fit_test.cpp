// Girths (convex hull perimeters of level sections) and the hoop demand of
// a tube garment on a body, against closed forms for regular polygons.
#include "mesh_ops/errors.h"
#include "solver/garment_fit.h"
#include "solver/hull_2d.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace mrcloth;

constexpr double kPi = 3.14159265358979323846;

/// A stack of regular n-gons (circumradius r about (cx, cz), one vertex at
/// angle 0) at heights y0, y0 + dy, ..., `rings` of them, joined by vertical
/// edges (and the bottom ring's own edges): a tube's points and edges.
struct Tube {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2i> edges;
  void add(int n, double r, double cx, double cz, double y0, double dy, int rings) {
    const int first = static_cast<int>(points.size());
    for (int h = 0; h < rings; ++h)
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * kPi * k / n;
        points.emplace_back(cx + r * std::cos(a), y0 + dy * h, cz + r * std::sin(a));
        if (h > 0) edges.emplace_back(first + (h - 1) * n + k, first + h * n + k);
        else edges.emplace_back(first + k, first + (k + 1) % n);
      }
  }
  Eigen::MatrixX3d rows() const {
    Eigen::MatrixX3d m(static_cast<Eigen::Index>(points.size()), 3);
    for (std::size_t k = 0; k < points.size(); ++k) m.row(static_cast<Eigen::Index>(k)) = points[k].transpose();
    return m;
  }
};

double polygon_perimeter(int n, double r) { return 2.0 * n * r * std::sin(kPi / n); }

TEST(ConvexHullPerimeter, SquareWithInnerAndRepeatedPoints) {
  const std::vector<Eigen::Vector2d> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {1, 1}, {0.5, 0}};
  EXPECT_NEAR(convex_hull_perimeter(points), 4.0, 1e-12);
}

TEST(ConvexHullPerimeter, DegenerateSets) {
  EXPECT_EQ(convex_hull_perimeter({}), 0.0);
  EXPECT_EQ(convex_hull_perimeter({{0.3, 0.4}}), 0.0);
  EXPECT_EQ(convex_hull_perimeter({{0.3, 0.4}, {0.3, 0.4}}), 0.0);
  // Collinear: there and back.
  EXPECT_NEAR(convex_hull_perimeter({{0, 0}, {1, 1}, {2, 2}, {0.5, 0.5}}), 2.0 * std::sqrt(8.0), 1e-12);
}

TEST(LevelSection, CrossingsInterpolateAndPlaneEdgesGiveBothEnds) {
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0,  //
      2, 1, 4,   //
      1, 1, 1,   //
      3, 1, 3;
  const std::vector<Eigen::Vector2i> edges = {{0, 1}, {2, 3}, {0, 2}};
  const std::vector<Eigen::Vector2d> at_quarter = level_section(p, edges, 1, 0.25);
  ASSERT_EQ(at_quarter.size(), 2u);  // edges 0-1 and 0-2 cross; 2-3 lies above
  EXPECT_NEAR(at_quarter[0].x(), 1.0, 1e-15);  // (z, x) of (0.5, 0.25, 1.0)
  EXPECT_NEAR(at_quarter[0].y(), 0.5, 1e-15);
  EXPECT_EQ(level_section(p, edges, 1, 1.0).size(), 4u);  // 0-1's end, both ends of 2-3, 0-2's end
  const std::vector<char> counted = {1, 1, 0, 1};
  EXPECT_EQ(level_section(p, edges, 1, 0.25, &counted).size(), 1u);
}

// A tube of radius 0.2 m round two legs of radius 0.06 m whose centres are
// 0.1 m apart in frame 0 and 0.3 m in frame 1: the hull of two regular
// 64-gons with vertices at +-90 degrees is the polygon's perimeter plus
// twice the distance.
TEST(HoopDemand, TwoLegsInATube) {
  Tube tube;
  tube.add(128, 0.2, 0.0, 0.0, 0.0, 0.1, 11);
  std::vector<Eigen::MatrixX3d> frames;
  Tube legs;
  for (const double apart : {0.1, 0.3}) {
    legs = Tube();
    legs.add(64, 0.06, -apart / 2, 0.0, 0.0, 0.07, 16);
    legs.add(64, 0.06, apart / 2, 0.0, 0.0, 0.07, 16);
    frames.push_back(legs.rows());
  }
  HoopDemandOptions o;
  o.levels = 5;  // at 0.9, 0.7, 0.5, 0.3, 0.1 m
  const std::vector<HoopLevel> levels = hoop_demand(tube.rows(), tube.edges, frames, legs.edges, {}, o);
  ASSERT_EQ(levels.size(), 5u);
  const double body = polygon_perimeter(64, 0.06) + 2.0 * 0.3, garment = polygon_perimeter(128, 0.2);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    EXPECT_NEAR(levels[k].height, 0.9 - 0.2 * static_cast<double>(k), 1e-12);
    EXPECT_NEAR(levels[k].garment_girth, garment, 1e-12);
    EXPECT_NEAR(levels[k].body_girth, body, 1e-12);
    EXPECT_EQ(levels[k].frame, 1);
    EXPECT_NEAR(levels[k].demand(), body / garment - 1.0, 1e-12);
  }
  EXPECT_EQ(most_demanding_level(levels), 0);  // every level the same section, exactly: the first
  // Only the left leg counted: its polygon alone (the same in both frames).
  std::vector<char> left(static_cast<std::size_t>(frames[0].rows()), 0);
  std::fill(left.begin(), left.begin() + 64 * 16, 1);
  const std::vector<HoopLevel> one = hoop_demand(tube.rows(), tube.edges, frames, legs.edges, left, o);
  EXPECT_NEAR(one[2].body_girth, polygon_perimeter(64, 0.06), 1e-12);
  EXPECT_LT(one[2].demand(), 0.0);
}

TEST(HoopDemand, LevelsWithoutSectionsAndBadInput) {
  Tube tube;
  tube.add(8, 0.2, 0, 0, 0.0, 1.0, 2);
  Tube ring;  // one ring at y = 0, below both levels (0.75 and 0.25 m): no body section
  ring.add(8, 0.1, 0, 0, 0.0, 1.0, 1);
  HoopDemandOptions o;
  o.levels = 2;
  const std::vector<HoopLevel> levels = hoop_demand(tube.rows(), tube.edges, {ring.rows()}, ring.edges, {}, o);
  for (const HoopLevel& level : levels) {
    EXPECT_EQ(level.frame, -1);
    EXPECT_EQ(level.body_girth, 0.0);
    EXPECT_GT(level.garment_girth, 0.0);
  }
  Tube flat;  // every garment edge lies in the plane y = 0, below both levels: no garment section
  flat.add(8, 0.2, 0, 0, 0.0, 1.0, 1);
  Eigen::MatrixX3d with_top = flat.rows();
  with_top.conservativeResize(with_top.rows() + 1, 3);
  with_top.row(with_top.rows() - 1) << 0.0, 1.0, 0.0;  // a lone point sets the top
  const std::vector<HoopLevel> open = hoop_demand(with_top, flat.edges, {}, {}, {}, o);
  EXPECT_EQ(open[0].garment_girth, 0.0);
  EXPECT_TRUE(std::isnan(open[0].demand()));
  EXPECT_EQ(most_demanding_level(open), -1);
  std::vector<HoopLevel> three(3);
  three[0].garment_girth = three[1].garment_girth = 1.0;
  three[0].body_girth = 1.02;
  three[1].body_girth = 1.30;  // three[2] has no garment section (NaN)
  EXPECT_EQ(most_demanding_level(three), 1);
  o.levels = 0;
  EXPECT_THROW(hoop_demand(tube.rows(), tube.edges, {}, {}, {}, o), ArgumentError);
  o.levels = 2;
  o.up_axis = 3;
  EXPECT_THROW(hoop_demand(tube.rows(), tube.edges, {}, {}, {}, o), ArgumentError);
  o.up_axis = 1;
  EXPECT_THROW(hoop_demand(tube.rows(), {{0, 99}}, {}, {}, {}, o), ArgumentError);
  EXPECT_THROW(hoop_demand(tube.rows(), tube.edges, {ring.rows(), ring.rows().topRows(3)}, ring.edges, {}, o),
               ArgumentError);
  EXPECT_THROW(hoop_demand(tube.rows(), tube.edges, {ring.rows()}, ring.edges, std::vector<char>(3, 1), o), ArgumentError);
}

}  // namespace
