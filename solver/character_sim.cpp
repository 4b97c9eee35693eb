#include "character_sim.h"

#include "joint_names.h"
#include "motion_filter.h"
#include "mesh_ops/atomic_file.h"
#include "mesh_ops/errors.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <tuple>

namespace mrcloth {
namespace {

// Zero velocity at both ends, so the body neither jerks into the pre-roll
// nor into the motion.
double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

void check(const CharacterRunOptions& o, const Motion& motion) {
  if (o.frames < 1) throw ArgumentError("frames must be >= 1, got " + std::to_string(o.frames));
  if (!(o.fps > 0.0)) throw ArgumentError("fps must be > 0");
  if (!(o.step_rate >= o.fps)) throw ArgumentError("the step rate must be at least the output fps");
  // Both bounds also keep the rounded counts within int (a step rate of
  // 1e300 rounded to a count past it, and ran one step a frame).
  if (!(o.step_rate <= kMostStepsPerFrame * o.fps))
    throw ArgumentError("the step rate must be at most " + std::to_string(kMostStepsPerFrame) +
                        " steps per output frame");
  if (!(o.preroll_seconds >= 0.0)) throw ArgumentError("pre-roll must be >= 0 seconds");
  if (!(o.preroll_seconds * o.fps <= std::numeric_limits<int>::max()))
    throw ArgumentError("the pre-roll must be fewer than 2^31 output frames");
  if (!(o.motion_start >= 0.0)) throw ArgumentError("motion start must be >= 0 seconds");
  if (motion.skeleton.find(o.pelvis_joint) < 0)
    throw ArgumentError("the motion's skeleton has no joint '" + o.pelvis_joint + "' to pin the waist to");
}

/// The joints of the legs a garment hangs on (the hips, hip joints, knees,
/// ankles) that `skeleton` has, by CMU name.
std::vector<int> leg_joints(const Skeleton& skeleton) {
  std::vector<int> joints;
  if (const int hips = skeleton.find("Hips"); hips >= 0) joints.push_back(hips);
  for (const char* name : kCmuLegJoints)
    if (const int joint = skeleton.find(name); joint >= 0) joints.push_back(joint);
  return joints;
}

}  // namespace

/// The body mesh, then the bridges; a point a bridge moved is projected
/// out of the mesh again (frictionless), so the mesh has the last word.
class SkinnedPosedBody::MeshAndBridges : public CollisionScene {
 public:
  MeshAndBridges(const MeshBody& mesh, const CapsuleBody* bridges) : mesh_(mesh), bridges_(bridges) {}
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction, ContactMemo* memo,
                 SurfaceNearby* nearby) const override {
    SurfaceNearby on_mesh, on_bridges;
    double largest = mesh_.resolve(start, position, friction, memo, nearby ? &on_mesh : nullptr);
    // Beyond every bridge and mitten (about half the resolves of an
    // adaptive skirt) they move nothing, and what they find near is no
    // nearer than the mesh's, which is within reach: the mesh's answer
    // stands, to the bit.
    if (!bridges_ || bridges_->beyond(position, kNearbyReach)) {
      if (nearby) *nearby = on_mesh;
      return largest;
    }
    const double bridged = bridges_->resolve(start, position, friction, nullptr, nearby ? &on_bridges : nullptr);
    if (bridged > 0.0) {
      largest = std::max({largest, bridged, mesh_.resolve(start, position, false, memo, nearby ? &on_mesh : nullptr)});
      // The mesh may have moved the point off where the bridges left it.
      if (nearby) on_bridges = nearest_surface(bridges_->colliders(), position, kNearbyReach);
    }
    if (nearby) *nearby = nearer(on_mesh, on_bridges);
    return largest;
  }
  double penetration(const Eigen::Vector3d& p) const override {
    return std::max(mesh_.penetration(p), bridges_ ? bridges_->penetration(p) : 0.0);
  }
  double depth(const Eigen::Vector3d& p) const override {
    return std::max(mesh_.depth(p), bridges_ ? bridges_->depth(p) : 0.0);
  }
  PointDepths depths(const Eigen::Vector3d& p, int* hint) const override {
    PointDepths deepest = mesh_.depths(p, hint);
    if (bridges_) {
      const PointDepths bridged = bridges_->depths(p);
      deepest.penetration = std::max(deepest.penetration, bridged.penetration);
      deepest.depth = std::max(deepest.depth, bridged.depth);
    }
    return deepest;
  }
  bool empty() const override { return false; }

 private:
  const MeshBody& mesh_;
  const CapsuleBody* bridges_;
};

SkinnedPosedBody::SkinnedPosedBody(SkinnedBody body, const Skeleton& skeleton, double thickness, double friction,
                                   CapsuleRig capsules, SkinnedBody drawn)
    : body_(std::move(body)),
      drawn_(std::move(drawn)),
      skeleton_(skeleton),
      mesh_(std::make_unique<MeshBody>(body_.rest_vertices, body_.triangles, thickness, friction)),
      turned_(body_) {
  if (!capsules.bones.empty() || !capsules.bridges.empty()) {
    capsules.thickness = thickness;
    capsules.friction = friction;
    bridges_ = std::make_unique<CapsuleBody>(std::move(capsules), skeleton);
  }
  scene_ = std::make_unique<MeshAndBridges>(*mesh_, bridges_.get());
}

SkinnedPosedBody::~SkinnedPosedBody() = default;

void SkinnedPosedBody::set_pose(const Pose& pose) {
  const Eigen::MatrixX3d vertices = skin(body_, skeleton_, pose);
  // Skin the blend has folded over (behind a bent knee) is not the outside.
  mesh_->update(vertices, turned_(skeleton_, pose, vertices));
  // The bridges sit between the body's own legs, not the capture subject's.
  if (bridges_) bridges_->pose(proportioned_pose(skeleton_, body_.joint_rest, pose));
}

const CollisionScene& SkinnedPosedBody::scene() const { return *scene_; }

BodySurface SkinnedPosedBody::surface(const Pose& pose) const {
  const SkinnedBody& shown = drawn_.rest_vertices.rows() > 0 ? drawn_ : body_;
  BodySurface surface;
  surface.vertices = skin(shown, skeleton_, pose);
  surface.faces.reserve(shown.triangles.size());
  for (const Eigen::Vector3i& t : shown.triangles) surface.faces.push_back({t[0], t[1], t[2]});
  if (shown.triangle_uvs.size() == shown.triangles.size())
    for (const auto& uv : shown.triangle_uvs) surface.uvs.push_back({uv[0], uv[1], uv[2]});
  if (bridges_) {
    // The bridges stand for skin between the legs, the mittens for the
    // hands: drawn, so the surface is what the cloth collides with.
    append_surface(surface,
                   capsule_surface(posed_capsules(bridges_->rig(), proportioned_pose(skeleton_, body_.joint_rest, pose))));
  }
  return surface;
}

Eigen::Isometry3d start_heading_turn(const Motion& motion, double time) {
  const Pose start = pose_at(motion, time);
  const Eigen::Vector3d left = start.global.front().linear() * Eigen::Vector3d::UnitX();
  // The rest pose's left is +X (BVH rest rotations are the identity); a
  // turn by angle a about +Y takes it to (cos a, 0, -sin a).
  if (std::hypot(left.x(), left.z()) < 1e-6) return Eigen::Isometry3d::Identity();  // lying on its side
  const double angle = std::atan2(-left.z(), left.x());
  if (std::abs(angle) <= kHeadingTurnThreshold) return Eigen::Isometry3d::Identity();
  const Eigen::Vector3d pivot = start.position(0);
  return Eigen::Translation3d(pivot) * Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()) *
         Eigen::Translation3d(-pivot);
}

Pose reference_pose(const Motion& motion, const CharacterRunOptions& options) {
  const Pose rest = rest_pose(motion.skeleton);
  const Pose first = pose_at(motion, options.motion_start);
  if (!options.garment_pose.global.empty() && options.garment_pose.global.size() != rest.global.size())
    throw ArgumentError("the garment pose has " + std::to_string(options.garment_pose.global.size()) +
                        " joints; the motion's skeleton has " + std::to_string(rest.global.size()));
  Pose pose = options.garment_pose.global.empty() ? rest : options.garment_pose;
  // Every root of the skeleton moves with its own first-frame position.
  for (std::size_t j = 0; j < motion.skeleton.joints.size(); ++j) {
    int root = static_cast<int>(j);
    while (motion.skeleton.joints[root].parent >= 0) root = motion.skeleton.joints[root].parent;
    pose.global[j].pretranslate(first.position(root) - rest.position(root));
  }
  // (Not multiplied by an identity: the poses of clips facing their rest pose keep every bit.)
  if (const Eigen::Isometry3d turn = start_heading_turn(motion, options.motion_start); !turn.matrix().isIdentity(0.0))
    for (Eigen::Isometry3d& global : pose.global) global = turn * global;
  return pose;
}

std::vector<std::vector<std::pair<int, double>>> waist_skin_weights(const SkinnedBody& body,
                                                                    const Eigen::MatrixX3d& body_vertices,
                                                                    const Eigen::MatrixX3d& points) {
  if (body_vertices.rows() == 0 || body_vertices.rows() != static_cast<Eigen::Index>(body.weights.size()))
    throw ArgumentError("waist_skin_weights: " + std::to_string(body_vertices.rows()) + " body vertices for " +
                        std::to_string(body.weights.size()) + " weight lists; expected one list per vertex");
  if (body.triangles.empty())
    throw ArgumentError("waist_skin_weights: the body has no triangles; expected its surface");
  // Weights blended over the nearest point's triangle vary continuously
  // along the skin. The nearest vertex's weights jump between neighbouring
  // points: where two body vertices' differ (a thigh's share against the
  // pelvis's), two pins millimetres apart turned about different joints,
  // and the waistband's short edges between them stretched with the skin's
  // motion (the shared trousers' d5 mesh: 89 % on 3.9 mm edges).
  const MeshBody surface = [&] {
    try {
      return MeshBody(body_vertices, body.triangles);
    } catch (const ArgumentError& error) {  // say whose surface it was
      throw ArgumentError(std::string("waist_skin_weights: the body's surface: ") + error.what());
    }
  }();
  std::vector<std::vector<std::pair<int, double>>> out;
  out.reserve(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    const MeshBody::SurfacePoint nearest = surface.nearest_point(points.row(p).transpose());
    std::map<int, double> blended;
    for (std::size_t k = 0; k < 3; ++k)
      for (const auto& [joint, weight] : body.weights[static_cast<std::size_t>(nearest.vertices[k])])
        blended[joint] += nearest.weights[k] * weight;
    std::vector<std::pair<int, double>> list;
    for (const auto& [joint, weight] : blended)
      if (weight > 0.0) list.emplace_back(joint, weight);
    out.push_back(std::move(list));
  }
  return out;
}

std::vector<std::vector<std::pair<int, double>>> smooth_along_waist(
    const std::vector<std::vector<std::pair<int, double>>>& weights, const Eigen::MatrixX3d& points, double sigma) {
  if (weights.size() != static_cast<std::size_t>(points.rows()))
    throw ArgumentError("smooth_along_waist: " + std::to_string(weights.size()) + " weight lists for " +
                        std::to_string(points.rows()) + " points; expected one list per point");
  if (!(sigma >= 0.0) || !std::isfinite(sigma))
    throw ArgumentError("smooth_along_waist: sigma " + std::to_string(sigma) + "; expected a finite value >= 0 (metres)");
  if (sigma == 0.0) return weights;
  const double reach2 = 9.0 * sigma * sigma;
  std::vector<std::vector<std::pair<int, double>>> out(weights.size());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    std::map<int, double> sum;  // per joint, in ascending joint order as waist_skin_weights lists them
    double total = 0.0;
    for (Eigen::Index j = 0; j < points.rows(); ++j) {
      const double d2 = (points.row(i) - points.row(j)).squaredNorm();
      if (d2 > reach2) continue;
      const double kernel = std::exp(-0.5 * d2 / (sigma * sigma));
      total += kernel;
      for (const auto& [joint, weight] : weights[static_cast<std::size_t>(j)]) sum[joint] += kernel * weight;
    }
    for (const auto& [joint, weight] : sum)
      if (weight > 0.0) out[static_cast<std::size_t>(i)].emplace_back(joint, weight / total);
  }
  return out;
}

void waist_follows_skin(CharacterRunOptions& options, const SkinnedBody& body, const Motion& motion,
                        const DynamicsModel& model) {
  if (model.pinned_vertices.empty()) return;
  options.body_joints = body.joint_rest;
  const Eigen::MatrixX3d pins = pinned_rows(model, model.rest);
  options.waist_weights = smooth_along_waist(
      waist_skin_weights(body, skin(body, motion.skeleton, reference_pose(motion, options)), pins), pins,
      options.waist_smoothing);
}

void fit_capsules_to_body(CapsuleRig& rig, const Skeleton& skeleton, const SkinnedBody& body,
                          const std::map<std::string, std::pair<double, double>>& overrides) {
  fit_capsule_radii(rig, skeleton, body.rest_vertices, body.weights, body.joint_rest);
  std::vector<BoneCapsule> kept;
  for (BoneCapsule bone : rig.bones) {
    const auto it = overrides.find(skeleton.joints[static_cast<std::size_t>(bone.joint)].name);
    if (it != overrides.end()) std::tie(bone.radius_head, bone.radius_tail) = it->second;
    if (bone.radius_head > 0.0 || bone.radius_tail > 0.0) kept.push_back(bone);
  }
  rig.bones = std::move(kept);
}

std::vector<BoneCapsule> hand_mitten_capsules(const Skeleton& skeleton, const SkinnedBody& body) {
  const Pose rest = proportioned_pose(skeleton, body.joint_rest, rest_pose(skeleton));
  const std::vector<int> hand_of = hand_vertices(body, skeleton);
  std::map<int, std::vector<Eigen::Vector3d>> points;  // per hand joint, its vertices in the rest pose
  for (std::size_t v = 0; v < hand_of.size(); ++v)
    if (hand_of[v] >= 0) points[hand_of[v]].push_back(body.rest_vertices.row(static_cast<Eigen::Index>(v)).transpose());
  // Per hand, a capsule along the principal axis of its vertices in the
  // rest pose, from the 5th to the 95th percentile along it, as thick as
  // the median distance from that axis (about half a palm's width, so
  // thicker than the palm; the spread fingers and thumb stay partly
  // outside), carried by the hand joint. (A fit to the whole hand's
  // cross-sections, as fit_capsule_radii fits limbs, came out 5 cm thick
  // and caught more cloth at the hip than the hand did.)
  std::vector<BoneCapsule> mittens;
  for (const auto& [hand, cloud] : points) {
    if (cloud.size() < 4) continue;  // too few points for an axis
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : cloud) centre += p;
    centre /= static_cast<double>(cloud.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3d& p : cloud) scatter += (p - centre) * (p - centre).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
    const Eigen::Vector3d axis = eigen.eigenvectors().col(2);  // eigenvalues ascend: the longest direction
    std::vector<double> along, across;
    for (const Eigen::Vector3d& p : cloud) {
      const double t = (p - centre).dot(axis);
      along.push_back(t);
      across.push_back((p - centre - t * axis).norm());
    }
    const auto quantile = [](std::vector<double> values, double q) {
      const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
      std::nth_element(values.begin(), values.begin() + k, values.end());
      return values[static_cast<std::size_t>(k)];
    };
    const double radius = quantile(across, 0.5);
    const double low = quantile(along, 0.05) + radius, high = std::max(low, quantile(along, 0.95) - radius);
    const Eigen::Matrix3d to_hand = rest.global[static_cast<std::size_t>(hand)].linear().transpose();
    BoneCapsule mitten;
    mitten.joint = mitten.child = hand;
    mitten.radius_head = mitten.radius_tail = radius;
    mitten.shift_head = to_hand * (centre + low * axis - rest.position(hand));
    mitten.shift_tail = to_hand * (centre + high * axis - rest.position(hand));
    mittens.push_back(mitten);
  }
  return mittens;
}

int clear_capsules_for_garment(CapsuleRig& rig, const Motion& motion, const CharacterRunOptions& options,
                               const std::vector<Eigen::Vector3d>& body_joints, const Eigen::MatrixX3d& garment) {
  return clear_capsules_of(rig, proportioned_pose(motion.skeleton, body_joints, reference_pose(motion, options)),
                           garment);
}

Pose character_pose(const Motion& motion, double time, const CharacterRunOptions& options, double* arm_angle) {
  Pose pose;
  if (time >= options.preroll_seconds) {
    pose = pose_at(motion, options.motion_start + time - options.preroll_seconds);
  } else {
    const Pose first = pose_at(motion, options.motion_start);
    pose = blend_poses(motion.skeleton, reference_pose(motion, options), first, smoothstep(time / options.preroll_seconds));
  }
  const double angle = options.arm_clearance ? clear_arms(*options.arm_clearance, motion.skeleton, pose) : 0.0;
  if (arm_angle) *arm_angle = angle;
  return pose;
}

LegSpeed fastest_leg_speed(const Motion& motion, int first_frame, int last_frame) {
  LegSpeed fastest;
  const std::vector<int> joints = leg_joints(motion.skeleton);
  const int end = last_frame < 0 ? static_cast<int>(motion.frames.rows()) - 1
                                 : std::min(last_frame, static_cast<int>(motion.frames.rows()) - 1);
  const int begin = std::max(0, first_frame);
  if (joints.empty() || end <= begin) return fastest;
  Pose before = frame_pose(motion, begin);
  for (int f = begin + 1; f <= end; ++f) {
    Pose after = frame_pose(motion, f);
    for (const int joint : joints) {
      const double speed = (after.position(joint) - before.position(joint)).norm() / motion.frame_time;
      if (speed > fastest.speed) fastest = {speed, f - 1, motion.skeleton.joints[static_cast<std::size_t>(joint)].name};
    }
    before = std::move(after);
  }
  return fastest;
}

double leg_jitter(const Motion& motion, int first_frame, int last_frame) {
  const std::vector<int> joints = leg_joints(motion.skeleton);
  const int end = last_frame < 0 ? static_cast<int>(motion.frames.rows()) - 1
                                 : std::min(last_frame, static_cast<int>(motion.frames.rows()) - 1);
  const int begin = std::max(0, first_frame);
  if (joints.empty() || end - begin < 2) return 0.0;
  std::vector<double> largest;
  largest.reserve(static_cast<std::size_t>(end - begin - 1));
  Pose before = frame_pose(motion, begin), now = frame_pose(motion, begin + 1);
  const double squared_time = motion.frame_time * motion.frame_time;
  for (int f = begin + 2; f <= end; ++f) {
    Pose after = frame_pose(motion, f);
    double most = 0.0;
    for (const int joint : joints)
      most = std::max(most, (after.position(joint) - 2.0 * now.position(joint) + before.position(joint)).norm());
    largest.push_back(most / squared_time);
    before = std::move(now);
    now = std::move(after);
  }
  const auto middle = largest.begin() + static_cast<std::ptrdiff_t>(largest.size() / 2);
  std::nth_element(largest.begin(), middle, largest.end());
  return *middle;
}

double smoothing_against_jitter(const Motion& motion, double already, int first_frame, int last_frame, double target) {
  const double candidates[] = {0.005, 0.01, 0.015, 0.02, 0.03, 0.05, 0.1};
  const double widest = candidates[std::size(candidates) - 1];
  const Eigen::Index rows = motion.frames.rows();
  const Eigen::Index last = last_frame < 0 ? rows - 1 : std::min<Eigen::Index>(last_frame, rows - 1);
  const auto margin = static_cast<Eigen::Index>(std::ceil(3.0 * widest / motion.frame_time)) + 2;
  const Eigen::Index from = std::max<Eigen::Index>(0, first_frame - margin);
  const Eigen::Index to = std::min<Eigen::Index>(rows, last + 1 + margin);
  Motion part = motion;
  part.frames = motion.frames.middleRows(from, to - from);
  for (const double total : candidates) {
    if (total <= already) continue;
    Motion smoothed = part;
    smooth_motion(smoothed, std::sqrt(total * total - already * already));  // Gaussians compose in quadrature
    if (leg_jitter(smoothed, static_cast<int>(first_frame - from), static_cast<int>(last - from)) < target) return total;
  }
  return widest;
}

double preroll_leg_speed(const Motion& motion, const CharacterRunOptions& options) {
  const Pose rest = reference_pose(motion, options);
  const Pose first = pose_at(motion, options.motion_start);
  double way = 0.0;
  for (const int joint : leg_joints(motion.skeleton))
    way = std::max(way, (first.position(joint) - rest.position(joint)).norm());
  if (!(way > 0.0)) return 0.0;
  // smoothstep's steepest slope is 1.5 times its mean.
  return options.preroll_seconds > 0.0 ? 1.5 * way / options.preroll_seconds : std::numeric_limits<double>::infinity();
}

int preroll_frame_count(const CharacterRunOptions& options) {
  if (!(options.preroll_seconds > 0.0)) return 0;
  return std::max(1, static_cast<int>(std::lround(options.preroll_seconds * options.fps)));
}

int steps_per_frame(const CharacterRunOptions& options) {
  return std::max(1, static_cast<int>(std::lround(options.step_rate / options.fps)));
}

namespace {

/// Where the pinned waist goes in a pose of the motion: with the pelvis
/// joint's frame, or skinned as the body is where the options give the
/// waist's skin weights (so the waist keeps its place on the skin).
class WaistTargets {
 public:
  /// Throws ArgumentError when the waist weights do not match the model's
  /// pins or name no joint of the motion's skeleton.
  WaistTargets(const DynamicsModel& model, const Motion& motion, const CharacterRunOptions& options)
      : motion_(motion),
        options_(options),
        pelvis_(motion.skeleton.find(options.pelvis_joint)),
        reference_(reference_pose(motion, options)),
        pelvis_rest_inverse_(reference_.global[pelvis_].inverse()),
        rest_(pinned_rows(model, model.rest)) {
    if (options.waist_weights.empty()) return;
    if (options.waist_weights.size() != model.pinned_vertices.size())
      throw ArgumentError("waist weights for " + std::to_string(options.waist_weights.size()) +
                          " vertices; the model pins " + std::to_string(model.pinned_vertices.size()));
    // Per joint, the inverse of the body's joint frame in the reference
    // pose (the waist's rest shape sits on that pose).
    for (const Eigen::Isometry3d& g : proportioned_pose(motion.skeleton, options.body_joints, reference_).global)
      reference_inverse_.push_back(g.inverse());
    for (const auto& list : options.waist_weights)
      for (const auto& [joint, weight] : list)
        if (joint < 0 || joint >= static_cast<int>(reference_inverse_.size()) || !std::isfinite(weight))
          throw ArgumentError("waist weight " + std::to_string(weight) + " on joint " + std::to_string(joint) +
                              ": expected a finite weight on a joint of the motion's skeleton");
  }

  /// The pinned vertices' rest positions (#pinned x 3, metres).
  const Positions& rest() const { return rest_; }

  /// Sets `pinned` (#pinned x 3, metres) to the waist's place in `pose`.
  void place(const Pose& pose, Positions& pinned) const {
    if (options_.waist_weights.empty()) {
      const Eigen::Isometry3d follow = pose.global[pelvis_] * pelvis_rest_inverse_;
      for (Eigen::Index k = 0; k < pinned.rows(); ++k)
        pinned.row(k) = (follow * Eigen::Vector3d(rest_.row(k).transpose())).transpose();
      return;
    }
    // Linear blend skinning, as skin() moves the body (same joints, pivots
    // and weights).
    const Pose skin_pose = proportioned_pose(motion_.skeleton, options_.body_joints, pose);
    for (Eigen::Index k = 0; k < pinned.rows(); ++k) {
      const Eigen::Vector3d x = rest_.row(k).transpose();
      Eigen::Vector3d y = Eigen::Vector3d::Zero();
      for (const auto& [joint, weight] : options_.waist_weights[static_cast<std::size_t>(k)])
        y += weight * (skin_pose.global[static_cast<std::size_t>(joint)] * (reference_inverse_[static_cast<std::size_t>(joint)] * x));
      pinned.row(k) = y.transpose();
    }
  }

 private:
  const Motion& motion_;
  const CharacterRunOptions& options_;
  int pelvis_;
  Pose reference_;
  Eigen::Isometry3d pelvis_rest_inverse_;
  Positions rest_;
  std::vector<Eigen::Isometry3d> reference_inverse_;  // per joint; empty for a rigid waist
};

/// The character's pose at a time, computed once for the pins and the body
/// of the same step (FK once a step); counts in `report` the steps at which
/// the arm clearance opened an arm.
class StepPoses {
 public:
  StepPoses(const Motion& motion, const CharacterRunOptions& options, CharacterRunReport& report)
      : motion_(motion), options_(options), report_(report) {}

  /// The pose at `time` (seconds on the run's clock); `count`: a step of
  /// the run, not a re-evaluation (the waist's check), whose arm is counted.
  const Pose& at(double time, bool count = true) {
    if (time != time_) {
      double arm_angle = 0.0;
      pose_ = character_pose(motion_, time, options_, &arm_angle);
      time_ = time;
      if (count) {
        report_.max_arm_angle = std::max(report_.max_arm_angle, arm_angle);
        if (arm_angle > 0.0) ++report_.arm_steps;
      }
    }
    return pose_;
  }

 private:
  const Motion& motion_;
  const CharacterRunOptions& options_;
  CharacterRunReport& report_;
  double time_ = -1.0;
  Pose pose_;
};

/// The pre-roll's options: `sim` for preroll_frames frames that span the
/// pre-roll exactly, so the motion starts at its first frame: a pre-roll
/// that is no whole number of output frames (0.516 s at 30 fps) takes them
/// a little longer or shorter. (Rounded to whole frames, the cloth went on
/// at clip times the pre-roll's remainder away from the ones the waist's
/// check and the body's cache were taken at.) No cache is written.
SimulationOptions preroll_options(const SimulationOptions& sim, const CharacterRunOptions& options, int preroll_frames) {
  SimulationOptions warmup = sim;
  warmup.frames = preroll_frames;
  if (std::abs(preroll_frames - options.preroll_seconds * options.fps) > 1e-9 * preroll_frames)
    warmup.fps = preroll_frames / options.preroll_seconds;
  warmup.cache_path.clear();
  return warmup;
}

}  // namespace

CharacterRunReport simulate_on_character(const DynamicsModel& model, ClothState& state, const Motion& motion,
                                         PosedBody& body, const CharacterRunOptions& options,
                                         const SimulationProgress& progress, std::vector<Positions>* frames_out) {
  check(options, motion);
  const WaistTargets waist(model, motion, options);
  CharacterRunReport report;
  StepPoses poses(motion, options, report);
  const PinTrajectory pins = [&](double time, Positions& pinned) { waist.place(poses.at(time), pinned); };
  MovingBodies bodies;
  bodies.scene = &body.scene();
  bodies.pose = [&](double time) { body.set_pose(poses.at(time)); };

  SimulationOptions sim = options.simulation;
  sim.fps = options.fps;
  sim.substeps = steps_per_frame(options);

  const int preroll_frames = preroll_frame_count(options);
  const int total_frames = preroll_frames + options.frames;
  // One factorisation for the pre-roll and the motion where they step
  // alike (a pre-roll of whole output frames): about a second at 49k vertices.
  const auto factorise_start = std::chrono::steady_clock::now();
  ImplicitIntegrator prepared;
  const auto keep_going = [&] { return !progress || progress(0, total_frames); };
  if (!keep_going() || !prepared.precompute(model, integrator_options(sim), keep_going)) {
    report.motion.cancelled = true;  // in the set-up: no frame done
    return report;
  }
  const double factorise_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - factorise_start).count();
  if (preroll_frames > 0) {
    const SimulationOptions warmup = preroll_options(sim, options, preroll_frames);
    SimulationProgress preroll_progress;
    if (progress) preroll_progress = [&](int done, int) { return progress(done, total_frames); };
    report.preroll = simulate(model, state, warmup, pins, preroll_progress, nullptr, bodies,
                              warmup.fps == sim.fps ? &prepared : nullptr);
    if (report.preroll.non_finite || report.preroll.cancelled) {
      report.motion.non_finite = report.preroll.non_finite;
      report.motion.cancelled = report.preroll.cancelled;
      return report;
    }
  }
  sim.frames = options.frames;
  // The waist error is measured on each output frame as it is recorded (its
  // pinned rows are the state's), against the targets the pins were given
  // at that frame's time: exact by construction, and this checks it. Frame
  // by frame, so a run holds no copy of its frames (24 bytes a vertex a
  // frame: 1.1 GB for 49k vertices over 800 frames).
  Positions target = waist.rest();
  const SimulationProgress motion_progress = [&](int done, int) {
    const double time = options.preroll_seconds + static_cast<double>(done) / options.fps;
    target = waist.rest();
    waist.place(poses.at(time, /*count=*/false), target);
    for (std::size_t k = 0; k < model.pinned_vertices.size(); ++k)
      report.max_waist_error = std::max(report.max_waist_error, (state.pinned.row(static_cast<Eigen::Index>(k)) -
                                                                 target.row(static_cast<Eigen::Index>(k))).norm());
    return !progress || progress(preroll_frames + done, total_frames);
  };
  report.motion = simulate(model, state, sim, pins, motion_progress, frames_out, bodies, &prepared);
  report.motion.precompute_ms += factorise_ms;
  return report;
}

double automatic_leg_bridges(int boundary_loop_count, const Eigen::MatrixX3d& placed_points, const Skeleton& skeleton) {
  if (boundary_loop_count != 2 || placed_points.rows() == 0) return 0.0;
  for (const char* name : kCmuLegJoints)
    if (skeleton.find(name) < 0) return 0.0;
  const Pose rest = rest_pose(skeleton);
  const double knee_height =
      std::max(rest.position(skeleton.find("LeftLeg")).y(), rest.position(skeleton.find("RightLeg")).y());
  return placed_points.col(1).minCoeff() >= knee_height ? 1.0 : 2.0;
}

GarmentClearance clear_garment_of_body(PosedBody& body, const Motion& motion, const CharacterRunOptions& options,
                                       Eigen::MatrixX3d& points, const std::vector<std::array<int, 3>>& hanging) {
  for (const auto& [vertex, a, b] : hanging)
    if (vertex < 0 || a < 0 || b < 0 || vertex >= points.rows() || a >= points.rows() || b >= points.rows())
      throw ArgumentError("clear_garment_of_body: hanging vertex " + std::to_string(vertex) + " with parents " +
                          std::to_string(a) + ", " + std::to_string(b) + " out of range");
  body.set_pose(reference_pose(motion, options));
  const CollisionScene& scene = body.scene();
  const Eigen::MatrixX3d before = points;
  const auto clear_points = [&] {
    bool moved = false;
    for (Eigen::Index v = 0; v < points.rows(); ++v) {
      const Eigen::Vector3d p = points.row(v).transpose();
      Eigen::Vector3d out = p;
      // A point at rest: its step starts where it is, and friction has nothing to act on.
      if (scene.resolve(p, out, false) > 0.0) {
        points.row(v) = out.transpose();
        moved = true;
      }
    }
    return moved;
  };
  // Back at its parents' midpoint a T-node may be inside again (the chord of
  // a curved body): its edge then moves out with it, as the integrator moves
  // a T-node's stencil. Moved parents are cleared again, so repeat a few times.
  const auto clear_t_nodes = [&] {
    bool moved = false;
    for (const auto& [vertex, a, b] : hanging) {
      const Eigen::Vector3d midpoint = 0.5 * (points.row(a) + points.row(b)).transpose();
      Eigen::Vector3d target = midpoint;
      if (scene.resolve(midpoint, target, false) > 0.0) {
        const Eigen::RowVector3d delta = (target - midpoint).transpose();
        points.row(a) += delta;
        points.row(b) += delta;
        moved = true;
      }
    }
    return moved;
  };
  clear_points();
  for (int pass = 0; pass < 4 && clear_t_nodes(); ++pass) clear_points();
  for (const auto& [vertex, a, b] : hanging) points.row(vertex) = 0.5 * (points.row(a) + points.row(b));

  GarmentClearance clearance;
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    const double move = (points.row(v) - before.row(v)).norm();
    if (move > 0.0) {
      ++clearance.moved;
      clearance.largest_move = std::max(clearance.largest_move, move);
    }
  }
  return clearance;
}

void write_body_cache(const Motion& motion, const PosedBody& body, const CharacterRunOptions& options,
                      const std::string& cache_path, const std::string& obj_path) {
  check(options, motion);
  std::unique_ptr<Pc2Writer> writer;
  std::unique_ptr<StagedFile> rest_mesh;
  std::vector<int> kept;  // the vertices the faces use (the hands the mittens replace are not)
  for (int f = 0; f < options.frames; ++f) {
    // The garment's output frame f is taken after (f + 1) frame intervals of
    // the motion, and its cache starts at frame 1 (its rest mesh is frame 0).
    const double time = options.preroll_seconds + static_cast<double>(f + 1) / options.fps;
    const BodySurface surface = body.surface(character_pose(motion, time, options));
    if (!writer) {
      kept = used_vertices(surface);
      writer = std::make_unique<Pc2Writer>(cache_path, static_cast<int>(kept.size()), 1.0, 1.0);
    }
    writer->add_frame(surface.vertices(kept, Eigen::all));
    if (f == 0 && !obj_path.empty()) {
      const BodySurface first = keep_vertices(surface, kept);
      rest_mesh = std::make_unique<StagedFile>(obj_path, ".obj", [&](const std::string& file) {
        write_obj(file, first.vertices, first.faces, first.uvs);
      });
    }
  }
  if (!writer) return;
  writer->finish();
  // Staged while the cache was written, so that neither stands alone.
  if (rest_mesh) rest_mesh->commit();
}

}  // namespace mrcloth
