#pragma once
// A capsule body: one tapered capsule per bone of a skeleton, posed by FK.
#include "collision_scene.h"
#include "skeleton.h"

#include <map>
#include <string>
#include <vector>

namespace mrcloth {

struct BoneCapsule {
  int joint = -1;          ///< the bone runs from this joint ...
  int child = -1;          ///< ... to this one (a child joint or End Site)
  double radius_head = 0;  ///< radius at `joint`, metres
  double radius_tail = 0;  ///< radius at `child`, metres
};

struct CapsuleRigOptions {
  double thickness = 0.004;  ///< cloth keeps this far from the capsules, metres
  double friction = 0.3;     ///< Coulomb coefficient
  /// Radius overrides by joint name, metres (head, tail), applied after defaults/fitting.
  std::map<std::string, std::pair<double, double>> radii;
};

struct CapsuleRig {
  std::vector<BoneCapsule> bones;
  double thickness = 0.004;
  double friction = 0.3;
};

/// Capsules along the bones of `skeleton` with default radii for the CMU
/// joint names (legs, spine, arms, neck, head; hands, fingers and toes get
/// none), scaled by the skeleton's height relative to a 1.65 m figure.
/// Bones of unknown names get a radius proportional to their length.
CapsuleRig make_capsule_rig(const Skeleton& skeleton, const CapsuleRigOptions& options = {});

/// Refits every capsule's radii to a body mesh in the rig's rest pose:
/// rest_vertices (#V x 3, metres, in the skeleton's rest space) and per
/// vertex its dominant bone weights (bone_weights[v] = list of (joint, w)):
/// a capsule's radius at each end is a robust (90th percentile) distance to
/// its axis of the vertices that the bone dominates near that end.
void fit_capsule_radii(CapsuleRig& rig, const Skeleton& skeleton, const Eigen::MatrixX3d& rest_vertices,
                       const std::vector<std::vector<std::pair<int, double>>>& bone_weights);

/// Analytic capsule colliders of the rig in a pose.
std::vector<Collider> posed_capsules(const CapsuleRig& rig, const Pose& pose);

/// A collision scene that follows a rig: call pose() before each step.
class CapsuleBody : public CollisionScene {
 public:
  CapsuleBody(CapsuleRig rig, const Skeleton& skeleton);
  void pose(const Pose& pose);
  double resolve(const Eigen::Vector3d& previous, Eigen::Vector3d& position) const override;
  double penetration(const Eigen::Vector3d& p) const override;
  bool empty() const override { return colliders_.empty(); }
  const std::vector<Collider>& colliders() const { return colliders_; }

 private:
  CapsuleRig rig_;
  std::vector<Collider> colliders_;
};

}  // namespace mrcloth
