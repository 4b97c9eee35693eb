#include "body_capsules.h"

#include <Eigen/Eigenvalues>

#include "mesh_ops/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace mrcloth {
namespace {

using Eigen::Vector3d;

/// The height the default radii were chosen for (a standing woman), metres.
constexpr double kReferenceHeight = 1.65;

/// Bones shorter than this fraction of the figure's height are zero-length
/// (CMU: Hips -> LHipJoint, Spine1 -> Neck, ... have offset 0 exactly).
constexpr double kZeroLengthFraction = 1e-6;

/// A bone of a name without a default gets this fraction of its length as
/// radius, within [kUnknownMin, kUnknownMax] (metres at the reference height).
constexpr double kUnknownRadiusPerLength = 0.15;
constexpr double kUnknownMin = 0.01;
constexpr double kUnknownMax = 0.15;

/// Vertices needed at one end of a bone to fit that end's radius.
constexpr std::size_t kMinFitSamples = 4;
constexpr double kFitPercentile = 0.75;
/// A cross-section this many times wider one way than the other gets two capsules.
constexpr double kTwinAspect = 1.3;

/// Default radii (head, tail) in metres for a 1.65 m woman, by CMU joint
/// name; a capsule runs from the named joint to each child. (0, 0): no
/// capsule (hands, fingers, toes). The values are chosen so that the default
/// garments modelled on that figure start outside the body:
///  - the skirt's waist ellipse at y = 1.02 is 0.258 x 0.184 m, so the lower
///    back narrows to 0.08 at the waist (a round section must fit the depth);
///  - its hip ellipse is 0.344 m wide with the hip joints at x = +-0.09, so
///    the pelvis (Hips -> each UpLeg, a bent capsule between the hip joints
///    through the hips centre) and the top of the thighs are 0.075, not the
///    0.085 of a round thigh, or they would poke through the skirt's sides.
struct DefaultRadii {
  const char* name;
  double head, tail;
};
constexpr DefaultRadii kDefaults[] = {
    {"Hips", 0.090, 0.075},  // pelvis; in CMU every Hips bone is zero-length -> a sphere
    {"LHipJoint", 0.090, 0.075},
    {"RHipJoint", 0.090, 0.075},
    {"LeftUpLeg", 0.075, 0.050},
    {"RightUpLeg", 0.075, 0.050},
    {"LeftLeg", 0.050, 0.035},
    {"RightLeg", 0.050, 0.035},
    {"LeftFoot", 0.040, 0.030},
    {"RightFoot", 0.040, 0.030},
    {"LeftToeBase", 0.0, 0.0},
    {"RightToeBase", 0.0, 0.0},
    {"LowerBack", 0.095, 0.080},
    {"Spine", 0.095, 0.120},
    {"Spine1", 0.120, 0.120},  // CMU: all its bones are zero-length -> a chest sphere
    {"Neck", 0.090, 0.055},    // CMU's Neck bone runs from the chest to the neck base
    {"Neck1", 0.050, 0.050},
    {"Head", 0.085, 0.065},
    {"LeftShoulder", 0.070, 0.050},
    {"RightShoulder", 0.070, 0.050},
    {"LeftArm", 0.045, 0.035},
    {"RightArm", 0.045, 0.035},
    {"LeftForeArm", 0.035, 0.030},
    {"RightForeArm", 0.035, 0.030},
    {"LeftHand", 0.0, 0.0},
    {"RightHand", 0.0, 0.0},
    {"LeftFingerBase", 0.0, 0.0},
    {"RightFingerBase", 0.0, 0.0},
    {"LeftHandIndex1", 0.0, 0.0},
    {"RightHandIndex1", 0.0, 0.0},
    {"LThumb", 0.0, 0.0},
    {"RThumb", 0.0, 0.0},
};

const DefaultRadii* find_default(const std::string& name) {
  for (const DefaultRadii& d : kDefaults)
    if (name == d.name) return &d;
  return nullptr;
}

/// Whether the nearest ancestor of joint j with a default radius has none
/// (a hand or a toe): its unnamed descendants (finger links) get none either.
bool under_bare_joint(const Skeleton& skeleton, int j) {
  for (int a = skeleton.joints[static_cast<std::size_t>(j)].parent; a >= 0; a = skeleton.joints[static_cast<std::size_t>(a)].parent)
    if (const DefaultRadii* known = find_default(skeleton.joints[static_cast<std::size_t>(a)].name))
      return known->head == 0.0 && known->tail == 0.0;
  return false;
}

/// Height of the figure in its rest pose: the top of the head (the highest
/// of "Head" and its descendants, i.e. its End Site; the highest joint when
/// there is no Head) minus the lowest joint (toe or foot). 0 if degenerate.
double skeleton_height(const Skeleton& skeleton, const Pose& rest) {
  const int n = static_cast<int>(skeleton.joints.size());
  if (n == 0) return 0.0;
  double low = std::numeric_limits<double>::infinity(), top = -low, head_top = -low;
  const int head = skeleton.find("Head");
  std::vector<bool> under_head(n, false);
  for (int j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    under_head[j] = j == head || (parent >= 0 && under_head[parent]);
    const double y = rest.position(j).y();
    low = std::min(low, y);
    top = std::max(top, y);
    if (under_head[j]) head_top = std::max(head_top, y);
  }
  const double height = (head >= 0 ? head_top : top) - low;
  return std::isfinite(height) && height > 0.0 ? height : 0.0;
}

void check_skeleton(const Skeleton& skeleton, const char* caller) {
  const int n = static_cast<int>(skeleton.joints.size());
  for (int j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent >= j || parent < -1)
      throw ArgumentError(std::string(caller) + ": joint " + std::to_string(j) + " (" + skeleton.joints[j].name +
                          ") has parent " + std::to_string(parent) + "; expected a parent listed before it, or -1");
  }
}

void check_rig(const CapsuleRig& rig, int joint_count, const char* caller) {
  const auto fail = [&](std::size_t i, const std::string& problem) {
    throw ArgumentError(std::string(caller) + ": capsule " + std::to_string(i) + ": " + problem);
  };
  for (std::size_t i = 0; i < rig.bones.size(); ++i) {
    const BoneCapsule& bone = rig.bones[i];
    if (bone.joint < 0 || bone.joint >= joint_count || bone.child < 0 || bone.child >= joint_count)
      fail(i, "joints " + std::to_string(bone.joint) + " -> " + std::to_string(bone.child) +
                  " are not both in the skeleton's " + std::to_string(joint_count) + " joints");
    if (!(std::isfinite(bone.radius_head) && std::isfinite(bone.radius_tail) && bone.radius_head >= 0.0 &&
          bone.radius_tail >= 0.0 && bone.radius_head + bone.radius_tail > 0.0))
      fail(i, "radii must be finite, >= 0 and not both 0 (got " + number_text(bone.radius_head) + ", " +
                  number_text(bone.radius_tail) + ")");
    if (!(bone.shift_head.allFinite() && bone.shift_tail.allFinite())) fail(i, "its shifts must be finite");
  }
  for (std::size_t i = 0; i < rig.bridges.size(); ++i) {
    const BridgeCapsule& bridge = rig.bridges[i];
    for (int joint : {bridge.joint_a, bridge.child_a, bridge.joint_b, bridge.child_b})
      if (joint < 0 || joint >= joint_count)
        throw ArgumentError(std::string(caller) + ": bridge " + std::to_string(i) + " names joint " +
                            std::to_string(joint) + ", not one of the skeleton's " + std::to_string(joint_count));
    if (!(bridge.at >= 0.0 && bridge.at <= 1.0 && std::isfinite(bridge.radius) && bridge.radius > 0.0))
      throw ArgumentError(std::string(caller) + ": bridge " + std::to_string(i) + " needs 0 <= at <= 1 and a radius > 0 (got at " +
                          number_text(bridge.at) + ", radius " + number_text(bridge.radius) + ")");
  }
  if (!(rig.thickness >= 0.0 && rig.thickness <= kMostContactThickness))
    throw ArgumentError(std::string(caller) + ": thickness must be from 0 to " + number_text(kMostContactThickness) +
                        " m (got " + number_text(rig.thickness) + ")");
  if (!(std::isfinite(rig.friction) && rig.friction >= 0.0))
    throw ArgumentError(std::string(caller) + ": friction must be a finite number >= 0 (got " + number_text(rig.friction) + ")");
}

/// The collider of one bone in a pose.
/// A bone capsule's end points in a pose: its joints, shifted in the joint's frame.
std::pair<Vector3d, Vector3d> capsule_ends(const BoneCapsule& bone, const Pose& pose) {
  const Eigen::Matrix3d turn = pose.global[static_cast<std::size_t>(bone.joint)].linear();
  return {pose.position(bone.joint) + turn * bone.shift_head, pose.position(bone.child) + turn * bone.shift_tail};
}

Collider bone_collider(const CapsuleRig& rig, const BoneCapsule& bone, const Pose& pose) {
  CapsuleCollider capsule;
  std::tie(capsule.a, capsule.b) = capsule_ends(bone, pose);
  capsule.radius_a = bone.radius_head;
  capsule.radius_b = bone.radius_tail;
  return Collider{capsule, rig.thickness, rig.friction};
}

/// The bridge's collider in a pose.
Collider bridge_collider(const CapsuleRig& rig, const BridgeCapsule& bridge, const Pose& pose) {
  CapsuleCollider capsule;
  capsule.a = pose.position(bridge.joint_a) + bridge.at * (pose.position(bridge.child_a) - pose.position(bridge.joint_a));
  capsule.b = pose.position(bridge.joint_b) + bridge.at * (pose.position(bridge.child_b) - pose.position(bridge.joint_b));
  capsule.radius_a = capsule.radius_b = bridge.radius;
  return Collider{capsule, rig.thickness, rig.friction};
}

/// Where the centre of a limb's cross-section lies relative to its bone
/// a -> c (metres): the mean of the samples' offsets perpendicular to the
/// bone (from a; for a zero-length bone, of their offsets from a).
Vector3d cross_section_centre(const std::vector<Vector3d>& samples, const Vector3d& a, const Vector3d& c) {
  const double length = (c - a).norm();
  const Vector3d axis = length > 0.0 ? Vector3d((c - a) / length) : Vector3d::Zero();
  Vector3d sum = Vector3d::Zero();
  for (const Vector3d& p : samples) {
    const Vector3d d = p - a;
    sum += d - d.dot(axis) * axis;
  }
  return sum / static_cast<double>(samples.size());
}

/// Nearest-rank percentile of unsorted values (non-empty).
double percentile(std::vector<double> values, double fraction) {
  const std::size_t n = values.size();
  std::size_t rank = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(n)));
  rank = std::clamp<std::size_t>(rank, 1, n) - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

}  // namespace

std::pair<double, double> segment_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return {(p - (a + t * ab)).norm(), t};
}

CapsuleRig make_capsule_rig(const Skeleton& skeleton, const CapsuleRigOptions& options) {
  check_skeleton(skeleton, "make_capsule_rig");
  for (const auto& [name, radii] : options.radii) {
    if (skeleton.find(name) < 0)
      throw ArgumentError("make_capsule_rig: radius override for \"" + name + "\", which is not a joint of the skeleton");
    if (!(std::isfinite(radii.first) && std::isfinite(radii.second) && radii.first >= 0.0 && radii.second >= 0.0))
      throw ArgumentError("make_capsule_rig: radius override for \"" + name + "\" must be finite and >= 0 (got " +
                          number_text(radii.first) + ", " + number_text(radii.second) + ")");
  }

  CapsuleRig rig;
  rig.thickness = options.thickness;
  rig.friction = options.friction;
  const int n = static_cast<int>(skeleton.joints.size());
  if (n == 0) {
    check_rig(rig, n, "make_capsule_rig");
    return rig;
  }

  const Pose rest = rest_pose(skeleton);
  const double height = skeleton_height(skeleton, rest);
  const double scale = height > 0.0 ? height / kReferenceHeight : 1.0;
  const double zero_length = kZeroLengthFraction * (height > 0.0 ? height : kReferenceHeight);

  std::vector<std::vector<int>> children(n);
  for (int j = 0; j < n; ++j)
    if (skeleton.joints[j].parent >= 0) children[skeleton.joints[j].parent].push_back(j);

  for (int j = 0; j < n; ++j) {
    const Joint& joint = skeleton.joints[j];
    if (joint.end_site || children[j].empty()) continue;  // a bone needs a far end
    const DefaultRadii* known = find_default(joint.name);
    const auto override_it = options.radii.find(joint.name);
    const bool overridden = override_it != options.radii.end();
    if (!known && !overridden && under_bare_joint(skeleton, j)) continue;  // a DAZ hand's finger links: no capsule, as CMU's

    std::vector<int> long_children;
    for (int c : children[j])
      if ((rest.position(c) - rest.position(j)).norm() > zero_length) long_children.push_back(c);

    const auto radii_for = [&](int child) -> std::pair<double, double> {
      if (overridden) return override_it->second;
      if (known) return {known->head * scale, known->tail * scale};
      const double length = (rest.position(child) - rest.position(j)).norm();
      const double r = std::clamp(kUnknownRadiusPerLength * length, kUnknownMin * scale, kUnknownMax * scale);
      return {r, r};
    };

    if (!long_children.empty()) {
      for (int c : long_children) {
        const auto [head, tail] = radii_for(c);
        if (head > 0.0 || tail > 0.0) rig.bones.push_back({j, c, head, tail});
      }
    } else if (overridden || known) {
      // Every bone of this joint is zero-length: a sphere at the joint, as
      // large as the larger radius, so the region (CMU's chest at Spine1,
      // the pelvis at Hips) stays covered. Unknown names get none: their
      // length-proportional radius would be 0.
      const auto [head, tail] = radii_for(children[j].front());
      const double r = std::max(head, tail);
      if (r > 0.0) rig.bones.push_back({j, children[j].front(), r, r});
    }
  }
  check_rig(rig, n, "make_capsule_rig");
  return rig;
}

namespace {

/// How a cross-section much wider one way than the other is covered by two
/// capsules side by side: `direction` (unit, across the axis) the wide way
/// and `offset` (metres) each twin's distance from the axis; offset 0 for
/// one round capsule.
struct TwinSpread {
  Vector3d direction = Vector3d::Zero();
  double offset = 0.0;
};

/// The samples' spread across the centred axis from `a_fit` to `c_fit`
/// (rest space, metres), by its principal directions (a sphere bone has no
/// axis and stays round).
TwinSpread twin_spread(const Vector3d& a_fit, const Vector3d& c_fit, const std::vector<Vector3d>& head_samples,
                       const std::vector<Vector3d>& tail_samples) {
  TwinSpread twin;
  const double length = (c_fit - a_fit).norm();
  if (!(length > 0.0)) return twin;
  const Vector3d axis = (c_fit - a_fit) / length;
  const Vector3d e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  std::vector<Eigen::Vector2d> offsets;
  for (const auto* samples : {&head_samples, &tail_samples})
    for (const Vector3d& p : *samples) {
      const Vector3d d = p - a_fit;
      offsets.emplace_back(d.dot(e1), d.dot(e2));
    }
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& o : offsets) covariance += o * o.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> principal(covariance);
  const Eigen::Vector2d major = principal.eigenvectors().col(1), minor = principal.eigenvectors().col(0);
  std::vector<double> along_major, along_minor;
  for (const Eigen::Vector2d& o : offsets) {
    along_major.push_back(std::abs(o.dot(major)));
    along_minor.push_back(std::abs(o.dot(minor)));
  }
  const double wide = percentile(along_major, kFitPercentile), narrow = percentile(along_minor, kFitPercentile);
  if (wide > kTwinAspect * narrow) {
    twin.direction = major.x() * e1 + major.y() * e2;
    twin.offset = wide - narrow;
  }
  return twin;
}

/// Fits one bone's capsule to the body vertices it dominates near its head
/// and tail (rest space). Each end moves to the centre of its cross-section:
/// a bone may run off-centre in its limb (the spine along the back), and a
/// capsule about it would have to be as wide as the limb's far side and
/// stick out of the near one. A cross-section much wider one way than the
/// other (the pelvis, the chest) gets two capsules side by side, each as
/// thick as the narrow way: one round capsule as wide as the hips would
/// stand 5-10 cm proud of the belly and the back. Too few vertices at both
/// ends: the bone as it was.
std::vector<BoneCapsule> fit_bone(const BoneCapsule& bone, const Pose& rest, const std::vector<Vector3d>& head_samples,
                                  const std::vector<Vector3d>& tail_samples) {
  const bool head_ok = head_samples.size() >= kMinFitSamples;
  const bool tail_ok = tail_samples.size() >= kMinFitSamples;
  if (!head_ok && !tail_ok) return {bone};
  const Vector3d a = rest.position(bone.joint), c = rest.position(bone.child);
  const Vector3d head_centre = head_ok ? cross_section_centre(head_samples, a, c) : Vector3d::Zero();
  const Vector3d tail_centre = tail_ok ? cross_section_centre(tail_samples, a, c) : Vector3d::Zero();
  const Vector3d head_shift = head_ok ? head_centre : tail_centre;
  const Vector3d tail_shift = tail_ok ? tail_centre : head_centre;
  const Vector3d a_fit = a + head_shift, c_fit = c + tail_shift;

  const TwinSpread twin = twin_spread(a_fit, c_fit, head_samples, tail_samples);
  const Vector3d& spread_direction = twin.direction;
  const double side_offset = twin.offset;

  const int count = side_offset > 0.0 ? 2 : 1;
  std::vector<BoneCapsule> out;
  for (int k = 0; k < count; ++k) {
    const Vector3d side = (count == 2 ? (k == 0 ? 1.0 : -1.0) * side_offset : 0.0) * spread_direction;
    out.push_back(bone);
    BoneCapsule& fit = out.back();
    // Each sample is covered by the nearer twin, so the radius is a
    // percentile of the distance to the nearer axis.
    const auto radius = [&](const std::vector<Vector3d>& samples) {
      std::vector<double> distances;
      distances.reserve(samples.size());
      for (const Vector3d& p : samples) {
        double d = segment_distance(p, a_fit + side, c_fit + side).first;
        if (count == 2) d = std::min(d, segment_distance(p, a_fit - side, c_fit - side).first);
        distances.push_back(d);
      }
      return percentile(std::move(distances), kFitPercentile);
    };
    const double head = head_ok ? radius(head_samples) : 0.0;
    const double tail = tail_ok ? radius(tail_samples) : 0.0;
    // A zero-length (sphere) bone puts every vertex at t = 0, so its head
    // radius serves both ends.
    fit.radius_head = head_ok ? head : tail;
    fit.radius_tail = tail_ok ? tail : head;
    if (!(fit.radius_head + fit.radius_tail > 0.0)) fit.radius_head = fit.radius_tail = 1e-6;
    // Shifts are kept in the joint's frame, so they turn with the bone.
    const Eigen::Matrix3d to_local = rest.global[bone.joint].linear().transpose();
    fit.shift_head = to_local * (head_shift + side);
    fit.shift_tail = to_local * (tail_shift + side);
  }
  return out;
}

}  // namespace

void fit_capsule_radii(CapsuleRig& rig, const Skeleton& skeleton, const Eigen::MatrixX3d& rest_vertices,
                       const std::vector<std::vector<std::pair<int, double>>>& bone_weights,
                       const std::vector<Eigen::Vector3d>& joint_rest) {
  const int n = static_cast<int>(skeleton.joints.size());
  check_skeleton(skeleton, "fit_capsule_radii");
  check_rig(rig, n, "fit_capsule_radii");
  if (static_cast<std::size_t>(rest_vertices.rows()) != bone_weights.size())
    throw ArgumentError("fit_capsule_radii: " + std::to_string(rest_vertices.rows()) + " vertices but " +
                        std::to_string(bone_weights.size()) + " weight lists; expected one list per vertex");
  if (rig.bones.empty()) return;
  const Pose rest = proportioned_pose(skeleton, joint_rest, rest_pose(skeleton));

  std::vector<std::vector<int>> bones_of(n);  // capsules by their head joint
  for (std::size_t b = 0; b < rig.bones.size(); ++b) bones_of[rig.bones[b].joint].push_back(static_cast<int>(b));

  // Each vertex goes to the nearest capsule axis among the capsules of its
  // dominant joint, at the end of that axis it is closer to.
  std::vector<std::vector<Vector3d>> head_samples(rig.bones.size()), tail_samples(rig.bones.size());
  for (Eigen::Index v = 0; v < rest_vertices.rows(); ++v) {
    const auto& weights = bone_weights[static_cast<std::size_t>(v)];
    int dominant = -1;
    double best_weight = -std::numeric_limits<double>::infinity();
    for (const auto& [joint, weight] : weights) {
      if (joint < 0 || joint >= n)
        throw ArgumentError("fit_capsule_radii: vertex " + std::to_string(v) + " is weighted to joint " +
                            std::to_string(joint) + "; the skeleton has " + std::to_string(n) + " joints");
      if (weight > best_weight) {
        best_weight = weight;
        dominant = joint;
      }
    }
    if (dominant < 0 || bones_of[dominant].empty()) continue;
    const Vector3d p = rest_vertices.row(v).transpose();
    if (!p.allFinite())
      throw ArgumentError("fit_capsule_radii: vertex " + std::to_string(v) + " has a non-finite coordinate");
    int nearest = -1;
    double nearest_distance = std::numeric_limits<double>::infinity(), nearest_t = 0.0;
    for (int b : bones_of[dominant]) {
      const BoneCapsule& bone = rig.bones[b];
      const auto [distance, t] = segment_distance(p, rest.position(bone.joint), rest.position(bone.child));
      if (distance < nearest_distance) {
        nearest = b;
        nearest_distance = distance;
        nearest_t = t;
      }
    }
    (nearest_t <= 0.5 ? head_samples : tail_samples)[nearest].push_back(p);
  }

  std::vector<BoneCapsule> fitted;
  for (std::size_t b = 0; b < rig.bones.size(); ++b) {
    const std::vector<BoneCapsule> capsules = fit_bone(rig.bones[b], rest, head_samples[b], tail_samples[b]);
    fitted.insert(fitted.end(), capsules.begin(), capsules.end());
  }
  rig.bones = std::move(fitted);
}

std::vector<Collider> posed_capsules(const CapsuleRig& rig, const Pose& pose) {
  const int joints = static_cast<int>(pose.global.size());
  for (std::size_t i = 0; i < rig.bones.size(); ++i) {
    const BoneCapsule& bone = rig.bones[i];
    if (bone.joint < 0 || bone.joint >= joints || bone.child < 0 || bone.child >= joints)
      throw ArgumentError("posed_capsules: capsule " + std::to_string(i) + " joins joints " +
                          std::to_string(bone.joint) + " -> " + std::to_string(bone.child) + " but the pose has " +
                          std::to_string(joints) + " joints");
  }
  check_rig(rig, joints, "posed_capsules");
  std::vector<Collider> colliders;
  colliders.reserve(rig.bones.size() + rig.bridges.size());
  for (const BoneCapsule& bone : rig.bones) colliders.push_back(bone_collider(rig, bone, pose));
  for (const BridgeCapsule& bridge : rig.bridges) colliders.push_back(bridge_collider(rig, bridge, pose));
  return colliders;
}

int clear_capsules_of(CapsuleRig& rig, const Pose& pose, const Eigen::MatrixX3d& points, double floor) {
  check_rig(rig, static_cast<int>(pose.global.size()), "clear_capsules_of");
  if (!(floor > 0.0 && floor <= 1.0))
    throw ArgumentError("clear_capsules_of: floor must be in (0, 1] (got " + number_text(floor) + ")");
  if (!points.allFinite()) throw ArgumentError("clear_capsules_of: the points must be finite");
  int shrunk = 0;
  for (BoneCapsule& bone : rig.bones) {
    const Collider full = bone_collider(rig, bone, pose);
    const auto scaled = [&](double s) {
      Collider c = full;
      auto& capsule = std::get<CapsuleCollider>(c.shape);
      capsule.radius_a *= s;
      capsule.radius_b *= s;
      return c;
    };
    const auto clear = [&](const Collider& c, const Vector3d& p) {
      return query_surface(c, p).distance >= rig.thickness;
    };
    double factor = 1.0;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      const Vector3d p = points.row(i).transpose();
      if (surely_clear(full, p) || clear(scaled(factor), p)) continue;
      // The distance grows as the radii shrink: bisect for the largest
      // factor that clears p (none above the floor: the floor).
      double inside = factor, outside = floor;
      if (!clear(scaled(floor), p)) {
        factor = floor;
        continue;
      }
      for (int k = 0; k < 50; ++k) {
        const double middle = 0.5 * (inside + outside);
        (clear(scaled(middle), p) ? outside : inside) = middle;
      }
      factor = outside;
    }
    if (factor < 1.0) {
      bone.radius_head *= factor;
      bone.radius_tail *= factor;
      ++shrunk;
    }
  }
  return shrunk;
}

void add_leg_bridges(CapsuleRig& rig, const Skeleton& skeleton, double reach) {
  check_skeleton(skeleton, "add_leg_bridges");
  check_rig(rig, static_cast<int>(skeleton.joints.size()), "add_leg_bridges");
  if (!(reach >= 0.5 && reach <= 2.0))
    throw ArgumentError("add_leg_bridges: reach must be in [0.5, 2] bones from the hips (got " + number_text(reach) + ")");
  const auto joint = [&](const char* name) {
    const int j = skeleton.find(name);
    if (j < 0) throw ArgumentError(std::string("add_leg_bridges: the skeleton has no joint '") + name + "'");
    return j;
  };
  // Thigh then shin of each leg: (joint, child) pairs.
  const std::pair<int, int> left[2] = {{joint("LeftUpLeg"), joint("LeftLeg")}, {joint("LeftLeg"), joint("LeftFoot")}};
  const std::pair<int, int> right[2] = {{joint("RightUpLeg"), joint("RightLeg")}, {joint("RightLeg"), joint("RightFoot")}};
  // The leg capsule's radius at fraction `at` of a bone (0 if none).
  const auto radius_at = [&](std::pair<int, int> bone, double at) {
    for (const BoneCapsule& b : rig.bones)
      if (b.joint == bone.first && b.child == bone.second) return b.radius_head + at * (b.radius_tail - b.radius_head);
    return 0.0;
  };
  for (int half = 1; half <= static_cast<int>(std::floor(2.0 * reach + 1e-9)); ++half) {
    const int k = (half - 1) / 2;      // thigh (0) or shin (1)
    const double at = half % 2 ? 0.5 : 1.0;
    const double radius = std::min(radius_at(left[k], at), radius_at(right[k], at));
    if (!(radius > 0.0))
      throw ArgumentError("leg bridges need a capsule on both " + std::string(k ? "shins" : "thighs") +
                          ", and the rig has none on one of them (a radius of 0 leaves a bone without one); expected "
                          "capsules on both legs, or no leg bridges");
    rig.bridges.push_back({left[k].first, left[k].second, right[k].first, right[k].second, at, radius});
  }
}

CapsuleBody::CapsuleBody(CapsuleRig rig, const Skeleton& skeleton) : rig_(std::move(rig)) {
  check_skeleton(skeleton, "CapsuleBody");
  check_rig(rig_, static_cast<int>(skeleton.joints.size()), "CapsuleBody");
  colliders_ = posed_capsules(rig_, rest_pose(skeleton));
  update_boxes();
  previous_ = colliders_;
}

void CapsuleBody::update_boxes() {
  boxes_.resize(colliders_.size());
  for (std::size_t i = 0; i < colliders_.size(); ++i) {
    const auto* capsule = std::get_if<CapsuleCollider>(&colliders_[i].shape);
    std::array<double, 6>& box = boxes_[i];
    if (!capsule) {  // not a capsule (the rig makes none such): never beyond
      box.fill(std::numeric_limits<double>::infinity());
      for (int c = 0; c < 3; ++c) box[static_cast<std::size_t>(c)] = -box[static_cast<std::size_t>(c)];
      continue;
    }
    const double grow = std::max(capsule->radius_a, capsule->radius_b) + colliders_[i].thickness;
    for (int c = 0; c < 3; ++c) {
      box[static_cast<std::size_t>(c)] = std::min(capsule->a(c), capsule->b(c)) - grow;
      box[static_cast<std::size_t>(c + 3)] = std::max(capsule->a(c), capsule->b(c)) + grow;
    }
  }
}

void CapsuleBody::pose(const Pose& pose) {
  const int joints = static_cast<int>(pose.global.size());
  for (std::size_t i = 0; i < rig_.bones.size(); ++i) {
    const BoneCapsule& bone = rig_.bones[i];
    if (bone.joint >= joints || bone.child >= joints)
      throw ArgumentError("CapsuleBody::pose: the pose has " + std::to_string(joints) + " joints; capsule " +
                          std::to_string(i) + " needs joints " + std::to_string(bone.joint) + " and " +
                          std::to_string(bone.child));
    // Only the end points move: update in place, no allocation per step.
    if (posed_) previous_[i].shape = colliders_[i].shape;
    auto& capsule = std::get<CapsuleCollider>(colliders_[i].shape);
    std::tie(capsule.a, capsule.b) = capsule_ends(bone, pose);
  }
  for (std::size_t k = 0; k < rig_.bridges.size(); ++k) {
    const BridgeCapsule& bridge = rig_.bridges[k];
    if (std::max({bridge.joint_a, bridge.child_a, bridge.joint_b, bridge.child_b}) >= joints)
      throw ArgumentError("CapsuleBody::pose: the pose has " + std::to_string(joints) + " joints; bridge " +
                          std::to_string(k) + " needs more");
    const std::size_t i = rig_.bones.size() + k;
    if (posed_) previous_[i].shape = colliders_[i].shape;
    colliders_[i] = bridge_collider(rig_, rig_.bridges[k], pose);
  }
  update_boxes();
  // The first pose may be far from the construction pose (the rest pose at
  // the origin): that jump is not a motion the cloth took part in.
  if (!posed_) previous_ = colliders_;
  posed_ = true;
  ++serial_;
}

double CapsuleBody::resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction,
                            ContactMemo* memo, SurfaceNearby* nearby) const {
  const double largest = resolve_with_memo(start, position, friction, memo);
  if (nearby) *nearby = nearest_surface(colliders_, position, kNearbyReach);
  return largest;
}

double CapsuleBody::resolve_with_memo(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction,
                                      ContactMemo* memo) const {
  // A memo lists every capsule whose thickened surface may come within
  // kMemoReach of its centre; within half that of the centre the others are
  // clear, so a point that ends there was resolved against all of them.
  constexpr double kMemoReach = 0.02;
  if (!memo || (memo->owner != nullptr && memo->owner != this))
    return resolve_point(previous_, colliders_, start, position, friction);
  const double trusted2 = 0.25 * kMemoReach * kMemoReach;
  if (memo->owner != this || memo->serial != serial_ || (position - memo->centre).squaredNorm() >= trusted2) {
    memo->items.clear();
    colliders_near(colliders_, position, kMemoReach, memo->items);
    memo->centre = position;
    memo->radius = kMemoReach;
    memo->owner = this;
    memo->serial = serial_;
  }
  const Eigen::Vector3d input = position;
  const double largest = resolve_point_among(previous_, colliders_, memo->items, start, position, friction);
  if ((position - memo->centre).squaredNorm() < trusted2) return largest;
  position = input;  // pushed beyond what the memo vouches for: every capsule answers
  return resolve_point(previous_, colliders_, start, position, friction);
}

bool CapsuleBody::beyond(const Eigen::Vector3d& p, double reach) const {
  // A tapered capsule lies inside the round one of its larger radius, which
  // lies inside its segment's box grown by that radius: a point that far
  // outside the box along one axis is that far from the capsule. A
  // micrometre more keeps the exact tests' rounding (surely_clear's and
  // nearest_surface's bound) on the same side.
  constexpr double kRoundingMargin = 1e-6;  // metres
  const double r = reach + kRoundingMargin;
  for (const std::array<double, 6>& box : boxes_) {
    bool outside = false;
    for (int c = 0; c < 3 && !outside; ++c)
      outside = p(c) < box[static_cast<std::size_t>(c)] - r || p(c) > box[static_cast<std::size_t>(c + 3)] + r;
    if (!outside) return false;
  }
  return true;
}

double CapsuleBody::penetration(const Eigen::Vector3d& p) const { return mrcloth::penetration(colliders_, p); }
double CapsuleBody::depth(const Eigen::Vector3d& p) const { return mrcloth::depth(colliders_, p); }

}  // namespace mrcloth
