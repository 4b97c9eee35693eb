#pragma once
// A garment on a moving character: the waist pinned to the pelvis, a body
// that collides (capsules or a skinned mesh), a pre-roll from the rest pose
// to the first motion frame, then the motion, recorded frame by frame.
#include "arm_clearance.h"
#include "body_capsules.h"
#include "body_skinned_mesh.h"
#include "mesh_body.h"
#include "body_surface.h"
#include "simulate.h"
#include "skeleton.h"

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mrcloth {

/// A collision body that follows a skeleton's pose.
class PosedBody {
 public:
  virtual ~PosedBody() = default;
  virtual void set_pose(const Pose& pose) = 0;
  virtual const CollisionScene& scene() const = 0;
  /// The body's surface in `pose`, for drawing (same faces for every pose;
  /// the collision state is untouched).
  virtual BodySurface surface(const Pose& pose) const = 0;
};

/// Capsules along the bones (CapsuleRig), posed by FK; with `joint_rest`
/// (a body's own rest joints, the ones its radii were fitted about) on that
/// body's proportions (proportioned_pose), else on the skeleton's.
class CapsulePosedBody : public PosedBody {
 public:
  CapsulePosedBody(CapsuleRig rig, const Skeleton& skeleton, std::vector<Eigen::Vector3d> joint_rest = {})
      : body_(std::move(rig), skeleton), skeleton_(skeleton), joint_rest_(std::move(joint_rest)) {}
  void set_pose(const Pose& pose) override { body_.pose(proportioned_pose(skeleton_, joint_rest_, pose)); }
  const CollisionScene& scene() const override { return body_; }
  BodySurface surface(const Pose& pose) const override {
    return capsule_surface(posed_capsules(body_.rig(), proportioned_pose(skeleton_, joint_rest_, pose)));
  }

 private:
  CapsuleBody body_;
  const Skeleton& skeleton_;
  std::vector<Eigen::Vector3d> joint_rest_;
};

/// A skinned triangle mesh, re-skinned and refit for every pose, with
/// optional capsules posed by the same skeleton on the body's proportions:
/// bridges between the legs (add_leg_bridges) and bones (the hands' mittens,
/// hand_mitten_capsules, for a body cut by without_hands). surface() draws
/// `drawn` (`body` textured; empty: `body`), the bridges and the mittens.
class SkinnedPosedBody : public PosedBody {
 public:
  SkinnedPosedBody(SkinnedBody body, const Skeleton& skeleton, double thickness = 0.004, double friction = 0.3,
                   CapsuleRig capsules = {}, SkinnedBody drawn = {});
  ~SkinnedPosedBody() override;
  SkinnedPosedBody(const SkinnedPosedBody&) = delete;  // its scene and turned-triangle test refer to its own members
  SkinnedPosedBody& operator=(const SkinnedPosedBody&) = delete;
  void set_pose(const Pose& pose) override;
  const CollisionScene& scene() const override;
  BodySurface surface(const Pose& pose) const override;  ///< the skinned mesh, then the bridges

 private:
  class MeshAndBridges;
  SkinnedBody body_;
  SkinnedBody drawn_;  ///< what surface() draws (empty: body_)
  const Skeleton& skeleton_;
  std::unique_ptr<MeshBody> mesh_;
  TurnedTriangles turned_;  ///< over body_, so declared after it
  std::unique_ptr<CapsuleBody> bridges_;  ///< the bridges and mittens; null without any
  std::unique_ptr<MeshAndBridges> scene_;
};

/// The most time steps an output frame may take: progress and cancellation
/// come between frames, so a frame's work is bounded (as simulate bounds
/// substeps).
constexpr int kMostStepsPerFrame = 1000;

struct CharacterRunOptions {
  int frames = 60;                   ///< output frames of the motion (after the pre-roll), >= 1
  double fps = 30.0;                 ///< output frames per second
  /// Time steps per second (the mocap rate), from fps to kMostStepsPerFrame
  /// x fps; rounded to a multiple of fps.
  double step_rate = 120.0;
  double preroll_seconds = 1.0;      ///< rest pose -> first motion frame, not recorded; >= 0
  double motion_start = 0.0;         ///< seconds into the clip where the recording starts
  std::string pelvis_joint = "Hips"; ///< the joint whose frame the pinned waist follows
  /// The pose the garment was modelled on, in the skeleton's rest space
  /// (root where the rest pose has it); the pre-roll starts from it. Empty:
  /// the rest pose. MakeHuman garments: mesh_pose of the body (its A-pose).
  Pose garment_pose;
  /// How the pinned waist moves. Empty: rigidly with the pelvis joint's
  /// frame. Otherwise one list of (joint, weight) per pinned vertex (in
  /// DynamicsModel::pinned_vertices order, weights summing to 1): the waist
  /// is skinned by the same joints as the body under it (see
  /// waist_skin_weights), about `body_joints`, so it moves as that skin
  /// does. A skinned body bends above the pelvis (MakeHuman's waist moves
  /// with the lower back), and a waist pinned rigidly to the pelvis ends up
  /// to 13 mm inside it.
  std::vector<std::vector<std::pair<int, double>>> waist_weights;
  std::vector<Eigen::Vector3d> body_joints;  ///< SkinnedBody::joint_rest of the body the weights come from; empty: the skeleton's
  /// Metres: waist_follows_skin averages the pins' skin weights over their
  /// neighbours within about this (smooth_along_waist's sigma), so the
  /// band does not stretch where the skin under it does; 0: each pin
  /// moves exactly as the skin under it.
  double waist_smoothing = 0.02;
  /// Opens the arms of every pose just enough to keep the hands out of the
  /// hips and thighs (clear_arms); null: the poses as the clip has them.
  std::shared_ptr<const ArmClearance> arm_clearance;
  SimulationOptions simulation;      ///< iterations, sweeps, gravity, extra colliders; frames/fps/substeps are set from the above
};

struct CharacterRunReport {
  SimulationReport preroll;          ///< the pre-roll (no cache)
  SimulationReport motion;           ///< the recorded motion (cache, timings per frame)
  double max_waist_error = 0.0;      ///< largest distance of a pinned vertex from its target at an output frame, metres
  double max_arm_angle = 0.0;        ///< largest angle options.arm_clearance opened an arm by at any step, radians
  int arm_steps = 0;                 ///< steps at which it opened one
};

/// The angle (radians) the clip's facing at `time` may differ from its rest
/// pose's before the reference pose is turned to it (start_heading_turn):
/// below it the pre-roll's turn is small (every shared clip starts within
/// 16 degrees of its rest pose's facing), above it the body spun while the
/// cloth settled (a clip turned 90 degrees ended its pre-roll 4.6 cm from
/// the same run unturned).
constexpr double kHeadingTurnThreshold = 30.0 * 3.14159265358979323846 / 180.0;

/// The turn about the vertical (+Y) through the root's position at `time`
/// that faces the rest pose as the clip faces at `time` (the root's +X, its
/// left, projected on the ground), where they differ by more than
/// kHeadingTurnThreshold; else the identity. reference_pose applies it,
/// and make_character turns the garment's placement by it, so a clip that
/// starts facing another way does not spin the figure in the pre-roll.
Eigen::Isometry3d start_heading_turn(const Motion& motion, double time);

/// The reference pose: options.garment_pose (by default the skeleton's rest
/// pose, for CMU the T-pose) moved so its root stands where the clip's root
/// is at motion_start, and turned by start_heading_turn. Garments are
/// simulated from their rest shape in this pose, and the pinned waist keeps
/// its place relative to the pelvis as posed here.
Pose reference_pose(const Motion& motion, const CharacterRunOptions& options);

/// Per point, the skin weights at the nearest point of the body's surface
/// (body.triangles): its triangle's vertices' weights blended by its
/// barycentric coordinates, so they vary continuously along the skin.
/// `points` (#P x 3, metres) and `body_vertices` (the body's vertices in the
/// same pose and space, #V x 3). For CharacterRunOptions::waist_weights,
/// with the pinned waist and the body both in the reference pose. Throws
/// ArgumentError for a vertex count other than the weights', no triangles,
/// or a surface MeshBody refuses (it must be closed and consistently
/// oriented, as the skinned collision body must).
std::vector<std::vector<std::pair<int, double>>> waist_skin_weights(const SkinnedBody& body,
                                                                    const Eigen::MatrixX3d& body_vertices,
                                                                    const Eigen::MatrixX3d& points);

/// Per point, the Gaussian-weighted mean (sigma `sigma`, metres, over the
/// points within 3 sigma, itself included) of the points' weight lists:
/// neighbouring pins then turn about nearly the same joints, so the band
/// between them keeps its length where linear blend skinning stretches the
/// skin under it (the shared trousers' waistband over the hip stretched
/// 53 % with each pin's own skin weights, 10 % with them averaged over 2 cm).
/// `weights` (one list per row of `points`, #P x 3, metres; each summing
/// to 1, and so is each result); sigma 0: the lists as given. Throws
/// ArgumentError for a count mismatch or a negative or non-finite sigma.
std::vector<std::vector<std::pair<int, double>>> smooth_along_waist(
    const std::vector<std::vector<std::pair<int, double>>>& weights, const Eigen::MatrixX3d& points, double sigma);

/// Makes the model's pinned waist follow the skin of `body` (the skinned
/// body the run collides with, or the one a capsule rig was fitted to):
/// sets options.waist_weights (from the body in the reference pose, so
/// options.garment_pose and motion_start must already be set; smoothed
/// over options.waist_smoothing) and options.body_joints. No pinned
/// vertices: nothing to set.
void waist_follows_skin(CharacterRunOptions& options, const SkinnedBody& body, const Motion& motion,
                        const DynamicsModel& model);

/// Fits the rig's radii to `body` (fit_capsule_radii about its own joints),
/// then lets `overrides` (joint name -> head, tail radius in metres) win
/// over the fit as they win over the defaults, and drops the bones left
/// without radius (0 removes a joint's capsule).
void fit_capsules_to_body(CapsuleRig& rig, const Skeleton& skeleton, const SkinnedBody& body,
                          const std::map<std::string, std::pair<double, double>>& overrides = {});

/// Capsules around the hands of a skinned body (mittens), for a body whose
/// hands are cut off its collision mesh (without_hands): per hand that
/// holds vertices (hand_vertices), one capsule carried by the hand joint,
/// along the principal axis of the hand's vertices in the rest pose from
/// their 5th to their 95th percentile along it, as thick as their median
/// distance from it (metres; about a palm's half-width). Empty when the
/// body has no hands.
std::vector<BoneCapsule> hand_mitten_capsules(const Skeleton& skeleton, const SkinnedBody& body);

/// Shrinks the capsules a garment starts inside of (clear_capsules_of),
/// posed as the run starts: the reference pose on `body_joints` (the
/// body's own joints the rig was fitted about; empty: the skeleton's).
/// `garment` (#V x 3, metres) is the placed garment. Returns how many
/// capsules shrank.
int clear_capsules_for_garment(CapsuleRig& rig, const Motion& motion, const CharacterRunOptions& options,
                               const std::vector<Eigen::Vector3d>& body_joints, const Eigen::MatrixX3d& garment);

/// What clear_garment_of_body did.
struct GarmentClearance {
  int moved = 0;              ///< points moved out
  double largest_move = 0.0;  ///< metres
};

/// Moves every garment point that starts inside `body`, or nearer to it
/// than its thickness, out to the thickness, in the pose the garment was
/// modelled on (reference_pose of `options`): a refined garment's new
/// points lie on its flat coarse faces, chords that cut into a curved body,
/// and a pinned waist there would stay inside for the whole run. `points`
/// (#V x 3, metres, placed) are changed in place; each `hanging` entry
/// {vertex, parent a, parent b} is then put back at its parents' midpoint,
/// as the T-node constraint requires, its edge moved out with it where that
/// midpoint is inside (a few passes). The body is left in that pose.
GarmentClearance clear_garment_of_body(PosedBody& body, const Motion& motion, const CharacterRunOptions& options,
                                       Eigen::MatrixX3d& points, const std::vector<std::array<int, 3>>& hanging);

/// How far down the legs bridges go for a garment (add_leg_bridges' reach,
/// 0 = none): one tube around both legs (two boundary loops: a skirt or
/// dress) gets them to the knees (1), or to the ankles (2) when any of its
/// points (#V x 3, metres, placed in the skeleton's rest space) lies below
/// the knees' rest height. Trousers (three loops), shirts and skeletons
/// without the CMU leg names get none.
double automatic_leg_bridges(int boundary_loop_count, const Eigen::MatrixX3d& placed_points, const Skeleton& skeleton);

/// The pose of the character at simulation time `time`: during the pre-roll
/// a smooth blend from the reference pose to the clip's pose at
/// motion_start, then the clip from motion_start; arms opened by
/// options.arm_clearance when it is set (`arm_angle`, if given, receives
/// the largest angle an arm was turned by, radians).
Pose character_pose(const Motion& motion, double time, const CharacterRunOptions& options,
                    double* arm_angle = nullptr);

/// The fastest a joint of the legs (the hips, hip joints, knees, ankles)
/// moves between two consecutive frames of a clip.
struct LegSpeed {
  double speed = 0.0;  ///< m/s
  int frame = -1;      ///< the first of the two frames (-1: no two frames)
  std::string joint;   ///< the joint's name
};

/// The LegSpeed over frames first_frame..last_frame of `motion` (-1: its
/// last). A capture's glitch (a root that jumps, a knee off for one frame)
/// or jitter moves them far faster than any stride, and cloth on the legs
/// tears: the shared clips peak at 3.5-5.2 m/s, the run 09_01 at 8.2; in a
/// sweep of 2026-11-27 07_06 with 1 degree of noise per frame 17 m/s (torn),
/// played four times as fast 16 (torn), a knee 90 degrees off for one
/// frame 65, a root jumping 1 m 120.
LegSpeed fastest_leg_speed(const Motion& motion, int first_frame = 0, int last_frame = -1);

/// How much a clip's legs jitter: over frames first_frame..last_frame (-1:
/// its last), the median of the largest acceleration of a joint of the legs
/// at a frame (its second difference of position over the frame time
/// squared). A clean walk's is small (the shared clips: see
/// kLegJitterWarning in the plugin); noise of a fraction of a degree per
/// frame at 120 frames a second makes it ten times that, and tears cloth on
/// the legs below the speed fastest_leg_speed warns of. m/s^2; 0 with fewer
/// than three frames or no leg joints.
double leg_jitter(const Motion& motion, int first_frame = 0, int last_frame = -1);

/// Of a few smoothings (seconds: 0.005 to 0.1), the least, more than
/// `already` (what `motion` was smoothed by), that brings leg_jitter over
/// frames first_frame..last_frame (-1: the last) under `target` (m/s^2);
/// the largest if none does. Smooths only those frames and the widest
/// window around them (a clip may hold hours).
double smoothing_against_jitter(const Motion& motion, double already, int first_frame, int last_frame, double target);

/// The fastest a hip, knee or ankle moves in the pre-roll (m/s): each one's
/// way from the rest pose to the motion's first frame over
/// options.preroll_seconds, at the blend's steepest (1.5 times the mean);
/// infinite with no pre-roll where one moves at all, 0 where none does.
/// Cloth on the legs tears where this is far beyond a walk's (sweep of
/// 2026-11-27: trousers whole from a 0.1 s pre-roll on CMU 07_06, torn
/// below 0.05 s).
double preroll_leg_speed(const Motion& motion, const CharacterRunOptions& options);

/// The output frames the pre-roll of options.preroll_seconds takes (at
/// options.fps, rounded, at least one for any pre-roll): simulated before
/// the motion's frames, spanning the pre-roll exactly (a little longer or
/// shorter than options.fps's where it is no whole number of them), and
/// counted first by simulate_on_character's progress.
int preroll_frame_count(const CharacterRunOptions& options);

/// The steps of each output frame: options.step_rate / options.fps rounded,
/// at least one (steps come in whole numbers per frame, so the rate run is
/// this times options.fps, which may differ from step_rate).
int steps_per_frame(const CharacterRunOptions& options);

/// Runs the pre-roll and the motion. The model's rest shape must sit on the
/// reference pose (place_garment in character_setup.h puts it there); its pinned vertices follow the pelvis
/// joint rigidly from there. `state` starts at rest and is advanced.
/// The cache (options.simulation.cache_path) holds the motion frames only.
/// `progress` is called after every pre-roll frame and every motion frame,
/// with frames done and preroll_frame_count(options) + options.frames;
/// returning false cancels either phase (report.motion.cancelled). It is
/// also called with 0 frames done between the phases of the set-up (the
/// factorisation), where false stops the run before its first frame.
CharacterRunReport simulate_on_character(const DynamicsModel& model, ClothState& state, const Motion& motion,
                                         PosedBody& body, const CharacterRunOptions& options,
                                         const SimulationProgress& progress = {},
                                         std::vector<Positions>* frames_out = nullptr);

/// The body at every output frame of a character run (the times the
/// garment's cache holds, from frame 1 as the garment's) as a PC2 cache at
/// `cache_path`, and its first frame as the OBJ rest mesh at `obj_path`
/// (empty: none); only the vertices its faces use (used_vertices). Atomic.
void write_body_cache(const Motion& motion, const PosedBody& body, const CharacterRunOptions& options,
                      const std::string& cache_path, const std::string& obj_path);

}  // namespace mrcloth
