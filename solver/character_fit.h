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

/// `levels` with the span a tube's levels divide (HoopDemandOptions::top,
/// bottom) set to where its level loops go all the way round: from the
/// lowest point of its top boundary loop to the highest of its bottom one
/// (`points`: #V x 3 positions of `tube`'s vertices, metres). Above a
/// waistband lower at the front than at the back, or below a hem longer
/// at the back, a level cuts only part of the tube, and the hull of that
/// arc is no girth. Unchanged when `levels` sets a span, when the garment
/// is not a tube, or when the loops overlap in height.
HoopDemandOptions full_round_span(const QuadMesh& tube, const Eigen::MatrixX3d& points, HoopDemandOptions levels);

/// The hoop demand (hoop_demand) of `garment` (placed: at rest in the
/// reference pose, metres; its active faces' sides are its edges) on
/// `body` over the output frames of the run `options` describes (levels
/// over full_round_span's span), at most
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
