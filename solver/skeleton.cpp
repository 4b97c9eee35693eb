// Skeletons and forward kinematics: Euler channels to local transforms,
// local transforms to global ones, interpolation and blending of poses.
#include "skeleton.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mesh_ops/errors.h"

namespace mrcloth {

int Skeleton::find(const std::string& name) const {
  for (std::size_t j = 0; j < joints.size(); ++j)
    if (joints[j].name == name) return static_cast<int>(j);
  return -1;
}

int Skeleton::channel_count() const {
  int count = 0;
  for (const Joint& joint : joints) count += static_cast<int>(joint.channels.size());
  return count;
}

namespace {

constexpr double kDegree = M_PI / 180.0;

/// A joint's local transform as a rotation and a translation (kept apart so
/// rotations can be slerped and translations lerped).
struct Local {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

void check_skeleton(const Skeleton& skeleton, const char* caller) {
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent < -1 || parent >= static_cast<int>(j))
      throw ArgumentError(std::string(caller) + ": joint " + std::to_string(j) + " '" + skeleton.joints[j].name +
                          "' has parent " + std::to_string(parent) + ", not an earlier joint");
  }
}

void check_motion(const Motion& motion, const char* caller) {
  check_skeleton(motion.skeleton, caller);
  const Eigen::Index columns = motion.frames.cols();
  if (columns != motion.skeleton.channel_count())
    throw ArgumentError(std::string(caller) + ": frames has " + std::to_string(columns) +
                        " columns but the skeleton has " + std::to_string(motion.skeleton.channel_count()) +
                        " channels");
  for (const Joint& joint : motion.skeleton.joints)
    if (joint.first_channel < 0 || joint.first_channel + static_cast<Eigen::Index>(joint.channels.size()) > columns)
      throw ArgumentError(std::string(caller) + ": joint '" + joint.name + "' has channels outside the frame columns");
  if (motion.frames.rows() < 1) throw ArgumentError(std::string(caller) + ": the motion has no frame");
}

/// The local transform of `joint` for one frame's channel values (`row`,
/// all channels of the skeleton): translation = offset + position channels,
/// rotation = R(first listed) * R(second) * R(third), angles in degrees.
Local local_transform(const Joint& joint, const Eigen::RowVectorXd& row) {
  Local local;
  local.translation = joint.offset;
  for (std::size_t k = 0; k < joint.channels.size(); ++k) {
    const double value = row[joint.first_channel + static_cast<Eigen::Index>(k)];
    switch (joint.channels[k]) {
      case Channel::x_position:
        local.translation.x() += value;
        break;
      case Channel::y_position:
        local.translation.y() += value;
        break;
      case Channel::z_position:
        local.translation.z() += value;
        break;
      case Channel::x_rotation:
        local.rotation = local.rotation * Eigen::AngleAxisd(value * kDegree, Eigen::Vector3d::UnitX());
        break;
      case Channel::y_rotation:
        local.rotation = local.rotation * Eigen::AngleAxisd(value * kDegree, Eigen::Vector3d::UnitY());
        break;
      case Channel::z_rotation:
        local.rotation = local.rotation * Eigen::AngleAxisd(value * kDegree, Eigen::Vector3d::UnitZ());
        break;
    }
  }
  return local;
}

Eigen::Isometry3d to_isometry(const Local& local) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = local.rotation.normalized().toRotationMatrix();
  transform.translation() = local.translation;
  return transform;
}

/// Global = parent global * local, parents first.
Pose forward_kinematics(const Skeleton& skeleton, const std::vector<Local>& locals) {
  Pose pose;
  pose.global.resize(skeleton.joints.size());
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    const Eigen::Isometry3d local = to_isometry(locals[j]);
    pose.global[j] = parent < 0 ? local : Eigen::Isometry3d(pose.global[parent] * local);
  }
  return pose;
}

std::vector<Local> frame_locals(const Motion& motion, Eigen::Index frame) {
  const auto& joints = motion.skeleton.joints;
  const Eigen::RowVectorXd row = motion.frames.row(frame);
  std::vector<Local> locals(joints.size());
  for (std::size_t j = 0; j < joints.size(); ++j) locals[j] = local_transform(joints[j], row);
  return locals;
}

/// slerp of rotations, lerp of translations, joint by joint.
std::vector<Local> interpolate(const std::vector<Local>& a, const std::vector<Local>& b, double t) {
  std::vector<Local> result(a.size());
  for (std::size_t j = 0; j < a.size(); ++j) {
    result[j].rotation = a[j].rotation.slerp(t, b[j].rotation);
    result[j].translation = (1.0 - t) * a[j].translation + t * b[j].translation;
  }
  return result;
}

/// Locals recovered from globals: local = parent_global^-1 * global.
std::vector<Local> locals_of(const Skeleton& skeleton, const Pose& pose) {
  std::vector<Local> locals(skeleton.joints.size());
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    const Eigen::Isometry3d local =
        parent < 0 ? pose.global[j] : Eigen::Isometry3d(pose.global[parent].inverse() * pose.global[j]);
    locals[j].rotation = Eigen::Quaterniond(local.linear()).normalized();
    locals[j].translation = local.translation();
  }
  return locals;
}

}  // namespace

void scale_motion(Motion& motion, double scale) {
  for (Joint& joint : motion.skeleton.joints) {
    joint.offset *= scale;
    for (std::size_t k = 0; k < joint.channels.size(); ++k) {
      const Channel c = joint.channels[k];
      if (is_position(c))
        motion.frames.col(joint.first_channel + static_cast<Eigen::Index>(k)) *= scale;
    }
  }
}

Pose rest_pose(const Skeleton& skeleton) {
  check_skeleton(skeleton, "rest_pose");
  std::vector<Local> locals(skeleton.joints.size());
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) locals[j].translation = skeleton.joints[j].offset;
  return forward_kinematics(skeleton, locals);
}

Pose frame_pose(const Motion& motion, int frame) {
  check_motion(motion, "frame_pose");
  if (frame < 0 || frame >= motion.frames.rows())
    throw ArgumentError("frame_pose: frame " + std::to_string(frame) + " outside 0.." +
                        std::to_string(motion.frames.rows() - 1));
  return forward_kinematics(motion.skeleton, frame_locals(motion, frame));
}

Pose pose_at(const Motion& motion, double time) {
  check_motion(motion, "pose_at");
  if (!std::isfinite(time)) throw ArgumentError("pose_at: the time must be finite");
  if (!(motion.frame_time > 0.0)) throw ArgumentError("pose_at: the motion's frame_time must be positive");
  const Eigen::Index last = motion.frames.rows() - 1;
  const double frame = std::clamp(time / motion.frame_time, 0.0, static_cast<double>(last));
  const Eigen::Index before = std::min(static_cast<Eigen::Index>(std::floor(frame)), last);
  const double w = frame - static_cast<double>(before);
  if (w == 0.0 || before == last) return forward_kinematics(motion.skeleton, frame_locals(motion, before));
  return forward_kinematics(motion.skeleton,
                            interpolate(frame_locals(motion, before), frame_locals(motion, before + 1), w));
}

Pose blend_poses(const Skeleton& skeleton, const Pose& a, const Pose& b, double t) {
  check_skeleton(skeleton, "blend_poses");
  const std::size_t n = skeleton.joints.size();
  if (a.global.size() != n || b.global.size() != n)
    throw ArgumentError("blend_poses: poses of " + std::to_string(a.global.size()) + " and " +
                        std::to_string(b.global.size()) + " joints for a skeleton of " + std::to_string(n));
  if (!(t >= 0.0 && t <= 1.0)) throw ArgumentError("blend_poses: t = " + std::to_string(t) + " outside [0, 1]");
  return forward_kinematics(skeleton, interpolate(locals_of(skeleton, a), locals_of(skeleton, b), t));
}

Pose proportioned_pose(const Skeleton& skeleton, const std::vector<Eigen::Vector3d>& joint_rest, const Pose& pose) {
  check_skeleton(skeleton, "proportioned_pose");
  const std::size_t n = skeleton.joints.size();
  if (pose.global.size() != n)
    throw ArgumentError("proportioned_pose: the pose has " + std::to_string(pose.global.size()) + " joints; expected " +
                        std::to_string(n) + " (the skeleton's)");
  if (joint_rest.empty()) return pose;
  if (joint_rest.size() != n)
    throw ArgumentError("proportioned_pose: " + std::to_string(joint_rest.size()) + " rest joints; expected " +
                        std::to_string(n) + " (the skeleton's)");
  const Pose rest = rest_pose(skeleton);
  Pose out = pose;
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Matrix3d turn = pose.global[j].linear() * rest.global[j].linear().transpose();
    const int parent = skeleton.joints[j].parent;
    if (parent < 0) {
      out.global[j].translation() =
          pose.position(static_cast<int>(j)) + turn * (joint_rest[j] - rest.position(static_cast<int>(j)));
    } else {
      const auto p = static_cast<std::size_t>(parent);
      const Eigen::Matrix3d parent_turn = pose.global[p].linear() * rest.global[p].linear().transpose();
      out.global[j].translation() = out.position(parent) + parent_turn * (joint_rest[j] - joint_rest[p]);
    }
  }
  return out;
}

}  // namespace mrcloth
