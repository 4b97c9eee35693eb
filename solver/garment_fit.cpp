#include "garment_fit.h"

#include "hull_2d.h"
#include "mesh_ops/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace mrcloth {

double HoopLevel::demand() const {
  if (!(garment_girth > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return body_girth / garment_girth - 1.0;
}

int most_demanding_level(const std::vector<HoopLevel>& levels) {
  int worst = -1;
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const double demand = levels[k].demand();
    if (std::isfinite(demand) && (worst < 0 || demand > levels[static_cast<std::size_t>(worst)].demand()))
      worst = static_cast<int>(k);
  }
  return worst;
}

std::vector<Eigen::Vector2d> level_section(const Eigen::MatrixX3d& points, const std::vector<Eigen::Vector2i>& edges,
                                           int up, double height, const std::vector<char>* counted) {
  const int a = (up + 1) % 3, b = (up + 2) % 3;
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2i& e : edges) {
    if (counted && !((*counted)[static_cast<std::size_t>(e(0))] && (*counted)[static_cast<std::size_t>(e(1))])) continue;
    const double h0 = points(e(0), up), h1 = points(e(1), up);
    if (height < std::min(h0, h1) || height > std::max(h0, h1)) continue;
    if (h0 == h1) {  // in the plane
      out.emplace_back(points(e(0), a), points(e(0), b));
      out.emplace_back(points(e(1), a), points(e(1), b));
      continue;
    }
    const double t = (height - h0) / (h1 - h0);
    out.emplace_back(points(e(0), a) + t * (points(e(1), a) - points(e(0), a)),
                     points(e(0), b) + t * (points(e(1), b) - points(e(0), b)));
  }
  return out;
}

namespace {

void require_edges(const std::vector<Eigen::Vector2i>& edges, Eigen::Index count, const char* what) {
  for (std::size_t k = 0; k < edges.size(); ++k)
    for (int end = 0; end < 2; ++end)
      if (edges[k](end) < 0 || edges[k](end) >= count)
        throw ArgumentError(std::string("hoop_demand: ") + what + " edge " + std::to_string(k) + " names vertex " +
                            std::to_string(edges[k](end)) + "; expected an index below " + std::to_string(count));
}

}  // namespace

std::vector<HoopLevel> hoop_demand(const Eigen::MatrixX3d& garment, const std::vector<Eigen::Vector2i>& garment_edges,
                                   const std::vector<Eigen::MatrixX3d>& body_frames,
                                   const std::vector<Eigen::Vector2i>& body_edges, const std::vector<char>& counted,
                                   const HoopDemandOptions& options) {
  if (options.levels < 1) throw ArgumentError("hoop_demand: " + std::to_string(options.levels) + " levels; expected at least 1");
  if (options.up_axis < 0 || options.up_axis > 2)
    throw ArgumentError("hoop_demand: up axis " + std::to_string(options.up_axis) + "; expected 0, 1 or 2");
  if (garment.rows() == 0) throw ArgumentError("hoop_demand: the garment has no points");
  require_edges(garment_edges, garment.rows(), "garment");
  const Eigen::Index body_count = body_frames.empty() ? 0 : body_frames.front().rows();
  for (std::size_t f = 0; f < body_frames.size(); ++f)
    if (body_frames[f].rows() != body_count)
      throw ArgumentError("hoop_demand: body frame " + std::to_string(f) + " has " + std::to_string(body_frames[f].rows()) +
                          " vertices; frame 0 has " + std::to_string(body_count));
  if (!body_frames.empty()) require_edges(body_edges, body_count, "body");
  if (!counted.empty() && counted.size() != static_cast<std::size_t>(body_count))
    throw ArgumentError("hoop_demand: " + std::to_string(counted.size()) + " body vertex flags; expected one per body vertex (" +
                        std::to_string(body_count) + ")");
  const int up = options.up_axis;
  const double top = std::isnan(options.top) ? garment.col(up).maxCoeff() : options.top;
  const double bottom = std::isnan(options.bottom) ? garment.col(up).minCoeff() : options.bottom;
  if (!(top > bottom))
    throw ArgumentError("hoop_demand: the levels' span runs from " + std::to_string(top) + " down to " +
                        std::to_string(bottom) + " m; expected its top above its bottom");
  std::vector<HoopLevel> levels(static_cast<std::size_t>(options.levels));
  for (int k = 0; k < options.levels; ++k) {
    HoopLevel& level = levels[static_cast<std::size_t>(k)];
    level.height = top - (k + 0.5) / options.levels * (top - bottom);
    level.garment_girth = convex_hull_perimeter(level_section(garment, garment_edges, up, level.height));
    for (std::size_t f = 0; f < body_frames.size(); ++f) {
      const std::vector<Eigen::Vector2d> section =
          level_section(body_frames[f], body_edges, up, level.height, counted.empty() ? nullptr : &counted);
      if (section.empty()) continue;
      const double girth = convex_hull_perimeter(section);
      if (level.frame < 0 || girth > level.body_girth) {
        level.body_girth = girth;
        level.frame = static_cast<int>(f);
      }
    }
  }
  return levels;
}

}  // namespace mrcloth
