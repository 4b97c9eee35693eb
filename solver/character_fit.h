#pragma once
// Whether a tube garment (a skirt or dress) can go round a character over a
// run at all (garment_fit.h on the posed body): said before the run, so a
// garment too narrow for the motion is a warning, not a mystery tear.
#include "character_sim.h"
#include "garment_fit.h"

#include <vector>

namespace mrcloth {

/// Every side of `polygons` (vertex indices) as an edge; a side two
/// polygons share comes twice (a section's hull does not mind).
std::vector<Eigen::Vector2i> polygon_edges(const std::vector<std::vector<int>>& polygons);

/// Per vertex of body.surface() (any pose: the same vertices), whether it
/// counts towards a skirt's girth: its nearest bone in the skeleton's rest
/// pose (arms out) does not end at an arm's joint (a name with Shoulder,
/// Arm, Hand, Finger or Thumb). Arms hang beside a skirt, not in it.
std::vector<char> vertices_off_arms(const PosedBody& body, const Skeleton& skeleton);

/// The hoop demand (hoop_demand) of `garment` (#G x 3 rest positions in the
/// reference pose, metres, and its edges) on `body` over the output frames
/// of the run `options` describes, every `stride`-th of them (>= 1), the
/// body's heights taken as the pelvis joint carries the waist: each frame
/// lowered by how far the pelvis rose since the reference pose. Each
/// level's `frame` is the output frame (0-based). Leaves the body's
/// collision state untouched.
std::vector<HoopLevel> run_hoop_demand(const Motion& motion, const PosedBody& body, const CharacterRunOptions& options,
                                       const Eigen::MatrixX3d& garment, const std::vector<Eigen::Vector2i>& garment_edges,
                                       const HoopDemandOptions& levels = {}, int stride = 1);

}  // namespace mrcloth
