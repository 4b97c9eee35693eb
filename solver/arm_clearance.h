#pragma once
// Keeps a character's hands and forearms out of its hips and thighs.
//
// A capture subject's hands brush their own hips; the same motion on a
// body of other proportions (MakeHuman under CMU subject 07: wider hips)
// drives the hands into the body. Cloth between them is pinched: inside
// the hand wherever it is, so no collision response can put it outside.
// Retargeting tools fix this by opening the arms; so does this: each pose's
// upper arm is turned outward (about the pelvis' forward axis, at the
// shoulder) by the smallest angle that keeps the forearm and hand capsules
// `clearance` away from the pelvis, lower back and thigh capsules. The
// angle is a continuous function of the pose, so the arms move smoothly.
#include "body_capsules.h"
#include "skeleton.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace mrcloth {

struct ArmClearanceOptions {
  /// Metres kept between arm and body capsules (surface to surface), >= 0.
  /// The capsules are fitted to a body's 75th-percentile radius, so its
  /// flat hand and soft hips stand out of them: with 1 cm the MakeHuman
  /// hand still reached into the trousers at the hip on CMU 07_03 (22 mm),
  /// with 2 cm nothing did on the four shared walks.
  double clearance = 0.02;
  double max_angle_deg = 40.0;  ///< the arms open by at most this much, degrees, in (0, 90]
};

/// What clear_arms needs, built once per character.
struct ArmClearance {
  CapsuleRig rig;                          ///< capsules for the check: arms (forearms, hands) and the body near them
  std::vector<Eigen::Vector3d> joint_rest; ///< the body's own rest joints the rig is posed on (empty: the skeleton's)
  struct Side {
    int shoulder = -1;                     ///< the joint turned (LeftArm / RightArm)
    std::vector<int> subtree;              ///< it and every joint below it
    std::vector<int> arm_capsules;         ///< rig.bones of its forearm and hand
  };
  std::vector<Side> sides;                 ///< empty: nothing to clear (a skeleton without CMU arm names)
  std::vector<int> body_capsules;          ///< rig.bones of the hips, lower back and thighs
  int hips = -1, left_leg = -1, right_leg = -1, chest = -1;  ///< joints giving the pelvis frame
  ArmClearanceOptions options;
};

/// Builds the check for a CMU-named skeleton: the default capsule rig with
/// hand capsules (`hand_radius`, metres), or, with a body (`body_vertices`
/// in the skeleton's rest pose, its per-vertex `weights` and `joint_rest`,
/// as SkinnedBody holds them), that rig fitted to the body. A skeleton
/// without the arm, leg and spine names gives an empty check.
ArmClearance make_arm_clearance(const Skeleton& skeleton, const ArmClearanceOptions& options = {},
                                const Eigen::MatrixX3d& body_vertices = {},
                                const std::vector<std::vector<std::pair<int, double>>>& weights = {},
                                const std::vector<Eigen::Vector3d>& joint_rest = {}, double hand_radius = 0.03);

/// Adds capsules that hang from the arms (the skinned body's hand mittens,
/// hand_mitten_capsules) to the check: each joins the side whose subtree
/// holds its joint, so the arms open to keep it clear as well. Capsules of
/// no side are left out.
void add_arm_capsules(ArmClearance& check, const std::vector<BoneCapsule>& capsules);

/// Surface-to-surface distance of the two sides' arm capsules to the body
/// capsules in `pose` (metres, negative when they overlap): [left, right]
/// in ArmClearance::sides order.
std::vector<double> arm_gaps(const ArmClearance& check, const Skeleton& skeleton, const Pose& pose);

/// Opens the arms of `pose` as the header says; returns the largest angle
/// an arm was turned by (radians, 0 when both were clear).
double clear_arms(const ArmClearance& check, const Skeleton& skeleton, Pose& pose);

}  // namespace mrcloth
