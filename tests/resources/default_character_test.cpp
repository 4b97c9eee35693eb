// The embedded default character: a CMU-named skeleton in metres with the
// proportions the default garments were made for, and procedural motions
// that start with a T-pose, move at their stated speeds and keep a foot on
// the ground without sliding.
#include "solver/skeleton.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

using Eigen::Vector3d;

const std::string kFolder = MRCLOTH_DEFAULT_CHARACTER_DIR;

/// The 31 joints of the CMU "MotionBuilder-friendly" files, in file order.
const std::vector<std::string> kCmuJoints = {
    "Hips",      "LHipJoint",    "LeftUpLeg",      "LeftLeg",       "LeftFoot",        "LeftToeBase",
    "RHipJoint", "RightUpLeg",   "RightLeg",       "RightFoot",     "RightToeBase",    "LowerBack",
    "Spine",     "Spine1",       "Neck",           "Neck1",         "Head",            "LeftShoulder",
    "LeftArm",   "LeftForeArm",  "LeftHand",       "LeftFingerBase", "LeftHandIndex1", "LThumb",
    "RightShoulder", "RightArm", "RightForeArm",   "RightHand",     "RightFingerBase", "RightHandIndex1",
    "RThumb"};

class DefaultCharacter : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    motions_ = new std::map<std::string, Motion>;
    for (const char* name : {"mannequin", "walk_instance", "walk_new", "squat"})
      (*motions_)[name] = read_bvh(kFolder + "/" + name + ".bvh");  // metres: scale 1
  }
  static void TearDownTestSuite() {
    delete motions_;
    motions_ = nullptr;
  }
  static const Motion& motion(const std::string& name) { return motions_->at(name); }
  /// The motion without its T-pose frame, as loaders use it.
  static Motion clip(const std::string& name) {
    BvhReadOptions options;
    options.skip_first_frame = true;
    return read_bvh(kFolder + "/" + name + ".bvh", options);
  }
  static std::map<std::string, Motion>* motions_;
};
std::map<std::string, Motion>* DefaultCharacter::motions_ = nullptr;

int joint(const Skeleton& skeleton, const std::string& name) {
  const int index = skeleton.find(name);
  EXPECT_GE(index, 0) << name;
  return index;
}

TEST_F(DefaultCharacter, MannequinIsACmuSkeleton) {
  const Skeleton& skeleton = motion("mannequin").skeleton;
  std::vector<std::string> names;
  for (const Joint& j : skeleton.joints)
    if (!j.end_site) names.push_back(j.name);
  EXPECT_EQ(names, kCmuJoints);
  for (const Joint& j : skeleton.joints) {
    if (j.end_site) continue;
    const std::vector<Channel> rotation{Channel::z_rotation, Channel::y_rotation, Channel::x_rotation};
    std::vector<Channel> expected = rotation;
    if (j.parent < 0) expected.insert(expected.begin(), {Channel::x_position, Channel::y_position, Channel::z_position});
    EXPECT_EQ(j.channels, expected) << j.name;
  }
  EXPECT_EQ(motion("mannequin").frames.rows(), 1);
  for (const char* name : {"walk_instance", "walk_new", "squat"}) {
    const Skeleton& other = motion(name).skeleton;
    ASSERT_EQ(other.joints.size(), skeleton.joints.size()) << name;
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
      EXPECT_EQ(other.joints[j].name, skeleton.joints[j].name) << name;
      EXPECT_EQ(other.joints[j].offset, skeleton.joints[j].offset) << name << " " << skeleton.joints[j].name;
    }
    EXPECT_NEAR(motion(name).frame_time, 1.0 / 120.0, 1e-10) << name;
  }
}

TEST_F(DefaultCharacter, MannequinIsA165MetreWomanMatchingTheGarments) {
  const Motion& m = motion("mannequin");
  const Skeleton& s = m.skeleton;
  const Pose pose = frame_pose(m, 0);
  double low = 1e9, top = -1e9;
  for (std::size_t j = 0; j < s.joints.size(); ++j) {
    low = std::min(low, pose.position(static_cast<int>(j)).y());
    top = std::max(top, pose.position(static_cast<int>(j)).y());
  }
  EXPECT_NEAR(low, 0.0, 1e-9) << "standing on the ground (toe tips)";
  EXPECT_NEAR(top, 1.65, 1e-9) << "head End Site at the top of the head";
  EXPECT_NEAR(pose.position(joint(s, "Head_end")).y(), 1.65, 1e-9);
  // The hips sit between the skirt's waist (1.02) and hips (0.90) lines.
  EXPECT_NEAR(pose.position(joint(s, "Hips")).y(), 0.94, 1e-9);
  EXPECT_EQ(pose.position(joint(s, "Hips")).x(), 0.0);
  EXPECT_EQ(pose.position(joint(s, "Hips")).z(), 0.0);
  // Left is +X, as in CMU; the hip joints are 18 cm apart.
  const Vector3d left_hip = pose.position(joint(s, "LeftUpLeg")), right_hip = pose.position(joint(s, "RightUpLeg"));
  EXPECT_NEAR(left_hip.x(), 0.09, 1e-9);
  EXPECT_NEAR(right_hip.x(), -0.09, 1e-9);
  EXPECT_NEAR(left_hip.y(), 0.865, 1e-9);
  EXPECT_NEAR(pose.position(joint(s, "LeftFoot")).x(), 0.075, 1e-9);
  EXPECT_NEAR(pose.position(joint(s, "LeftFoot")).y(), 0.075, 1e-9);
  // T-pose: the arms horizontal, the span equal to the height.
  const Vector3d left_tip = pose.position(joint(s, "LeftHandIndex1_end"));
  const Vector3d right_tip = pose.position(joint(s, "RightHandIndex1_end"));
  EXPECT_NEAR(left_tip.y(), pose.position(joint(s, "LeftArm")).y(), 1e-9);
  EXPECT_NEAR(left_tip.x() - right_tip.x(), 1.65, 1e-9);
  // The toes point forward (+Z).
  EXPECT_GT(pose.position(joint(s, "LeftToeBase")).z(), 0.1);
}

TEST_F(DefaultCharacter, EveryFileStartsWithATPose) {
  for (const char* name : {"mannequin", "walk_instance", "walk_new", "squat"}) {
    const Motion& m = motion(name);
    for (const Joint& j : m.skeleton.joints)
      for (std::size_t k = 0; k < j.channels.size(); ++k) {
        const Channel c = j.channels[k];
        if (c == Channel::x_rotation || c == Channel::y_rotation || c == Channel::z_rotation) {
          EXPECT_EQ(m.frames(0, j.first_channel + static_cast<Eigen::Index>(k)), 0.0) << name << " " << j.name;
        }
      }
    EXPECT_NEAR(m.frames(0, 1), 0.94, 1e-9) << name << ": the T-pose stands on the ground";
    if (m.frames.rows() > 1) {
      EXPECT_EQ(m.frames(0, 0), m.frames(1, 0)) << name << ": the T-pose is where the motion starts";
      EXPECT_EQ(m.frames(0, 2), m.frames(1, 2)) << name;
    }
  }
}

/// Lowest point of a foot's sole: heel and ball pads (5 cm behind and 13 cm
/// ahead of the ankle, on the ground when the foot is flat) and the toe tip.
struct Sole {
  double heel, ball, tip;
  double lowest() const { return std::min({heel, ball, tip}); }
};

Sole sole(const Skeleton& s, const Pose& pose, const Pose& rest, const std::string& side) {
  const int foot = s.find(side + "Foot"), toe_end = s.find(side + "ToeBase_end");
  const Vector3d ankle = rest.position(foot);
  const double ground = rest.position(toe_end).y();
  const auto pad = [&](const Vector3d& rest_point) {
    return (pose.global[foot] * (rest.global[foot].inverse() * rest_point)).y();
  };
  return Sole{pad(Vector3d(ankle.x(), ground, ankle.z() - 0.05)), pad(Vector3d(ankle.x(), ground, ankle.z() + 0.13)),
              pose.position(toe_end).y()};
}

double knee_flexion_degrees(const Skeleton& s, const Pose& pose, const std::string& side) {
  const Vector3d hip = pose.position(s.find(side + "UpLeg")), knee = pose.position(s.find(side + "Leg")),
                 ankle = pose.position(s.find(side + "Foot"));
  const Vector3d thigh = knee - hip, shank = ankle - knee;
  return std::atan2(thigh.cross(shank).norm(), thigh.dot(shank)) * 180.0 / M_PI;
}

struct WalkFacts {
  double speed, duration, sway, lowest, highest_contact, slip, knee_max, arm_leg_correlation;
};

WalkFacts measure_walk(const Motion& m) {
  const Skeleton& s = m.skeleton;
  const Pose rest = rest_pose(s);
  WalkFacts facts{};
  facts.lowest = 1e9;
  facts.highest_contact = -1e9;
  const int hips = s.find("Hips");
  const Vector3d start = frame_pose(m, 0).position(hips);
  std::array<Vector3d, 2> planted{Vector3d::Constant(1e9), Vector3d::Constant(1e9)};
  double sxy = 0, sxx = 0, syy = 0;
  for (Eigen::Index f = 0; f < m.frames.rows(); ++f) {
    const Pose pose = frame_pose(m, static_cast<int>(f));
    const Vector3d root = pose.position(hips);
    facts.sway = std::max(facts.sway, std::abs(root.x() - start.x()));
    double frame_lowest = 1e9;
    for (int k = 0; k < 2; ++k) {
      const std::string side = k == 0 ? "Left" : "Right";
      const Sole foot = sole(s, pose, rest, side);
      frame_lowest = std::min(frame_lowest, foot.lowest());
      facts.knee_max = std::max(facts.knee_max, knee_flexion_degrees(s, pose, side));
      // A flat foot (heel and ball on the ground) must not slide.
      const Vector3d ankle = pose.position(s.find(side + "Foot"));
      const bool flat = std::abs(foot.heel) < 1e-3 && std::abs(foot.ball) < 1e-3;
      if (flat && planted[k].x() < 1e8) facts.slip = std::max(facts.slip, (ankle - planted[k]).norm());
      planted[k] = flat ? ankle : Vector3d::Constant(1e9);
    }
    facts.lowest = std::min(facts.lowest, frame_lowest);
    facts.highest_contact = std::max(facts.highest_contact, frame_lowest);
    // Arms swing opposite to the legs: the left wrist is forward when the
    // left ankle is back.
    const double arm = pose.position(s.find("LeftHand")).z() - root.z();
    const double leg = pose.position(s.find("LeftFoot")).z() - root.z();
    sxy += arm * leg;
    sxx += arm * arm;
    syy += leg * leg;
  }
  const Vector3d end = frame_pose(m, static_cast<int>(m.frames.rows() - 1)).position(hips);
  facts.duration = m.duration();
  facts.speed = (end - start).z() / facts.duration;
  facts.arm_leg_correlation = sxy / std::sqrt(sxx * syy);
  return facts;
}

TEST_F(DefaultCharacter, WalksMoveForwardWithAFootOnTheGround) {
  struct Expected {
    const char* name;
    double speed;
  };
  for (const Expected& e : {Expected{"walk_instance", 1.2}, Expected{"walk_new", 1.0}}) {
    const Motion m = clip(e.name);
    const WalkFacts facts = measure_walk(m);
    EXPECT_NEAR(facts.duration, 8.0, 1e-6) << e.name;
    EXPECT_NEAR(facts.speed, e.speed, 0.005) << e.name << ": m/s along +Z";
    EXPECT_LT(facts.sway, 0.03) << e.name << ": straight ahead";
    EXPECT_GT(facts.lowest, -0.001) << e.name << ": no foot below the ground";
    EXPECT_LT(facts.highest_contact, 0.001) << e.name << ": a foot on the ground in every frame";
    EXPECT_LT(facts.slip, 1e-3) << e.name << ": a flat foot slides, m per frame";
    EXPECT_GT(facts.knee_max, 50.0) << e.name << ": swing knee flexion";
    EXPECT_LT(facts.knee_max, 70.0) << e.name;
    EXPECT_LT(facts.arm_leg_correlation, -0.5) << e.name << ": arms swing opposite to the legs";
  }
}

TEST_F(DefaultCharacter, SquatGoesDownTwiceWithTheFeetPlanted) {
  const Motion m = clip("squat");
  const Skeleton& s = m.skeleton;
  const int hips = s.find("Hips");
  const Pose first = frame_pose(m, 0);
  double lowest_hips = 1e9, knee_max = 0, feet_moved = 0;
  int descents = 0;
  bool standing = true;  // counts a descent when the hips pass 0.6 m after being above 0.7 m
  for (Eigen::Index f = 0; f < m.frames.rows(); ++f) {
    const Pose pose = frame_pose(m, static_cast<int>(f));
    const double y = pose.position(hips).y();
    lowest_hips = std::min(lowest_hips, y);
    if (standing && y < 0.6) {
      ++descents;
      standing = false;
    }
    if (y > 0.7) standing = true;
    for (const char* side : {"Left", "Right"}) {
      knee_max = std::max(knee_max, knee_flexion_degrees(s, pose, side));
      for (const std::string part : {"Foot", "ToeBase", "ToeBase_end"}) {
        const int j = s.find(side + part);
        feet_moved = std::max(feet_moved, (pose.position(j) - first.position(j)).norm());
      }
    }
  }
  EXPECT_EQ(descents, 2);
  EXPECT_LT(lowest_hips, 0.55) << "deep squats";
  EXPECT_GT(knee_max, 110.0);
  EXPECT_LT(feet_moved, 1e-4) << "the feet stay where they are";
  EXPECT_NEAR(m.duration(), 7.0, 1e-6);
}

}  // namespace
}  // namespace mrcloth
