#pragma once
// Skeletons and motions (BVH), and forward kinematics. Lengths in metres
// after the reader's scale; rotations are Euler angles in degrees in the
// file, applied in the file's channel order (BVH convention: the channel
// listed first is the outermost rotation, R = R_first * R_second * R_third).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace mrcloth {

enum class Channel { x_position, y_position, z_position, x_rotation, y_rotation, z_rotation };

/// Whether a channel moves its joint (rather than turning it).
inline bool is_position(Channel c) {
  return c == Channel::x_position || c == Channel::y_position || c == Channel::z_position;
}

struct Joint {
  std::string name;                 ///< unique; an End Site is named "<parent>_end"
  int parent = -1;                  ///< index of the parent joint, -1 for a root
  Eigen::Vector3d offset{0, 0, 0};  ///< rest offset from the parent, metres
  std::vector<Channel> channels;    ///< in file order; empty for an End Site
  int first_channel = 0;            ///< column of its first channel in Motion::frames
  bool end_site = false;
};

/// Joints in file order: a parent always precedes its children.
struct Skeleton {
  std::vector<Joint> joints;
  /// Index of the joint with this name, -1 if none.
  int find(const std::string& name) const;
  /// Number of channels over all joints.
  int channel_count() const;
};

struct Motion {
  Skeleton skeleton;
  double frame_time = 1.0 / 120.0;  ///< seconds per frame, > 0
  /// #frames x channel_count, angles in degrees, positions in metres as
  /// displacements from the joint's offset (read_bvh and write_bvh convert).
  Eigen::MatrixXd frames;
  double duration() const { return frames.rows() > 1 ? (frames.rows() - 1) * frame_time : 0.0; }
};

/// What a joint's position channels hold in a BVH file.
enum class PositionChannels {
  /// The joint's translation from its parent; its OFFSET is only where it
  /// rests. Blender, MotionBuilder and three.js read and write this.
  absolute,
  /// A displacement added to the OFFSET (some converters write this).
  relative,
};

struct BvhReadOptions {
  double scale = 1.0;             ///< metres per file unit (CMU: 0.056444; centimetres: 0.01)
  bool skip_first_frame = false;  ///< drop frame 0 (every CMU clip starts with an added T-pose)
  /// The two readings differ only where a joint with position channels has
  /// a non-zero OFFSET (a CMU clip's root has none: both read it alike).
  PositionChannels position_channels = PositionChannels::absolute;
};

/// Reads a BVH file (any channel order and subset per joint, End Sites,
/// the MOTION block). Throws InputError "<file>:<line>: <problem>; expected
/// <what>" for unbalanced braces, a channel count that does not match the
/// data, non-numeric values, truncated motion, or a frame time <= 0.
Motion read_bvh(const std::string& path, const BvhReadOptions& options = {});

/// Multiplies every length of the motion (offsets, position channels) by
/// `scale`: the same numbers as reading its file with that scale.
void scale_motion(Motion& motion, double scale);

/// Writes a motion as BVH (offsets and positions divided by `scale`), atomically,
/// its position channels absolute (offset plus displacement): read back with
/// the default options it gives the same motion.
void write_bvh(const std::string& path, const Motion& motion, double scale = 1.0);

/// Global transform of every joint (index as in the skeleton).
struct Pose {
  std::vector<Eigen::Isometry3d> global;
  Eigen::Vector3d position(int joint) const { return global[joint].translation(); }
};

/// The rest pose: every rotation 0, every joint at its offset (for CMU: the T-pose).
Pose rest_pose(const Skeleton& skeleton);

/// The pose of frame f exactly.
Pose frame_pose(const Motion& motion, int frame);

/// The pose at a time in seconds (frame 0 at t = 0), clamped to the clip:
/// root positions interpolated linearly, every joint's local rotation by
/// quaternion slerp between the two nearest frames.
Pose pose_at(const Motion& motion, double time);

/// Blends two poses of the same skeleton joint by joint (slerp on local
/// rotations, lerp on root translation) with weight t in [0, 1]; for
/// pre-rolls from the rest pose to a first frame.
Pose blend_poses(const Skeleton& skeleton, const Pose& a, const Pose& b, double t);

/// `pose` on a body with its own bone lengths: every joint keeps its
/// global rotation, and the joints are carried down the chain from
/// `joint_rest` (per joint, where the body's joint is in the rest pose,
/// metres; empty: the skeleton's own) exactly as skin() carries a skinned
/// body's pivots, so capsules posed by it follow that body's limbs. In the
/// rest pose the joints are at joint_rest.
Pose proportioned_pose(const Skeleton& skeleton, const std::vector<Eigen::Vector3d>& joint_rest, const Pose& pose);

}  // namespace mrcloth
