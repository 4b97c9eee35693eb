#pragma once
// Planar convex hulls, through CGAL (the one place the solver uses it).
#include <Eigen/Core>

#include <vector>

namespace mrcloth {

/// Length of the convex hull's boundary of `points` (any count, duplicates
/// and collinear points allowed), in their units: 0 for fewer than two
/// distinct points, twice their distance for two or a collinear set.
double convex_hull_perimeter(const std::vector<Eigen::Vector2d>& points);

}  // namespace mrcloth
