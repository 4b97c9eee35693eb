#pragma once
// Joint names. The characters read a skeleton's joints by their CMU
// MotionBuilder names (Hips, LowerBack, Spine1, LeftUpLeg, ...): the
// pelvis the waist follows, the capsules' default radii, the MakeHuman
// rig's bones, the leg bridges. A clip named another way is renamed once,
// after reading, by a renaming that a known convention gives or the user
// writes.
#include "skeleton.h"

#include <map>
#include <string>

namespace mrcloth {

/// The joints of the legs by their CMU names, hip joint to ankle, left then
/// right: what moves a garment on the legs.
constexpr const char* kCmuLegJoints[] = {"LeftUpLeg", "LeftLeg", "LeftFoot", "RightUpLeg", "RightLeg", "RightFoot"};

/// A joint's name in the file -> the name it takes (a CMU MotionBuilder name).
using JointRenaming = std::map<std::string, std::string>;

/// Naming conventions recognised from the names alone.
enum class JointConvention {
  cmu,      ///< the CMU MotionBuilder names: a joint "Hips"
  daz,      ///< DAZ/Poser (the CMU clips' DAZ-friendly conversion): "hip", "lThigh", "rThigh", ...
  mixamo,   ///< Mixamo: every joint "mixamorig:<name>" (or "mixamorig<digits>:", "_" for ":"), below a chain of others at most (Blender's "Armature")
  unknown,  ///< none of these
};

/// The convention of a skeleton's joint names (End Sites are not looked at).
JointConvention joint_convention(const Skeleton& skeleton);

/// The renaming onto CMU names for the skeleton's convention: empty for cmu
/// and unknown. Only joints with a CMU counterpart are renamed: DAZ's eyes
/// and finger links keep their names (the rig has no bone for them, so they
/// follow their parents), as does Mixamo's tail of spine and finger joints.
/// DAZ: hip -> Hips, abdomen -> LowerBack, chest -> Spine1, neck -> Neck,
/// head -> Head, l/rCollar -> Left/RightShoulder, l/rShldr -> ...Arm,
/// l/rForeArm -> ...ForeArm, l/rHand -> ...Hand, l/rButtock -> L/RHipJoint,
/// l/rThigh -> ...UpLeg, l/rShin -> ...Leg, l/rFoot -> ...Foot. Mixamo: the
/// prefix dropped, then Spine -> LowerBack, Spine1 -> Spine, Spine2 -> Spine1.
JointRenaming cmu_renaming(const Skeleton& skeleton);

/// Renames joints as `renaming` says (End Sites "<parent>_end" with their
/// parent). Throws ArgumentError naming an entry whose source is not a
/// joint of the skeleton, or a name two joints would then share.
void rename_joints(Skeleton& skeleton, const JointRenaming& renaming);

}  // namespace mrcloth
