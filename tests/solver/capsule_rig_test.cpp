// The capsule body: default radii by CMU name and by height, zero-length
// bones, posing by FK, distances against the exact capsule query, and the
// radius fit on a synthetic body.
#include "solver/body_capsules.h"

#include "mesh_ops/errors.h"
#include "solver/character_sim.h"
#include "solver/colliders.h"
#include "solver/skeleton.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <variant>
#include <vector>

namespace mrcloth {
namespace {

using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

/// Builds skeletons joint by joint: root channels XYZ position + ZYX
/// rotation, every other joint ZYX rotation, End Sites none (as CMU).
struct SkeletonBuilder {
  Skeleton skeleton;
  int add(const std::string& name, int parent, const Vector3d& offset, bool end_site = false) {
    Joint joint;
    joint.name = name;
    joint.parent = parent;
    joint.offset = offset;
    joint.end_site = end_site;
    joint.first_channel = skeleton.channel_count();
    if (!end_site) {
      if (parent < 0)
        joint.channels = {Channel::x_position, Channel::y_position, Channel::z_position};
      joint.channels.insert(joint.channels.end(), {Channel::z_rotation, Channel::y_rotation, Channel::x_rotation});
    }
    skeleton.joints.push_back(joint);
    return static_cast<int>(skeleton.joints.size()) - 1;
  }
};

/// A CMU-structured figure exactly 1.65 m tall in its rest pose (head End
/// Site at y = 1.65 - 0.94 above the Hips, toe End Site 0.94 below), with
/// CMU's zero-length bones (Hips -> LHipJoint, RHipJoint, LowerBack;
/// Spine1 -> Neck, LeftShoulder, RightShoulder; Hand -> FingerBase, Thumb),
/// every length multiplied by `scale`.
Skeleton cmu_like(double scale = 1.0) {
  SkeletonBuilder b;
  const auto v = [scale](double x, double y, double z) { return Vector3d(scale * x, scale * y, scale * z); };
  const int hips = b.add("Hips", -1, v(0, 0, 0));
  for (int s = 0; s < 2; ++s) {
    const double x = s == 0 ? 1.0 : -1.0;
    const std::string lr = s == 0 ? "Left" : "Right";
    const int hip = b.add(s == 0 ? "LHipJoint" : "RHipJoint", hips, v(0, 0, 0));
    const int up = b.add(lr + "UpLeg", hip, v(x * 0.09, -0.075, 0));
    const int leg = b.add(lr + "Leg", up, v(x * -0.007, -0.395, 0));
    const int foot = b.add(lr + "Foot", leg, v(x * -0.008, -0.395, 0));
    const int toe = b.add(lr + "ToeBase", foot, v(0, -0.05, 0.13));
    b.add(lr + "ToeBase_end", toe, v(0, -0.025, 0.06), true);
  }
  const int lower = b.add("LowerBack", hips, v(0, 0, 0));
  const int spine = b.add("Spine", lower, v(0, 0.12, 0));
  const int spine1 = b.add("Spine1", spine, v(0, 0.16, 0));
  const int neck = b.add("Neck", spine1, v(0, 0, 0));
  const int neck1 = b.add("Neck1", neck, v(0, 0.19, 0));
  const int head = b.add("Head", neck1, v(0, 0.09, 0));
  b.add("Head_end", head, v(0, 0.15, 0), true);
  for (int s = 0; s < 2; ++s) {
    const double x = s == 0 ? 1.0 : -1.0;
    const std::string lr = s == 0 ? "Left" : "Right";
    const int shoulder = b.add(lr + "Shoulder", spine1, v(0, 0, 0));
    const int arm = b.add(lr + "Arm", shoulder, v(x * 0.17, 0.15, 0));
    const int fore = b.add(lr + "ForeArm", arm, v(x * 0.28, 0, 0));
    const int hand = b.add(lr + "Hand", fore, v(x * 0.23, 0, 0));
    const int finger = b.add(lr + "FingerBase", hand, v(0, 0, 0));
    const int index = b.add(lr + "HandIndex1", finger, v(x * 0.08, 0, 0));
    b.add(lr + "HandIndex1_end", index, v(x * 0.065, 0, 0), true);
    const int thumb = b.add(s == 0 ? "LThumb" : "RThumb", hand, v(0, 0, 0));
    b.add(std::string(s == 0 ? "LThumb" : "RThumb") + "_end", thumb, v(x * 0.045, 0, x * 0.045), true);
  }
  return b.skeleton;
}

/// One 1 m bone straight up from the origin: "root" -> its End Site.
Skeleton one_bone() {
  SkeletonBuilder b;
  const int root = b.add("root", -1, Vector3d::Zero());
  b.add("root_end", root, Vector3d(0, 1, 0), true);
  return b.skeleton;
}

/// The capsules whose head joint has this name.
std::vector<BoneCapsule> bones_named(const CapsuleRig& rig, const Skeleton& skeleton, const std::string& name) {
  std::vector<BoneCapsule> out;
  for (const BoneCapsule& bone : rig.bones)
    if (skeleton.joints[bone.joint].name == name) out.push_back(bone);
  return out;
}

const CapsuleCollider& capsule_of(const Collider& collider) { return std::get<CapsuleCollider>(collider.shape); }

TEST(CapsuleRig, DefaultRadiiByCmuName) {
  const Skeleton skeleton = cmu_like();
  const CapsuleRig rig = make_capsule_rig(skeleton);
  struct Expected {
    const char* name;
    const char* child;
    double head, tail;
  };
  // The defaults of a 1.65 m figure (this one is exactly 1.65 m: scale 1).
  for (const Expected& e : {Expected{"LeftUpLeg", "LeftLeg", 0.075, 0.050}, Expected{"RightUpLeg", "RightLeg", 0.075, 0.050},
                            Expected{"LeftLeg", "LeftFoot", 0.050, 0.035}, Expected{"LeftFoot", "LeftToeBase", 0.040, 0.030},
                            Expected{"LowerBack", "Spine", 0.095, 0.080}, Expected{"Spine", "Spine1", 0.095, 0.120},
                            Expected{"Neck", "Neck1", 0.090, 0.055}, Expected{"Neck1", "Head", 0.050, 0.050},
                            Expected{"Head", "Head_end", 0.085, 0.065}, Expected{"LeftArm", "LeftForeArm", 0.045, 0.035},
                            Expected{"RightForeArm", "RightHand", 0.035, 0.030},
                            Expected{"LHipJoint", "LeftUpLeg", 0.090, 0.075}}) {
    const auto bones = bones_named(rig, skeleton, e.name);
    ASSERT_EQ(bones.size(), 1u) << e.name;
    EXPECT_EQ(skeleton.joints[bones[0].child].name, e.child) << e.name;
    EXPECT_NEAR(bones[0].radius_head, e.head, 1e-12) << e.name;
    EXPECT_NEAR(bones[0].radius_tail, e.tail, 1e-12) << e.name;
  }
  // Hands, fingers and toes get none.
  for (const char* none : {"LeftHand", "RightHand", "LeftFingerBase", "LeftHandIndex1", "LThumb", "RThumb",
                           "LeftToeBase", "RightToeBase"})
    EXPECT_TRUE(bones_named(rig, skeleton, none).empty()) << none;
  EXPECT_DOUBLE_EQ(rig.thickness, CapsuleRigOptions{}.thickness);
  EXPECT_DOUBLE_EQ(rig.friction, CapsuleRigOptions{}.friction);
  EXPECT_NO_THROW(validate_colliders(posed_capsules(rig, rest_pose(skeleton))));
}

TEST(CapsuleRig, RadiiScaleWithTheSkeletonsHeight) {
  const Skeleton small = cmu_like(1.0), big = cmu_like(2.0), cmu_units = cmu_like(1.0 / 0.056444);
  const CapsuleRig a = make_capsule_rig(small), b = make_capsule_rig(big), c = make_capsule_rig(cmu_units);
  ASSERT_EQ(a.bones.size(), b.bones.size());
  ASSERT_EQ(a.bones.size(), c.bones.size());
  for (std::size_t i = 0; i < a.bones.size(); ++i) {
    EXPECT_EQ(a.bones[i].joint, b.bones[i].joint);
    EXPECT_EQ(a.bones[i].child, b.bones[i].child);
    EXPECT_NEAR(b.bones[i].radius_head, 2.0 * a.bones[i].radius_head, 1e-12) << "capsule " << i;
    EXPECT_NEAR(b.bones[i].radius_tail, 2.0 * a.bones[i].radius_tail, 1e-12) << "capsule " << i;
    EXPECT_NEAR(c.bones[i].radius_head * 0.056444, a.bones[i].radius_head, 1e-12) << "capsule " << i;
  }
}

TEST(CapsuleRig, ZeroLengthBonesAreSkippedOrBecomeSpheres) {
  const Skeleton skeleton = cmu_like();
  const CapsuleRig rig = make_capsule_rig(skeleton);
  const Pose rest = rest_pose(skeleton);
  for (const BoneCapsule& bone : rig.bones) {
    const double length = (rest.position(bone.child) - rest.position(bone.joint)).norm();
    if (length > 0.0) continue;
    // Only a joint whose every bone is zero-length keeps one: a sphere.
    for (const Joint& joint : skeleton.joints) {
      if (joint.parent == bone.joint) {
        EXPECT_EQ(joint.offset.norm(), 0.0) << skeleton.joints[bone.joint].name << " has a real bone, yet a sphere";
      }
    }
    EXPECT_EQ(bone.radius_head, bone.radius_tail) << skeleton.joints[bone.joint].name;
  }
  // CMU's Hips and Spine1 have only zero-length bones: pelvis and chest spheres.
  const auto hips = bones_named(rig, skeleton, "Hips");
  ASSERT_EQ(hips.size(), 1u);
  EXPECT_NEAR(hips[0].radius_head, 0.090, 1e-12);
  const auto chest = bones_named(rig, skeleton, "Spine1");
  ASSERT_EQ(chest.size(), 1u);
  EXPECT_NEAR(chest[0].radius_head, 0.120, 1e-12);
  // The pelvis is covered from hip joint to hip joint: the LHipJoint and
  // RHipJoint capsules meet at the Hips.
  const Vector3d left = rest.position(skeleton.find("LeftUpLeg")), right = rest.position(skeleton.find("RightUpLeg"));
  CapsuleBody body(rig, skeleton);
  for (int i = 0; i <= 10; ++i) {
    const Vector3d p = left + (right - left) * (i / 10.0);
    EXPECT_GT(body.penetration(p), 0.02) << "the pelvis is not covered at " << p.transpose();
  }
  // Colliders stay valid (no NaN from a zero-length axis).
  const auto colliders = posed_capsules(rig, rest);
  EXPECT_NO_THROW(validate_colliders(colliders));
  for (const Collider& c : colliders) EXPECT_TRUE(std::isfinite(query_surface(c, Vector3d(0.3, 1.0, 0.2)).distance));
}

TEST(CapsuleRig, UnknownNamesGetRadiiProportionalToLength) {
  SkeletonBuilder b;
  const int root = b.add("root", -1, Vector3d::Zero());
  const int mid = b.add("mid", root, Vector3d(0, 0.4, 0));
  const int tip = b.add("tip", mid, Vector3d(0, 1.25, 0));
  b.add("tip_end", tip, Vector3d(0, 0.01, 0), true);
  // Height 1.66 m: scale 1.66 / 1.65 for the clamps.
  const CapsuleRig rig = make_capsule_rig(b.skeleton);
  ASSERT_EQ(rig.bones.size(), 3u);
  const double scale = 1.66 / 1.65;
  EXPECT_NEAR(rig.bones[0].radius_head, 0.15 * 0.4, 1e-12);
  EXPECT_NEAR(rig.bones[0].radius_tail, 0.15 * 0.4, 1e-12);
  EXPECT_NEAR(rig.bones[1].radius_head, 0.15 * scale, 1e-12) << "clamped to 0.15 m at 1.65 m";
  EXPECT_NEAR(rig.bones[2].radius_head, 0.01 * scale, 1e-12) << "clamped to 0.01 m at 1.65 m";
}

TEST(CapsuleRig, UnknownNamesUnderAHandGetNoneAsTheHandsOwn) {
  // A DAZ-like hand: LeftHand (no capsule by default) with finger links of
  // unknown names; a forearm before it and an eye under the head for contrast.
  SkeletonBuilder b;
  const int hips = b.add("Hips", -1, Vector3d::Zero());
  const int arm = b.add("LeftForeArm", hips, Vector3d(0.2, 0.4, 0));
  const int hand = b.add("LeftHand", arm, Vector3d(0.25, 0, 0));
  const int finger = b.add("lIndex1", hand, Vector3d(0.08, 0, 0));
  const int link = b.add("lIndex2", finger, Vector3d(0.03, 0, 0));
  b.add("lIndex2_end", link, Vector3d(0.02, 0, 0), true);
  const int head = b.add("Head", hips, Vector3d(0, 0.8, 0));
  const int eye = b.add("leftEye", head, Vector3d(0.03, 0.05, 0.08));
  b.add("leftEye_end", eye, Vector3d(0, 0, 0.01), true);
  b.add("Head_end", head, Vector3d(0, 0.2, 0), true);
  const CapsuleRig rig = make_capsule_rig(b.skeleton);
  for (const BoneCapsule& bone : rig.bones)
    EXPECT_TRUE(bone.joint != hand && bone.joint != finger && bone.joint != link) << b.skeleton.joints[bone.joint].name;
  EXPECT_EQ(bones_named(rig, b.skeleton, "LeftForeArm").size(), 1u);
  EXPECT_EQ(bones_named(rig, b.skeleton, "leftEye").size(), 1u) << "under the head, which has a capsule";
  // An override still puts one on a finger.
  CapsuleRigOptions options;
  options.radii["lIndex1"] = {0.01, 0.01};
  EXPECT_EQ(bones_named(make_capsule_rig(b.skeleton, options), b.skeleton, "lIndex1").size(), 1u);
}

TEST(CapsuleRig, OverridesReplaceAddAndRemoveCapsules) {
  const Skeleton skeleton = cmu_like();
  CapsuleRigOptions options;
  options.thickness = 0.01;
  options.friction = 0.5;
  options.radii["LeftUpLeg"] = {0.1, 0.06};
  options.radii["LeftHand"] = {0.03, 0.02};  // none by default: now one per real bone
  options.radii["RightUpLeg"] = {0.0, 0.0};  // removed
  const CapsuleRig rig = make_capsule_rig(skeleton, options);
  EXPECT_DOUBLE_EQ(rig.thickness, 0.01);
  EXPECT_DOUBLE_EQ(rig.friction, 0.5);
  const auto thigh = bones_named(rig, skeleton, "LeftUpLeg");
  ASSERT_EQ(thigh.size(), 1u);
  EXPECT_DOUBLE_EQ(thigh[0].radius_head, 0.1);
  EXPECT_DOUBLE_EQ(thigh[0].radius_tail, 0.06);
  const auto hand = bones_named(rig, skeleton, "LeftHand");
  ASSERT_EQ(hand.size(), 1u) << "LeftHand -> LeftFingerBase and -> LThumb are zero-length: one sphere";
  EXPECT_DOUBLE_EQ(hand[0].radius_head, 0.03);
  EXPECT_TRUE(bones_named(rig, skeleton, "RightUpLeg").empty());

  CapsuleRigOptions typo;
  typo.radii["LeftUpperLeg"] = {0.1, 0.1};
  EXPECT_THROW(make_capsule_rig(skeleton, typo), ArgumentError);
  CapsuleRigOptions negative;
  negative.radii["Head"] = {-0.1, 0.1};
  EXPECT_THROW(make_capsule_rig(skeleton, negative), ArgumentError);
  CapsuleRigOptions thickness;
  thickness.thickness = -0.001;
  EXPECT_THROW(make_capsule_rig(skeleton, thickness), ArgumentError);
  thickness.thickness = kMostContactThickness;
  EXPECT_NO_THROW(make_capsule_rig(skeleton, thickness));
  thickness.thickness = std::nextafter(kMostContactThickness, 1.0);
  EXPECT_THROW(make_capsule_rig(skeleton, thickness), ArgumentError);
}

/// A motion of the CMU-like skeleton with random joint angles.
Motion random_motion(const Skeleton& skeleton, int frames, unsigned seed) {
  Motion motion;
  motion.skeleton = skeleton;
  motion.frames = Eigen::MatrixXd::Zero(frames, skeleton.channel_count());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-60.0, 60.0), shift(-0.5, 0.5);
  for (int f = 0; f < frames; ++f) {
    for (Eigen::Index c = 0; c < motion.frames.cols(); ++c) motion.frames(f, c) = angle(rng);
    motion.frames(f, 0) = shift(rng);
    motion.frames(f, 1) = 0.94 + shift(rng);
    motion.frames(f, 2) = shift(rng);
  }
  return motion;
}

TEST(CapsuleRig, PosedCapsulesFollowForwardKinematics) {
  const Skeleton skeleton = cmu_like();
  const CapsuleRig rig = make_capsule_rig(skeleton);
  const Motion motion = random_motion(skeleton, 5, 7);
  CapsuleBody body(rig, skeleton);
  for (int f = 0; f < 5; ++f) {
    const Pose pose = frame_pose(motion, f);
    const auto colliders = posed_capsules(rig, pose);
    ASSERT_EQ(colliders.size(), rig.bones.size());
    body.pose(pose);
    ASSERT_EQ(body.colliders().size(), rig.bones.size());
    for (std::size_t i = 0; i < rig.bones.size(); ++i) {
      const BoneCapsule& bone = rig.bones[i];
      const CapsuleCollider& c = capsule_of(colliders[i]);
      EXPECT_LT((c.a - pose.position(bone.joint)).norm(), 1e-12) << "frame " << f << " capsule " << i;
      EXPECT_LT((c.b - pose.position(bone.child)).norm(), 1e-12) << "frame " << f << " capsule " << i;
      EXPECT_EQ(c.radius_a, bone.radius_head);
      EXPECT_EQ(c.radius_b, bone.radius_tail);
      EXPECT_EQ(colliders[i].thickness, rig.thickness);
      EXPECT_EQ(colliders[i].friction, rig.friction);
      const CapsuleCollider& d = capsule_of(body.colliders()[i]);
      EXPECT_EQ(d.a, c.a);
      EXPECT_EQ(d.b, c.b);
    }
    // Bones keep their rest lengths under any rotation.
    const Pose rest = rest_pose(skeleton);
    for (const BoneCapsule& bone : rig.bones)
      EXPECT_NEAR((pose.position(bone.child) - pose.position(bone.joint)).norm(),
                  (rest.position(bone.child) - rest.position(bone.joint)).norm(), 1e-12);
  }
  EXPECT_THROW(body.pose(Pose{}), ArgumentError) << "a pose of another skeleton";
}

TEST(CapsuleBody, ARigThatDoesNotFitItsSkeletonIsRefusedNamingTheCapsule) {
  // Each damage to a valid rig is refused where a body is made of it, the
  // message naming the capsule or bridge and what was expected.
  const Skeleton skeleton = cmu_like();
  const int joints = static_cast<int>(skeleton.joints.size());
  CapsuleRig valid = make_capsule_rig(skeleton);
  add_leg_bridges(valid, skeleton, 1.0);
  ASSERT_FALSE(valid.bridges.empty());
  ASSERT_NO_THROW(CapsuleBody(valid, skeleton));
  const auto refused = [&](const std::function<void(CapsuleRig&)>& damage, const std::string& part) {
    CapsuleRig rig = valid;
    damage(rig);
    try {
      CapsuleBody body(rig, skeleton);
      ADD_FAILURE() << "no error; expected one naming '" << part << "'";
    } catch (const ArgumentError& error) {
      EXPECT_NE(std::string(error.what()).find("CapsuleBody: " + part), std::string::npos) << error.what();
    }
  };
  refused([&](CapsuleRig& r) { r.bones[2].child = joints; },
          "capsule 2: joints " + std::to_string(valid.bones[2].joint) + " -> " + std::to_string(joints) +
              " are not both in the skeleton's " + std::to_string(joints) + " joints");
  refused([](CapsuleRig& r) { r.bones[1].radius_head = -0.01; }, "capsule 1: radii must be finite, >= 0 and not both 0");
  refused([](CapsuleRig& r) { r.bones[1].radius_head = r.bones[1].radius_tail = 0.0; }, "capsule 1: radii must be");
  refused([](CapsuleRig& r) { r.bones[0].radius_tail = std::nan(""); }, "capsule 0: radii must be");
  refused([](CapsuleRig& r) { r.bones[3].shift_tail.x() = std::numeric_limits<double>::infinity(); },
          "capsule 3: its shifts must be finite");
  refused([](CapsuleRig& r) { r.bridges[0].child_b = -1; }, "bridge 0 names joint -1, not one of the skeleton's");
  refused([](CapsuleRig& r) { r.bridges[0].at = 1.5; }, "bridge 0 needs 0 <= at <= 1 and a radius > 0");
  refused([](CapsuleRig& r) { r.bridges[0].radius = 0.0; }, "bridge 0 needs 0 <= at <= 1 and a radius > 0");
  refused([](CapsuleRig& r) { r.thickness = 0.5; }, "thickness must be from 0 to 0.05 m");
  refused([](CapsuleRig& r) { r.friction = -1.0; }, "friction must be a finite number >= 0 (got -1)");
  Skeleton looped = skeleton;
  looped.joints[3].parent = 5;
  try {
    CapsuleBody body(valid, looped);
    ADD_FAILURE() << "a joint whose parent comes after it";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("CapsuleBody: joint 3 (" + skeleton.joints[3].name + ") has parent 5"),
              std::string::npos)
        << error.what();
  }
}

TEST(CapsuleBody, PenetrationIsTheDeepestExactCapsuleQuery) {
  const Skeleton skeleton = cmu_like();
  CapsuleRigOptions options;
  options.thickness = 0.006;
  const CapsuleRig rig = make_capsule_rig(skeleton, options);
  const Motion motion = random_motion(skeleton, 3, 11);
  CapsuleBody body(rig, skeleton);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int inside = 0, unsettled = 0;
  for (int f = 0; f < 3; ++f) {
    const Pose pose = frame_pose(motion, f);
    body.pose(pose);
    // The oracle builds each capsule from the joint positions itself and
    // asks the exact cone-sphere query; the body must agree everywhere.
    for (int k = 0; k < 2000; ++k) {
      const Vector3d centre = pose.position(0);
      const Vector3d p = centre + Vector3d(0.5 * unit(rng), 0.9 * unit(rng), 0.5 * unit(rng));
      double deepest = 0.0;
      for (const BoneCapsule& bone : rig.bones) {
        Collider c{CapsuleCollider{pose.position(bone.joint), pose.position(bone.child), bone.radius_head, bone.radius_tail},
                   0.006, rig.friction};
        deepest = std::max(deepest, 0.006 - query_surface(c, p).distance);
      }
      inside += deepest > 0.006;
      ASSERT_NEAR(body.penetration(p), deepest, 1e-12) << "frame " << f << " point " << p.transpose();
      // resolve() pushes the point out (settling between overlapping
      // capsules within its sweep limit) and never deeper.
      Vector3d q = p;
      body.resolve(p, q);
      const double after = body.penetration(q);
      EXPECT_LE(after, deepest + 1e-12);
      unsettled += after > 1e-3;
    }
  }
  EXPECT_GT(inside, 100) << "the samples must probe the inside too";
  EXPECT_LT(unsettled, 60) << "of 6000 points, resolve() left this many more than 1 mm inside";
}

TEST(CapsuleBody, AMemoNeverChangesAnAnswer) {
  // Collision rounds as the integrator runs them: each point resolved with
  // friction, then nudged (as the strain limiter does) and resolved again
  // without, over three poses of a random motion, by one body with memos
  // and one without. The answers must agree, and most later rounds must be
  // answered from the memo's short list (fewer capsules than the body has).
  const Skeleton skeleton = cmu_like();
  CapsuleRigOptions options;
  options.thickness = 0.006;
  const CapsuleRig rig = make_capsule_rig(skeleton, options);
  const Motion motion = random_motion(skeleton, 3, 17);
  CapsuleBody with(rig, skeleton), without(rig, skeleton);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::normal_distribution<double> nudge(0.0, 0.002);
  // Points near the surfaces of the first pose (within 3 cm, either side);
  // the later poses move the capsules about them.
  std::vector<Vector3d> points;
  with.pose(frame_pose(motion, 0));
  std::uniform_int_distribution<std::size_t> pick(0, with.colliders().size() - 1);
  while (points.size() < 1500) {
    const auto* capsule = std::get_if<CapsuleCollider>(&with.colliders()[pick(rng)].shape);
    if (!capsule || !((capsule->b - capsule->a).norm() > 1e-3)) continue;
    const Vector3d axis = capsule->b - capsule->a;
    const Vector3d side = axis.unitOrthogonal();
    const double angle = 3.14159 * unit(rng), t = 0.5 + 0.5 * unit(rng);
    const Vector3d radial = Eigen::AngleAxisd(angle, axis.normalized()) * side;
    const double radius = (1.0 - t) * capsule->radius_a + t * capsule->radius_b;
    points.push_back(capsule->a + t * axis + (radius + 0.03 * unit(rng)) * radial);
  }
  std::vector<ContactMemo> memos(points.size());
  int short_lists = 0, pushes = 0;
  for (int f = 0; f < 3; ++f) {
    const Pose pose = frame_pose(motion, f);
    with.pose(pose);
    without.pose(pose);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vector3d start = points[i];
      Vector3d a = start + Vector3d(0.01, -0.005, 0.003), b = a;
      for (int round = 0; round < 4; ++round) {
        const double ca = with.resolve(start, a, round == 0, &memos[i]);
        const double cb = without.resolve(start, b, round == 0);
        ASSERT_LT((a - b).norm(), 1e-12) << "frame " << f << " point " << i << " round " << round;
        ASSERT_NEAR(ca, cb, 1e-12);
        pushes += cb > 0.0;
        short_lists += memos[i].owner == &with && memos[i].items.size() < with.colliders().size();
        const Vector3d moved(nudge(rng), nudge(rng), nudge(rng));
        a += moved;
        b += moved;
      }
    }
  }
  EXPECT_GT(pushes, 2000) << "the samples must probe contacts";
  EXPECT_GT(short_lists, 15000) << "of 18000 resolves, this many used a short list";
  // A memo another scene owns is left alone.
  ContactMemo foreign;
  int other_scene = 0;
  foreign.owner = &other_scene;
  foreign.items = {12345};
  Vector3d q(0, 0, 0);
  with.resolve(q, q, true, &foreign);
  EXPECT_EQ(foreign.owner, &other_scene);
  EXPECT_EQ(foreign.items, std::vector<int>{12345});
}

TEST(CapsuleBody, BeyondMeansNothingMovesAndNothingIsWithinReach) {
  // Random points about a posed rig with leg bridges (the capsules a
  // skinned body adds): wherever beyond(p, reach) says so, a resolve must
  // leave p exactly where it was and push nothing, and the nearest surface
  // must lie no nearer than reach. Points on a capsule's thickened surface
  // and just outside it are never beyond.
  const Skeleton skeleton = cmu_like();
  CapsuleRigOptions options;
  options.thickness = 0.004;
  CapsuleRig rig = make_capsule_rig(skeleton, options);
  add_leg_bridges(rig, skeleton, 1.0);
  CapsuleBody body(rig, skeleton);
  const Motion motion = random_motion(skeleton, 2, 5);
  body.pose(frame_pose(motion, 0));
  body.pose(frame_pose(motion, 1));
  constexpr double kReach = 0.01;
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Collider& c : body.colliders()) {
    const auto& capsule = std::get<CapsuleCollider>(c.shape);
    lo = lo.cwiseMin(capsule.a).cwiseMin(capsule.b);
    hi = hi.cwiseMax(capsule.a).cwiseMax(capsule.b);
  }
  lo.array() -= 0.3;
  hi.array() += 0.3;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int beyond = 0, near = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vector3d p = lo + (hi - lo).cwiseProduct(Vector3d(unit(rng), unit(rng), unit(rng)));
    if (!body.beyond(p, kReach)) {
      ++near;
      continue;
    }
    ++beyond;
    Vector3d moved = p;
    ASSERT_EQ(body.resolve(p + Vector3d(0.01, 0.0, 0.0), moved, true), 0.0) << k;
    ASSERT_EQ(moved, p) << k;
    const SurfaceNearby nearby = nearest_surface(body.colliders(), p, kReach);
    ASSERT_FALSE(nearby.has_plane) << k;
    ASSERT_GE(nearby.clearance, kReach) << k;
  }
  EXPECT_GT(beyond, 5000) << "the samples must probe points the boxes exclude";
  EXPECT_GT(near, 1000) << "and points they do not";
  // On each capsule's thickened surface, and reach outside it: not beyond.
  for (const Collider& c : body.colliders()) {
    const auto& capsule = std::get<CapsuleCollider>(c.shape);
    const Vector3d side = (capsule.b - capsule.a).unitOrthogonal();
    const Vector3d on = 0.5 * (capsule.a + capsule.b) + (0.5 * (capsule.radius_a + capsule.radius_b) + c.thickness) * side;
    EXPECT_FALSE(body.beyond(on, 0.0));
    EXPECT_FALSE(body.beyond(on + kReach * side, kReach));
  }
}

TEST(CapsuleBody, HandComputedDistancesOfOneTaperedCapsule) {
  // One bone from (0, 0, 0) to (0, 1, 0) with radii 0.1 -> 0.05 (overridden).
  const Skeleton skeleton = one_bone();
  CapsuleRigOptions options;
  options.thickness = 0.0;
  options.radii["root"] = {0.1, 0.05};
  CapsuleBody body(make_capsule_rig(skeleton, options), skeleton);
  ASSERT_EQ(body.colliders().size(), 1u);
  // Beyond the ends the surface is the end spheres.
  EXPECT_NEAR(body.penetration(Vector3d(0, -0.05, 0)), 0.05, 1e-12);
  EXPECT_NEAR(body.penetration(Vector3d(0, 1.02, 0)), 0.03, 1e-12);
  EXPECT_NEAR(body.penetration(Vector3d(0.06, -0.06, 0)), 0.1 - std::hypot(0.06, 0.06), 1e-12);
  // Along the side the surface is the cone tangent to both spheres: with
  // s = (ra - rb) / L = 0.05 and c = sqrt(1 - s^2), a point at height t and
  // distance h from the axis is s t + c h - ra from it. The axis point at
  // mid-height is 0.1 - 0.025 = 0.075 deep, not 0.075 / c: the cone's
  // normal tilts towards the thin end.
  const double s = 0.05, c = std::sqrt(1.0 - s * s);
  EXPECT_NEAR(body.penetration(Vector3d(0, 0.5, 0)), 0.1 - s * 0.5, 1e-12);
  EXPECT_NEAR(body.penetration(Vector3d(0.03, 0.5, -0.04)), 0.1 - s * 0.5 - c * 0.05, 1e-12);
  EXPECT_EQ(body.penetration(Vector3d(0.3, 0.5, 0)), 0.0);
  EXPECT_NEAR(query_surface(body.colliders()[0], Vector3d(0.3, 0.5, 0)).distance, s * 0.5 + c * 0.3 - 0.1, 1e-12);
  // The thickness adds a layer: a point 3 mm outside is 1 mm too close at 4 mm.
  options.thickness = 0.004;
  CapsuleBody thick(make_capsule_rig(skeleton, options), skeleton);
  EXPECT_NEAR(thick.penetration(Vector3d(0, -0.103, 0)), 0.001, 1e-12);
  const Vector3d previous(0, -0.103, 0);
  Vector3d p = previous;
  EXPECT_NEAR(thick.resolve(previous, p), 0.001, 1e-12);
  EXPECT_NEAR(p.y(), -0.104, 1e-12);
  EXPECT_FALSE(thick.empty());
}

/// A cylinder of `radius` around the segment from a to b: rings of points
/// (the side of a body mesh), all weighted to `joint`.
void add_cylinder(Eigen::MatrixX3d& vertices, std::vector<std::vector<std::pair<int, double>>>& weights,
                  const Vector3d& a, const Vector3d& b, double radius, int joint) {
  const Vector3d axis = (b - a).normalized();
  const Vector3d e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  const int rings = 21, around = 24;
  const Eigen::Index first = vertices.rows();
  vertices.conservativeResize(first + rings * around, 3);
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < around; ++k) {
      const double angle = 2.0 * kPi * (k + 0.5 * (r % 2)) / around;
      const Vector3d p = a + (b - a) * (r / (rings - 1.0)) + radius * (std::cos(angle) * e1 + std::sin(angle) * e2);
      vertices.row(first + r * around + k) = p.transpose();
      weights.push_back({{joint, 0.8}, {0, 0.2}});
    }
}

TEST(CapsuleRig, FitRecoversACylindersRadius) {
  // Root, a tilted bone from "upper" to "lower", and an End Site.
  SkeletonBuilder b;
  const int root = b.add("root", -1, Vector3d::Zero());
  const int upper = b.add("upper", root, Vector3d(0.1, 1.0, 0.0));
  const int lower = b.add("lower", upper, Vector3d(0.05, -0.4, 0.1));
  b.add("lower_end", lower, Vector3d(0.0, -0.3, 0.0), true);
  CapsuleRig rig = make_capsule_rig(b.skeleton);
  const Pose rest = rest_pose(b.skeleton);

  Eigen::MatrixX3d vertices(0, 3);
  std::vector<std::vector<std::pair<int, double>>> weights;
  add_cylinder(vertices, weights, rest.position(upper), rest.position(lower), 0.07, upper);
  add_cylinder(vertices, weights, rest.position(lower), rest.position(lower + 1), 0.045, lower);
  // A few outliers (5 %, three times as far) must not move a 75th percentile.
  const Eigen::Index clean = vertices.rows();
  for (Eigen::Index v = 0; v < clean; v += 20) {
    const Vector3d p = vertices.row(v).transpose();
    const int joint = weights[v][0].first;
    const Vector3d a = rest.position(joint);
    const Vector3d axis = (rest.position(joint + 1) - a).normalized();
    const Vector3d radial = (p - a) - (p - a).dot(axis) * axis;
    vertices.conservativeResize(vertices.rows() + 1, 3);
    vertices.row(vertices.rows() - 1) = (p + 2.0 * radial).transpose();
    weights.push_back(weights[v]);
  }
  // Vertices dominated by a joint without capsules are ignored.
  vertices.conservativeResize(vertices.rows() + 1, 3);
  vertices.row(vertices.rows() - 1) = Eigen::RowVector3d(5, 5, 5);
  weights.push_back({{root, 0.1}, {upper, 0.05}, {lower + 1, 0.85}});

  fit_capsule_radii(rig, b.skeleton, vertices, weights);
  bool saw_upper = false, saw_lower = false;
  for (const BoneCapsule& bone : rig.bones) {
    if (bone.joint == upper) {
      saw_upper = true;
      EXPECT_NEAR(bone.radius_head, 0.07, 0.0007);
      EXPECT_NEAR(bone.radius_tail, 0.07, 0.0007);
    } else if (bone.joint == lower) {
      saw_lower = true;
      EXPECT_NEAR(bone.radius_head, 0.045, 0.00045);
      EXPECT_NEAR(bone.radius_tail, 0.045, 0.00045);
    }
  }
  EXPECT_TRUE(saw_upper && saw_lower);

  weights.pop_back();
  EXPECT_THROW(fit_capsule_radii(rig, b.skeleton, vertices, weights), ArgumentError) << "one weight list per vertex";
}

TEST(CapsuleRig, FitAboutTheBodysOwnJointsAndPoseOnThem) {
  // The body's limb runs 6 cm beside the skeleton's bone (a body of other
  // proportions than the capture subject): fitted about the skeleton's
  // bone the capsule is shifted onto the limb; about the body's own joints
  // it needs no shift, and proportioned_pose puts it on the limb.
  SkeletonBuilder b;
  const int root = b.add("root", -1, Vector3d::Zero());
  const int upper = b.add("upper", root, Vector3d(0.0, 1.0, 0.0));
  const int end = b.add("upper_end", upper, Vector3d(0.0, -0.5, 0.0), true);
  const Pose rest = rest_pose(b.skeleton);
  std::vector<Vector3d> joint_rest = {rest.position(root), rest.position(upper) + Vector3d(0.06, 0, 0),
                                      rest.position(end) + Vector3d(0.06, 0, 0.0)};
  Eigen::MatrixX3d vertices(0, 3);
  std::vector<std::vector<std::pair<int, double>>> weights;
  add_cylinder(vertices, weights, joint_rest[upper], joint_rest[end], 0.05, upper);

  CapsuleRig about_skeleton = make_capsule_rig(b.skeleton);
  fit_capsule_radii(about_skeleton, b.skeleton, vertices, weights);
  CapsuleRig about_body = make_capsule_rig(b.skeleton);
  fit_capsule_radii(about_body, b.skeleton, vertices, weights, joint_rest);
  std::size_t limb = 0;
  while (limb < about_body.bones.size() && about_body.bones[limb].joint != upper) ++limb;
  ASSERT_LT(limb, about_body.bones.size());
  EXPECT_LT((about_skeleton.bones[limb].shift_head - Vector3d(0.06, 0, 0)).norm(), 1e-9);
  EXPECT_NEAR(about_skeleton.bones[limb].radius_head, 0.05, 0.0005);
  EXPECT_LT(about_body.bones[limb].shift_head.norm() + about_body.bones[limb].shift_tail.norm(), 1e-9);
  EXPECT_NEAR(about_body.bones[limb].radius_head, 0.05, 0.0005);
  EXPECT_NEAR(about_body.bones[limb].radius_tail, 0.05, 0.0005);

  // Posed: the bone turned 90 degrees about z at the root; the capsule's
  // axis is the body's limb, turned with it (exact).
  Pose turned = rest;
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(kPi / 2, Vector3d::UnitZ()).toRotationMatrix();
  for (Eigen::Isometry3d& g : turned.global) g.prerotate(quarter);
  CapsulePosedBody body(about_body, b.skeleton, joint_rest);
  body.set_pose(turned);
  const CapsuleCollider& c = capsule_of(static_cast<const CapsuleBody&>(body.scene()).colliders()[limb]);
  EXPECT_LT((c.a - quarter * joint_rest[upper]).norm(), 1e-12);
  EXPECT_LT((c.b - quarter * joint_rest[end]).norm(), 1e-12);
  EXPECT_THROW(proportioned_pose(b.skeleton, {Vector3d::Zero()}, rest), ArgumentError) << "one rest joint per joint";
}

TEST(CapsuleRig, FitCentresCapsulesAndSplitsWideCrossSections) {
  // A torso-like limb: an elliptic cylinder (semi-axes 0.12 across, 0.07
  // front to back) whose bone runs 4 cm behind its centre. One round
  // capsule about the bone would have to be ~0.15 wide and stand 8 cm proud
  // of the front; the fit centres the axis and puts two capsules side by
  // side along the wide direction.
  SkeletonBuilder b;
  const int root = b.add("root", -1, Vector3d::Zero());
  const int spine = b.add("spine", root, Vector3d(0.0, 1.0, 0.0));
  const int top = b.add("spine_end", spine, Vector3d(0.0, 0.4, 0.0), true);
  const Pose rest = rest_pose(b.skeleton);
  const Vector3d centre(0.0, 0.0, 0.04);
  const double wide = 0.12, narrow = 0.07;
  Eigen::MatrixX3d vertices(21 * 48, 3);
  std::vector<std::vector<std::pair<int, double>>> weights;
  for (int r = 0; r < 21; ++r)
    for (int k = 0; k < 48; ++k) {
      const double angle = 2.0 * kPi * k / 48.0;
      const Vector3d p = rest.position(spine) + centre + Vector3d(wide * std::cos(angle), 0.4 * r / 20.0, narrow * std::sin(angle));
      vertices.row(r * 48 + k) = p.transpose();
      weights.push_back({{spine, 1.0}});
    }
  CapsuleRig rig = make_capsule_rig(b.skeleton);
  fit_capsule_radii(rig, b.skeleton, vertices, weights);
  std::vector<BoneCapsule> twins;
  for (const BoneCapsule& bone : rig.bones)
    if (bone.joint == spine) twins.push_back(bone);
  ASSERT_EQ(twins.size(), 2u);
  EXPECT_LT((twins[0].shift_head + twins[1].shift_head - 2.0 * centre).norm(), 1e-9) << "centred";
  EXPECT_LT((twins[0].shift_tail + twins[1].shift_tail - 2.0 * centre).norm(), 1e-9);
  const Vector3d side = twins[0].shift_head - centre;
  EXPECT_LT(std::abs(side.y()) + std::abs(side.z()), 1e-9) << "spread across the wide direction";
  EXPECT_GT(std::abs(side.x()), 0.03);
  for (const BoneCapsule& twin : twins) {
    // Out of the ellipse by at most 1.5 cm front to back and across.
    EXPECT_LE(twin.radius_head, narrow + 0.015);
    EXPECT_LE(std::abs(side.x()) + twin.radius_head, wide + 0.015);
  }
  // Posed, the twins turn with the bone (shifts in the joint's frame).
  Pose turned = rest;
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(kPi / 2, Vector3d::UnitY()).toRotationMatrix();
  for (Eigen::Isometry3d& g : turned.global) g.prerotate(quarter);
  const std::vector<Collider> posed = posed_capsules(rig, turned);
  CapsuleBody body(rig, b.skeleton);  // the body a simulation collides with poses them the same way
  body.pose(turned);
  for (std::size_t i = 0; i < rig.bones.size(); ++i) {
    if (rig.bones[i].joint != spine) continue;
    for (const Collider* collider : {&posed[i], &body.colliders()[i]}) {
      const CapsuleCollider& c = capsule_of(*collider);
      EXPECT_LT((c.a - quarter * (rest.position(spine) + rig.bones[i].shift_head)).norm(), 1e-12);
      EXPECT_LT((c.b - quarter * (rest.position(top) + rig.bones[i].shift_tail)).norm(), 1e-12);
    }
  }
  BoneCapsule bad = twins[0];
  bad.shift_tail.x() = std::numeric_limits<double>::quiet_NaN();
  rig.bones.push_back(bad);
  EXPECT_THROW(posed_capsules(rig, rest), ArgumentError) << "non-finite shift";
}

TEST(CapsuleRig, CapsulesShrinkToClearAGarmentStartingInsideThem) {
  // One straight bone of radius 0.1 (thickness 4 mm) and a second far away;
  // a garment point 8 cm from the first bone's axis, mid-bone, must end
  // exactly 4 mm outside: radius 0.076, both ends by the same factor.
  SkeletonBuilder b;
  const int root = b.add("root", -1, Vector3d::Zero());
  const int upper = b.add("upper", root, Vector3d(0.0, 1.0, 0.0));
  b.add("upper_end", upper, Vector3d(0.0, -0.5, 0.0), true);
  CapsuleRigOptions options;
  options.radii = {{"root", {0.05, 0.05}}, {"upper", {0.1, 0.1}}};
  CapsuleRig rig = make_capsule_rig(b.skeleton, options);
  const Pose rest = rest_pose(b.skeleton);
  std::size_t limb = 0, other = 0;
  for (std::size_t i = 0; i < rig.bones.size(); ++i) (rig.bones[i].joint == upper ? limb : other) = i;
  ASSERT_NE(limb, other);
  const CapsuleRig before = rig;
  Eigen::MatrixX3d points(3, 3);
  points << 0.08, 0.75, 0.0,   // inside the limb
      0.0, 0.75, 0.3,          // outside everything
      0.2, 0.2, 0.0;           // outside everything
  EXPECT_EQ(clear_capsules_of(rig, rest, points), 1);
  EXPECT_NEAR(rig.bones[limb].radius_head, 0.076, 1e-9);
  EXPECT_NEAR(rig.bones[limb].radius_tail, 0.076, 1e-9);
  EXPECT_EQ(rig.bones[other].radius_head, before.bones[other].radius_head) << "a capsule nothing is inside keeps its size";
  EXPECT_NEAR(query_surface(posed_capsules(rig, rest)[limb], points.row(0).transpose()).distance, 0.004, 1e-9);
  // A point on both bones' axes (root -> upper runs up the same line):
  // both capsules shrink to the floor only.
  Eigen::MatrixX3d on_axis(1, 3);
  on_axis << 0.0, 0.75, 0.0;
  EXPECT_EQ(clear_capsules_of(rig, rest, on_axis, 0.5), 2);
  EXPECT_NEAR(rig.bones[limb].radius_head, 0.038, 1e-12);
  EXPECT_NEAR(rig.bones[other].radius_tail, 0.025, 1e-12);
  EXPECT_THROW(clear_capsules_of(rig, rest, on_axis, 0.0), ArgumentError);
}

TEST(CapsuleRig, FitKeepsRadiiWithoutVertices) {
  const Skeleton skeleton = cmu_like();
  CapsuleRig rig = make_capsule_rig(skeleton);
  const CapsuleRig before = rig;
  fit_capsule_radii(rig, skeleton, Eigen::MatrixX3d(0, 3), {});
  for (std::size_t i = 0; i < rig.bones.size(); ++i) {
    EXPECT_EQ(rig.bones[i].radius_head, before.bones[i].radius_head);
    EXPECT_EQ(rig.bones[i].radius_tail, before.bones[i].radius_tail);
  }
}

TEST(CapsuleRig, LegBridgesSpanTheLegsAtHalfBones) {
  const Skeleton skeleton = cmu_like();
  const Motion motion = random_motion(skeleton, 3, 13);
  const int up[2] = {skeleton.find("LeftUpLeg"), skeleton.find("RightUpLeg")};
  const int knee[2] = {skeleton.find("LeftLeg"), skeleton.find("RightLeg")};
  const int ankle[2] = {skeleton.find("LeftFoot"), skeleton.find("RightFoot")};
  for (const double reach : {0.5, 1.0, 1.5, 2.0}) {
    CapsuleRig rig = make_capsule_rig(skeleton);
    const std::size_t bones = rig.bones.size();
    add_leg_bridges(rig, skeleton, reach);
    ASSERT_EQ(rig.bridges.size(), static_cast<std::size_t>(2 * reach)) << "reach " << reach;
    CapsuleBody body(rig, skeleton);
    for (int f = 0; f < 3; ++f) {
      const Pose pose = frame_pose(motion, f);
      const auto colliders = posed_capsules(rig, pose);
      ASSERT_EQ(colliders.size(), bones + rig.bridges.size());
      body.pose(pose);
      for (std::size_t k = 0; k < rig.bridges.size(); ++k) {
        // Half bones from the hips: mid-thigh, knee, mid-shin, ankle.
        const int (&from)[2] = k < 2 ? up : knee;
        const int (&to)[2] = k < 2 ? knee : ankle;
        const double at = k % 2 == 0 ? 0.5 : 1.0;
        const CapsuleCollider& c = capsule_of(colliders[bones + k]);
        const Vector3d left = pose.position(from[0]) + at * (pose.position(to[0]) - pose.position(from[0]));
        const Vector3d right = pose.position(from[1]) + at * (pose.position(to[1]) - pose.position(from[1]));
        EXPECT_LT((c.a - left).norm(), 1e-12) << "bridge " << k;
        EXPECT_LT((c.b - right).norm(), 1e-12) << "bridge " << k;
        EXPECT_EQ(c.radius_a, c.radius_b);
        const CapsuleCollider& d = capsule_of(body.colliders()[bones + k]);
        EXPECT_EQ(d.a, c.a);
        EXPECT_EQ(d.b, c.b);
      }
    }
  }
  // As thick as the thinner leg there: the default thigh is 0.075 -> 0.050.
  CapsuleRig rig = make_capsule_rig(skeleton);
  add_leg_bridges(rig, skeleton, 1.0);
  EXPECT_NEAR(rig.bridges[0].radius, 0.0625, 1e-12);
  EXPECT_NEAR(rig.bridges[1].radius, 0.050, 1e-12);

  EXPECT_THROW(add_leg_bridges(rig, skeleton, 0.25), ArgumentError);
  EXPECT_THROW(add_leg_bridges(rig, skeleton, 2.5), ArgumentError);
  const Skeleton other = one_bone();
  CapsuleRig other_rig = make_capsule_rig(other);
  try {
    add_leg_bridges(other_rig, other);
    ADD_FAILURE() << "a skeleton without CMU leg names";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("LeftUpLeg"), std::string::npos) << e.what();
  }
}

TEST(CapsuleRig, FitToABodyLetsOverridesWinAndDropsEmptyBones) {
  // An empty body leaves the fit at the defaults (FitKeepsRadiiWithoutVertices);
  // the overrides then replace a bone's radii, and (0, 0) removes it.
  const Skeleton skeleton = cmu_like();
  CapsuleRig rig = make_capsule_rig(skeleton);
  const CapsuleRig defaults = rig;
  SkinnedBody body;
  body.rest_vertices = Eigen::MatrixX3d(0, 3);
  const std::string thigh = "LeftUpLeg", shin = "RightLeg";
  fit_capsules_to_body(rig, skeleton, body, {{thigh, {0.08, 0.06}}, {shin, {0.0, 0.0}}});
  ASSERT_EQ(rig.bones.size() + 1, defaults.bones.size()) << "one bone removed";
  for (const BoneCapsule& bone : rig.bones) {
    const std::string& name = skeleton.joints[static_cast<std::size_t>(bone.joint)].name;
    EXPECT_NE(name, shin);
    if (name == thigh) {
      EXPECT_EQ(bone.radius_head, 0.08);
      EXPECT_EQ(bone.radius_tail, 0.06);
    }
  }
}

TEST(CapsuleRig, AutomaticLegBridgesByLoopsAndHemHeight) {
  // Reach 1 (knees) for a two-loop garment whose lowest point is at or
  // above the knees' rest height, 2 (ankles) below it, 0 for other loop
  // counts and for skeletons without the CMU leg names.
  const Skeleton skeleton = cmu_like();
  const Pose rest = rest_pose(skeleton);
  const double knee = std::max(rest.position(skeleton.find("LeftLeg")).y(), rest.position(skeleton.find("RightLeg")).y());
  Eigen::MatrixX3d points(3, 3);
  points << 0.0, knee + 0.4, 0.0, 0.1, knee + 0.2, 0.0, -0.1, knee, 0.0;
  EXPECT_EQ(automatic_leg_bridges(2, points, skeleton), 1.0);
  points(2, 1) = knee - 1e-9;
  EXPECT_EQ(automatic_leg_bridges(2, points, skeleton), 2.0);
  EXPECT_EQ(automatic_leg_bridges(3, points, skeleton), 0.0) << "trousers";
  EXPECT_EQ(automatic_leg_bridges(1, points, skeleton), 0.0);
  EXPECT_EQ(automatic_leg_bridges(2, Eigen::MatrixX3d(0, 3), skeleton), 0.0);
  EXPECT_EQ(automatic_leg_bridges(2, points, one_bone()), 0.0);
}

/// The body remembers where its capsules were before the last pose, so a
/// point a capsule swept past within the step comes out on its own side.
TEST(CapsuleBody, KeepsPointsOnTheSideTheyWereOn) {
  const Skeleton skeleton = one_bone();
  CapsuleRigOptions options;
  options.thickness = 0.0;
  options.friction = 0.0;
  options.radii["root"] = {0.1, 0.1};
  CapsuleBody body(make_capsule_rig(skeleton, options), skeleton);
  Pose pose = rest_pose(skeleton);
  const auto place = [&](double x) {
    for (Eigen::Isometry3d& g : pose.global) g.translation().x() = x;
    pose.global[1].translation() = pose.global[0].translation() + Vector3d(0, 1, 0);
    body.pose(pose);
  };
  place(-0.12);  // the first pose: nothing moved yet
  const Vector3d start(0, 0.5, 0);
  Vector3d position = start;
  EXPECT_EQ(body.resolve(start, position), 0.0) << "0.02 clear of the surface";
  place(0.03);  // swept 0.15 in +x: the point is now 0.03 behind the axis
  EXPECT_NEAR(body.resolve(start, position), 0.13, 1e-12);
  EXPECT_NEAR(position.x(), 0.13, 1e-12);
}

TEST(CapsuleRig, CmuWalkSkeleton) {
  const std::string path = std::string(MRCLOTH_SHARED_DATA) + "/motions/cmu_mb/07_06.bvh";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data not found: " << path;
  BvhReadOptions read;
  read.scale = 0.056444;
  read.skip_first_frame = true;
  const Motion motion = read_bvh(path, read);
  const CapsuleRig rig = make_capsule_rig(motion.skeleton);
  for (const char* name : {"LeftUpLeg", "RightUpLeg", "LeftLeg", "RightLeg", "LeftFoot", "LowerBack", "Spine",
                           "Spine1", "Neck", "Head", "LeftArm", "RightForeArm", "LHipJoint", "RHipJoint"})
    EXPECT_FALSE(bones_named(rig, motion.skeleton, name).empty()) << name;
  for (const char* name : {"LeftHand", "LeftToeBase", "LThumb"})
    EXPECT_TRUE(bones_named(rig, motion.skeleton, name).empty()) << name;
  CapsuleBody body(rig, motion.skeleton);
  for (int f = 0; f < motion.frames.rows(); f += 50) {
    body.pose(frame_pose(motion, f));
    EXPECT_NO_THROW(validate_colliders(body.colliders())) << "frame " << f;
    // The hips are inside the body, a point a metre in front is not.
    const Vector3d hips = frame_pose(motion, f).position(0);
    EXPECT_GT(body.penetration(hips), 0.0);
    EXPECT_EQ(body.penetration(hips + Vector3d(0, 0, 1)), 0.0);
  }
}

}  // namespace
}  // namespace mrcloth
