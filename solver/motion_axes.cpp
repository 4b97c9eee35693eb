#include "motion_axes.h"

#include "mesh_ops/errors.h"

#include <cmath>
#include <initializer_list>
#include <string>

namespace mrcloth {
namespace {

/// The turn's matrix: row k = sign[k] * unit vector of axis[k].
Eigen::Matrix3d matrix_of(const AxisTurn& turn) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) m(k, turn.axis[static_cast<std::size_t>(k)]) = turn.sign[static_cast<std::size_t>(k)];
  return m;
}

void check_turn(const AxisTurn& turn) {
  bool seen[3] = {false, false, false};
  for (int k = 0; k < 3; ++k) {
    const int a = turn.axis[static_cast<std::size_t>(k)];
    const double s = turn.sign[static_cast<std::size_t>(k)];
    if (a < 0 || a > 2 || seen[a] || !(s == 1.0 || s == -1.0))
      throw ArgumentError("turn_axes: the turn is not a signed permutation of x, y and z");
    seen[a] = true;
  }
  if (!(matrix_of(turn).determinant() > 0.0))
    throw ArgumentError("turn_axes: the turn mirrors the figure; expected a rotation (determinant +1)");
}

/// The signed axis nearest to v (its largest component): {axis, sign}.
std::pair<int, double> nearest_axis(const Eigen::Vector3d& v) {
  int a = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(v(k)) > std::abs(v(a))) a = k;
  return {a, v(a) < 0.0 ? -1.0 : 1.0};
}

/// Where the old axis `a` goes: the new axis k with axis[k] == a, and its sign.
std::pair<int, double> image_of(const AxisTurn& turn, int a) {
  for (int k = 0; k < 3; ++k)
    if (turn.axis[static_cast<std::size_t>(k)] == a) return {k, turn.sign[static_cast<std::size_t>(k)]};
  return {a, 1.0};  // unreachable for a checked turn
}

Channel position_channel(int axis) {
  return axis == 0 ? Channel::x_position : axis == 1 ? Channel::y_position : Channel::z_position;
}
Channel rotation_channel(int axis) {
  return axis == 0 ? Channel::x_rotation : axis == 1 ? Channel::y_rotation : Channel::z_rotation;
}

}  // namespace

bool AxisTurn::identity() const {
  return axis == std::array<int, 3>{0, 1, 2} && sign == std::array<double, 3>{1.0, 1.0, 1.0};
}

AxisTurn AxisTurn::inverse() const {
  AxisTurn back;
  for (int k = 0; k < 3; ++k) {
    back.axis[static_cast<std::size_t>(axis[static_cast<std::size_t>(k)])] = k;
    back.sign[static_cast<std::size_t>(axis[static_cast<std::size_t>(k)])] = sign[static_cast<std::size_t>(k)];
  }
  return back;
}

std::string AxisTurn::describe() const {
  if (identity()) return "";
  const char* names = "xyz";
  std::string out;
  for (int k = 0; k < 3; ++k) {
    if (k > 0) out += ", ";
    out += std::string(1, names[k]) + " = " + (sign[static_cast<std::size_t>(k)] < 0.0 ? "-" : "") +
           names[axis[static_cast<std::size_t>(k)]];
  }
  return out;
}

AxisTurn upright_turn(const Skeleton& skeleton, std::string* undecided) {
  // The first of each list the skeleton has (a clip renamed by hand may
  // lack the head, or the hips' leg joints).
  const auto first_of = [&](std::initializer_list<const char*> names) {
    for (const char* name : names)
      if (const int j = skeleton.find(name); j >= 0) return j;
    return -1;
  };
  const int hips = skeleton.find("Hips");
  const int top = first_of({"Head", "Neck1", "Neck", "Spine2", "Spine1", "Spine"});
  const int left = first_of({"LeftUpLeg", "LeftShoulder", "LeftArm", "LeftFoot"});
  const int right = left < 0 ? -1
                             : skeleton.find(std::string("Right") + skeleton.joints[static_cast<std::size_t>(left)].name.substr(4));
  const auto refuse = [&](const std::string& why) {
    if (undecided) *undecided = why;
    return AxisTurn{};
  };
  if (hips < 0 || top < 0 || left < 0 || right < 0)
    return refuse(std::string("it has no ") +
                  (hips < 0 ? "Hips" : top < 0 ? "Head, Neck or Spine" : "left and right legs, shoulders, arms or feet") +
                  " by CMU names");
  const Pose rest = rest_pose(skeleton);
  const Eigen::Vector3d up = rest.position(top) - rest.position(hips);
  const Eigen::Vector3d across = rest.position(left) - rest.position(right);
  if (!(up.norm() > 0.0) || !(across.norm() > 0.0)) return refuse("its rest pose puts those joints at one point");
  const auto [up_axis, up_sign] = nearest_axis(up);
  const auto [left_axis, left_sign] = nearest_axis(across);
  if (up_axis == left_axis) return refuse("its up and its left snap to the same axis");
  if (undecided) undecided->clear();
  AxisTurn turn;
  turn.axis = {left_axis, up_axis, 3 - left_axis - up_axis};
  turn.sign = {left_sign, up_sign, 1.0};
  if (matrix_of(turn).determinant() < 0.0) turn.sign[2] = -1.0;  // z = x cross y
  return turn;
}

void turn_axes(Motion& motion, const AxisTurn& turn) {
  check_turn(turn);
  if (turn.identity()) return;
  std::vector<double> flip(static_cast<std::size_t>(motion.frames.cols()), 1.0);
  for (Joint& joint : motion.skeleton.joints) {
    const Eigen::Vector3d old = joint.offset;
    for (int k = 0; k < 3; ++k)
      joint.offset(k) = turn.sign[static_cast<std::size_t>(k)] * old(turn.axis[static_cast<std::size_t>(k)]);
    for (std::size_t c = 0; c < joint.channels.size(); ++c) {
      Channel& channel = joint.channels[c];
      const bool position = is_position(channel);
      const int old_axis = channel == Channel::x_position || channel == Channel::x_rotation   ? 0
                           : channel == Channel::y_position || channel == Channel::y_rotation ? 1
                                                                                                : 2;
      const auto [new_axis, sign] = image_of(turn, old_axis);
      channel = position ? position_channel(new_axis) : rotation_channel(new_axis);
      const auto column = static_cast<std::size_t>(joint.first_channel) + c;
      if (column < flip.size()) flip[column] = sign;
    }
  }
  for (Eigen::Index c = 0; c < motion.frames.cols(); ++c)
    if (flip[static_cast<std::size_t>(c)] < 0.0) motion.frames.col(c) = -motion.frames.col(c);
}

}  // namespace mrcloth
