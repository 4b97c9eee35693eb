#pragma once
// A capsule body: one tapered capsule per bone of a skeleton, posed by FK.
#include "collision_scene.h"
#include "skeleton.h"

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mrcloth {

struct BoneCapsule {
  int joint = -1;          ///< the bone runs from this joint ...
  int child = -1;          ///< ... to this one (a child joint or End Site)
  double radius_head = 0;  ///< radius at `joint`, metres
  double radius_tail = 0;  ///< radius at `child`, metres
  /// Where the capsule's ends sit relative to `joint` and `child`, in the
  /// joint's frame (turning with the bone), metres: a fitted capsule is
  /// centred in its limb, which the bone need not be.
  Eigen::Vector3d shift_head{0, 0, 0}, shift_tail{0, 0, 0};
};

/// A capsule across the gap between two bones, from the point at `at` along
/// the first (joint_a -> child_a, 0 = joint, 1 = child) to the point at `at`
/// along the second: the web between the legs that keeps a skirt from
/// folding in between them (see add_leg_bridges).
struct BridgeCapsule {
  int joint_a = -1, child_a = -1;  ///< the first bone
  int joint_b = -1, child_b = -1;  ///< the second bone
  double at = 1.0;                 ///< position along both bones, in [0, 1]
  double radius = 0;               ///< metres, > 0
};

struct CapsuleRigOptions {
  double thickness = 0.004;  ///< cloth keeps this far from the capsules, metres, 0 to kMostContactThickness
  double friction = 0.3;     ///< Coulomb coefficient
  /// Radius overrides by joint name, metres (head, tail), applied after defaults/fitting.
  std::map<std::string, std::pair<double, double>> radii;
};

struct CapsuleRig {
  std::vector<BoneCapsule> bones;
  std::vector<BridgeCapsule> bridges;  ///< collide after the bones, in this order
  double thickness = 0.004;
  double friction = 0.3;
};

/// Distance from p to segment [a, b] (metres) and the parameter t in [0, 1]
/// of the closest point (t = 0 for a zero-length segment).
std::pair<double, double> segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Capsules along the bones of `skeleton` with default radii for the CMU
/// joint names (legs, spine, arms, neck, head; hands, fingers and toes get
/// none), scaled by the skeleton's height relative to a 1.65 m figure.
/// Bones of unknown names get a radius proportional to their length.
CapsuleRig make_capsule_rig(const Skeleton& skeleton, const CapsuleRigOptions& options = {});

/// Refits every capsule's radii to a body mesh in the rig's rest pose:
/// rest_vertices (#V x 3, metres, in the skeleton's rest space) and per
/// vertex its dominant bone weights (bone_weights[v] = list of (joint, w)):
/// each end of a capsule moves to the centre of the cross-section of the
/// vertices the bone dominates near that end (shift_head / shift_tail), and
/// its radius there is a robust (75th percentile) distance of those vertices
/// to the centred axis. A bone whose cross-section is over 1.3 times wider
/// one way than the other (pelvis, chest) becomes two capsules side by
/// side, as thick as the narrow way, so rig.bones can grow. The axes
/// run between `joint_rest` (per joint, the body's own rest joints, metres,
/// see SkinnedBody::joint_rest; empty: the skeleton's rest joints): a body
/// whose proportions differ from the capture subject's (MakeHuman under a
/// CMU skeleton: up to 20 cm at the neck and arms) is fitted about its own
/// limbs, and the capsules must then be posed with proportioned_pose.
void fit_capsule_radii(CapsuleRig& rig, const Skeleton& skeleton, const Eigen::MatrixX3d& rest_vertices,
                       const std::vector<std::vector<std::pair<int, double>>>& bone_weights,
                       const std::vector<Eigen::Vector3d>& joint_rest = {});

/// Shrinks every bone capsule that a garment starts inside of until the
/// garment is clear of it: `points` (#P x 3, metres) are the garment's
/// vertices where it starts, `pose` the rig's pose then (as posed for
/// collision, e.g. proportioned_pose of the garment's pose). A capsule's
/// two radii shrink by one factor, the largest that leaves every point at
/// least the rig's thickness outside, but not below `floor` of their size
/// (a point on the bone itself would remove the capsule). Capsules fitted
/// to a body sit partly outside it wherever it is narrower than a linear
/// taper (the waist, the small of the back), and a garment modelled on
/// the body would start inside them. Returns how many capsules shrank.
int clear_capsules_of(CapsuleRig& rig, const Pose& pose, const Eigen::MatrixX3d& points, double floor = 0.25);

/// Bridges between the legs for a skirt or dress (a garment with one tube
/// around both legs): a real body's thighs meet, a capsule rig's leave a
/// gap into which the cloth folds and where scissoring thighs trap it. Adds
/// a bridge at every half bone from mid-thigh down to `reach` (in bones
/// from the hips: 1 = the knees, 2 = the ankles, so a knee-length skirt
/// needs 1 and a long dress 2), each as thick as the thinner leg capsule
/// there. The legs are found by their CMU names (LeftUpLeg -> LeftLeg ->
/// LeftFoot and Right...); ArgumentError names what is missing.
void add_leg_bridges(CapsuleRig& rig, const Skeleton& skeleton, double reach = 1.0);

/// Analytic capsule colliders of the rig in a pose: its bones, then its bridges.
std::vector<Collider> posed_capsules(const CapsuleRig& rig, const Pose& pose);

/// A collision scene that follows a rig: call pose() before each step. It
/// remembers the previous pose, so cloth is kept on the side of each
/// capsule it was on when the step began (see resolve_point).
class CapsuleBody : public CollisionScene {
 public:
  CapsuleBody(CapsuleRig rig, const Skeleton& skeleton);
  void pose(const Pose& pose);
  /// With a memo, later collision rounds of the same pose test only the
  /// capsules that were near the point when the memo was made: the same
  /// answers while the point stays near there.
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                 ContactMemo* memo = nullptr, SurfaceNearby* nearby = nullptr) const override;
  double penetration(const Eigen::Vector3d& p) const override;
  double depth(const Eigen::Vector3d& p) const override;
  bool empty() const override { return colliders_.empty(); }
  const std::vector<Collider>& colliders() const { return colliders_; }
  const CapsuleRig& rig() const { return rig_; }
  /// True when p is certainly more than `reach` (metres, >= 0) outside
  /// every thickened capsule of the current pose: resolve then moves
  /// nothing, and nearest_surface(colliders(), p, reach) finds no surface
  /// within reach. One box test per capsule, no square root.
  bool beyond(const Eigen::Vector3d& p, double reach) const;

 private:
  double resolve_with_memo(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction,
                           ContactMemo* memo) const;
  void update_boxes();
  CapsuleRig rig_;
  std::vector<Collider> colliders_;
  std::vector<Collider> previous_;  ///< the capsules before the last pose()
  /// Per collider, the box of its thickened capsule in the current pose
  /// (lo x y z, hi x y z); a collider that is not a capsule gets an
  /// infinite box and is never beyond.
  std::vector<std::array<double, 6>> boxes_;
  bool posed_ = false;              ///< false until the first pose(): no motion to carry yet
  unsigned long long serial_ = 0;   ///< counts pose() calls: a memo is good for the pose it was made in
};

}  // namespace mrcloth
