// The character set-up the plugin and bench_character share: the root
// re-centred on where the recording starts with every pose unchanged, the
// refusals, the garment placed exactly, and on the skinned body cleared of
// it (the shared MakeHuman data; skipped without it).
#include "solver/character_setup.h"

#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/uniform_refine.h"
#include "solver/character_sim.h"
#include "solver/dynamics_model.h"
#include "solver/figure_size.h"
#include "solver/implicit_integrator.h"
#include "solver/motion_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

std::string resource(const std::string& relative) { return std::string(MRCLOTH_RESOURCES) + "/" + relative; }
std::string shared(const std::string& relative) { return std::string(MRCLOTH_SHARED_DATA) + "/" + relative; }

Motion walk() { return read_bvh(resource("characters/walk_new.bvh"), {}); }

QuadMesh default_skirt() { return load_garment(resource("garments/default_skirt.obj"), {}).mesh; }

/// The placed garment's model, its top loop pinned (the waist).
DynamicsModel waist_pinned(const QuadMesh& placed) {
  DynamicsOptions d;
  d.pinned = boundary_loop_by_name(placed, "top");
  return build_dynamics(placed, d);
}

/// simulate_on_character's settings for `frames` output frames.
CharacterRunOptions run_options(const Character& character, const CharacterSetup& setup, const DynamicsModel& model,
                                int frames) {
  SimulationOptions simulation;
  simulation.frames = frames;
  return character_run_options(character, setup, model, simulation);
}

/// The default skirt placed on the walk's first frame, its waist pinned,
/// with a pre-roll of `preroll` seconds.
struct SkirtOnWalk {
  explicit SkirtOnWalk(double preroll) : setup(first_frame_setup(preroll)), character(make_character(walk(), setup, skirt)),
                                          model(waist_pinned(place_garment(character, setup, skirt).mesh)) {}
  static CharacterSetup first_frame_setup(double preroll) {
    CharacterSetup setup;
    setup.place = GarmentPlacement::first_frame;
    setup.preroll_seconds = preroll;
    return setup;
  }
  const QuadMesh skirt = default_skirt();
  CharacterSetup setup;
  Character character;
  DynamicsModel model;
};

TEST(CharacterSetup, WithoutFirstFrameDropsExactlyTheFirst) {
  const Motion full = walk();
  const Motion clip = without_first_frame(full);
  ASSERT_EQ(clip.frames.rows(), full.frames.rows() - 1);
  EXPECT_EQ(clip.frame_time, full.frame_time);
  EXPECT_TRUE(clip.frames == full.frames.bottomRows(full.frames.rows() - 1));
}

TEST(CharacterSetup, RecentringTheRootKeepsEveryPose) {
  const Motion before = walk();
  Motion after = before;
  const Eigen::Vector3d start = pose_at(before, 2.5).position(0);
  recentre_root(after, start);
  EXPECT_LT((rest_pose(after.skeleton).position(0) - start).norm(), 1e-12);
  for (int frame : {0, 1, 300, static_cast<int>(before.frames.rows()) - 1}) {
    const Pose a = frame_pose(before, frame), b = frame_pose(after, frame);
    for (std::size_t j = 0; j < before.skeleton.joints.size(); ++j)
      EXPECT_LT((a.position(static_cast<int>(j)) - b.position(static_cast<int>(j))).norm(), 1e-12)
          << "joint " << before.skeleton.joints[j].name << " at frame " << frame;
  }
}

TEST(CharacterSetup, RefusesWhatItCannotBuild) {
  const Motion full = walk();
  const QuadMesh skirt = default_skirt();
  CharacterSetup mesh_without_files;
  mesh_without_files.body = CharacterBodyKind::mesh;
  EXPECT_THROW(make_character(full, mesh_without_files, skirt), ArgumentError);
  CharacterSetup unknown_joint;
  unknown_joint.radii["Tail"] = {0.05, 0.05};
  EXPECT_THROW(make_character(full, unknown_joint, skirt), ArgumentError);
  CharacterSetup too_late;
  too_late.motion_start = without_first_frame(full).duration() + 0.1;
  EXPECT_THROW(make_character(full, too_late, skirt), ArgumentError);
  CharacterSetup skin_without_files;
  skin_without_files.waist = WaistFollows::skin;
  EXPECT_THROW(make_character(full, skin_without_files, skirt), ArgumentError);
  Motion no_pelvis = full;
  no_pelvis.skeleton.joints.front().name = "Root";
  EXPECT_THROW(make_character(no_pelvis, CharacterSetup{}, skirt), ArgumentError);
}

TEST(CharacterSetup, RefusesAFigureInTheWrongUnits) {
  const QuadMesh skirt = default_skirt();
  BvhReadOptions centimetres;
  centimetres.scale = 0.01;  // the walk is in metres
  const Motion tiny = read_bvh(resource("characters/walk_new.bvh"), centimetres);
  try {
    make_character(tiny, CharacterSetup{}, skirt);
    FAIL() << "a figure with legs of 8 mm was accepted";
  } catch (const FigureSizeError& error) {
    EXPECT_NEAR(error.scale.legs, 0.01 * figure_scale(walk().skeleton).legs, 1e-12);
    EXPECT_FALSE(error.scale.against_body);
    EXPECT_NE(std::string(error.what()).find("the motion's units look wrong"), std::string::npos) << error.what();
  }
  // Against the MakeHuman body's legs: CMU 07_06 read in inches (a toddler's
  // 0.36 m) passes as a figure, not as that body's skeleton.
  const std::string clip = shared("motions/cmu_mb/07_06.bvh");
  if (!std::filesystem::exists(clip)) GTEST_SKIP() << "shared data absent (" << clip << ")";
  BvhReadOptions inches;
  inches.scale = 0.0254;
  const Motion small = read_bvh(clip, inches);
  EXPECT_NO_THROW(make_character(small, CharacterSetup{}, skirt));
  CharacterSetup on_body;
  on_body.makehuman = makehuman_files(shared("bodies/makehuman"));
  try {
    make_character(small, on_body, skirt);
    FAIL() << "a figure with half the MakeHuman body's legs was accepted on it";
  } catch (const FigureSizeError& error) {
    EXPECT_TRUE(error.scale.against_body);
    EXPECT_NEAR(error.scale.expected, 0.81, 0.02) << "the MakeHuman body's legs";
    EXPECT_NEAR(error.scale.factor(), 0.45, 0.02);
  }
}

TEST(CharacterSetup, CapsulesStartWhereTheRecordingStartsAndTheGarmentIsPlacedExactly) {
  const Motion full = walk();
  const QuadMesh skirt = default_skirt();
  CharacterSetup setup;
  setup.place = GarmentPlacement::first_frame;
  setup.motion_start = 1.5;
  Character character = make_character(full, setup, skirt);
  // The clip without its T-pose, from where the recording starts.
  const Motion clip = without_first_frame(full);
  EXPECT_EQ(character.motion->frames.rows(), clip.frames.rows());
  EXPECT_LT((rest_pose(character.motion->skeleton).position(0) - pose_at(clip, 1.5).position(0)).norm(), 1e-12);
  EXPECT_LT((pose_at(*character.motion, 1.5).position(0) - pose_at(clip, 1.5).position(0)).norm(), 1e-12);
  EXPECT_GT(character.leg_bridges, 0.0) << "a skirt (two boundary loops) gets bridges between the legs";
  EXPECT_GT(character.body_capsules, 0);
  EXPECT_TRUE(character.arm_clearance != nullptr);
  EXPECT_TRUE(character.waist_skin == nullptr) << "no MakeHuman body: the waist follows the pelvis";

  const PlacedGarment placed = place_garment(character, setup, skirt);
  ASSERT_EQ(placed.mesh.n_vertices(), skirt.n_vertices());
  EXPECT_EQ(placed.clearance.moved, 0) << "on capsules the capsules are shrunk, the garment is not moved";
  for (const auto v : skirt.vertices()) {
    const auto& p = skirt.point(v);
    const Eigen::Vector3d expected = character.placement * Eigen::Vector3d(p[0], p[1], p[2]);
    const auto& q = placed.mesh.point(v);
    EXPECT_EQ(Eigen::Vector3d(q[0], q[1], q[2]), expected) << "vertex " << v.idx();
  }
  const DynamicsModel model = waist_pinned(placed.mesh);
  const CharacterRunOptions run = run_options(character, setup, model, 7);
  EXPECT_EQ(run.frames, 7);
  EXPECT_EQ(run.motion_start, 1.5);
  EXPECT_EQ(run.preroll_seconds, setup.preroll_seconds);
  EXPECT_TRUE(run.waist_weights.empty());
}

// One progress over the pre-roll's frames and then the motion's (so a
// long pre-roll shows progress), and a cancel in the pre-roll stops the run
// there: no motion frame is simulated.
TEST(CharacterSetup, ProgressCountsThePrerollAndCancelsIt) {
  SkirtOnWalk on_walk(0.2);
  const DynamicsModel& model = on_walk.model;
  Character& character = on_walk.character;
  const CharacterRunOptions run = run_options(character, on_walk.setup, model, 3);
  ASSERT_EQ(preroll_frame_count(run), 6) << "0.2 s at 30 fps";

  std::vector<std::pair<int, int>> calls;
  ClothState state = rest_state(model);
  int setup_calls = 0;  // 0 frames done: between the phases of the set-up (the factorisation), first
  const CharacterRunReport whole = simulate_on_character(model, state, *character.motion, *character.body, run,
                                                         [&](int done, int total) {
                                                           if (done == 0 && calls.empty()) {
                                                             EXPECT_EQ(total, 9);
                                                             ++setup_calls;
                                                           } else {
                                                             calls.emplace_back(done, total);
                                                           }
                                                           return true;
                                                         });
  EXPECT_GE(setup_calls, 2);
  ASSERT_EQ(calls.size(), 9u);
  for (std::size_t k = 0; k < calls.size(); ++k)
    EXPECT_EQ(calls[k], std::make_pair(static_cast<int>(k) + 1, 9)) << "call " << k;
  EXPECT_EQ(whole.preroll.frames, 6);
  EXPECT_EQ(whole.motion.frames, 3);
  EXPECT_FALSE(whole.motion.cancelled);

  int seen = 0;
  ClothState stopped = rest_state(model);
  const CharacterRunReport cancelled = simulate_on_character(model, stopped, *character.motion, *character.body, run,
                                                             [&](int done, int) {
                                                               seen = done;
                                                               return done < 4;
                                                             });
  EXPECT_EQ(seen, 4) << "no call after the one that cancelled";
  EXPECT_TRUE(cancelled.preroll.cancelled);
  EXPECT_TRUE(cancelled.motion.cancelled);
  EXPECT_EQ(cancelled.motion.frames, 0);

  // Stopped in the set-up: no frame of either phase runs.
  ClothState unset = rest_state(model);
  const CharacterRunReport in_setup = simulate_on_character(model, unset, *character.motion, *character.body, run,
                                                            [&](int done, int) {
                                                              EXPECT_EQ(done, 0) << "a frame ran";
                                                              return false;
                                                            });
  EXPECT_TRUE(in_setup.motion.cancelled);
  EXPECT_EQ(in_setup.preroll.frames, 0);
  EXPECT_EQ(in_setup.motion.frames, 0);
}

// A frame's work is bounded (progress and cancellation come between
// frames), and the counts rounded from the rates fit in int: a step rate of
// 1e300 rounded to a count past it (undefined) and ran one step a frame.
TEST(CharacterSetup, StepRatesAndPrerollsBeyondTheirBoundsAreRefused) {
  SkirtOnWalk on_walk(0.2);
  const DynamicsModel& model = on_walk.model;
  Character& character = on_walk.character;
  const auto refused = [&](CharacterRunOptions run, const std::string& expected) {
    ClothState state = rest_state(model);
    try {
      simulate_on_character(model, state, *character.motion, *character.body, run, {});
      ADD_FAILURE() << "expected ArgumentError: " << expected;
    } catch (const ArgumentError& error) {
      EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
  };
  CharacterRunOptions run = run_options(character, on_walk.setup, model, 1);
  run.step_rate = kMostStepsPerFrame * run.fps;
  EXPECT_EQ(steps_per_frame(run), kMostStepsPerFrame);
  for (const double rate : {kMostStepsPerFrame * run.fps * (1 + 1e-12), 3e10, 1e300}) {
    run.step_rate = rate;
    refused(run, "the step rate must be at most 1000 steps per output frame");
  }
  run.step_rate = 120.0;
  run.fps = 1e300;
  run.step_rate = 1e300;
  refused(run, "the pre-roll must be fewer than 2^31 output frames");
}

// A pre-roll of no whole number of output frames (0.216 s at 30 fps: 6.48)
// spans its frames exactly, so the motion starts at its first frame: the
// pins follow the waist's targets at the clip times the report checks
// them at (to round-off), and the body's cache is taken at those times.
// With the frames rounded (0.2 s) and the clip run on from there, the
// waist was ~1.9 mm off per millisecond of the remainder.
TEST(CharacterSetup, APrerollOfNoWholeFramesKeepsTheMotionOnItsClock) {
  const QuadMesh skirt = default_skirt();
  for (const double preroll : {0.216, 0.01}) {
    CharacterSetup setup;
    setup.place = GarmentPlacement::first_frame;
    setup.preroll_seconds = preroll;
    Character character = make_character(walk(), setup, skirt);
    const DynamicsModel model = waist_pinned(place_garment(character, setup, skirt).mesh);
    const CharacterRunOptions run = run_options(character, setup, model, 3);
    EXPECT_EQ(preroll_frame_count(run), preroll == 0.01 ? 1 : 6) << "at least one frame for any pre-roll";
    ClothState state = rest_state(model);
    const CharacterRunReport report = simulate_on_character(model, state, *character.motion, *character.body, run);
    EXPECT_NEAR(state.time, preroll + 3.0 / 30.0, 1e-12) << preroll;
    EXPECT_LT(report.max_waist_error, 1e-9) << preroll;
  }
}

// The legs' speed in the pre-roll goes as its inverse, and is infinite
// without one (the rest pose jumps to the first frame in a step).
TEST(CharacterSetup, PrerollLegSpeedGoesAsItsInverse) {
  const QuadMesh skirt = default_skirt();
  CharacterSetup setup;
  setup.place = GarmentPlacement::first_frame;
  Character character = make_character(walk(), setup, skirt);
  CharacterRunOptions run = run_options(character, setup, waist_pinned(place_garment(character, setup, skirt).mesh), 3);
  run.preroll_seconds = 0.5;
  const double half_second = preroll_leg_speed(*character.motion, run);
  EXPECT_GT(half_second, 0.5) << "walk_new's legs stand apart at its first frame";
  EXPECT_LT(half_second, 2.0) << "a walk's pre-roll of 0.5 s is slower than its stride";
  run.preroll_seconds = 0.25;
  EXPECT_EQ(preroll_leg_speed(*character.motion, run), 2.0 * half_second);
  run.preroll_seconds = 0.0;
  EXPECT_EQ(preroll_leg_speed(*character.motion, run), std::numeric_limits<double>::infinity());
}

// A glitch in a capture: the root 1 m off for one frame moves every leg
// joint 1 m in a frame, 120 m/s at 120 Hz, in and out again; the clean
// walk stays under a run's feet.
TEST(CharacterSetup, FastestLegSpeedFindsAGlitch) {
  Motion clip = walk();
  const LegSpeed clean = fastest_leg_speed(clip, 1);
  EXPECT_GT(clean.speed, 1.0);
  EXPECT_LT(clean.speed, 8.0);
  const int root_x = clip.skeleton.joints[0].first_channel;  // the root's Xposition
  ASSERT_EQ(clip.skeleton.joints[0].channels[0], Channel::x_position);
  clip.frames(60, root_x) += 1.0;
  const LegSpeed glitch = fastest_leg_speed(clip, 1);
  EXPECT_TRUE(glitch.frame == 59 || glitch.frame == 60) << glitch.frame << ": frames 59 -> 60 or 60 -> 61";
  // 1 m plus the joint's own step (a foot: under 3 cm at 120 Hz).
  EXPECT_NEAR(glitch.speed, 1.0 / clip.frame_time, 0.03 / clip.frame_time) << glitch.joint;
  EXPECT_EQ(fastest_leg_speed(clip, 61).speed, fastest_leg_speed(walk(), 61).speed) << "after the glitch";
  EXPECT_EQ(fastest_leg_speed(clip, 1, 59).speed, fastest_leg_speed(walk(), 1, 59).speed) << "before it";
}

// The legs' jitter: exact where the figure only accelerates (every leg
// joint with the root), small on the clean walk, large with noise on its
// angles, and back down once smoothed.
TEST(CharacterSetup, LegJitterIsTheMedianLargestLegAcceleration) {
  Motion still = walk();
  const int root_x = still.skeleton.joints[0].first_channel;
  for (Eigen::Index f = 1; f < still.frames.rows(); ++f) still.frames.row(f) = still.frames.row(0);
  const double a = 3.5;  // m/s^2 along x
  for (Eigen::Index f = 0; f < still.frames.rows(); ++f) {
    const double t = static_cast<double>(f) * still.frame_time;
    still.frames(f, root_x) += 0.5 * a * t * t;
  }
  EXPECT_NEAR(leg_jitter(still), a, 1e-6 * a);
  EXPECT_EQ(leg_jitter(still, 5, 6), 0.0) << "two frames have no second difference";

  const Motion clean = walk();
  const double calm = leg_jitter(clean, 1);
  EXPECT_GT(calm, 1.0);
  EXPECT_LT(calm, 100.0);
  Motion noisy = clean;
  std::mt19937 random(5);
  std::normal_distribution<double> half_degree(0.0, 0.5);
  for (const Joint& joint : noisy.skeleton.joints)
    for (std::size_t k = 0; k < joint.channels.size(); ++k)
      if (!is_position(joint.channels[k]))
        for (Eigen::Index f = 1; f < noisy.frames.rows(); ++f)
          noisy.frames(f, joint.first_channel + static_cast<Eigen::Index>(k)) += half_degree(random);
  EXPECT_GT(leg_jitter(noisy, 1), 5.0 * calm);
  // The smoothing suggested against it is the least of its candidates that works.
  const double target = 2.0 * calm;
  const double suggested = smoothing_against_jitter(noisy, 0.0, 1, -1, target);
  const auto jitter_after = [&](double sigma) {
    Motion smoothed = noisy;
    smooth_motion(smoothed, sigma, 1);
    return leg_jitter(smoothed, 1);
  };
  EXPECT_LT(jitter_after(suggested), target) << suggested;
  const std::vector<double> candidates = {0.005, 0.01, 0.015, 0.02, 0.03, 0.05, 0.1};
  const auto at = std::find(candidates.begin(), candidates.end(), suggested);
  ASSERT_NE(at, candidates.end()) << suggested;
  EXPECT_GE(jitter_after(at == candidates.begin() ? 0.0 : *(at - 1)), target) << "the candidate before " << suggested;
  smooth_motion(noisy, 0.02, 1);
  EXPECT_LT(leg_jitter(noisy, 1), 2.0 * calm);
}

/// The clip turned by `degrees` about the vertical through the origin: the
/// root's rotation and position channels of every frame (its channels are
/// X, Y, Z position and Z, Y, X rotation, as the embedded clips').
Motion turned_clip(const Motion& clip, double degrees) {
  Motion turned = clip;
  const Joint& root = turned.skeleton.joints.front();
  EXPECT_EQ(root.channels, (std::vector<Channel>{Channel::x_position, Channel::y_position, Channel::z_position,
                                                 Channel::z_rotation, Channel::y_rotation, Channel::x_rotation}));
  const double radians = 3.14159265358979323846 / 180.0;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(degrees * radians, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Index c = root.first_channel;
  for (Eigen::Index f = 0; f < turned.frames.rows(); ++f) {
    const Eigen::Vector3d at = root.offset + turned.frames.row(f).segment<3>(c).transpose();
    turned.frames.row(f).segment<3>(c) = (turn * at - root.offset).transpose();
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(turned.frames(f, c + 3) * radians, Eigen::Vector3d::UnitZ()) *
                                     Eigen::AngleAxisd(turned.frames(f, c + 4) * radians, Eigen::Vector3d::UnitY()) *
                                     Eigen::AngleAxisd(turned.frames(f, c + 5) * radians, Eigen::Vector3d::UnitX()) *
                                     Eigen::Matrix3d::Identity();
    const Eigen::Vector3d zyx = (turn * rotation).eulerAngles(2, 1, 0);
    for (int k = 0; k < 3; ++k) turned.frames(f, c + 3 + k) = zyx[k] / radians;
  }
  return turned;
}

// A clip that starts facing another way than its rest pose: the reference
// pose (where the pre-roll starts) and the garment on it are turned to the
// clip's facing, so the figure does not spin while the cloth settles; then
// the same walk turned by 90 and by 180 degrees runs to the same cloth
// turned by 90 degrees: within 0.4-4 mm over these frames (the runs add in
// other orders: contacts resolved in space order, ties broken otherwise);
// with the figure spinning in the pre-roll 8-24 cm apart. A clip facing its
// rest pose is not turned (the bits of every earlier run).
TEST(CharacterSetup, AClipStartingTurnedTurnsTheReferencePoseNotThePreroll) {
  const QuadMesh skirt = default_skirt();
  const Motion clean = without_first_frame(walk());
  EXPECT_TRUE(start_heading_turn(clean, 0.0).matrix().isIdentity(0.0)) << "the walk starts facing its rest pose";
  const auto heading = [](const Eigen::Isometry3d& turn) {
    const Eigen::Vector3d left = turn.linear() * Eigen::Vector3d::UnitX();
    return std::atan2(-left.z(), left.x()) * 180.0 / 3.14159265358979323846;
  };
  const Eigen::Vector3d left = pose_at(clean, 0.0).global.front().linear() * Eigen::Vector3d::UnitX();
  const double own = std::atan2(-left.z(), left.x()) * 180.0 / 3.14159265358979323846;
  EXPECT_LT(std::abs(own), 30.0);
  EXPECT_NEAR(heading(start_heading_turn(turned_clip(clean, 90.0), 0.0)), 90.0 + own, 1e-9);

  std::vector<std::vector<Positions>> runs;
  for (const double degrees : {90.0, 180.0}) {
    Motion full = walk();
    full = turned_clip(full, degrees);
    CharacterSetup setup;
    setup.place = GarmentPlacement::none;
    setup.preroll_seconds = 0.3;
    Character character = make_character(full, setup, skirt);
    const DynamicsModel model = waist_pinned(place_garment(character, setup, skirt).mesh);
    const CharacterRunOptions run = run_options(character, setup, model, 6);
    // The pre-roll starts facing as the clip starts: its root's left is the first frame's, on the ground.
    const Pose start = reference_pose(*character.motion, run);
    const Eigen::Vector3d start_left = start.global.front().linear() * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d first_left = pose_at(*character.motion, 0.0).global.front().linear() * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(std::atan2(-start_left.z(), start_left.x()), std::atan2(-first_left.z(), first_left.x()), 1e-12)
        << degrees;
    ClothState state = rest_state(model);
    std::vector<Positions> frames;
    simulate_on_character(model, state, *character.motion, *character.body, run, {}, &frames);
    runs.push_back(std::move(frames));
  }
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(3.14159265358979323846 / 2.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  ASSERT_EQ(runs[0].size(), 6u);
  for (std::size_t f = 0; f < runs[0].size(); ++f) {
    const Positions expected = (runs[0][f] * quarter.transpose()).eval();  // each row turned by a quarter
    EXPECT_LT((runs[1][f] - expected).rowwise().norm().maxCoeff(), 0.01) << "output frame " << f;
  }
}

TEST(CharacterSetup, OnTheSkinnedBodyARefinedGarmentStartsClearOfIt) {
  const std::string skirt_path = shared("garments/makehuman/skirthelper.obj");
  if (!std::filesystem::exists(skirt_path)) GTEST_SKIP() << "shared data absent (" << skirt_path << ")";
  BvhReadOptions bvh;
  bvh.scale = 0.056444;
  const Motion full = read_bvh(shared("motions/cmu_mb/07_06.bvh"), bvh);
  QuadMesh skirt = load_garment(skirt_path, {"dm"}).mesh;
  uniform_refine(skirt, 1);
  CharacterSetup setup;
  setup.body = CharacterBodyKind::mesh;
  setup.makehuman = makehuman_files(shared("bodies/makehuman"));
  setup.place = GarmentPlacement::makehuman;
  Character character = make_character(full, setup, skirt);
  EXPECT_GT(character.body_vertices, 10000);
  ASSERT_TRUE(character.waist_skin != nullptr);
  const PlacedGarment placed = place_garment(character, setup, skirt);
  EXPECT_GT(placed.clearance.moved, 0) << "refined points on flat coarse faces cut into the hips";
  // The body is left in the garment's pose: nothing is within its thickness.
  const CollisionScene& scene = character.body->scene();
  double deepest = 0.0;
  for (const auto v : placed.mesh.vertices()) {
    const auto& p = placed.mesh.point(v);
    deepest = std::max(deepest, scene.penetration(Eigen::Vector3d(p[0], p[1], p[2])));
  }
  EXPECT_LT(deepest, 1e-6);
  const DynamicsModel model = waist_pinned(placed.mesh);
  const CharacterRunOptions run = run_options(character, setup, model, SimulationOptions{}.frames);
  EXPECT_EQ(run.waist_weights.size(), model.pinned_vertices.size()) << "the waist follows the skin";
}

}  // namespace
}  // namespace mrcloth
