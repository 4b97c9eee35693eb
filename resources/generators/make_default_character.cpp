// make_default_character: writes mrcloth's embedded default character, a
// procedurally proportioned mannequin of a standing 1.65 m woman with the
// CMU skeleton (joint names, hierarchy and channels of the CMU
// "MotionBuilder-friendly" BVH files), and three procedural motions for it.
//
//   make_default_character <output-folder> [--report]
//
// writes, into the folder:
//   mannequin.bvh      the skeleton, one frame: the T-pose standing on the ground
//   walk_instance.bvh  a straight walk, 1.2 m/s, step 0.65 m, 8 s (the instance motion)
//   walk_new.bvh       a similar new walk, 1.0 m/s, step 0.58 m, 8 s
//   squat.bvh          two deep squats, 7 s
// --report prints a summary of every motion (speeds, joint ranges, ground contact).
//
// The committed resources/characters/*.bvh are this program's output (CMake
// target `regenerate_default_character`); a test regenerates them and
// requires the bytes to match, so change the parameters here, regenerate,
// and commit both together.
//
// Conventions of the files (see also resources/characters/README.md):
//  - lengths in METRES: read them with BvhReadOptions::scale = 1.0 (the
//    default), not CMU's 0.056444;
//  - Y up, facing and walking along +Z, ground at y = 0, the figure's left is +X;
//  - root OFFSET 0 like CMU: all-zero channels put the Hips at the origin;
//  - frame 0 of every file is a T-pose (every rotation 0) standing on the
//    ground at the root's x, z of frame 1, like the T-pose CMU adds to every
//    clip: loaders drop it with skip_first_frame (or use it to ramp the
//    cloth in); the default garments are modelled on this T-pose;
//  - frame time 1/120 s; channels: root Xposition Yposition Zposition
//    Zrotation Yrotation Xrotation, all others Zrotation Yrotation Xrotation
//    (R = Rz Ry Rx, degrees).
//
// The mannequin matches the default garments: the Hips joint is at
// y = 0.94 (between the skirt's waist, y = 1.02, and hips, y = 0.90), the
// hip joints at x = +-0.09, y = 0.865, inside the skirt's hip ellipse.
//
// The gait: the feet are placed on the ground, planted through stance
// (heel strike rolling onto the flat foot, heel rise about the ball, toe
// roll about the toe tip) and carried forward in swing; the pelvis moves
// along +Z at the walking speed with a vertical bob, side sway, rotation and
// list; the root height is lowered wherever a leg would otherwise have to
// stretch beyond its length, so the stance foot stays on the ground; the legs
// follow by two-bone inverse kinematics (knees bending forward), which gives
// the stance and swing knee flexion; the arms swing opposite to the legs.
//
// Standard library and Eigen only, on purpose: the character must not
// depend on the code it is used to test (mrcloth's BVH reader and writer).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "generated_file.h"

namespace {

using mrcloth::generators::write_atomically;

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;
constexpr double kFrameRate = 120.0;

double radians(double degrees) { return degrees * kPi / 180.0; }
double degrees(double radians) { return radians * 180.0 / kPi; }

Matrix3d rot_x(double degrees_) { return Eigen::AngleAxisd(radians(degrees_), Vector3d::UnitX()).toRotationMatrix(); }
Matrix3d rot_y(double degrees_) { return Eigen::AngleAxisd(radians(degrees_), Vector3d::UnitY()).toRotationMatrix(); }
Matrix3d rot_z(double degrees_) { return Eigen::AngleAxisd(radians(degrees_), Vector3d::UnitZ()).toRotationMatrix(); }

/// 0 at x <= 0, 1 at x >= 1, C1 in between.
double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

double lerp(double a, double b, double t) { return a + (b - a) * t; }

/// Fractional part in [0, 1).
double fraction(double x) { return x - std::floor(x); }

// ---------------------------------------------------------------------------
// The skeleton

/// Rest-pose (T-pose) dimensions of the mannequin, metres. Heights are of
/// the joints when standing (Hips at hips_height, every rotation 0).
struct Proportions {
  double hips_height = 0.94;         ///< Hips joint (root)
  double hip_joint_x = 0.09;         ///< LeftUpLeg at +x, RightUpLeg at -x
  double hip_joint_drop = 0.075;     ///< hip joints below the Hips joint
  double knee_x = 0.083;             ///< legs converge slightly towards the feet
  double ankle_x = 0.075;
  double ankle_height = 0.075;       ///< LeftFoot joint
  double ball_forward = 0.13;        ///< LeftToeBase ahead of the ankle
  double ball_height = 0.025;        ///< LeftToeBase joint
  double toe_forward = 0.06;         ///< toe tip (End Site) ahead of the ball, on the ground
  double heel_back = 0.05;           ///< heel contact behind the ankle (on the ground)
  double spine_rise = 0.12;          ///< Spine above the Hips (y 1.06, just above the waist)
  double spine1_rise = 0.16;         ///< Spine1 (chest) above Spine (y 1.22)
  double neck1_rise = 0.19;          ///< Neck1 (base of the neck) above Neck = Spine1 (y 1.41)
  double head_rise = 0.09;           ///< Head (base of the skull) above Neck1 (y 1.50)
  double head_top = 0.15;            ///< top of the head (End Site) above Head: y 1.65
  double shoulder_x = 0.17;          ///< LeftArm (shoulder joint) at +x
  double shoulder_rise = 0.15;       ///< shoulder joints above Spine1 (y 1.37)
  double upper_arm = 0.28;
  double forearm = 0.23;
  double finger_base = 0.08;         ///< LeftHandIndex1 from the wrist
  double finger_tip = 0.065;         ///< its End Site; arm span 2 x 0.825 = 1.65 m
  double thumb = 0.045;              ///< thumb End Site offset along x and z
};

struct Joint {
  std::string name;
  int parent = -1;
  Vector3d offset{0, 0, 0};
  bool end_site = false;
};

/// Indices of the joints the motions drive.
struct Rig {
  std::vector<Joint> joints;
  int hips, lowerback, spine, spine1, neck, neck1, head;
  std::array<int, 2> hipjoint, upleg, leg, foot, toe, shoulder, arm, forearm, hand;  // [0] left, [1] right
};

int add_joint(std::vector<Joint>& joints, const std::string& name, int parent, const Vector3d& offset,
              bool end_site = false) {
  joints.push_back({name, parent, offset, end_site});
  return static_cast<int>(joints.size()) - 1;
}

/// The CMU hierarchy, in the CMU files' order, with the mannequin's offsets.
/// side = +1 for the left (+x), -1 for the right.
Rig make_rig(const Proportions& p) {
  Rig rig;
  auto& j = rig.joints;
  rig.hips = add_joint(j, "Hips", -1, Vector3d::Zero());
  for (int s = 0; s < 2; ++s) {
    const double side = s == 0 ? 1.0 : -1.0;
    const std::string lr = s == 0 ? "Left" : "Right";
    const double thigh_y = p.hips_height - p.hip_joint_drop;
    const double knee_y = 0.5 * (thigh_y + p.ankle_height);  // thigh and shank equally long
    rig.hipjoint[s] = add_joint(j, s == 0 ? "LHipJoint" : "RHipJoint", rig.hips, Vector3d::Zero());
    rig.upleg[s] = add_joint(j, lr + "UpLeg", rig.hipjoint[s], Vector3d(side * p.hip_joint_x, -p.hip_joint_drop, 0));
    rig.leg[s] = add_joint(j, lr + "Leg", rig.upleg[s], Vector3d(side * (p.knee_x - p.hip_joint_x), knee_y - thigh_y, 0));
    rig.foot[s] = add_joint(j, lr + "Foot", rig.leg[s], Vector3d(side * (p.ankle_x - p.knee_x), p.ankle_height - knee_y, 0));
    rig.toe[s] = add_joint(j, lr + "ToeBase", rig.foot[s], Vector3d(0, p.ball_height - p.ankle_height, p.ball_forward));
    add_joint(j, lr + "ToeBase_end", rig.toe[s], Vector3d(0, -p.ball_height, p.toe_forward), true);
  }
  rig.lowerback = add_joint(j, "LowerBack", rig.hips, Vector3d::Zero());
  rig.spine = add_joint(j, "Spine", rig.lowerback, Vector3d(0, p.spine_rise, 0));
  rig.spine1 = add_joint(j, "Spine1", rig.spine, Vector3d(0, p.spine1_rise, 0));
  rig.neck = add_joint(j, "Neck", rig.spine1, Vector3d::Zero());
  rig.neck1 = add_joint(j, "Neck1", rig.neck, Vector3d(0, p.neck1_rise, 0));
  rig.head = add_joint(j, "Head", rig.neck1, Vector3d(0, p.head_rise, 0));
  add_joint(j, "Head_end", rig.head, Vector3d(0, p.head_top, 0), true);
  for (int s = 0; s < 2; ++s) {
    const double side = s == 0 ? 1.0 : -1.0;
    const std::string lr = s == 0 ? "Left" : "Right";
    rig.shoulder[s] = add_joint(j, lr + "Shoulder", rig.spine1, Vector3d::Zero());
    rig.arm[s] = add_joint(j, lr + "Arm", rig.shoulder[s], Vector3d(side * p.shoulder_x, p.shoulder_rise, 0));
    rig.forearm[s] = add_joint(j, lr + "ForeArm", rig.arm[s], Vector3d(side * p.upper_arm, 0, 0));
    rig.hand[s] = add_joint(j, lr + "Hand", rig.forearm[s], Vector3d(side * p.forearm, 0, 0));
    const int finger_base = add_joint(j, lr + "FingerBase", rig.hand[s], Vector3d::Zero());
    const int index = add_joint(j, lr + "HandIndex1", finger_base, Vector3d(side * p.finger_base, 0, 0));
    add_joint(j, lr + "HandIndex1_end", index, Vector3d(side * p.finger_tip, 0, 0), true);
    const int thumb = add_joint(j, s == 0 ? "LThumb" : "RThumb", rig.hand[s], Vector3d::Zero());
    add_joint(j, std::string(s == 0 ? "LThumb" : "RThumb") + "_end", thumb, Vector3d(side * p.thumb, 0, p.thumb), true);
  }
  return rig;
}

/// One frame: the root position and every joint's local rotation.
struct Frame {
  Vector3d root{0, 0, 0};
  std::vector<Matrix3d> local;
};

Frame identity_frame(const Rig& rig) {
  Frame frame;
  frame.local.assign(rig.joints.size(), Matrix3d::Identity());
  return frame;
}

/// Global positions and orientations (BVH: global = parent * T(offset) * R).
struct Posed {
  std::vector<Vector3d> position;
  std::vector<Matrix3d> rotation;
};

Posed forward_kinematics(const Rig& rig, const Frame& frame) {
  Posed posed;
  const std::size_t n = rig.joints.size();
  posed.position.resize(n);
  posed.rotation.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Joint& joint = rig.joints[i];
    if (joint.parent < 0) {
      posed.position[i] = frame.root + joint.offset;
      posed.rotation[i] = frame.local[i];
    } else {
      const auto p = static_cast<std::size_t>(joint.parent);
      posed.position[i] = posed.position[p] + posed.rotation[p] * joint.offset;
      posed.rotation[i] = posed.rotation[p] * frame.local[i];
    }
  }
  return posed;
}

/// Euler angles (degrees) of R = Rz(z) Ry(y) Rx(x): the BVH channel order
/// Zrotation Yrotation Xrotation. y in [-90, 90]; continuous near identity.
Vector3d zyx_degrees(const Matrix3d& r) {
  const double y = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double z = std::atan2(r(1, 0), r(0, 0));
  const double x = std::atan2(r(2, 1), r(2, 2));
  return Vector3d(degrees(z), degrees(y), degrees(x));
}

// ---------------------------------------------------------------------------
// Building blocks of the motions

/// Orthonormal frame of a limb segment: axis (along the bone), forward
/// (the direction the joint below bends away from) and their cross product.
Matrix3d segment_frame(const Vector3d& axis, const Vector3d& forward_hint) {
  const Vector3d a = axis.normalized();
  const Vector3d f = (forward_hint - forward_hint.dot(a) * a).normalized();
  Matrix3d m;
  m.col(0) = a;
  m.col(1) = f;
  m.col(2) = a.cross(f);
  return m;
}

/// A leg posed by two-bone IK: hip at `hip`, ankle target `ankle`, knee
/// bending towards `pole`. Returns world orientations of thigh and shank.
struct LegPose {
  Matrix3d thigh, shank;
  Vector3d ankle;  ///< where the ankle ends up (the target, unless out of reach)
};

LegPose solve_leg(const Rig& rig, int side, const Vector3d& hip, const Vector3d& ankle, const Vector3d& pole) {
  const Vector3d thigh_rest = rig.joints[rig.leg[side]].offset;
  const Vector3d shank_rest = rig.joints[rig.foot[side]].offset;
  const double l1 = thigh_rest.norm(), l2 = shank_rest.norm();
  const Vector3d to_ankle = ankle - hip;
  const Vector3d u = to_ankle.normalized();
  const double d = std::clamp(to_ankle.norm(), std::abs(l1 - l2) + 1e-6, l1 + l2 - 1e-9);
  const double along = (l1 * l1 - l2 * l2 + d * d) / (2.0 * d);
  const double across = std::sqrt(std::max(0.0, l1 * l1 - along * along));
  const Vector3d w = (pole - pole.dot(u) * u).normalized();
  const Vector3d knee = hip + along * u + across * w;
  LegPose leg;
  leg.ankle = hip + d * u;
  // Rest frames: the bone direction and +Z (the knee bends forward).
  const Matrix3d thigh_rest_frame = segment_frame(thigh_rest, Vector3d::UnitZ());
  const Matrix3d shank_rest_frame = segment_frame(shank_rest, Vector3d::UnitZ());
  leg.thigh = segment_frame(knee - hip, w) * thigh_rest_frame.transpose();
  leg.shank = segment_frame(leg.ankle - knee, w) * shank_rest_frame.transpose();
  return leg;
}

/// The highest the root can be for the ankle to be reachable by a leg of
/// length `reach`, given where the hip joint is with the root at y = 0.
double highest_root(const Vector3d& hip_at_zero, const Vector3d& ankle, double reach) {
  const double dx = hip_at_zero.x() - ankle.x(), dz = hip_at_zero.z() - ankle.z();
  const double horizontal2 = dx * dx + dz * dz;
  const double vertical = std::sqrt(std::max(0.0, reach * reach - horizontal2));
  return ankle.y() + vertical - hip_at_zero.y();
}

/// A foot on or above the ground: the ankle, the foot's pitch about X
/// (degrees, + = heel up, toes down) and the toes' pitch relative to the foot.
struct FootState {
  Vector3d ankle{0, 0, 0};
  double pitch = 0.0;
  double toe = 0.0;
};

/// Ankle of a foot rotated by `pitch` (degrees, about X) about a pivot
/// (heel contact, ball joint) at `contact_offset` from the ankle of the flat foot.
Vector3d ankle_about(const Vector3d& flat_ankle, const Vector3d& contact_offset, double pitch) {
  const Vector3d contact = flat_ankle + contact_offset;
  return contact + rot_x(pitch) * (-contact_offset);
}

/// Legs and arms over one gait cycle; phases are fractions of the cycle
/// starting at this foot's heel strike.
struct WalkOptions {
  std::string file;
  double speed = 1.2;              ///< m/s along +Z
  double step_length = 0.65;       ///< m between successive heel strikes of opposite feet; a cycle is two steps
  double duration = 8.0;           ///< s (frame 0, the T-pose, comes on top)
  double hips_height = 0.935;      ///< Hips height at mid-stance (lowered where a leg cannot reach), m
  double bob = 0.012;              ///< nominal drop of the Hips at double support, m
  double sway = 0.02;              ///< side sway of the pelvis towards the stance foot, m
  double pelvis_yaw = 5.0;         ///< pelvis rotation, degrees (the swinging side forward)
  double pelvis_list = 4.0;        ///< pelvis drop on the swinging side, degrees
  double pelvis_tilt = 4.0;        ///< anterior tilt, degrees
  double trunk_lean = 2.0;         ///< forward lean of the trunk above the pelvis, degrees
  double thorax_counter = 0.5;     ///< thorax rotates back by this fraction of the pelvis yaw
  double foot_x = 0.07;            ///< ankles at +-foot_x
  double plant_offset = 0.21;      ///< flat-foot ankle ahead of the hips at heel strike, in cycles
  double heel_strike = 12.0;       ///< toes up at heel strike, degrees
  double heel_rise = 30.0;         ///< heel rise about the ball before the toe roll, degrees
  double toe_roll = 25.0;          ///< further rotation about the toe tip until toe-off, degrees
  double swing_lift = 0.04;        ///< early-swing lift of the ankle's path above a plain S-curve, m
  double arm_down = 80.0;          ///< arms lowered from the T-pose, degrees (10 degrees of abduction remain)
  double arm_swing = 16.0;         ///< shoulder flexion amplitude, degrees
  double arm_forward = 3.0;        ///< mean shoulder flexion, degrees
  double elbow = 15.0;             ///< mean elbow flexion, degrees
  double elbow_swing = 10.0;       ///< more flexion with the arm forward, degrees
};

/// Stance and swing event phases (fractions of the cycle).
constexpr double kFootFlat = 0.08;
constexpr double kHeelOff = 0.32;
constexpr double kToeRoll = 0.50;
constexpr double kToeOff = 0.60;

struct Walker {
  const Rig& rig;
  const Proportions& body;
  WalkOptions o;
  double stride() const { return 2.0 * o.step_length; }
  double period() const { return stride() / o.speed; }

  Vector3d heel_offset() const { return Vector3d(0, -body.ankle_height, -body.heel_back); }
  /// The ball joint (LeftToeBase): the heel rises about it with the toes flat.
  Vector3d ball_offset() const { return Vector3d(0, body.ball_height - body.ankle_height, body.ball_forward); }
  Vector3d tip_offset() const { return Vector3d(0, -body.ankle_height, body.ball_forward + body.toe_forward); }

  /// The ankle of the flat foot planted in cycle k (the foot's own cycles).
  Vector3d planted(int side, double cycle) const {
    const double x = side == 0 ? o.foot_x : -o.foot_x;
    const double shift = side == 0 ? 0.0 : 0.5;
    return Vector3d(x, body.ankle_height, stride() * (cycle + shift + o.plant_offset));
  }

  /// Stance of one foot at phase p in [0, kToeOff] of its cycle k.
  FootState stance(int side, double k, double p) const {
    const Vector3d flat = planted(side, k);
    FootState f;
    if (p < kFootFlat) {  // heel strike: rolling onto the flat foot about the heel
      f.pitch = -o.heel_strike * (1.0 - smoothstep(p / kFootFlat));
      f.ankle = ankle_about(flat, heel_offset(), f.pitch);
    } else if (p < kHeelOff) {
      f.ankle = flat;
    } else if (p < kToeRoll) {  // heel rise about the ball joint, toes flat on the ground
      f.pitch = o.heel_rise * smoothstep((p - kHeelOff) / (kToeRoll - kHeelOff));
      f.ankle = ankle_about(flat, ball_offset(), f.pitch);
      f.toe = -f.pitch;
    } else {  // toe roll: foot and toes together about the toe tip
      const double roll = o.toe_roll * smoothstep((p - kToeRoll) / (kToeOff - kToeRoll));
      const Vector3d risen = ankle_about(flat, ball_offset(), o.heel_rise);
      const Vector3d tip = flat + tip_offset();
      f.ankle = tip + rot_x(roll) * (risen - tip);
      f.pitch = o.heel_rise + roll;
      f.toe = -o.heel_rise;
    }
    return f;
  }

  /// Any phase: stance, or swing from this cycle's toe-off to the next heel strike.
  FootState foot(int side, double t) const {
    const double u = t / period() - (side == 0 ? 0.0 : 0.5);
    const double k = std::floor(u);
    const double p = u - k;
    if (p < kToeOff) return stance(side, k, p);
    const FootState off = stance(side, k, kToeOff);
    const FootState strike = stance(side, k + 1.0, 0.0);
    const double q = (p - kToeOff) / (1.0 - kToeOff);
    FootState f;
    // Forward: a cubic leaving at half the mean speed and arriving at rest
    // (the foot decelerates for heel strike). Up: a cubic Bezier whose first
    // control point is lifted, so the ankle stays up while the thigh comes
    // forward in early swing: the knee flexes most there and the toes clear.
    const double start_speed = 0.5;
    const double along = start_speed * q + (3.0 - 2.0 * start_speed) * q * q + (start_speed - 2.0) * q * q * q;
    const double b0 = (1 - q) * (1 - q) * (1 - q), b1 = 3 * (1 - q) * (1 - q) * q, b2 = 3 * (1 - q) * q * q,
                 b3 = q * q * q;
    f.ankle.x() = lerp(off.ankle.x(), strike.ankle.x(), q);
    f.ankle.z() = lerp(off.ankle.z(), strike.ankle.z(), along);
    f.ankle.y() = b0 * off.ankle.y() + b1 * (off.ankle.y() + o.swing_lift) + b2 * strike.ankle.y() + b3 * strike.ankle.y();
    if (q < 0.4) {
      f.pitch = off.pitch * (1.0 - smoothstep(q / 0.4));
      f.toe = off.toe * (1.0 - smoothstep(q / 0.4));
    } else {
      f.pitch = strike.pitch * smoothstep((q - 0.4) / 0.6);
    }
    return f;
  }

  /// Phase of the left foot's cycle at time t.
  double phase(double t) const { return fraction(t / period()); }

  Frame frame(double t) const {
    Frame frame = identity_frame(rig);
    const double p = phase(t);
    const double c = std::cos(2.0 * kPi * p), s = std::sin(2.0 * kPi * p);
    // Pelvis: the left side forward at left heel strike (negative yaw brings
    // +x forward), the swinging side dropped (left stance in the first half).
    const double yaw = -o.pelvis_yaw * c;
    const double list = o.pelvis_list * s;
    const Matrix3d pelvis = rot_y(yaw) * rot_z(list) * rot_x(o.pelvis_tilt);
    frame.local[rig.hips] = pelvis;

    const std::array<FootState, 2> feet{foot(0, t), foot(1, t)};
    Vector3d root(o.sway * s, 0.0, o.speed * t);
    // Highest at mid-stance, lowest at double support (twice per cycle).
    const double nominal = o.hips_height - o.bob * 0.5 * (1.0 - std::cos(4.0 * kPi * (p - 0.25)));
    double height = nominal;
    std::array<Vector3d, 2> hip_at_zero;
    for (int side = 0; side < 2; ++side) {
      const Vector3d offset = rig.joints[rig.upleg[side]].offset;
      hip_at_zero[side] = root + pelvis * offset;
      const double reach = 0.998 * (rig.joints[rig.leg[side]].offset.norm() + rig.joints[rig.foot[side]].offset.norm());
      height = std::min(height, highest_root(hip_at_zero[side], feet[side].ankle, reach));
    }
    height = std::max(height, nominal - 0.08);  // never crouch: out of reach, the foot lifts instead
    root.y() = height;
    frame.root = root;

    const Vector3d forward = rot_y(yaw) * Vector3d::UnitZ();
    for (int side = 0; side < 2; ++side) {
      const Vector3d hip = hip_at_zero[side] + Vector3d(0, height, 0);
      const LegPose leg = solve_leg(rig, side, hip, feet[side].ankle, forward);
      frame.local[rig.upleg[side]] = pelvis.transpose() * leg.thigh;  // LHipJoint: identity
      frame.local[rig.leg[side]] = leg.thigh.transpose() * leg.shank;
      frame.local[rig.foot[side]] = leg.shank.transpose() * rot_x(feet[side].pitch);
      frame.local[rig.toe[side]] = rot_x(feet[side].toe);
    }

    // Trunk: undo the pelvis list and most of its rotation, the thorax
    // turning a little the other way; the head looks straight ahead.
    frame.local[rig.lowerback] = rot_x(-o.pelvis_tilt + o.trunk_lean) * rot_z(-list) * rot_y(-yaw);
    frame.local[rig.spine] = rot_y(-0.5 * o.thorax_counter * yaw);
    frame.local[rig.spine1] = rot_y(-0.5 * o.thorax_counter * yaw);
    frame.local[rig.neck1] = rot_y(0.5 * o.thorax_counter * yaw) * rot_x(-0.5 * o.trunk_lean);
    frame.local[rig.head] = rot_y(0.5 * o.thorax_counter * yaw) * rot_x(-0.5 * o.trunk_lean);

    // Arms: each swings forward when the opposite leg does (left arm
    // forward at right heel strike, p = 0.5).
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? 1.0 : -1.0;
      const double swing = (side == 0 ? -c : c);  // +1 fully forward
      const double flexion = o.arm_forward + o.arm_swing * swing;
      const double elbow = o.elbow + o.elbow_swing * 0.5 * (1.0 + swing);
      frame.local[rig.arm[side]] = rot_x(-flexion) * rot_z(-sign * o.arm_down);
      frame.local[rig.forearm[side]] = rot_y(-sign * elbow);
    }
    return frame;
  }
};

/// Two deep squats, feet planted a little wider than the hips.
struct SquatOptions {
  std::string file = "squat.bvh";
  double stand = 0.5;          ///< s standing before, between (x 1.2) and after the squats
  double down = 1.25;          ///< s from standing to the bottom
  double hold = 0.2;           ///< s at the bottom
  double up = 1.25;            ///< s back up
  double bottom = 0.48;        ///< Hips height at the bottom, m
  double back = 0.12;          ///< Hips move back by this at the bottom, m
  double pelvis_tilt = 25.0;   ///< forward, at the bottom, degrees
  double trunk_lean = 20.0;    ///< further forward lean of the trunk, degrees
  double arms_forward = 75.0;  ///< arms raised forward for balance, degrees
  double foot_x = 0.11;        ///< ankles at +-foot_x
  double arm_down = 80.0;      ///< standing arm pose as in the walk
  double elbow = 12.0;
  int repetitions = 2;
  double duration() const {
    return stand * 2.0 + repetitions * (down + hold + up) + (repetitions - 1) * 1.2 * stand;
  }
  /// Depth 0 (standing) .. 1 (bottom) at time t.
  double depth(double t) const {
    double start = stand;
    for (int r = 0; r < repetitions; ++r) {
      if (t < start) return 0.0;
      if (t < start + down) return 0.5 - 0.5 * std::cos(kPi * (t - start) / down);
      if (t < start + down + hold) return 1.0;
      if (t < start + down + hold + up) return 0.5 + 0.5 * std::cos(kPi * (t - start - down - hold) / up);
      start += down + hold + up + 1.2 * stand;
    }
    return 0.0;
  }
};

Frame squat_frame(const Rig& rig, const Proportions& body, const SquatOptions& o, double t) {
  Frame frame = identity_frame(rig);
  const double d = o.depth(t);
  const Matrix3d pelvis = rot_x(d * o.pelvis_tilt);
  frame.local[rig.hips] = pelvis;
  Vector3d root(0.0, 0.0, -d * o.back);
  const double nominal = lerp(body.hips_height - 0.002, o.bottom, d);
  double height = nominal;
  std::array<Vector3d, 2> hip_at_zero, ankle;
  for (int side = 0; side < 2; ++side) {
    hip_at_zero[side] = root + pelvis * rig.joints[rig.upleg[side]].offset;
    ankle[side] = Vector3d(side == 0 ? o.foot_x : -o.foot_x, body.ankle_height, 0.0);
    const double reach = 0.998 * (rig.joints[rig.leg[side]].offset.norm() + rig.joints[rig.foot[side]].offset.norm());
    height = std::min(height, highest_root(hip_at_zero[side], ankle[side], reach));
  }
  root.y() = height;
  frame.root = root;
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    const Vector3d hip = hip_at_zero[side] + Vector3d(0, height, 0);
    // Knees track over the toes, slightly outwards.
    const LegPose leg = solve_leg(rig, side, hip, ankle[side], Vector3d(0.25 * sign, 0, 1));
    frame.local[rig.upleg[side]] = pelvis.transpose() * leg.thigh;
    frame.local[rig.leg[side]] = leg.thigh.transpose() * leg.shank;
    frame.local[rig.foot[side]] = leg.shank.transpose();  // foot flat on the ground
    const double flexion = d * o.arms_forward;
    frame.local[rig.arm[side]] = rot_x(-flexion) * rot_z(-sign * o.arm_down * (1.0 - 0.15 * d));
    frame.local[rig.forearm[side]] = rot_y(-sign * o.elbow);
  }
  frame.local[rig.lowerback] = rot_x(0.5 * d * o.trunk_lean);
  frame.local[rig.spine] = rot_x(0.3 * d * o.trunk_lean);
  frame.local[rig.spine1] = rot_x(0.2 * d * o.trunk_lean);
  // The head stays level: undo the pelvis tilt and the trunk's lean.
  frame.local[rig.neck1] = rot_x(-0.6 * d * (o.pelvis_tilt + o.trunk_lean));
  frame.local[rig.head] = rot_x(-0.4 * d * (o.pelvis_tilt + o.trunk_lean));
  return frame;
}

// ---------------------------------------------------------------------------
// Writing

/// Fixed-point text with trailing zeros dropped and -0 printed as 0, so the
/// output never depends on the sign of a rounding residue.
std::string number(double value, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  std::string text = buffer;
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

constexpr int kLengthDecimals = 5;  // 0.01 mm
constexpr int kAngleDecimals = 4;

void write_joint(std::ostringstream& out, const Rig& rig, int index, int depth) {
  const Joint& joint = rig.joints[index];
  const std::string indent(depth, '\t');
  if (joint.end_site) {
    out << indent << "End Site\n";
  } else {
    out << indent << (joint.parent < 0 ? "ROOT " : "JOINT ") << joint.name << '\n';
  }
  out << indent << "{\n";
  out << indent << "\tOFFSET " << number(joint.offset.x(), kLengthDecimals) << ' '
      << number(joint.offset.y(), kLengthDecimals) << ' ' << number(joint.offset.z(), kLengthDecimals) << '\n';
  if (!joint.end_site) {
    out << indent << '\t'
        << (joint.parent < 0 ? "CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation"
                             : "CHANNELS 3 Zrotation Yrotation Xrotation")
        << '\n';
  }
  for (std::size_t c = 0; c < rig.joints.size(); ++c)
    if (rig.joints[c].parent == index) write_joint(out, rig, static_cast<int>(c), depth + 1);
  out << indent << "}\n";
}

std::string bvh_text(const Rig& rig, const std::vector<Frame>& frames) {
  std::ostringstream out;
  out << "HIERARCHY\n";
  write_joint(out, rig, rig.hips, 0);
  out << "MOTION\n"
      << "Frames: " << frames.size() << '\n'
      << "Frame Time: " << number(1.0 / kFrameRate, 10) << '\n';
  for (const Frame& frame : frames) {
    out << number(frame.root.x(), kLengthDecimals) << ' ' << number(frame.root.y(), kLengthDecimals) << ' '
        << number(frame.root.z(), kLengthDecimals);
    for (std::size_t j = 0; j < rig.joints.size(); ++j) {
      if (rig.joints[j].end_site) continue;
      const Vector3d angles = zyx_degrees(frame.local[j]);
      for (int k = 0; k < 3; ++k) out << ' ' << number(angles(k), kAngleDecimals);
    }
    out << '\n';
  }
  return out.str();
}

/// The T-pose frame CMU puts first: every rotation 0, standing on the
/// ground at the x, z of the motion's first frame.
Frame t_pose(const Rig& rig, const Proportions& body, const Vector3d& first_root) {
  Frame frame = identity_frame(rig);
  frame.root = Vector3d(first_root.x(), body.hips_height, first_root.z());
  return frame;
}

// ---------------------------------------------------------------------------
// --report: what the motions do, measured on the generator's own FK

double angle_between(const Vector3d& a, const Vector3d& b) {
  return degrees(std::atan2(a.cross(b).norm(), a.dot(b)));
}

void report(const Rig& rig, const Proportions& body, const std::string& name, const std::vector<Frame>& frames) {
  double hips_low = 1e9, hips_high = -1e9, knee_max = 0.0, hip_flex = -1e9, hip_ext = 1e9, lowest = 1e9,
         highest_contact = -1e9, slip = 0.0;
  std::array<Vector3d, 2> last_flat{Vector3d::Constant(1e9), Vector3d::Constant(1e9)};
  for (std::size_t f = 1; f < frames.size(); ++f) {
    const Posed posed = forward_kinematics(rig, frames[f]);
    hips_low = std::min(hips_low, posed.position[rig.hips].y());
    hips_high = std::max(hips_high, posed.position[rig.hips].y());
    double frame_lowest = 1e9;
    for (int s = 0; s < 2; ++s) {
      const Vector3d hip = posed.position[rig.upleg[s]], knee = posed.position[rig.leg[s]],
                     ankle = posed.position[rig.foot[s]];
      knee_max = std::max(knee_max, angle_between(knee - hip, ankle - knee));
      // Hip flexion in the pelvis' sagittal plane: + forward.
      const Vector3d thigh = posed.rotation[rig.hips].transpose() * (knee - hip);
      const double flex = degrees(std::atan2(thigh.z(), -thigh.y()));
      hip_flex = std::max(hip_flex, flex);
      hip_ext = std::min(hip_ext, flex);
      const Matrix3d foot = posed.rotation[rig.foot[s]];
      const Vector3d heel = ankle + foot * Vector3d(0, -body.ankle_height, -body.heel_back);
      const Vector3d ball = ankle + foot * Vector3d(0, -body.ankle_height, body.ball_forward);
      const Vector3d tip = posed.position[rig.toe[s] + 1];
      const double low = std::min({heel.y(), ball.y(), tip.y()});
      frame_lowest = std::min(frame_lowest, low);
      const bool flat = std::abs(heel.y()) < 1e-4 && std::abs(ball.y()) < 1e-4;
      if (flat && last_flat[s].x() < 1e8) slip = std::max(slip, (ankle - last_flat[s]).norm());
      last_flat[s] = flat ? ankle : Vector3d::Constant(1e9);
    }
    lowest = std::min(lowest, frame_lowest);
    highest_contact = std::max(highest_contact, frame_lowest);
  }
  const Posed first = forward_kinematics(rig, frames[1]), last = forward_kinematics(rig, frames.back());
  const double seconds = static_cast<double>(frames.size() - 2) / kFrameRate;
  std::printf("%s: %zu frames (T-pose + %.3f s); root speed %.3f m/s; Hips y %.3f..%.3f; knee flexion max %.1f deg;"
              " hip flexion %.1f..%.1f deg; lowest foot point per frame %.4f..%.4f m; flat-foot slip %.2e m\n",
              name.c_str(), frames.size(), seconds,
              (last.position[rig.hips] - first.position[rig.hips]).z() / seconds, hips_low, hips_high, knee_max,
              hip_ext, hip_flex, lowest, highest_contact, slip);
}

}  // namespace

int main(int argc, char** argv) {
  const bool help = argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h");
  const bool with_report = argc == 3 && std::string(argv[2]) == "--report";
  if (help || argc < 2 || argc > 3 || (argc == 3 && !with_report)) {
    std::cerr << "usage: make_default_character <output-folder> [--report]\n"
                 "Writes mrcloth's default mannequin and motions as BVH in metres (read with scale 1.0):\n"
                 "mannequin.bvh, walk_instance.bvh, walk_new.bvh, squat.bvh. Frame 0 of each is a T-pose.\n";
    return help ? 0 : 2;
  }
  try {
    const std::filesystem::path folder = argv[1];
    if (!std::filesystem::is_directory(folder)) throw std::runtime_error("no such folder: " + folder.string());
    const Proportions body;
    const Rig rig = make_rig(body);
    const auto frame_count = [](double seconds) { return static_cast<int>(std::lround(seconds * kFrameRate)) + 1; };

    std::vector<std::pair<std::string, std::vector<Frame>>> files;
    files.push_back({"mannequin.bvh", {t_pose(rig, body, Vector3d::Zero())}});

    WalkOptions instance;
    instance.file = "walk_instance.bvh";
    WalkOptions fresh;
    fresh.file = "walk_new.bvh";
    fresh.speed = 1.0;
    fresh.step_length = 0.58;
    fresh.bob = 0.010;
    fresh.pelvis_yaw = 4.0;
    fresh.pelvis_list = 3.5;
    fresh.arm_swing = 12.0;
    fresh.elbow_swing = 8.0;
    fresh.heel_rise = 28.0;
    fresh.toe_roll = 22.0;
    fresh.swing_lift = 0.035;
    for (const WalkOptions& options : {instance, fresh}) {
      const Walker walker{rig, body, options};
      std::vector<Frame> frames;
      const int count = frame_count(options.duration);
      for (int f = 0; f < count; ++f) frames.push_back(walker.frame(f / kFrameRate));
      frames.insert(frames.begin(), t_pose(rig, body, frames.front().root));
      files.push_back({options.file, std::move(frames)});
    }

    const SquatOptions squat;
    {
      std::vector<Frame> frames;
      const int count = frame_count(squat.duration());
      for (int f = 0; f < count; ++f) frames.push_back(squat_frame(rig, body, squat, f / kFrameRate));
      frames.insert(frames.begin(), t_pose(rig, body, frames.front().root));
      files.push_back({squat.file, std::move(frames)});
    }

    for (const auto& [name, frames] : files) {
      write_atomically(bvh_text(rig, frames), folder / name);
      if (with_report && frames.size() > 2) report(rig, body, name, frames);
    }
  } catch (const std::exception& e) {
    std::cerr << "make_default_character: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
