#include "character_setup.h"

#include "figure_size.h"
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"

#include <array>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

Eigen::MatrixX3d placed_points(const QuadMesh& garment, const Eigen::Isometry3d& placement) {
  Eigen::MatrixX3d placed(static_cast<Eigen::Index>(garment.n_vertices()), 3);
  for (const auto vertex : garment.vertices()) {
    const auto& p = garment.point(vertex);
    placed.row(vertex.idx()) = (placement * Eigen::Vector3d(p[0], p[1], p[2])).transpose();
  }
  return placed;
}

/// Where the run starts: the garment's pose and the recording's start.
CharacterRunOptions start_of_run(const Character& character, const CharacterSetup& setup) {
  CharacterRunOptions start;
  start.garment_pose = character.garment_pose;
  start.motion_start = setup.motion_start;
  return start;
}

void check(const Motion& full, const CharacterSetup& setup) {
  const CharacterRunOptions defaults;
  if (full.skeleton.joints.empty() || full.frames.rows() < 1)
    throw ArgumentError("the motion has no joints or no frames");
  if (full.skeleton.find(defaults.pelvis_joint) < 0)
    throw ArgumentError("the motion has no joint '" + defaults.pelvis_joint + "', which the pinned waist follows");
  if (setup.skip_first && full.frames.rows() < 2)
    throw ArgumentError("the motion has a single frame, so skipping the first leaves nothing");
  for (const auto& [name, radii] : setup.radii)
    if (full.skeleton.find(name) < 0) throw ArgumentError("a radius is given for joint '" + name + "', which the skeleton lacks");
  if (setup.body == CharacterBodyKind::mesh && !setup.makehuman)
    throw ArgumentError("a skinned-mesh body needs the MakeHuman files (base.obj, rig, weights)");
  if (setup.waist == WaistFollows::skin && !setup.makehuman)
    throw ArgumentError("a waist that follows the skin needs the MakeHuman files");
}

}  // namespace

ClipChanges standardise_clip(Motion& clip, const ClipConventions& conventions) {
  ClipChanges changes;
  changes.renamed = conventions.auto_joint_names ? cmu_renaming(clip.skeleton) : conventions.joint_names;
  rename_joints(clip.skeleton, changes.renamed);
  if (conventions.auto_axes) changes.turned = upright_turn(clip.skeleton, &changes.axes_undecided);  // reads the renamed joints
  turn_axes(clip, changes.turned);
  return changes;
}

Motion without_first_frame(const Motion& motion) {
  Motion clip;
  clip.skeleton = motion.skeleton;
  clip.frame_time = motion.frame_time;
  clip.frames = motion.frames.bottomRows(motion.frames.rows() - 1);
  return clip;
}

void recentre_root(Motion& motion, const Eigen::Vector3d& root_at_start) {
  Joint& root = motion.skeleton.joints.front();
  for (std::size_t k = 0; k < root.channels.size(); ++k) {
    int axis = -1;
    switch (root.channels[k]) {
      case Channel::x_position: axis = 0; break;
      case Channel::y_position: axis = 1; break;
      case Channel::z_position: axis = 2; break;
      default: break;
    }
    if (axis < 0) continue;
    const double shift = root_at_start[axis] - root.offset[axis];
    motion.frames.col(root.first_channel + static_cast<Eigen::Index>(k)).array() -= shift;
    root.offset[axis] += shift;
  }
}

namespace {

/// The clip with its root recentred to start where the run starts (`full`),
/// and the part of it the run plays (`run`: without the first frame when
/// the setup skips it).
struct RecentredClip {
  Motion full;
  Motion run;
};

RecentredClip recentred_clip(const Motion& full_clip, const CharacterSetup& setup) {
  RecentredClip clip{full_clip, {}};
  const Motion unshifted = setup.skip_first ? without_first_frame(clip.full) : clip.full;
  if (setup.motion_start > unshifted.duration() + 1e-9)
    throw ArgumentError("the motion start (" + std::to_string(setup.motion_start) + " s) is beyond the clip's length (" +
                        std::to_string(unshifted.duration()) + " s)");
  recentre_root(clip.full, pose_at(unshifted, setup.motion_start).position(0));
  clip.run = setup.skip_first ? without_first_frame(clip.full) : clip.full;
  return clip;
}

/// A figure in the wrong units runs to the end with absurd numbers: refused
/// against an adult's size, before the body is read and then against it.
void require_plausible(const FigureScale& figure) {
  if (!plausible(figure)) throw FigureSizeError(describe(figure) + ": the motion's units look wrong", figure);
}

/// MakeHuman's body fitted to `skeleton` where the setup names its files.
std::optional<SkinnedBody> read_body(const CharacterSetup& setup, const Skeleton& skeleton) {
  require_plausible(figure_scale(skeleton));
  if (!setup.makehuman) return std::nullopt;
  SkinnedBody skinned = load_makehuman_body(*setup.makehuman, skeleton);
  require_plausible(figure_scale(skeleton, leg_length(skeleton, skinned.joint_rest)));
  return skinned;
}

/// The arms' clearance of the hips (null where the setup turns it off),
/// keeping `mittens`, the hands' capsules, clear too.
std::shared_ptr<const ArmClearance> arm_clearance_of(const CharacterSetup& setup, const Skeleton& skeleton,
                                                     const std::optional<SkinnedBody>& skinned,
                                                     const std::vector<BoneCapsule>& mittens) {
  if (setup.arm_clearance < 0.0) return nullptr;
  ArmClearanceOptions arms;
  arms.clearance = setup.arm_clearance;
  ArmClearance check =
      skinned ? make_arm_clearance(skeleton, arms, skinned->rest_vertices, skinned->weights, skinned->joint_rest)
              : make_arm_clearance(skeleton, arms);
  add_arm_capsules(check, mittens);
  return std::make_shared<const ArmClearance>(std::move(check));
}

/// The skinned body: the mesh, with capsules for the hands (`mittens`, the
/// mesh's hands then left out) and bridges between the legs.
void set_mesh_body(Character& character, const CharacterSetup& setup, const Skeleton& skeleton, SkinnedBody skinned,
                   const std::vector<BoneCapsule>& mittens) {
  character.body_vertices = static_cast<int>(skinned.rest_vertices.rows());
  CapsuleRig capsules;
  if (character.leg_bridges > 0.0) {
    // Sized like default leg capsules; the rig's bones are dropped, the mesh is the body.
    capsules = make_capsule_rig(skeleton);
    add_leg_bridges(capsules, skeleton, character.leg_bridges);
    capsules.bones.clear();
  }
  capsules.bones = mittens;
  character.hand_mittens = static_cast<int>(mittens.size());
  if (character.hand_mittens > 0) {
    // Drawn as it collides (its caches are what a reviewer measures the
    // cloth against), textured as the whole body is.
    SkinnedBody collided = without_hands(skinned, skeleton);
    SkinnedBody drawn = collided;
    carry_uvs(skinned, drawn);
    character.body = std::make_unique<SkinnedPosedBody>(std::move(collided), skeleton, setup.thickness,
                                                        setup.friction, std::move(capsules), std::move(drawn));
  } else {
    character.body = std::make_unique<SkinnedPosedBody>(std::move(skinned), skeleton, setup.thickness, setup.friction,
                                                        std::move(capsules));
  }
}

/// The capsule rig: default radii (or fitted to the MakeHuman body where
/// there is one), shrunk where the garment, at `placed`, starts inside.
void set_capsule_body(Character& character, const CharacterSetup& setup, const Skeleton& skeleton,
                      const std::optional<SkinnedBody>& skinned, const Eigen::MatrixX3d& placed) {
  CapsuleRigOptions rig_options;
  rig_options.thickness = setup.thickness;
  rig_options.friction = setup.friction;
  rig_options.radii = setup.radii;
  CapsuleRig rig = make_capsule_rig(skeleton, rig_options);
  if (skinned) {
    fit_capsules_to_body(rig, skeleton, *skinned, setup.radii);
    character.fitted_capsules = true;
  }
  // The garment must start outside every capsule: shrink those it starts
  // inside (fitted capsules stand out of a body wherever it is narrower
  // than a linear taper).
  const std::vector<Eigen::Vector3d> joints = skinned ? skinned->joint_rest : std::vector<Eigen::Vector3d>{};
  character.capsules_shrunk =
      clear_capsules_for_garment(rig, *character.motion, start_of_run(character, setup), joints, placed);
  character.body_capsules = static_cast<int>(rig.bones.size());
  if (character.leg_bridges > 0.0) add_leg_bridges(rig, skeleton, character.leg_bridges);
  character.body = std::make_unique<CapsulePosedBody>(std::move(rig), skeleton, joints);
}

}  // namespace

Character make_character(const Motion& full_clip, const CharacterSetup& setup, const QuadMesh& garment) {
  check(full_clip, setup);
  Character character;
  RecentredClip clip = recentred_clip(full_clip, setup);
  const int pelvis = clip.full.skeleton.find(CharacterRunOptions{}.pelvis_joint);
  if (setup.place == GarmentPlacement::first_frame)
    character.placement = rest_pose(clip.full.skeleton).global[pelvis] * frame_pose(clip.full, 0).global[pelvis].inverse();
  character.motion = std::make_unique<Motion>(std::move(clip.run));
  const Skeleton& skeleton = character.motion->skeleton;

  std::optional<SkinnedBody> skinned = read_body(setup, skeleton);
  if (setup.place == GarmentPlacement::makehuman) {
    if (!skinned) throw ArgumentError("a garment placed on MakeHuman's base.obj needs the MakeHuman files");
    // Modelled on base.obj: in the body's A-pose, where the pre-roll starts.
    character.placement = Eigen::Translation3d(skinned->obj_offset);
    character.garment_pose = mesh_pose(*skinned, skeleton);
  }
  // Where the clip starts facing another way, the reference pose is turned
  // to it (reference_pose), and the garment with it.
  if (const Eigen::Isometry3d turn = start_heading_turn(*character.motion, setup.motion_start);
      !turn.matrix().isIdentity(0.0))
    character.placement = turn * character.placement;
  const Eigen::MatrixX3d placed = placed_points(garment, character.placement);
  character.leg_bridges = setup.leg_bridges >= 0.0
                              ? setup.leg_bridges
                              : automatic_leg_bridges(static_cast<int>(boundary_loops(garment).size()), placed,
                                                      skeleton);
  // The skinned body's hands collide as capsules: the arms open to keep
  // those clear of the hips too, or cloth is pinched between them.
  const std::vector<BoneCapsule> mittens = setup.body == CharacterBodyKind::mesh && setup.hand_mittens && skinned
                                               ? hand_mitten_capsules(skeleton, *skinned)
                                               : std::vector<BoneCapsule>{};
  character.arm_clearance = arm_clearance_of(setup, skeleton, skinned, mittens);
  const bool waist_on_skin = setup.waist == WaistFollows::skin || (setup.waist == WaistFollows::automatic && skinned);
  if (waist_on_skin) character.waist_skin = std::make_shared<const SkinnedBody>(*skinned);

  if (setup.body == CharacterBodyKind::mesh)
    set_mesh_body(character, setup, skeleton, std::move(*skinned), mittens);
  else
    set_capsule_body(character, setup, skeleton, skinned, placed);
  return character;
}

PlacedGarment place_garment(Character& character, const CharacterSetup& setup, const QuadMesh& garment) {
  PlacedGarment placed{copy_mesh(garment), {}};
  QuadMesh& mesh = placed.mesh;
  Eigen::MatrixX3d points = placed_points(garment, character.placement);
  // On the skinned body every garment starts outside it, out to its
  // thickness: a refined garment's new points lie on its flat coarse faces,
  // chords that cut into the curved body, and garments as modelled touch it
  // (the MakeHuman trousers' waistband starts 2 mm inside, and a pinned
  // waist stays where it starts relative to the skin). (Before the strain
  // limiter kept pushed points in front of their contact planes, moving the
  // trousers' few touching points made them stretch 802 % instead of 116 %;
  // now 57 %.) Capsules are shrunk to the garment instead (make_character).
  if (setup.body == CharacterBodyKind::mesh) {
    std::vector<std::array<int, 3>> hanging;
    const Layers layers = get_layers(mesh);
    for (const auto vertex : mesh.vertices())
      if (mesh.property(layers.hanging, vertex)) {
        const OpenMesh::Vec2i ends = mesh.property(layers.parents, vertex);
        hanging.push_back({vertex.idx(), ends[0], ends[1]});
      }
    placed.clearance =
        clear_garment_of_body(*character.body, *character.motion, start_of_run(character, setup), points, hanging);
  }
  for (const auto vertex : mesh.vertices())
    mesh.set_point(vertex, OpenMesh::Vec3d(points(vertex.idx(), 0), points(vertex.idx(), 1), points(vertex.idx(), 2)));
  return placed;
}

CharacterRunOptions character_run_options(const Character& character, const CharacterSetup& setup,
                                          const DynamicsModel& model, const SimulationOptions& simulation) {
  CharacterRunOptions run = start_of_run(character, setup);
  run.frames = simulation.frames;
  run.fps = simulation.fps;
  run.step_rate = setup.step_rate;
  run.preroll_seconds = setup.preroll_seconds;
  run.simulation = simulation;
  run.arm_clearance = character.arm_clearance;
  run.waist_smoothing = setup.waist_smoothing;
  if (character.waist_skin) waist_follows_skin(run, *character.waist_skin, *character.motion, model);
  return run;
}

}  // namespace mrcloth
