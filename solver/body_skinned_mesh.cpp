#include "body_skinned_mesh.h"

#include "mesh_ops/errors.h"

#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mrcloth {

// ---------------------------------------------------------------------------
// skin

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

/// Checks a body's per-joint and per-vertex arrays against the skeleton.
void check_body(const SkinnedBody& body, std::size_t n, const char* caller) {
  const auto fail = [&](const std::string& problem) { throw ArgumentError(std::string(caller) + ": " + problem); };
  if (!body.joint_rest.empty() && body.joint_rest.size() != n)
    fail("the body has " + std::to_string(body.joint_rest.size()) + " joint pivots; expected " + std::to_string(n) +
         " (the skeleton's)");
  if (body.weights.size() != static_cast<std::size_t>(body.rest_vertices.rows()))
    fail("the body has " + std::to_string(body.weights.size()) + " weight lists for " +
         std::to_string(body.rest_vertices.rows()) + " vertices; expected one per vertex");
  const bool has_input = body.input_vertices.rows() > 0;
  if (has_input && (body.input_vertices.rows() != body.rest_vertices.rows() || body.input_joints.size() != n ||
                    body.rest_correction.size() != n))
    fail("the body's input mesh (" + std::to_string(body.input_vertices.rows()) + " vertices, " +
         std::to_string(body.input_joints.size()) + " joints, " + std::to_string(body.rest_correction.size()) +
         " corrections) does not match its " + std::to_string(body.rest_vertices.rows()) + " vertices and the " +
         std::to_string(n) + " joints of the skeleton");
}

}  // namespace

namespace {

/// Per joint, the rotation taking the skinning source (the input mesh in its
/// own pose, or the rest mesh) to `pose`.
std::vector<Matrix3d> joint_turns(const SkinnedBody& body, const Skeleton& skeleton, const Pose& pose) {
  const std::size_t n = skeleton.joints.size();
  const Pose rest = rest_pose(skeleton);
  const bool from_input = body.input_vertices.rows() > 0;
  std::vector<Matrix3d> turn(n);
  for (std::size_t j = 0; j < n; ++j) {
    turn[j] = pose.global[j].linear() * rest.global[j].linear().transpose();
    if (from_input) turn[j] = turn[j] * body.rest_correction[j];
  }
  return turn;
}

}  // namespace

std::vector<char> turned_triangles(const SkinnedBody& body, const Skeleton& skeleton, const Pose& pose,
                                   const Eigen::MatrixX3d& posed) {
  TurnedTriangles turned(body);
  return turned(skeleton, pose, posed);
}

namespace {
const Eigen::MatrixX3d& source_vertices(const SkinnedBody& body) {
  return body.input_vertices.rows() > 0 ? body.input_vertices : body.rest_vertices;
}
}  // namespace

TurnedTriangles::TurnedTriangles(const SkinnedBody& body) : body_(body) {
  // Checked once here, not in check_body: skin() and mesh_pose() do not
  // read the triangles, and check_body runs every step.
  for (std::size_t t = 0; t < body.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (body.triangles[t][k] < 0 || body.triangles[t][k] >= body.rest_vertices.rows())
        throw ArgumentError("turned_triangles: the body's triangle " + std::to_string(t) + " names vertex " +
                            std::to_string(body.triangles[t][k]) + "; expected an index below " +
                            std::to_string(body.rest_vertices.rows()));
  const Eigen::MatrixX3d& source = source_vertices(body);
  source_normal_.reserve(body.triangles.size());
  // A corner out of the source's range reads as the origin: operator()
  // refuses such a body (check_body) before it uses anything built here.
  const auto row = [&](int v) {
    return v >= 0 && v < source.rows() ? Vector3d(source.row(v).transpose()) : Vector3d::Zero();
  };
  for (const Eigen::Vector3i& tri : body.triangles)
    source_normal_.push_back((row(tri[1]) - row(tri[0])).cross(row(tri[2]) - row(tri[0])));
  // A triangle whose corners all follow one joint alone, each by a positive
  // weight w, moves as that joint turns it, scaled by w: its normal and the
  // carried one are the same rotation of its source normal times w^2 and
  // 3 w, so it never turns over. (On MakeHuman's body with the CMU rig 58 %
  // of the triangles.) Only the others are tested, and only their corners'
  // blends are formed.
  const auto sole_joint = [&](int v) {
    if (v < 0 || static_cast<std::size_t>(v) >= body.weights.size()) return -1;  // check_body's to refuse
    const auto& weights = body.weights[static_cast<std::size_t>(v)];
    return weights.size() == 1 && weights[0].second > 0.0 ? weights[0].first : -1;
  };
  std::vector<char> needed(body.weights.size(), 0);
  for (std::size_t t = 0; t < body.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = body.triangles[t];
    const int joint = sole_joint(tri[0]);
    if (joint >= 0 && sole_joint(tri[1]) == joint && sole_joint(tri[2]) == joint) continue;
    may_turn_.push_back(static_cast<int>(t));
    for (int k = 0; k < 3; ++k)
      if (tri[k] >= 0 && static_cast<std::size_t>(tri[k]) < needed.size()) needed[static_cast<std::size_t>(tri[k])] = 1;
  }
  for (std::size_t v = 0; v < needed.size(); ++v)
    if (needed[v]) blended_.push_back(static_cast<int>(v));
}

const std::vector<char>& TurnedTriangles::operator()(const Skeleton& skeleton, const Pose& pose,
                                                     const Eigen::MatrixX3d& posed) {
  const SkinnedBody& body = body_;
  const std::size_t n = skeleton.joints.size();
  if (pose.global.size() != n)
    throw ArgumentError("turned_triangles: the pose has " + std::to_string(pose.global.size()) + " joints; expected " +
                        std::to_string(n) + " (the skeleton's)");
  check_body(body, n, "turned_triangles");
  const Eigen::MatrixX3d& source = source_vertices(body);
  if (posed.rows() != source.rows())
    throw ArgumentError("turned_triangles: " + std::to_string(posed.rows()) + " posed vertices; expected " +
                        std::to_string(source.rows()));
  const std::vector<Matrix3d> turn = joint_turns(body, skeleton, pose);
  // Per vertex, the linear part of its blend (its first weight's term
  // written, not added to zeros: the same values, one pass fewer over the
  // buffer; a zero's sign may differ, which no sign test below can see).
  blend_.resize(static_cast<std::size_t>(source.rows()));
  for (const int corner : blended_) {
    const auto v = static_cast<std::size_t>(corner);
    const auto& weights = body.weights[v];
    if (weights.empty()) {
      blend_[v].setZero();
      continue;
    }
    blend_[v] = weights[0].second * turn[static_cast<std::size_t>(weights[0].first)];
    for (std::size_t k = 1; k < weights.size(); ++k)
      blend_[v] += weights[k].second * turn[static_cast<std::size_t>(weights[k].first)];
  }
  turned_.assign(body.triangles.size(), 0);
  for (const int may_turn : may_turn_) {
    const auto t = static_cast<std::size_t>(may_turn);
    const Eigen::Vector3i& tri = body.triangles[t];
    const auto row = [&](int v) { return Vector3d(posed.row(v).transpose()); };
    const Vector3d carried = (blend_[static_cast<std::size_t>(tri[0])] + blend_[static_cast<std::size_t>(tri[1])] +
                              blend_[static_cast<std::size_t>(tri[2])]) * source_normal_[t];
    const Vector3d normal = (row(tri[1]) - row(tri[0])).cross(row(tri[2]) - row(tri[0]));
    turned_[t] = normal.dot(carried) < 0.0 ? 1 : 0;
  }
  return turned_;
}

namespace {

/// Whether `joint` is a hand itself (CMU's names), not a finger below one.
bool is_hand(const Joint& joint) { return joint.name == "LeftHand" || joint.name == "RightHand"; }

}  // namespace

std::vector<char> hand_joints(const Skeleton& skeleton) {
  std::vector<char> hand(skeleton.joints.size(), 0);
  // Parents precede their children, so one pass carries the flag down.
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    const bool below = joint.parent >= 0 && hand[static_cast<std::size_t>(joint.parent)];
    hand[j] = is_hand(joint) || below ? 1 : 0;
  }
  return hand;
}

std::vector<int> hand_vertices(const SkinnedBody& body, const Skeleton& skeleton) {
  const std::vector<char> hand = hand_joints(skeleton);
  std::vector<int> out(body.weights.size(), -1);
  for (std::size_t v = 0; v < body.weights.size(); ++v) {
    double on_hands = 0.0, heaviest = -1.0;
    int joint = -1;
    for (const auto& [j, w] : body.weights[v]) {
      if (j < 0 || static_cast<std::size_t>(j) >= hand.size() || !hand[static_cast<std::size_t>(j)]) continue;
      on_hands += w;
      if (w > heaviest) {
        heaviest = w;
        joint = j;
      }
    }
    if (!(on_hands > 0.5)) continue;
    while (joint >= 0 && !is_hand(skeleton.joints[static_cast<std::size_t>(joint)]))
      joint = skeleton.joints[static_cast<std::size_t>(joint)].parent;
    out[v] = joint;
  }
  return out;
}

SkinnedBody without_hands(const SkinnedBody& body, const Skeleton& skeleton) {
  check_body(body, skeleton.joints.size(), "without_hands");
  const std::vector<int> hand = hand_vertices(body, skeleton);
  SkinnedBody out = body;
  out.triangles.clear();
  out.triangle_uvs.clear();  // a body for collisions: drawn from the body with its hands
  for (const Eigen::Vector3i& t : body.triangles)
    if (hand[static_cast<std::size_t>(t[0])] < 0 && hand[static_cast<std::size_t>(t[1])] < 0 &&
        hand[static_cast<std::size_t>(t[2])] < 0)
      out.triangles.push_back(t);
  // The openings: directed edges of the kept triangles whose reverse no
  // kept triangle has, chained head to tail.
  std::map<std::pair<int, int>, int> directed;
  for (const Eigen::Vector3i& t : out.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  std::map<int, int> next;  // boundary edge a -> b, by a
  for (const auto& [edge, count] : directed) {
    if (directed.count({edge.second, edge.first})) continue;
    if (!next.emplace(edge.first, edge.second).second)
      throw ArgumentError("without_hands: vertex " + std::to_string(edge.first) +
                          " starts two edges of the cut's openings; expected one simple opening per hand");
  }
  // One opening for each hand that holds vertices.
  std::set<int> hands_with_vertices(hand.begin(), hand.end());
  hands_with_vertices.erase(-1);
  const int hands = static_cast<int>(hands_with_vertices.size());
  std::vector<std::vector<int>> loops;
  std::set<int> seen;
  for (const auto& [start, unused] : next) {
    if (seen.count(start)) continue;
    std::vector<int> loop;
    for (int v = start; !seen.count(v);) {
      seen.insert(v);
      loop.push_back(v);
      const auto it = next.find(v);
      if (it == next.end())
        throw ArgumentError("without_hands: the opening at vertex " + std::to_string(v) + " does not close");
      v = it->second;
    }
    loops.push_back(std::move(loop));
  }
  if (static_cast<int>(loops.size()) != hands)
    throw ArgumentError("without_hands: cutting the hands off leaves " + std::to_string(loops.size()) +
                        " openings; expected one per hand (" + std::to_string(hands) + ")");
  const bool has_input = body.input_vertices.rows() > 0;
  const Eigen::Index first_new = body.rest_vertices.rows();
  out.rest_vertices.conservativeResize(first_new + static_cast<Eigen::Index>(loops.size()), 3);
  if (has_input) out.input_vertices.conservativeResize(first_new + static_cast<Eigen::Index>(loops.size()), 3);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const std::vector<int>& loop = loops[l];
    const auto centre = static_cast<int>(first_new + static_cast<Eigen::Index>(l));
    Eigen::RowVector3d rest = Eigen::RowVector3d::Zero(), input = Eigen::RowVector3d::Zero();
    std::map<int, double> weights;
    for (int v : loop) {
      rest += body.rest_vertices.row(v);
      if (has_input) input += body.input_vertices.row(v);
      for (const auto& [joint, w] : body.weights[static_cast<std::size_t>(v)]) weights[joint] += w;
    }
    const double n = static_cast<double>(loop.size());
    out.rest_vertices.row(centre) = rest / n;
    if (has_input) out.input_vertices.row(centre) = input / n;
    std::vector<std::pair<int, double>> mean;
    for (const auto& [joint, w] : weights) mean.emplace_back(joint, w / n);
    out.weights.push_back(std::move(mean));
    // The kept triangle has a -> b; the cap's triangle runs b -> a.
    for (int a : loop) out.triangles.emplace_back(next.at(a), a, centre);
  }
  return out;
}

void carry_uvs(const SkinnedBody& from, SkinnedBody& to) {
  to.triangle_uvs.clear();
  if (from.triangle_uvs.size() != from.triangles.size()) return;
  std::map<std::array<int, 3>, std::size_t> same;  // a triangle of `from`, as its corners run, to its index
  std::map<int, Eigen::Vector2d> at_vertex;
  for (std::size_t t = 0; t < from.triangles.size(); ++t) {
    const Eigen::Vector3i& c = from.triangles[t];
    same[{c[0], c[1], c[2]}] = t;
    for (int k = 0; k < 3; ++k) at_vertex.emplace(c[k], from.triangle_uvs[t][static_cast<std::size_t>(k)]);
  }
  for (const Eigen::Vector3i& c : to.triangles) {
    if (const auto found = same.find({c[0], c[1], c[2]}); found != same.end()) {
      to.triangle_uvs.push_back(from.triangle_uvs[found->second]);
      continue;
    }
    std::array<Eigen::Vector2d, 3> uvs;
    Eigen::Vector2d fallback = Eigen::Vector2d::Zero();
    for (int k = 2; k >= 0; --k)
      if (const auto uv = at_vertex.find(c[k]); uv != at_vertex.end()) fallback = uv->second;
    for (int k = 0; k < 3; ++k) {
      const auto uv = at_vertex.find(c[k]);
      uvs[static_cast<std::size_t>(k)] = uv != at_vertex.end() ? uv->second : fallback;
    }
    to.triangle_uvs.push_back(uvs);
  }
}

Eigen::MatrixX3d skin(const SkinnedBody& body, const Skeleton& skeleton, const Pose& pose) {
  const std::size_t n = skeleton.joints.size();
  if (pose.global.size() != n) {
    throw ArgumentError("skin: the pose has " + std::to_string(pose.global.size()) + " joints; expected " +
                        std::to_string(n) + " (the skeleton's)");
  }
  check_body(body, n, "skin");
  // Skin from the input mesh when there is one (its own pose, undone by the
  // rest correction), else from the rest mesh.
  const bool from_input = body.input_vertices.rows() > 0;
  const Eigen::MatrixX3d& source = from_input ? body.input_vertices : body.rest_vertices;
  const Pose rest = rest_pose(skeleton);
  std::vector<Vector3d> pivot_source(n);
  for (std::size_t j = 0; j < n; ++j) {
    pivot_source[j] = from_input ? body.input_joints[j]
                      : body.joint_rest.empty() ? rest.position(static_cast<int>(j))
                                                : body.joint_rest[j];
  }

  // Per joint, once per pose: the rotation relative to the source pose, and
  // where the pivot goes, carried down the body's own chain (the body keeps
  // its bone lengths; only rotations and the root's motion come from the
  // skeleton).
  const std::vector<Matrix3d> turn = joint_turns(body, skeleton, pose);
  std::vector<Vector3d> pivot(n), shift(n);
  for (std::size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent < 0) {
      pivot[j] = pose.position(static_cast<int>(j)) + turn[j] * (pivot_source[j] - rest.position(static_cast<int>(j)));
    } else {
      const auto p = static_cast<std::size_t>(parent);
      pivot[j] = pivot[p] + turn[p] * (pivot_source[j] - pivot_source[p]);
    }
    shift[j] = pivot[j] - turn[j] * pivot_source[j];
  }

  Eigen::MatrixX3d out(source.rows(), 3);
  for (Eigen::Index v = 0; v < source.rows(); ++v) {
    const Vector3d x = source.row(v).transpose();
    Vector3d y = Vector3d::Zero();
    for (const auto& [joint, w] : body.weights[static_cast<std::size_t>(v)]) {
      if (joint < 0 || static_cast<std::size_t>(joint) >= n)
        throw ArgumentError("skin: vertex " + std::to_string(v) + " is weighted to joint " + std::to_string(joint) +
                            "; expected a joint index below " + std::to_string(n));
      const auto j = static_cast<std::size_t>(joint);
      y += w * (turn[j] * x + shift[j]);
    }
    out.row(v) = y.transpose();
  }
  return out;
}

Pose mesh_pose(const SkinnedBody& body, const Skeleton& skeleton) {
  const std::size_t n = skeleton.joints.size();
  check_body(body, n, "mesh_pose");
  Pose pose = rest_pose(skeleton);
  if (body.input_vertices.rows() == 0) return pose;
  for (std::size_t j = 0; j < n; ++j) {
    const Matrix3d global = body.rest_correction[j].transpose() * pose.global[j].linear();
    const int parent = skeleton.joints[j].parent;
    Vector3d position = pose.global[j].translation();
    if (parent >= 0) {
      const Eigen::Isometry3d& up = pose.global[static_cast<std::size_t>(parent)];
      position = up.translation() + up.linear() * skeleton.joints[j].offset;
    }
    pose.global[j].linear() = global;
    pose.global[j].translation() = position;
  }
  return pose;
}

}  // namespace mrcloth
