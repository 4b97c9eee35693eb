// Arm clearance: the smallest outward turn of each upper arm that keeps the
// forearm and hand capsules clear of the hips and thighs, on the embedded
// walk (capsule rig) and on the MakeHuman body under CMU 07_06 (shared data).
#include "solver/arm_clearance.h"

#include "mesh_ops/errors.h"
#include "solver/body_skinned_mesh.h"
#include "solver/skeleton.h"
#include "test_meshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

namespace mrcloth {
namespace {

using Eigen::Vector3d;

Motion embedded_walk() { return read_bvh(std::string(MRCLOTH_RESOURCES) + "/characters/walk_instance.bvh"); }

/// `pose` with both upper arms turned inward (towards the body's midline)
/// by `degrees` about the pelvis' forward axis: hands pushed into the hips.
Pose arms_in(const Skeleton& skeleton, Pose pose, double degrees) {
  const Vector3d across = pose.position(skeleton.find("LeftUpLeg")) - pose.position(skeleton.find("RightUpLeg"));
  const Vector3d up = pose.position(skeleton.find("Spine1")) - pose.position(skeleton.find("Hips"));
  const Vector3d forward = across.cross(up).normalized();
  for (const char* arm : {"LeftArm", "RightArm"}) {
    const int shoulder = skeleton.find(arm);
    const double side = (pose.position(shoulder) - pose.position(skeleton.find("Hips"))).dot(across) >= 0 ? 1.0 : -1.0;
    const Vector3d pivot = pose.position(shoulder);
    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.translate(pivot).rotate(Eigen::AngleAxisd(-side * degrees * M_PI / 180.0, forward)).translate(-pivot);
    std::vector<char> below(skeleton.joints.size(), 0);
    below[static_cast<std::size_t>(shoulder)] = 1;
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
      const int parent = skeleton.joints[j].parent;
      if (parent >= 0 && below[static_cast<std::size_t>(parent)]) below[j] = 1;
      if (below[j]) pose.global[j] = turn * pose.global[j];
    }
  }
  return pose;
}

TEST(ArmClearance, HandsPushedIntoTheHipsComeOutToTheClearance) {
  const Motion walk = embedded_walk();
  const Skeleton& skeleton = walk.skeleton;
  const ArmClearance check = make_arm_clearance(skeleton);
  ASSERT_EQ(check.sides.size(), 2u);
  ASSERT_FALSE(check.body_capsules.empty());
  int opened = 0;
  for (int frame = 1; frame < walk.frames.rows(); frame += 7) {
    Pose pose = arms_in(skeleton, frame_pose(walk, frame), 25.0);
    const std::vector<double> before = arm_gaps(check, skeleton, pose);
    const double angle = clear_arms(check, skeleton, pose);
    const std::vector<double> after = arm_gaps(check, skeleton, pose);
    for (std::size_t s = 0; s < after.size(); ++s) {
      // The bisection stops within 1e-4 rad: at most 0.1 mm short at an arm's length.
      EXPECT_GE(after[s], check.options.clearance - 1e-4) << "frame " << frame << " side " << s;
      if (before[s] < check.options.clearance) {
        ++opened;
        // The smallest angle: 1e-3 rad less leaves the arm short of the clearance.
        EXPECT_LT(after[s], check.options.clearance + 5e-3) << "opened further than needed, frame " << frame;
      }
    }
    EXPECT_LE(angle, check.options.max_angle_deg * M_PI / 180.0 + 1e-12);
  }
  EXPECT_GT(opened, 10) << "the hands never met the hips; the test proves nothing";
}

TEST(ArmClearance, OnlyTheArmsMoveAndRigidly) {
  const Motion walk = embedded_walk();
  const Skeleton& skeleton = walk.skeleton;
  const ArmClearance check = make_arm_clearance(skeleton);
  const Pose before = arms_in(skeleton, frame_pose(walk, 30), 30.0);
  Pose after = before;
  ASSERT_GT(clear_arms(check, skeleton, after), 0.0);
  std::vector<char> arm(skeleton.joints.size(), 0);
  for (const ArmClearance::Side& side : check.sides)
    for (int j : side.subtree) arm[static_cast<std::size_t>(j)] = 1;
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    if (!arm[j]) {
      EXPECT_EQ(after.global[j].matrix(), before.global[j].matrix()) << skeleton.joints[j].name << " moved";
      continue;
    }
    // Rotations stay rotations, bones keep their lengths, the shoulder stays put.
    EXPECT_LT((after.global[j].linear() * after.global[j].linear().transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    if (parent >= 0) {
      EXPECT_NEAR((after.position(static_cast<int>(j)) - after.position(parent)).norm(),
                  (before.position(static_cast<int>(j)) - before.position(parent)).norm(), 1e-12);
    }
  }
  for (const ArmClearance::Side& side : check.sides)
    EXPECT_LT((after.position(side.shoulder) - before.position(side.shoulder)).norm(), 1e-12);
}

TEST(ArmClearance, ClearPosesAreUntouchedAndTheAngleIsContinuous) {
  const Motion walk = embedded_walk();
  const Skeleton& skeleton = walk.skeleton;
  const ArmClearance check = make_arm_clearance(skeleton);
  // The T-pose: arms far from the hips, nothing to do, bit for bit.
  Pose rest = rest_pose(skeleton);
  const Pose untouched = rest;
  EXPECT_EQ(clear_arms(check, skeleton, rest), 0.0);
  for (std::size_t j = 0; j < rest.global.size(); ++j) EXPECT_EQ(rest.global[j].matrix(), untouched.global[j].matrix());
  // Pushing the arms in by a little more each time opens them by a little
  // more: the angle needed follows the push without jumps.
  const Pose frame = frame_pose(walk, 40);
  double previous = -1.0;
  for (double push = 0.0; push <= 30.0; push += 0.5) {
    Pose pose = arms_in(skeleton, frame, push);
    const double angle = clear_arms(check, skeleton, pose);
    if (previous >= 0.0) {
      EXPECT_LT(std::abs(angle - previous), 0.5 * M_PI / 180.0 + 2e-4) << "push " << push;
    }
    previous = angle;
  }
  EXPECT_GT(previous, 0.0) << "a 30 degree push should bring the hands into the hips";
}

TEST(ArmClearance, AddedCapsulesJoinTheirArmAndAreKeptClearToo) {
  // A fat capsule in the left hand (as a skinned body's mitten): it joins
  // the left arm, so the left gap becomes its own, never larger, and
  // clearing the arms keeps it clear; a capsule on the hips joins no arm.
  const Motion walk = embedded_walk();
  const Skeleton& skeleton = walk.skeleton;
  ArmClearance check = make_arm_clearance(skeleton);
  ASSERT_EQ(check.sides.size(), 2u);
  const ArmClearance before = check;
  BoneCapsule mitten;
  mitten.joint = mitten.child = skeleton.find("LeftHand");
  mitten.radius_head = mitten.radius_tail = 0.08;
  BoneCapsule elsewhere = mitten;
  elsewhere.joint = elsewhere.child = skeleton.find("Hips");
  add_arm_capsules(check, {mitten, elsewhere});
  ASSERT_EQ(check.rig.bones.size(), before.rig.bones.size() + 1) << "the hips' capsule joins no arm";
  const int left = check.sides[0].shoulder == skeleton.find("LeftArm") ? 0 : 1;
  EXPECT_EQ(check.sides[static_cast<std::size_t>(left)].arm_capsules.size(),
            before.sides[static_cast<std::size_t>(left)].arm_capsules.size() + 1);
  EXPECT_EQ(check.sides[static_cast<std::size_t>(1 - left)].arm_capsules,
            before.sides[static_cast<std::size_t>(1 - left)].arm_capsules);
  int fatter = 0;
  for (int frame = 1; frame < walk.frames.rows(); frame += 11) {
    Pose pose = arms_in(skeleton, frame_pose(walk, frame), 10.0);
    const std::vector<double> thin = arm_gaps(before, skeleton, pose), fat = arm_gaps(check, skeleton, pose);
    EXPECT_LE(fat[static_cast<std::size_t>(left)], thin[static_cast<std::size_t>(left)] + 1e-15) << "frame " << frame;
    EXPECT_EQ(fat[static_cast<std::size_t>(1 - left)], thin[static_cast<std::size_t>(1 - left)]) << "frame " << frame;
    fatter += fat[static_cast<std::size_t>(left)] < thin[static_cast<std::size_t>(left)] - 0.01;
    clear_arms(check, skeleton, pose);
    EXPECT_GE(arm_gaps(check, skeleton, pose)[static_cast<std::size_t>(left)], check.options.clearance - 1e-4)
        << "frame " << frame;
  }
  EXPECT_GT(fatter, 0) << "the fat capsule never came nearer the hips than the hand's own; the test proves nothing";
}

TEST(ArmClearance, SkeletonsWithoutCmuArmsAreLeftAlone) {
  Skeleton skeleton;
  Joint root;
  root.name = "root";
  root.channels = {Channel::x_position, Channel::y_position, Channel::z_position};
  skeleton.joints.push_back(root);
  const ArmClearance check = make_arm_clearance(skeleton);
  EXPECT_TRUE(check.sides.empty());
  Pose pose = rest_pose(skeleton);
  EXPECT_EQ(clear_arms(check, skeleton, pose), 0.0);
  EXPECT_THROW(make_arm_clearance(skeleton, {-0.01, 40.0}), ArgumentError);
  EXPECT_THROW(make_arm_clearance(skeleton, {0.01, 0.0}), ArgumentError);
}

// CMU 07_06 on the MakeHuman body: the capture subject's hands brush their
// hips, the wider MakeHuman hips take them in. Every frame ends clear.
TEST(ArmClearance, MakeHumanOnCmuWalkEveryFrameEndsClear) {
  namespace fs = std::filesystem;
  const std::string bvh = test::shared_data("motions/cmu_mb/07_06.bvh");
  const MakeHumanOptions files = makehuman_files(test::shared_data("bodies/makehuman"));
  for (const std::string& f : {bvh, files.base_obj, files.skeleton_file, files.weights_file})
    if (!fs::exists(f)) GTEST_SKIP() << "shared data absent: " << f;
  const Motion walk = read_bvh(bvh, {0.056444, true});
  const SkinnedBody body = load_makehuman_body(files, walk.skeleton);
  const ArmClearance check =
      make_arm_clearance(walk.skeleton, {}, body.rest_vertices, body.weights, body.joint_rest);
  int inside = 0;
  double largest = 0.0;
  for (int frame = 0; frame < walk.frames.rows(); ++frame) {
    Pose pose = frame_pose(walk, frame);
    for (double gap : arm_gaps(check, walk.skeleton, pose)) inside += gap < 0.0;
    largest = std::max(largest, clear_arms(check, walk.skeleton, pose));
    for (double gap : arm_gaps(check, walk.skeleton, pose)) EXPECT_GE(gap, check.options.clearance - 1e-4) << frame;
  }
  std::printf("07_06 on MakeHuman: %d arm-frames with a hand in the body, arms opened by at most %.2f degrees\n",
              inside, largest * 180.0 / M_PI);
  EXPECT_GT(inside, 0) << "the hands never entered the hips; the test proves nothing";
  EXPECT_LT(largest * 180.0 / M_PI, 15.0) << "a walk should need only a small correction";
}

}  // namespace
}  // namespace mrcloth
