// Joint naming conventions: recognised from the names, renamed onto the CMU
// MotionBuilder names without touching the geometry, and refused renamings.
#include "solver/joint_names.h"

#include "mesh_ops/errors.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

/// A chain of joints with these names (each 0.1 m above its parent), an End
/// Site after the last.
Skeleton chain(const std::vector<std::string>& names) {
  Skeleton s;
  for (std::size_t k = 0; k < names.size(); ++k) {
    Joint j;
    j.name = names[k];
    j.parent = static_cast<int>(k) - 1;
    j.offset = {0.0, k == 0 ? 0.0 : 0.1, 0.0};
    j.channels = {Channel::z_rotation, Channel::x_rotation, Channel::y_rotation};
    j.first_channel = 3 * static_cast<int>(k);
    s.joints.push_back(j);
  }
  Joint end;
  end.name = names.back() + "_end";
  end.parent = static_cast<int>(names.size()) - 1;
  end.offset = {0.0, 0.1, 0.0};
  end.end_site = true;
  s.joints.push_back(end);
  return s;
}

std::vector<std::string> names_of(const Skeleton& s) {
  std::vector<std::string> out;
  for (const Joint& j : s.joints) out.push_back(j.name);
  return out;
}

TEST(JointNames, CmuNamesAreKeptAndUnknownOnesLeftAlone) {
  const Skeleton cmu = chain({"Hips", "LowerBack", "Spine"});
  EXPECT_EQ(joint_convention(cmu), JointConvention::cmu);
  EXPECT_TRUE(cmu_renaming(cmu).empty());
  const Skeleton other = chain({"pelvis", "spine_01", "spine_02"});
  EXPECT_EQ(joint_convention(other), JointConvention::unknown);
  EXPECT_TRUE(cmu_renaming(other).empty());
}

TEST(JointNames, MixamoPrefixesAreDroppedAndTheSpineShifted) {
  for (const std::string prefix : {"mixamorig:", "mixamorig1:", "mixamorig_"}) {
    Skeleton s = chain({prefix + "Hips", prefix + "Spine", prefix + "Spine1", prefix + "Spine2", prefix + "Neck"});
    ASSERT_EQ(joint_convention(s), JointConvention::mixamo) << prefix;
    rename_joints(s, cmu_renaming(s));
    EXPECT_EQ(names_of(s), (std::vector<std::string>{"Hips", "LowerBack", "Spine", "Spine1", "Neck", "Neck_end"})) << prefix;
  }
  // Below a chain of other joints (Blender's "Armature" root), which keep their names.
  Skeleton armature = chain({"Armature", "mixamorig:Hips", "mixamorig:Spine"});
  ASSERT_EQ(joint_convention(armature), JointConvention::mixamo);
  rename_joints(armature, cmu_renaming(armature));
  EXPECT_EQ(names_of(armature), (std::vector<std::string>{"Armature", "Hips", "LowerBack", "LowerBack_end"}));
  // One joint without the prefix below a prefixed one: not Mixamo's names.
  EXPECT_EQ(joint_convention(chain({"mixamorig:Hips", "Spine"})), JointConvention::unknown);
  EXPECT_EQ(joint_convention(chain({"mixamorig:", "mixamorigX:Spine"})), JointConvention::unknown);
}

TEST(JointNames, RefusesRenamingsThatNameNoJointOrClash) {
  Skeleton s = chain({"hip", "abdomen", "chest"});
  const Skeleton before = s;
  try {
    rename_joints(s, {{"hips", "Hips"}});
    FAIL() << "expected ArgumentError";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("no joint \"hips\""), std::string::npos) << e.what();
  }
  try {
    rename_joints(s, {{"hip", "Hips"}, {"abdomen", "Hips"}});
    FAIL() << "expected ArgumentError";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("two joints would be named \"Hips\": \"hip\" (renamed \"hip\" -> \"Hips\") and "
                                         "\"abdomen\" (renamed \"abdomen\" -> \"Hips\")"),
              std::string::npos)
        << e.what();
  }
  try {
    rename_joints(s, {{"chest", "hip"}});
    FAIL() << "expected ArgumentError";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("\"hip\" (kept)"), std::string::npos) << "onto a name another joint keeps: " << e.what();
    EXPECT_NE(std::string(e.what()).find("\"chest\" (renamed \"chest\" -> \"hip\")"), std::string::npos) << e.what();
  }
  EXPECT_THROW(rename_joints(s, {{"chest", ""}}), ArgumentError);
  EXPECT_THROW(rename_joints(s, {{"chest_end", "Spine1_end"}}), ArgumentError) << "End Sites follow their parent";
  EXPECT_EQ(names_of(s), names_of(before)) << "a refused renaming changes nothing";
  // Swapping two names is a renaming, not a clash.
  rename_joints(s, {{"abdomen", "chest"}, {"chest", "abdomen"}});
  EXPECT_EQ(names_of(s), (std::vector<std::string>{"hip", "chest", "abdomen", "abdomen_end"}));
}

TEST(JointNames, TheDazClipIsRenamedOntoCmuNamesWithItsGeometryUntouched) {
  const std::string path = test::shared_data("motions/cmu_daz/16_15_daz.bvh");
  if (!fs::exists(path)) GTEST_SKIP() << "shared data absent: " << path << " (set MRCLOTH_SHARED_DATA)";
  const Motion motion = read_bvh(path, {0.01, false});
  ASSERT_EQ(joint_convention(motion.skeleton), JointConvention::daz);
  const JointRenaming renaming = cmu_renaming(motion.skeleton);
  // The trunk, 4 per arm, 4 per leg: 5 + 2 x 8; eyes and finger links keep theirs.
  EXPECT_EQ(renaming.size(), 21u);
  EXPECT_EQ(renaming.at("hip"), "Hips");
  EXPECT_EQ(renaming.at("lButtock"), "LHipJoint");
  EXPECT_EQ(renaming.at("rShin"), "RightLeg");
  EXPECT_EQ(renaming.count("leftEye") + renaming.count("lIndex1"), 0u);
  Skeleton renamed = motion.skeleton;
  rename_joints(renamed, renaming);
  EXPECT_EQ(joint_convention(renamed), JointConvention::cmu);
  EXPECT_TRUE(cmu_renaming(renamed).empty()) << "renaming twice changes nothing";
  for (const char* name : {"Hips", "LowerBack", "Spine1", "Neck", "Head", "LeftShoulder", "RightArm", "LeftForeArm",
                           "RightHand", "LHipJoint", "RightUpLeg", "LeftLeg", "RightFoot", "leftEye", "lIndex1",
                           "LeftFoot_end"})
    EXPECT_GE(renamed.find(name), 0) << name;
  ASSERT_EQ(renamed.joints.size(), motion.skeleton.joints.size());
  std::set<std::string> unique;
  for (std::size_t j = 0; j < renamed.joints.size(); ++j) {
    unique.insert(renamed.joints[j].name);
    const Joint& a = renamed.joints[j];
    const Joint& b = motion.skeleton.joints[j];
    EXPECT_EQ(a.parent, b.parent);
    EXPECT_EQ(a.offset, b.offset);
    EXPECT_EQ(a.channels, b.channels);
    EXPECT_EQ(a.first_channel, b.first_channel);
    EXPECT_EQ(a.end_site, b.end_site);
    EXPECT_EQ(renaming.count(b.name) ? renaming.at(b.name) : a.name, a.name);
  }
  EXPECT_EQ(unique.size(), renamed.joints.size());
}

}  // namespace
}  // namespace mrcloth
