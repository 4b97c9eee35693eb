#pragma once
// Whether a tube garment (a skirt or dress) can go round a character over a
// run at all (garment_fit.h on the posed body): said before the run, so a
// garment too narrow for the motion is a warning, not a mystery tear.
#include "character_sim.h"
#include "garment_fit.h"
#include "mesh_ops/quad_mesh.h"

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

/// Whether `garment` is one tube (two boundary loops: a skirt or dress),
/// the garment a girth is measured for.
bool is_tube_garment(const QuadMesh& garment);

/// The hoop demand (hoop_demand) of `garment` (placed: at rest in the
/// reference pose, metres; its active faces' sides are its edges) on
/// `body` over the output frames of the run `options` describes, at most
/// `max_samples` of them (>= 1; evenly strided), the body's heights taken
/// as the pelvis joint carries the waist: each frame lowered by how far
/// the pelvis rose since the reference pose. Each level's `frame` is the
/// output frame (0-based). Empty unless is_tube_garment(garment). Leaves
/// the body's collision state untouched. What multirescloth.simulate
/// warns from before a run.
std::vector<HoopLevel> run_hoop_demand(const Motion& motion, const PosedBody& body, const CharacterRunOptions& options,
                                       const QuadMesh& garment, const HoopDemandOptions& levels = {},
                                       int max_samples = 100);

}  // namespace mrcloth
