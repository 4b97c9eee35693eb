#pragma once
// A garment run on a character, set up in one place: the clip re-centred
// on where the recording starts, the collision body (capsules, fitted to
// the MakeHuman body when it is given, or its skinned mesh) with bridges
// between the legs, the hands kept out of the hips, the garment placed in
// the skeleton's rest space and, on the skinned body, moved clear of it,
// and the run's settings (the waist on the skin). The plugin's
// multirescloth.simulate / recordInstance and bench_character both build
// their runs here, so the benchmark measures what a user's run does.
#include "character_sim.h"
#include "joint_names.h"
#include "motion_axes.h"
#include "mesh_ops/quad_mesh.h"

#include <Eigen/Geometry>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace mrcloth {

enum class CharacterBodyKind { capsules, mesh };

/// Where the garment's rest positions are, relative to the skeleton's rest
/// pose (which simulate_on_character needs them in).
enum class GarmentPlacement {
  none,         ///< already in the skeleton's rest space
  makehuman,    ///< modelled on MakeHuman's base.obj (loaded in dm): + SkinnedBody::obj_offset
  first_frame,  ///< modelled on the clip's frame 0 (CMU's added T-pose, the embedded walks' T-pose)
};

/// What the pinned waist of a garment on a character follows.
enum class WaistFollows { automatic, pelvis, skin };

/// What a run on a character asks for (the plugin's `body`, `place`,
/// `preroll`, `stepRate`, `skipFirst` and `motion.start` options), SI units.
struct CharacterSetup {
  CharacterBodyKind body = CharacterBodyKind::capsules;
  /// The MakeHuman body (base.obj, rig, weights): the skinned mesh, or what
  /// the capsules are fitted to. Required for `mesh`; none: capsules with
  /// default radii.
  std::optional<MakeHumanOptions> makehuman;
  double thickness = 0.004;  ///< metres kept between the body and the cloth, 0 to kMostContactThickness
  double friction = 0.3;     ///< Coulomb coefficient of the body, >= 0
  /// Capsule radius overrides by joint name (head, tail), metres; 0 removes the capsule.
  std::map<std::string, std::pair<double, double>> radii;
  /// Bridges between the legs (add_leg_bridges): < 0 automatic
  /// (automatic_leg_bridges), 0 none, else the reach in bones from the hips.
  double leg_bridges = -1.0;
  /// Arms opened just enough to keep the hands this far (metres) from the
  /// hips and thighs (arm_clearance.h); < 0: the clip's arms as they are.
  double arm_clearance = ArmClearanceOptions{}.clearance;
  /// Skinned mesh body: the hands leave the collision mesh (without_hands:
  /// wrists capped) and collide as fitted capsules (hand_mitten_capsules),
  /// which have no gaps between fingers for cloth to be caught in and torn.
  /// The body is drawn as it collides: capped wrists and mittens.
  bool hand_mittens = true;
  /// Automatic: the skin whenever the MakeHuman body is given, else the pelvis.
  WaistFollows waist = WaistFollows::automatic;
  double waist_smoothing = 0.02;  ///< metres: a skinned waist's weights averaged along it (CharacterRunOptions::waist_smoothing)
  GarmentPlacement place = GarmentPlacement::none;
  bool skip_first = true;        ///< drop the clip's frame 0 (CMU's added T-pose)
  double motion_start = 0.0;     ///< seconds into the clip (after skip_first) where the recording starts
  double preroll_seconds = 1.0;  ///< rest pose -> first motion frame, not recorded
  double step_rate = 120.0;      ///< time steps per second
};

/// A character ready to run: the motion (kept at a fixed address, as the
/// posed body refers to its skeleton), the collision body, and the rigid
/// transform taking the garment's rest positions into the skeleton's rest
/// space.
struct Character {
  std::unique_ptr<Motion> motion;
  std::unique_ptr<PosedBody> body;
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
  Pose garment_pose;            ///< the pose the garment was modelled on (empty: the rest pose)
  int body_vertices = 0;        ///< skinned mesh vertices (0 for capsules)
  int body_capsules = 0;        ///< capsules (0 for a mesh)
  int hand_mittens = 0;         ///< capsules standing in for the skinned mesh's hands (0: it collides with its own)
  double leg_bridges = 0.0;     ///< the reach of the bridges between the legs, bones (0: none)
  bool fitted_capsules = false; ///< capsule radii fitted to the MakeHuman body
  int capsules_shrunk = 0;      ///< capsules shrunk so the garment starts outside them
  /// The MakeHuman body whose skin the waist follows; null: the pelvis.
  std::shared_ptr<const SkinnedBody> waist_skin;
  /// The hands kept out of the hips (on the body's own proportions); null: off.
  std::shared_ptr<const ArmClearance> arm_clearance;
};

/// How a clip read from another exporter is made the characters' own.
struct ClipConventions {
  bool auto_joint_names = true;  ///< rename a known convention's joints onto CMU names (joint_names.h)
  JointRenaming joint_names;     ///< with !auto_joint_names: this renaming (empty: the names as read)
  bool auto_axes = true;         ///< stand a clip recorded with other axes upright (motion_axes.h)
};

/// What standardise_clip did.
struct ClipChanges {
  JointRenaming renamed;  ///< joints renamed onto CMU names
  AxisTurn turned;        ///< the axes turned to stand it upright
  std::string axes_undecided;  ///< with axes "auto": why no turn could be worked out ("": one was, or none asked)
};

/// Renames the clip's joints onto CMU names and stands it Y up, left along
/// +X, as `conventions` say, before anything reads its joints. Throws
/// ArgumentError for a renaming that names no joint or makes two alike.
ClipChanges standardise_clip(Motion& clip, const ClipConventions& conventions = {});

/// The clip without its frame 0.
Motion without_first_frame(const Motion& motion);

/// Moves the root's rest position to `root_at_start` (metres): the root
/// OFFSET takes it and every frame's root position channels lose the
/// difference, so every frame's pose is unchanged but the rest pose (where
/// the pre-roll starts and the garment is modelled) stands where the
/// recording starts instead of at the origin.
void recentre_root(Motion& motion, const Eigen::Vector3d& root_at_start);

/// Builds the character for `garment` (its boundary loops and placed
/// points decide the automatic leg bridges; capsules are shrunk to it) from
/// the clip as read (`full`, frame 0 kept). Throws ArgumentError for a clip
/// without frames, without the pelvis joint, too short for skip_first or
/// motion_start, a radius for a joint the skeleton lacks, or a mesh body
/// without the MakeHuman files; FigureSizeError (an ArgumentError) for a
/// figure whose size says its units are wrong (figure_size.h: against an
/// adult's legs, and the MakeHuman body's when it is given); InputError for
/// unreadable MakeHuman files.
Character make_character(const Motion& full, const CharacterSetup& setup, const QuadMesh& garment);

/// The garment as the run uses it: a copy in the skeleton's rest space
/// (character.placement), on the skinned body moved clear of it
/// (clear_garment_of_body, T-nodes kept on their edges; the character's
/// body is left in the garment's pose).
struct PlacedGarment {
  QuadMesh mesh;
  GarmentClearance clearance;  ///< what the clearing moved (nothing on capsules)
};
PlacedGarment place_garment(Character& character, const CharacterSetup& setup, const QuadMesh& garment);

/// simulate_on_character's settings for `model` (built from the placed
/// garment): the garment pose, pre-roll, step rate and motion start from
/// the setup, the arm clearance, the waist on the skin when the character
/// has one; frames, fps and the solver settings from `simulation`.
CharacterRunOptions character_run_options(const Character& character, const CharacterSetup& setup,
                                          const DynamicsModel& model, const SimulationOptions& simulation);

}  // namespace mrcloth
