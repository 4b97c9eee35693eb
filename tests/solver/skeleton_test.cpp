// Forward kinematics: Euler order against hand-written rotation matrices,
// rigid bones over whole real clips, interpolation by slerp, blending.
#include "solver/skeleton.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "mesh_ops/errors.h"
#include "test_meshes.h"

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

constexpr double kCmuScale = 0.056444;
constexpr double kDeg = M_PI / 180.0;

fs::path empty_folder(const std::string& name) { return test::fresh_folder("skeleton_test", name); }

Motion read_text(const std::string& name, const std::string& text, double scale = 1.0,
                 PositionChannels positions = PositionChannels::absolute) {
  const fs::path path = empty_folder(name) / (name + ".bvh");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
  }
  return read_bvh(path.string(), {scale, false, positions});
}

bool have_motions() { return fs::exists(test::shared_data("motions")); }

#define SKIP_WITHOUT_SHARED_DATA()                                       \
  if (!have_motions())                                                   \
  GTEST_SKIP() << "shared data absent: " << test::shared_data("motions") \
               << " (set MRCLOTH_SHARED_DATA to the folder with motions/cmu_mb and motions/cmu_daz)"

// ---- an independent reference: rotation matrices written out by hand ------

Eigen::Matrix3d rx(double degrees) {
  const double c = std::cos(degrees * kDeg), s = std::sin(degrees * kDeg);
  return (Eigen::Matrix3d() << 1, 0, 0, 0, c, -s, 0, s, c).finished();
}
Eigen::Matrix3d ry(double degrees) {
  const double c = std::cos(degrees * kDeg), s = std::sin(degrees * kDeg);
  return (Eigen::Matrix3d() << c, 0, s, 0, 1, 0, -s, 0, c).finished();
}
Eigen::Matrix3d rz(double degrees) {
  const double c = std::cos(degrees * kDeg), s = std::sin(degrees * kDeg);
  return (Eigen::Matrix3d() << c, -s, 0, s, c, 0, 0, 0, 1).finished();
}

/// BVH convention: the first listed channel is the outermost rotation.
Eigen::Matrix3d euler(const std::string& order, const Eigen::Vector3d& degrees) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  for (int k = 0; k < 3; ++k)
    r = r * (order[k] == 'X' ? rx(degrees[k]) : order[k] == 'Y' ? ry(degrees[k]) : rz(degrees[k]));
  return r;
}

/// Reference FK of one frame (or of the slerp between two frames at weight w),
/// from the channel values directly.
std::vector<Eigen::Isometry3d> reference_fk(const Motion& motion, int f0, int f1, double w) {
  const Skeleton& skeleton = motion.skeleton;
  std::vector<Eigen::Isometry3d> global(skeleton.joints.size());
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    Eigen::Matrix3d r[2] = {Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()};
    Eigen::Vector3d t[2] = {joint.offset, joint.offset};
    for (int side = 0; side < 2; ++side) {
      const int f = side == 0 ? f0 : f1;
      for (std::size_t k = 0; k < joint.channels.size(); ++k) {
        const double v = motion.frames(f, joint.first_channel + static_cast<int>(k));
        switch (joint.channels[k]) {
          case Channel::x_position:
            t[side].x() += v;
            break;
          case Channel::y_position:
            t[side].y() += v;
            break;
          case Channel::z_position:
            t[side].z() += v;
            break;
          case Channel::x_rotation:
            r[side] = r[side] * rx(v);
            break;
          case Channel::y_rotation:
            r[side] = r[side] * ry(v);
            break;
          case Channel::z_rotation:
            r[side] = r[side] * rz(v);
            break;
        }
      }
    }
    const Eigen::Quaterniond q = Eigen::Quaterniond(r[0]).slerp(w, Eigen::Quaterniond(r[1]));
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.linear() = q.toRotationMatrix();
    local.translation() = (1 - w) * t[0] + w * t[1];
    global[j] = joint.parent < 0 ? local : Eigen::Isometry3d(global[joint.parent] * local);
  }
  return global;
}

double pose_distance(const std::vector<Eigen::Isometry3d>& a, const std::vector<Eigen::Isometry3d>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t j = 0; j < std::min(a.size(), b.size()); ++j)
    worst = std::max(worst, (a[j].matrix() - b[j].matrix()).cwiseAbs().maxCoeff());
  return worst;
}

/// A root with a rotation-only channel list in `order` (e.g. "ZYX"), a child
/// at `child_offset` with its own channels, and an End Site above the child.
std::string two_joint_bvh(const std::string& order, const Eigen::Vector3d& root_degrees,
                          const Eigen::Vector3d& child_degrees, const std::string& child_offset = "1 0 0") {
  std::string channels;
  for (const char axis : order) channels += std::string(" ") + axis + "rotation";
  std::string text = "HIERARCHY\nROOT Root\n{\n\tOFFSET 0 0 0\n\tCHANNELS 3" + channels +
                     "\n\tJOINT Child\n\t{\n\t\tOFFSET " + child_offset +
                     "\n\t\tCHANNELS 3 Zrotation Xrotation Yrotation\n\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 1 0\n" +
                     "\t\t}\n\t}\n}\nMOTION\nFrames: 1\nFrame Time: 0.0083333\n";
  char row[256];
  std::snprintf(row, sizeof row, "%.17g %.17g %.17g %.17g %.17g %.17g\n", root_degrees[0], root_degrees[1],
                root_degrees[2], child_degrees[0], child_degrees[1], child_degrees[2]);
  return text + row;
}

// ---- rotation order --------------------------------------------------------

TEST(ForwardKinematics, EulerOrderAnalyticCases) {
  // ZYX with Z = 90: x goes to y.
  {
    const Motion m = read_text("zyx_90_0_0", two_joint_bvh("ZYX", {90, 0, 0}, {0, 0, 0}));
    const Pose pose = frame_pose(m, 0);
    EXPECT_LT((pose.position(1) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
    EXPECT_LT((pose.position(2) - Eigen::Vector3d(-1, 1, 0)).norm(), 1e-15);
  }
  // ZYX with Z = 90, Y = 90: Rz(90) Ry(90) (1,0,0) = Rz(90) (0,0,-1) = (0,0,-1).
  {
    const Motion m = read_text("zyx_90_90_0", two_joint_bvh("ZYX", {90, 90, 0}, {0, 0, 0}));
    EXPECT_LT((frame_pose(m, 0).position(1) - Eigen::Vector3d(0, 0, -1)).norm(), 1e-15);
  }
  // The same angles listed the other way round (XYZ, X = 0, Y = 90, Z = 90):
  // Rx(0) Ry(90) Rz(90) (1,0,0) = Ry(90) (0,1,0) = (0,1,0): the order matters.
  {
    const Motion m = read_text("xyz_0_90_90", two_joint_bvh("XYZ", {0, 90, 90}, {0, 0, 0}));
    EXPECT_LT((frame_pose(m, 0).position(1) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
  }
  // A rotated child: root Z = 90, child X = 90 (child list is ZXY: 0, 90, 0).
  // Child at Rz(90)(1,0,0) = (0,1,0); End Site at + Rz(90) Rx(90) (0,1,0) = + (0,0,1).
  {
    const Motion m = read_text("nested", two_joint_bvh("ZYX", {90, 0, 0}, {0, 90, 0}));
    const Pose pose = frame_pose(m, 0);
    EXPECT_LT((pose.position(1) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
    EXPECT_LT((pose.position(2) - Eigen::Vector3d(0, 1, 1)).norm(), 1e-15);
  }
}

TEST(ForwardKinematics, EveryEulerOrderMatchesHandWrittenMatrices) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-180.0, 180.0);
  for (const char* order : {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"}) {
    SCOPED_TRACE(order);
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::Vector3d root(angle(rng), angle(rng), angle(rng));
      const Eigen::Vector3d child(angle(rng), angle(rng), angle(rng));
      const Motion m = read_text("order", two_joint_bvh(order, root, child, "0.3 -1.2 0.7"), 0.5);
      const Pose pose = frame_pose(m, 0);
      const Eigen::Matrix3d r_root = euler(order, root);
      const Eigen::Matrix3d r_child = r_root * euler("ZXY", child);
      const Eigen::Vector3d child_position = r_root * (0.5 * Eigen::Vector3d(0.3, -1.2, 0.7));
      EXPECT_LT((pose.global[0].linear() - r_root).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT((pose.global[1].linear() - r_child).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT((pose.position(1) - child_position).norm(), 1e-12);
      EXPECT_LT((pose.position(2) - (child_position + r_child * Eigen::Vector3d(0, 0.5, 0))).norm(), 1e-12);
    }
  }
}

TEST(ForwardKinematics, PositionChannelsAreTheTranslationOrAddToTheOffsetAndAreScaled) {
  const std::string text =
      "HIERARCHY\nROOT Root\n{\n\tOFFSET 1 0 0\n\tCHANNELS 4 Zrotation Xposition Zposition Yposition\n"
      "\tEnd Site\n\t{\n\t\tOFFSET 0 2 0\n\t}\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n90 2 3 4\n";
  // Absolute (the default): the channels say where the root is.
  const Pose pose = frame_pose(read_text("positions", text, 0.01), 0);
  EXPECT_LT((pose.position(0) - Eigen::Vector3d(0.02, 0.04, 0.03)).norm(), 1e-15);
  EXPECT_LT((pose.position(1) - Eigen::Vector3d(0.02 - 0.02, 0.04, 0.03)).norm(), 1e-15);
  // Relative: they move it from its offset.
  const Pose moved = frame_pose(read_text("positions_relative", text, 0.01, PositionChannels::relative), 0);
  EXPECT_LT((moved.position(0) - Eigen::Vector3d(0.03, 0.04, 0.03)).norm(), 1e-15);
  EXPECT_LT((moved.position(1) - Eigen::Vector3d(0.03 - 0.02, 0.04, 0.03)).norm(), 1e-15);
}

TEST(ForwardKinematics, RestPoseIsEveryChannelZero) {
  const Motion m = read_text("rest", two_joint_bvh("ZYX", {10, 20, 30}, {40, 50, 60}, "1 2 3"));
  const Pose rest = rest_pose(m.skeleton);
  ASSERT_EQ(rest.global.size(), 3u);
  EXPECT_EQ(rest.position(1), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(rest.position(2), Eigen::Vector3d(1, 3, 3));
  for (const auto& g : rest.global) EXPECT_TRUE(g.linear().isIdentity(0.0));
  Motion zero = m;
  zero.frames.setZero();
  EXPECT_LT(pose_distance(rest.global, frame_pose(zero, 0).global), 1e-15);
}

TEST(ForwardKinematics, BonesStayRigidThroughoutTheWalk) {
  SKIP_WITHOUT_SHARED_DATA();
  const Motion motion = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, false});
  const Skeleton& skeleton = motion.skeleton;
  double worst = 0.0;
  int checked = 0;
  const auto check = [&](const Pose& pose) {
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
      const Joint& joint = skeleton.joints[j];
      if (joint.parent < 0) continue;
      bool positional = false;
      for (const Channel c : joint.channels)
        positional |= c == Channel::x_position || c == Channel::y_position || c == Channel::z_position;
      if (positional) continue;
      const double length = (pose.position(static_cast<int>(j)) - pose.position(joint.parent)).norm();
      worst = std::max(worst, std::abs(length - joint.offset.norm()));
      ++checked;
    }
  };
  for (int f = 0; f < motion.frames.rows(); ++f) check(frame_pose(motion, f));
  for (double t = 0.0; t < motion.duration(); t += 0.0137) check(pose_at(motion, t));
  EXPECT_GT(checked, 418 * 30);
  EXPECT_LT(worst, 1e-9);

  // The root follows its position channels: at frame 0 Hips = (7.5514, 15.923, -40.3324) CMU units.
  EXPECT_LT((frame_pose(motion, 0).position(0) - kCmuScale * Eigen::Vector3d(7.5514, 15.923, -40.3324)).norm(), 1e-12);
  // A walk: the hips stay about a metre high (leg ~ 0.9 m) and travel along z.
  const Pose first = frame_pose(motion, 1), last = frame_pose(motion, static_cast<int>(motion.frames.rows()) - 1);
  EXPECT_GT(first.position(0).y(), 0.7);
  EXPECT_LT(first.position(0).y(), 1.1);
  EXPECT_GT(std::abs(last.position(0).z() - first.position(0).z()), 2.0);
}

TEST(ForwardKinematics, DazClipWithZxyOrder) {
  SKIP_WITHOUT_SHARED_DATA();
  const Motion motion = read_bvh(test::shared_data("motions/cmu_daz/16_15_daz.bvh"), {0.01, false});
  for (int f : {0, 100, 471}) {
    const Pose pose = frame_pose(motion, f);
    EXPECT_LT(pose_distance(pose.global, reference_fk(motion, f, f, 0.0)), 1e-12) << "frame " << f;
    for (std::size_t j = 1; j < motion.skeleton.joints.size(); ++j) {
      const Joint& joint = motion.skeleton.joints[j];
      EXPECT_NEAR((pose.position(static_cast<int>(j)) - pose.position(joint.parent)).norm(), joint.offset.norm(), 1e-9)
          << joint.name;
    }
  }
  EXPECT_LT((frame_pose(motion, 0).position(0) - 0.01 * Eigen::Vector3d(7.07107, 85.0114, -144.899)).norm(), 1e-12);
}

// ---- interpolation -----------------------------------------------------------

/// Root: Xposition and Zrotation; frames (0, 10), (1, 30), (3, 50); frame time 1/8 s.
Motion single_axis_motion() {
  return read_text(
      "single_axis",
      "HIERARCHY\nROOT Root\n{\n\tOFFSET 0 0 0\n\tCHANNELS 2 Xposition Zrotation\n\tJOINT Child\n\t{\n"
      "\t\tOFFSET 1 0 0\n\t\tCHANNELS 1 Xrotation\n\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 1 0\n\t\t}\n\t}\n}\n"
      "MOTION\nFrames: 3\nFrame Time: 0.125\n0 10 0\n1 30 0\n3 50 90\n");
}

double z_angle_degrees(const Eigen::Isometry3d& transform) {
  const Eigen::AngleAxisd aa(transform.linear());
  return aa.angle() * (aa.axis().z() < 0 ? -1.0 : 1.0) / kDeg;
}

TEST(PoseAt, MidpointOfASingleAxisRotationIsTheMeanAngle) {
  const Motion m = single_axis_motion();
  const Pose mid = pose_at(m, 0.0625);  // frame 0.5
  EXPECT_NEAR(z_angle_degrees(mid.global[0]), 20.0, 1e-12);
  EXPECT_NEAR(mid.position(0).x(), 0.5, 1e-15);
  EXPECT_LT((mid.position(1) - Eigen::Vector3d(0.5 + std::cos(20 * kDeg), std::sin(20 * kDeg), 0)).norm(), 1e-12);
  const Pose quarter = pose_at(m, 0.125 + 0.03125);  // frame 1.25: 35 degrees, x = 1.5
  EXPECT_NEAR(z_angle_degrees(quarter.global[0]), 35.0, 1e-12);
  EXPECT_NEAR(quarter.position(0).x(), 1.5, 1e-15);
  // The child's own rotation (0 -> 90 about x) is slerped too: 22.5 degrees at frame 1.25.
  const Eigen::Matrix3d child_local = quarter.global[0].linear().transpose() * quarter.global[1].linear();
  EXPECT_LT((child_local - rx(22.5)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(PoseAt, FrameTimesGiveFramesAndTheClipIsClamped) {
  const Motion m = single_axis_motion();
  for (int f = 0; f < 3; ++f) EXPECT_LT(pose_distance(pose_at(m, f * 0.125).global, frame_pose(m, f).global), 1e-15);
  EXPECT_LT(pose_distance(pose_at(m, -1.0).global, frame_pose(m, 0).global), 1e-15);
  EXPECT_LT(pose_distance(pose_at(m, -1e-9).global, frame_pose(m, 0).global), 1e-15);
  EXPECT_LT(pose_distance(pose_at(m, 0.25 + 1e-9).global, frame_pose(m, 2).global), 1e-15);
  EXPECT_LT(pose_distance(pose_at(m, 1e6).global, frame_pose(m, 2).global), 1e-15);
  EXPECT_DOUBLE_EQ(m.duration(), 0.25);
  EXPECT_THROW(pose_at(m, std::nan("")), ArgumentError);
  EXPECT_THROW(frame_pose(m, -1), ArgumentError);
  EXPECT_THROW(frame_pose(m, 3), ArgumentError);
  Motion broken = m;
  broken.frames.conservativeResize(Eigen::NoChange, 2);
  EXPECT_THROW(frame_pose(broken, 0), ArgumentError);
}

TEST(PoseAt, MidpointsOfTheWalkAreFkOfSlerpedLocalRotations) {
  SKIP_WITHOUT_SHARED_DATA();
  const Motion motion = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  for (int k : {0, 57, 200, 415}) {
    SCOPED_TRACE(k);
    const double time = (k + 0.5) * motion.frame_time;
    EXPECT_LT(pose_distance(pose_at(motion, time).global, reference_fk(motion, k, k + 1, 0.5)), 1e-9);
    EXPECT_LT(pose_distance(frame_pose(motion, k).global, reference_fk(motion, k, k, 0.0)), 1e-12);
  }
}

// ---- blending -----------------------------------------------------------------

TEST(BlendPoses, EndsReproduceTheInputs) {
  const Motion m = single_axis_motion();
  const Pose a = frame_pose(m, 0), b = frame_pose(m, 1);
  EXPECT_LT(pose_distance(blend_poses(m.skeleton, a, b, 0.0).global, a.global), 1e-12);
  EXPECT_LT(pose_distance(blend_poses(m.skeleton, a, b, 1.0).global, b.global), 1e-12);
  const Pose half = blend_poses(m.skeleton, a, b, 0.5);
  EXPECT_NEAR(z_angle_degrees(half.global[0]), 20.0, 1e-12);
  EXPECT_NEAR(half.position(0).x(), 0.5, 1e-15);
  EXPECT_LT(pose_distance(half.global, pose_at(m, 0.0625).global), 1e-12);

  EXPECT_THROW(blend_poses(m.skeleton, a, Pose{}, 0.5), ArgumentError);
  EXPECT_THROW(blend_poses(m.skeleton, a, b, 1.5), ArgumentError);
  EXPECT_THROW(blend_poses(m.skeleton, a, b, -0.1), ArgumentError);
}

TEST(BlendPoses, PreRollFromRestToTheFirstWalkFrame) {
  SKIP_WITHOUT_SHARED_DATA();
  const Motion motion = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  const Pose rest = rest_pose(motion.skeleton);
  const Pose first = frame_pose(motion, 0);
  EXPECT_LT(pose_distance(blend_poses(motion.skeleton, rest, first, 0.0).global, rest.global), 1e-12);
  EXPECT_LT(pose_distance(blend_poses(motion.skeleton, rest, first, 1.0).global, first.global), 1e-12);
  for (double t : {0.25, 0.5, 0.75}) {
    const Pose blended = blend_poses(motion.skeleton, rest, first, t);
    EXPECT_LT((blended.position(0) - ((1 - t) * rest.position(0) + t * first.position(0))).norm(), 1e-12);
    for (std::size_t j = 1; j < motion.skeleton.joints.size(); ++j) {
      const Joint& joint = motion.skeleton.joints[j];
      EXPECT_NEAR((blended.position(static_cast<int>(j)) - blended.position(joint.parent)).norm(), joint.offset.norm(),
                  1e-9);
    }
  }
}

}  // namespace
}  // namespace mrcloth
