#include "joint_names.h"

#include "mesh_ops/errors.h"

#include <map>
#include <set>
#include <tuple>

namespace mrcloth {
namespace {

/// The Mixamo prefix of a name ("mixamorig:", "mixamorig1:", "mixamorig_"), or 0.
std::size_t mixamo_prefix(const std::string& name) {
  const std::string stem = "mixamorig";
  if (name.compare(0, stem.size(), stem) != 0) return 0;
  std::size_t at = stem.size();
  while (at < name.size() && name[at] >= '0' && name[at] <= '9') ++at;
  if (at >= name.size() || (name[at] != ':' && name[at] != '_')) return 0;
  return at + 1 < name.size() ? at + 1 : 0;
}

JointRenaming daz_renaming() {
  JointRenaming r = {{"hip", "Hips"}, {"abdomen", "LowerBack"}, {"chest", "Spine1"}, {"neck", "Neck"}, {"head", "Head"}};
  for (const auto& [daz, side, hip] : {std::tuple{"l", "Left", "LHipJoint"}, std::tuple{"r", "Right", "RHipJoint"}}) {
    const std::string s = daz, cmu = side;
    r[s + "Collar"] = cmu + "Shoulder";
    r[s + "Shldr"] = cmu + "Arm";
    r[s + "ForeArm"] = cmu + "ForeArm";
    r[s + "Hand"] = cmu + "Hand";
    r[s + "Buttock"] = hip;
    r[s + "Thigh"] = cmu + "UpLeg";
    r[s + "Shin"] = cmu + "Leg";
    r[s + "Foot"] = cmu + "Foot";
  }
  return r;
}

}  // namespace

JointConvention joint_convention(const Skeleton& skeleton) {
  if (skeleton.find("Hips") >= 0) return JointConvention::cmu;
  if (skeleton.find("hip") >= 0 && skeleton.find("lThigh") >= 0 && skeleton.find("rThigh") >= 0) return JointConvention::daz;
  // Every joint from the first prefixed one on is prefixed; the joints
  // before it, if any, are the chain above it (a DCC tool's "Armature").
  std::size_t first = 0;
  while (first < skeleton.joints.size() && mixamo_prefix(skeleton.joints[first].name) == 0) ++first;
  if (first == skeleton.joints.size() || skeleton.joints[first].end_site) return JointConvention::unknown;
  for (int up = skeleton.joints[first].parent, k = static_cast<int>(first) - 1; k >= 0; --k) {
    if (k != up) return JointConvention::unknown;
    up = skeleton.joints[static_cast<std::size_t>(k)].parent;
  }
  for (std::size_t j = first; j < skeleton.joints.size(); ++j)
    if (!skeleton.joints[j].end_site && mixamo_prefix(skeleton.joints[j].name) == 0) return JointConvention::unknown;
  return JointConvention::mixamo;
}

JointRenaming cmu_renaming(const Skeleton& skeleton) {
  JointRenaming out;
  switch (joint_convention(skeleton)) {
    case JointConvention::daz: {
      const JointRenaming daz = daz_renaming();
      for (const Joint& joint : skeleton.joints) {
        const auto found = daz.find(joint.name);
        if (!joint.end_site && found != daz.end()) out[joint.name] = found->second;
      }
      break;
    }
    case JointConvention::mixamo: {
      const JointRenaming spine = {{"Spine", "LowerBack"}, {"Spine1", "Spine"}, {"Spine2", "Spine1"}};
      for (const Joint& joint : skeleton.joints) {
        if (joint.end_site || mixamo_prefix(joint.name) == 0) continue;  // the chain above keeps its names
        std::string name = joint.name.substr(mixamo_prefix(joint.name));
        const auto found = spine.find(name);
        out[joint.name] = found != spine.end() ? found->second : name;
      }
      break;
    }
    case JointConvention::cmu:
    case JointConvention::unknown: break;
  }
  return out;
}

void rename_joints(Skeleton& skeleton, const JointRenaming& renaming) {
  for (const auto& [from, to] : renaming) {
    const int j = skeleton.find(from);
    if (j < 0 || skeleton.joints[static_cast<std::size_t>(j)].end_site)
      throw ArgumentError("joint renaming \"" + from + "\" -> \"" + to + "\": the skeleton has no joint \"" + from + "\"");
    if (to.empty()) throw ArgumentError("joint renaming \"" + from + "\": the new name is empty; expected a joint name");
  }
  std::vector<std::string> names(skeleton.joints.size());
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    if (joint.end_site && joint.parent >= 0) {
      const std::string& parent = skeleton.joints[static_cast<std::size_t>(joint.parent)].name;
      const auto found = renaming.find(parent);
      names[j] = found != renaming.end() && joint.name == parent + "_end" ? found->second + "_end" : joint.name;
      continue;
    }
    const auto found = renaming.find(joint.name);
    names[j] = found != renaming.end() ? found->second : joint.name;
  }
  std::map<std::string, std::size_t> seen;  // new name -> the first joint given it
  const auto told = [&](std::size_t j) {
    const std::string& name = skeleton.joints[j].name;
    return names[j] == name ? "\"" + name + "\" (kept)" : "\"" + name + "\" (renamed \"" + name + "\" -> \"" + names[j] + "\")";
  };
  for (std::size_t j = 0; j < names.size(); ++j) {
    const auto [first, inserted] = seen.emplace(names[j], j);
    if (!inserted)
      throw ArgumentError("joint renaming: two joints would be named \"" + names[j] + "\": " + told(first->second) +
                          " and " + told(j) + "; expected names that stay unique");
  }
  for (std::size_t j = 0; j < names.size(); ++j) skeleton.joints[j].name = names[j];
}

}  // namespace mrcloth
