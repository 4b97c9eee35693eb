#include "hull_2d.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <cmath>
#include <iterator>

namespace mrcloth {

double convex_hull_perimeter(const std::vector<Eigen::Vector2d>& points) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = Kernel::Point_2;
  std::vector<Point> in;
  in.reserve(points.size());
  for (const Eigen::Vector2d& p : points) in.emplace_back(p.x(), p.y());
  std::vector<Point> hull;
  CGAL::convex_hull_2(in.begin(), in.end(), std::back_inserter(hull));
  if (hull.size() < 2) return 0.0;
  double perimeter = 0.0;
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Point& a = hull[k];
    const Point& b = hull[(k + 1) % hull.size()];
    perimeter += std::sqrt(CGAL::to_double(CGAL::squared_distance(a, b)));
  }
  return perimeter;
}

}  // namespace mrcloth
