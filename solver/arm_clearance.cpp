#include "arm_clearance.h"

#include "mesh_ops/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace mrcloth {
namespace {

using Eigen::Vector3d;

constexpr const char* kBodyNear[] = {"Hips", "LHipJoint", "RHipJoint", "LeftUpLeg", "RightUpLeg", "LowerBack"};

/// Closest points of segments [p0, p1] and [q0, q1]: parameters (s, t) in
/// [0, 1]^2 (Ericson, Real-Time Collision Detection, 5.1.9).
std::pair<double, double> closest_parameters(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0,
                                             const Vector3d& q1) {
  const Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double tiny = 1e-24;
  if (a <= tiny && e <= tiny) return {0.0, 0.0};
  if (a <= tiny) return {0.0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= tiny) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  const double b = d1.dot(d2), denom = a * e - b * b;
  double s = denom > tiny ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, t};
}

/// Surface-to-surface distance of two tapered capsules, measured between
/// their axes' closest points less the radii there (negative: overlap).
double capsule_gap(const CapsuleCollider& x, const CapsuleCollider& y) {
  const auto [s, t] = closest_parameters(x.a, x.b, y.a, y.b);
  const Vector3d px = x.a + s * (x.b - x.a), py = y.a + t * (y.b - y.a);
  const double rx = x.radius_a + s * (x.radius_b - x.radius_a), ry = y.radius_a + t * (y.radius_b - y.radius_a);
  return (px - py).norm() - rx - ry;
}

std::vector<int> subtree_of(const Skeleton& skeleton, int root) {
  std::vector<int> out{root};
  // Parents precede children, so one pass in order collects the subtree.
  std::vector<char> inside(skeleton.joints.size(), 0);
  inside[static_cast<std::size_t>(root)] = 1;
  for (std::size_t j = static_cast<std::size_t>(root) + 1; j < skeleton.joints.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent >= 0 && inside[static_cast<std::size_t>(parent)]) {
      inside[j] = 1;
      out.push_back(static_cast<int>(j));
    }
  }
  return out;
}

double side_gap(const ArmClearance& check, const ArmClearance::Side& side, const std::vector<Collider>& posed) {
  double gap = std::numeric_limits<double>::infinity();
  for (int a : side.arm_capsules)
    for (int b : check.body_capsules)
      gap = std::min(gap, capsule_gap(std::get<CapsuleCollider>(posed[static_cast<std::size_t>(a)].shape),
                                      std::get<CapsuleCollider>(posed[static_cast<std::size_t>(b)].shape)));
  return gap;
}

/// The pelvis' forward axis in `pose`: across the hips, times up the spine.
Vector3d forward_axis(const ArmClearance& check, const Pose& pose) {
  const Vector3d across = pose.position(check.left_leg) - pose.position(check.right_leg);
  const Vector3d up = pose.position(check.chest) - pose.position(check.hips);
  const Vector3d forward = across.cross(up);
  const double length = forward.norm();
  return length > 0.0 ? Vector3d(forward / length) : Vector3d::UnitZ();
}

/// `pose` with side's subtree turned by `angle` about `axis` through the shoulder.
void turn_arm(const ArmClearance::Side& side, const Pose& pose, const Vector3d& axis, double angle, Pose& out) {
  const Vector3d pivot = pose.position(side.shoulder);
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.translate(pivot).rotate(Eigen::AngleAxisd(angle, axis)).translate(-pivot);
  for (int j : side.subtree) out.global[static_cast<std::size_t>(j)] = turn * pose.global[static_cast<std::size_t>(j)];
}

}  // namespace

ArmClearance make_arm_clearance(const Skeleton& skeleton, const ArmClearanceOptions& options,
                                const Eigen::MatrixX3d& body_vertices,
                                const std::vector<std::vector<std::pair<int, double>>>& weights,
                                const std::vector<Eigen::Vector3d>& joint_rest, double hand_radius) {
  if (!(options.clearance >= 0.0) || !std::isfinite(options.clearance))
    throw ArgumentError("arm clearance must be >= 0 metres");
  if (!(options.max_angle_deg > 0.0 && options.max_angle_deg <= 90.0))
    throw ArgumentError("the arms' largest opening angle must be in (0, 90] degrees");
  if (!(hand_radius > 0.0)) throw ArgumentError("the hand radius must be > 0 metres");
  ArmClearance check;
  check.options = options;
  for (const char* name : {"Hips", "LeftUpLeg", "RightUpLeg", "Spine1", "LeftArm", "RightArm", "LeftForeArm",
                           "RightForeArm", "LeftHand", "RightHand"})
    if (skeleton.find(name) < 0) return check;  // not a CMU-named skeleton: nothing to clear
  CapsuleRigOptions rig_options;
  rig_options.radii["LeftHand"] = {hand_radius, hand_radius};
  rig_options.radii["RightHand"] = {hand_radius, hand_radius};
  check.rig = make_capsule_rig(skeleton, rig_options);
  if (body_vertices.rows() > 0) fit_capsule_radii(check.rig, skeleton, body_vertices, weights, joint_rest);
  check.joint_rest = joint_rest;
  check.hips = skeleton.find("Hips");
  check.left_leg = skeleton.find("LeftUpLeg");
  check.right_leg = skeleton.find("RightUpLeg");
  check.chest = skeleton.find("Spine1");
  for (std::size_t i = 0; i < check.rig.bones.size(); ++i) {
    const std::string& name = skeleton.joints[static_cast<std::size_t>(check.rig.bones[i].joint)].name;
    for (const char* near : kBodyNear)
      if (name == near) check.body_capsules.push_back(static_cast<int>(i));
  }
  for (const auto& [arm, forearm, hand] : {std::array<const char*, 3>{"LeftArm", "LeftForeArm", "LeftHand"},
                                           std::array<const char*, 3>{"RightArm", "RightForeArm", "RightHand"}}) {
    ArmClearance::Side side;
    side.shoulder = skeleton.find(arm);
    side.subtree = subtree_of(skeleton, side.shoulder);
    for (std::size_t i = 0; i < check.rig.bones.size(); ++i) {
      const std::string& name = skeleton.joints[static_cast<std::size_t>(check.rig.bones[i].joint)].name;
      if (name == forearm || name == hand) side.arm_capsules.push_back(static_cast<int>(i));
    }
    if (!side.arm_capsules.empty()) check.sides.push_back(std::move(side));
  }
  if (check.body_capsules.empty()) check.sides.clear();
  return check;
}

void add_arm_capsules(ArmClearance& check, const std::vector<BoneCapsule>& capsules) {
  for (const BoneCapsule& capsule : capsules)
    for (ArmClearance::Side& side : check.sides) {
      if (std::find(side.subtree.begin(), side.subtree.end(), capsule.joint) == side.subtree.end()) continue;
      side.arm_capsules.push_back(static_cast<int>(check.rig.bones.size()));
      check.rig.bones.push_back(capsule);
      break;
    }
}

std::vector<double> arm_gaps(const ArmClearance& check, const Skeleton& skeleton, const Pose& pose) {
  std::vector<double> gaps;
  if (check.sides.empty()) return gaps;
  const std::vector<Collider> posed = posed_capsules(check.rig, proportioned_pose(skeleton, check.joint_rest, pose));
  for (const ArmClearance::Side& side : check.sides) gaps.push_back(side_gap(check, side, posed));
  return gaps;
}

double clear_arms(const ArmClearance& check, const Skeleton& skeleton, Pose& pose) {
  if (check.sides.empty()) return 0.0;
  const double wanted = check.options.clearance;
  const double max_angle = check.options.max_angle_deg * M_PI / 180.0;
  const Vector3d forward = forward_axis(check, pose);
  const Vector3d across = pose.position(check.left_leg) - pose.position(check.right_leg);
  double largest = 0.0;
  Pose trial = pose;
  for (const ArmClearance::Side& side : check.sides) {
    // Turning about +forward swings a hanging arm towards +across (the left
    // hip's side): the left arm opens with +angle, the right with -angle.
    const double outward = (pose.position(side.shoulder) - pose.position(check.hips)).dot(across) >= 0.0 ? 1.0 : -1.0;
    const auto gap_at = [&](double angle) {
      turn_arm(side, pose, forward, outward * angle, trial);
      const std::vector<Collider> posed =
          posed_capsules(check.rig, proportioned_pose(skeleton, check.joint_rest, trial));
      return side_gap(check, side, posed);
    };
    if (gap_at(0.0) >= wanted) continue;
    double angle = max_angle;
    if (gap_at(max_angle) >= wanted) {
      // The gap grows as the arm opens: bisect for the smallest angle that
      // clears, to 1e-4 rad (0.1 mm at the hand), so the angle is a
      // continuous function of the pose.
      double lo = 0.0, hi = max_angle;
      while (hi - lo > 1e-4) {
        const double mid = 0.5 * (lo + hi);
        (gap_at(mid) >= wanted ? hi : lo) = mid;
      }
      angle = hi;
    }
    turn_arm(side, pose, forward, outward * angle, pose);
    trial = pose;
    largest = std::max(largest, angle);
  }
  return largest;
}

}  // namespace mrcloth
