// Motion axes: a clip recorded Z up or facing another way is stood upright
// by an exact signed permutation of its axes.
#include "solver/motion_axes.h"

#include "mesh_ops/errors.h"
#include "solver/character_setup.h"
#include "solver/joint_names.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

/// Every turn of the axes that is a rotation (24).
std::vector<AxisTurn> all_rotations() {
  std::vector<AxisTurn> out;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms)
    for (int s = 0; s < 8; ++s) {
      AxisTurn t;
      t.axis = {p[0], p[1], p[2]};
      t.sign = {s & 1 ? -1.0 : 1.0, s & 2 ? -1.0 : 1.0, s & 4 ? -1.0 : 1.0};
      Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
      for (int k = 0; k < 3; ++k) m(k, t.axis[static_cast<std::size_t>(k)]) = t.sign[static_cast<std::size_t>(k)];
      if (m.determinant() > 0.0) out.push_back(t);
    }
  return out;
}

Eigen::Matrix3d matrix(const AxisTurn& t) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) m(k, t.axis[static_cast<std::size_t>(k)]) = t.sign[static_cast<std::size_t>(k)];
  return m;
}

Motion shared_clip(const std::string& relative, double scale) {
  Motion m = read_bvh(test::shared_data(relative), {scale, false});
  rename_joints(m.skeleton, cmu_renaming(m.skeleton));
  return m;
}

#define SKIP_WITHOUT(relative)                   \
  if (!fs::exists(test::shared_data(relative))) \
  GTEST_SKIP() << "shared data absent: " << test::shared_data(relative) << " (set MRCLOTH_SHARED_DATA)"

TEST(MotionAxes, EveryTurnMovesEveryPoseRigidlyAndTurnsBackToTheBit) {
  SKIP_WITHOUT("motions/cmu_mb/07_06.bvh");
  const Motion clip = shared_clip("motions/cmu_mb/07_06.bvh", 0.056444);
  const std::vector<AxisTurn> turns = all_rotations();
  ASSERT_EQ(turns.size(), 24u);
  for (const AxisTurn& turn : turns) {
    Motion turned = clip;
    turn_axes(turned, turn);
    const Eigen::Matrix3d p = matrix(turn);
    for (int f : {0, 57, 200}) {
      const Pose a = frame_pose(clip, f), b = frame_pose(turned, f);
      for (std::size_t j = 0; j < clip.skeleton.joints.size(); ++j) {
        EXPECT_LE((b.position(static_cast<int>(j)) - p * a.position(static_cast<int>(j))).norm(), 1e-12)
            << turn.describe() << " frame " << f << " joint " << clip.skeleton.joints[j].name;
        EXPECT_LE((b.global[j].linear() - p * a.global[j].linear() * p.transpose()).norm(), 1e-12);
      }
    }
    Motion back = turned;
    turn_axes(back, turn.inverse());
    EXPECT_EQ(back.frames, clip.frames) << turn.describe();
    for (std::size_t j = 0; j < clip.skeleton.joints.size(); ++j) {
      EXPECT_EQ(back.skeleton.joints[j].offset, clip.skeleton.joints[j].offset);
      EXPECT_EQ(back.skeleton.joints[j].channels, clip.skeleton.joints[j].channels);
    }
    // The turned clip is found turned, and the turn found is this one undone.
    const AxisTurn found = upright_turn(turned.skeleton);
    EXPECT_EQ(found.axis, turn.inverse().axis) << turn.describe();
    EXPECT_EQ(found.sign, turn.inverse().sign) << turn.describe();
  }
}

TEST(MotionAxes, TheSharedClipsStandUprightAlready) {
  SKIP_WITHOUT("motions/cmu_daz/16_15_daz.bvh");
  for (const char* clip : {"07_06", "07_03", "08_03", "02_01", "09_01", "13_29_squats_f3760-4580"})
    EXPECT_TRUE(upright_turn(shared_clip(std::string("motions/cmu_mb/") + clip + ".bvh", 0.056444).skeleton).identity())
        << clip;
  EXPECT_TRUE(upright_turn(shared_clip("motions/cmu_daz/16_15_daz.bvh", 0.01).skeleton).identity());
  EXPECT_EQ(AxisTurn{}.describe(), "");
}

TEST(MotionAxes, TheEmbeddedClipsStandUprightAlready) {
  // The main job's runs must not change: its mannequin and motions are
  // written Y up, left along +X, with CMU names.
  for (const char* clip : {"mannequin", "walk_instance", "walk_new", "squat"}) {
    const Motion m = read_bvh(std::string(MRCLOTH_RESOURCES) + "/characters/" + clip + ".bvh");
    EXPECT_EQ(joint_convention(m.skeleton), JointConvention::cmu) << clip;
    EXPECT_TRUE(upright_turn(m.skeleton).identity()) << clip;
  }
}

TEST(MotionAxes, StandardisingAClipRenamesThenTurnsItBackToTheBit) {
  SKIP_WITHOUT("motions/cmu_mb/07_06.bvh");
  const Motion clip = shared_clip("motions/cmu_mb/07_06.bvh", 0.056444);
  // 07_06 as a Z-up Mixamo export would hold it.
  Motion exported = clip;
  AxisTurn z_up;
  z_up.axis = {0, 2, 1};
  z_up.sign = {1.0, 1.0, -1.0};
  turn_axes(exported, z_up.inverse());
  JointRenaming to_mixamo;
  for (const Joint& joint : clip.skeleton.joints)
    if (!joint.end_site) to_mixamo[joint.name] = "mixamorig:" + joint.name;
  to_mixamo["LowerBack"] = "mixamorig:Spine";
  to_mixamo["Spine"] = "mixamorig:Spine1";
  to_mixamo["Spine1"] = "mixamorig:Spine2";
  rename_joints(exported.skeleton, to_mixamo);

  Motion as_is = exported;
  const ClipChanges none = standardise_clip(as_is, {false, {}, false});
  EXPECT_TRUE(none.renamed.empty());
  EXPECT_TRUE(none.turned.identity());
  EXPECT_EQ(as_is.frames, exported.frames);

  const ClipChanges changes = standardise_clip(exported);
  EXPECT_EQ(changes.renamed.size(), to_mixamo.size());
  EXPECT_EQ(changes.turned.describe(), "x = x, y = z, z = -y") << "found after the renaming, from Hips, Head and the legs";
  EXPECT_EQ(exported.frames, clip.frames);
  for (std::size_t j = 0; j < clip.skeleton.joints.size(); ++j) {
    EXPECT_EQ(exported.skeleton.joints[j].name, clip.skeleton.joints[j].name);
    EXPECT_EQ(exported.skeleton.joints[j].offset, clip.skeleton.joints[j].offset);
    EXPECT_EQ(exported.skeleton.joints[j].channels, clip.skeleton.joints[j].channels);
  }
}

TEST(MotionAxes, ZUpIsNamedAndMirrorsAreRefused) {
  AxisTurn z_up;  // y = z, z = -y: a Z-up clip stood upright
  z_up.axis = {0, 2, 1};
  z_up.sign = {1.0, 1.0, -1.0};
  EXPECT_EQ(z_up.describe(), "x = x, y = z, z = -y");
  Motion m;
  AxisTurn mirror;
  mirror.sign = {-1.0, 1.0, 1.0};
  EXPECT_THROW(turn_axes(m, mirror), ArgumentError);
  AxisTurn twice;
  twice.axis = {0, 0, 2};
  EXPECT_THROW(turn_axes(m, twice), ArgumentError);
  // Without the joints it reads, no turn, and it says why.
  Skeleton bare;
  bare.joints.push_back({"root", -1, {0, 0, 0}, {}, 0, false});
  std::string why = "stale";
  EXPECT_TRUE(upright_turn(bare, &why).identity());
  EXPECT_EQ(why, "it has no Hips by CMU names");
}

TEST(MotionAxes, WithoutAHeadTheNeckSaysWhichWayIsUp) {
  // A Z-up figure (up +Z, left +X) named by hand without its head: the neck
  // and the shoulders stand in for the head and the legs.
  Skeleton s;
  s.joints.push_back({"Hips", -1, {0, 0, 1}, {}, 0, false});
  s.joints.push_back({"Neck", 0, {0, 0, 0.5}, {}, 0, false});
  s.joints.push_back({"LeftShoulder", 1, {0.2, 0, 0}, {}, 0, false});
  s.joints.push_back({"RightShoulder", 1, {-0.2, 0, 0}, {}, 0, false});
  std::string why = "stale";
  const AxisTurn turn = upright_turn(s, &why);
  EXPECT_EQ(turn.describe(), "x = x, y = z, z = -y");
  EXPECT_EQ(why, "");
  // Without a right side to match, no turn: it says what is missing.
  s.joints.pop_back();
  EXPECT_TRUE(upright_turn(s, &why).identity());
  EXPECT_EQ(why, "it has no left and right legs, shoulders, arms or feet by CMU names");
}

}  // namespace
}  // namespace mrcloth
