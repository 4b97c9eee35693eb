#pragma once
// Whether a tube garment (a skirt) can go round a moving body at all: at
// each of several heights, the girth of the garment at rest against the
// largest girth of the body's section there over a motion. Where the body
// needs more than the cloth's stretch limit, no solver can keep the garment
// whole and within its limit: the stride asks for cloth that is not there.
#include <Eigen/Core>

#include <limits>
#include <vector>

namespace mrcloth {

struct HoopDemandOptions {
  int levels = 8;   ///< heights, >= 1: the middles of equal bands from `top` to `bottom`
  int up_axis = 1;  ///< 0, 1 or 2: the vertical axis (y in the skeleton's space)
  /// The span the levels divide, metres along the up axis (top > bottom);
  /// NaN: the garment's highest / lowest point. run_hoop_demand sets the
  /// span where a tube's level loops go all the way round (see there).
  double top = std::numeric_limits<double>::quiet_NaN();
  double bottom = std::numeric_limits<double>::quiet_NaN();
};

/// One height. A girth is the perimeter of the convex hull of a mesh's
/// section by the level plane there (where its edges cross it), seen along
/// the up axis, in metres.
struct HoopLevel {
  double height = 0.0;         ///< metres along the up axis
  double garment_girth = 0.0;  ///< of the garment at rest (0: no section)
  double body_girth = 0.0;     ///< of the body's counted edges, the largest over the frames (0: no section)
  int frame = -1;              ///< the frame of body_girth (-1: no counted body edge crosses this level in any frame)
  /// The strain a level loop of the garment needs to go round the body
  /// there: body_girth / garment_girth - 1 (< 0: slack; NaN without a
  /// garment section).
  double demand() const;
};

/// The index of the level whose demand is largest (the first of equals),
/// -1 when no level has a garment section.
int most_demanding_level(const std::vector<HoopLevel>& levels);

/// Where `edges` (vertex index pairs into `points`, #P x 3, metres) cross
/// the plane at `height` along `up`, projected along it; an edge lying in
/// the plane gives both ends. `counted` (per point, or null: all): only
/// edges with both ends counted.
std::vector<Eigen::Vector2d> level_section(const Eigen::MatrixX3d& points, const std::vector<Eigen::Vector2i>& edges,
                                           int up, double height, const std::vector<char>* counted = nullptr);

/// Levels from the garment's top to its bottom. `garment`: #G x 3 rest
/// positions and its edges; `body_frames`: per frame #B x 3 positions in
/// the garment's space and the body's edges (metres); `counted`: per body
/// vertex whether it counts (empty: every one), e.g. not the arms, which
/// hang beside a skirt rather than in it. Throws ArgumentError for bad
/// options, edges naming missing vertices, frames of different vertex
/// counts or a mask of the wrong size.
std::vector<HoopLevel> hoop_demand(const Eigen::MatrixX3d& garment, const std::vector<Eigen::Vector2i>& garment_edges,
                                   const std::vector<Eigen::MatrixX3d>& body_frames,
                                   const std::vector<Eigen::Vector2i>& body_edges, const std::vector<char>& counted = {},
                                   const HoopDemandOptions& options = {});

}  // namespace mrcloth
