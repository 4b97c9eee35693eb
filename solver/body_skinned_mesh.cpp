#include "body_skinned_mesh.h"

#include "json_lite.h"
#include "mesh_ops/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mrcloth {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// ---------------------------------------------------------------------------
// base.obj: all vertices (the skeleton's joints are means of helper vertices
// beyond the body), and the faces of one group.

struct ObjData {
  std::vector<Vector3d> vertices;            ///< every 'v' line, file units
  std::vector<std::vector<int>> group_faces;  ///< 0-based vertex indices of the faces in the group
};

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

[[noreturn]] void obj_error(const std::string& path, int line, const std::string& problem, const std::string& expected) {
  throw InputError(path + ":" + std::to_string(line) + ": " + problem + "; expected " + expected);
}

ObjData read_obj_group(const std::string& path, std::string_view group) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file for reading; expected a readable OBJ file");
  ObjData obj;
  std::vector<int> face_lines;
  bool in_group = false;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    const std::vector<std::string_view> words = split_words(text);
    if (words.empty() || words[0][0] == '#') continue;
    if (words[0] == "v") {
      if (words.size() < 4) obj_error(path, line, "a vertex with fewer than 3 coordinates", "v x y z");
      Vector3d v;
      for (int k = 0; k < 3; ++k) {
        const std::string_view word = words[static_cast<std::size_t>(k) + 1];
        const auto result = std::from_chars(word.data(), word.data() + word.size(), v(k));
        if (result.ec != std::errc() || result.ptr != word.data() + word.size() || !std::isfinite(v(k)))
          obj_error(path, line, "vertex coordinate \"" + std::string(word) + "\" is not a finite number", "v x y z");
      }
      obj.vertices.push_back(v);
    } else if (words[0] == "g" || words[0] == "o") {
      in_group = std::find(words.begin() + 1, words.end(), group) != words.end();
    } else if (words[0] == "f" && in_group) {
      if (words.size() < 4) obj_error(path, line, "a face with fewer than 3 vertices", "f v1 v2 v3 ...");
      std::vector<int> face;
      for (std::size_t k = 1; k < words.size(); ++k) {
        const std::string_view word = words[k].substr(0, words[k].find('/'));
        long index = 0;
        const auto result = std::from_chars(word.data(), word.data() + word.size(), index);
        if (result.ec != std::errc() || result.ptr != word.data() + word.size() || index == 0)
          obj_error(path, line, "face vertex \"" + std::string(words[k]) + "\" has no vertex index", "v, v/vt, v//vn or v/vt/vn with v != 0");
        // Negative indices count back from the last vertex read so far.
        const long resolved = index > 0 ? index - 1 : static_cast<long>(obj.vertices.size()) + index;
        if (resolved < 0) obj_error(path, line, "face vertex " + std::to_string(index) + " is before the first vertex", "an index of a vertex");
        face.push_back(static_cast<int>(resolved));
      }
      obj.group_faces.push_back(std::move(face));
      face_lines.push_back(line);
    }
  }
  if (in.bad()) throw InputError(path + ": read error; expected a readable OBJ file");
  if (obj.group_faces.empty())
    throw InputError(path + ": no faces in group \"" + std::string(group) + "\"; expected the body as group \"" + std::string(group) + "\"");
  for (std::size_t f = 0; f < obj.group_faces.size(); ++f)
    for (int v : obj.group_faces[f])
      if (v >= static_cast<int>(obj.vertices.size()))
        obj_error(path, face_lines[f], "face vertex " + std::to_string(v + 1) + " does not exist",
                  "an index <= " + std::to_string(obj.vertices.size()));
  return obj;
}

// ---------------------------------------------------------------------------
// The MakeHuman rig: joints (means of mesh vertices), bones, weights.

struct RigBone {
  std::string head, tail;                ///< joint names
  std::string parent;                    ///< the parent bone's name; empty for the root
  std::vector<std::string> weight_bones;  ///< default-skeleton bones whose weights this bone takes
};

/// The mhskel name of a skeleton joint (the BVH calls the index finger
/// "...HandIndex1", MakeHuman's CMU rig "...HandFinger1").
std::string rig_name(const std::string& joint) {
  if (joint == "LeftHandIndex1") return "LeftHandFinger1";
  if (joint == "RightHandIndex1") return "RightHandFinger1";
  return joint;
}

std::vector<std::string> unique_strings(const JsonValue& list, const std::string& what) {
  std::vector<std::string> out;
  for (const JsonValue& item : list.as_array(what)) {
    const std::string& name = item.as_string(what + " entry");
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  }
  return out;
}

/// Joint positions (file units) by name, each the mean of the listed vertices.
std::map<std::string, Vector3d> rig_joints(const JsonValue& rig, const std::vector<Vector3d>& vertices) {
  std::map<std::string, Vector3d> joints;
  for (const auto& [name, list] : rig.at("joints", "the skeleton file").as_object("\"joints\"")) {
    const std::string what = "joint \"" + name + "\"";
    const std::vector<JsonValue>& indices = list.as_array(what);
    if (indices.empty()) list.fail(what + " lists no vertices; expected at least one vertex index");
    Vector3d sum = Vector3d::Zero();
    for (const JsonValue& item : indices) {
      const int v = item.as_int(what + " vertex");
      if (v < 0 || v >= static_cast<int>(vertices.size()))
        item.fail(what + " lists vertex " + std::to_string(v) + "; expected an index below " + std::to_string(vertices.size()) + " (the base mesh's vertex count)");
      sum += vertices[static_cast<std::size_t>(v)];
    }
    joints[name] = sum / static_cast<double>(indices.size());
  }
  return joints;
}

std::map<std::string, RigBone> rig_bones(const JsonValue& rig, const std::map<std::string, Vector3d>& joints) {
  std::map<std::string, RigBone> bones;
  for (const auto& [name, entry] : rig.at("bones", "the skeleton file").as_object("\"bones\"")) {
    const std::string what = "bone \"" + name + "\"";
    RigBone bone;
    bone.head = entry.at("head", what).as_string(what + " head");
    bone.tail = entry.at("tail", what).as_string(what + " tail");
    for (const std::string* joint : {&bone.head, &bone.tail})
      if (!joints.count(*joint)) entry.fail(what + " names joint \"" + *joint + "\", which \"joints\" does not list; expected a listed joint");
    if (const JsonValue* parent = entry.find("parent"); parent != nullptr && !parent->is_null())
      bone.parent = parent->as_string(what + " parent");
    const JsonValue* weights = entry.find("weights_reference");
    if (weights == nullptr || weights->is_null()) weights = &entry.at("reference", what);
    if (!weights->is_null()) bone.weight_bones = unique_strings(*weights, what + " reference");
    bones[name] = std::move(bone);
  }
  return bones;
}

/// Per body vertex (skeleton joint, weight) pairs, merged by joint.
using VertexWeights = std::vector<std::vector<std::pair<int, double>>>;

void add_weight(std::vector<std::pair<int, double>>& list, int joint, double weight) {
  for (auto& entry : list) {
    if (entry.first == joint) {
      entry.second += weight;
      return;
    }
  }
  list.emplace_back(joint, weight);
}

/// Reads the .mhw weights and maps them to skeleton joints. `joint_of_bone`
/// gives, per default bone, the joints whose rig bones reference it;
/// `body_index` maps base-mesh vertices to body vertices (-1: not in the body).
VertexWeights map_weights(const JsonValue& mhw, const std::map<std::string, std::vector<int>>& joint_of_bone,
                          const std::vector<int>& body_index, int body_count, int fallback_joint) {
  struct Entry {
    int vertex;
    double weight;
  };
  std::vector<std::pair<std::string, std::vector<Entry>>> bones;
  for (const auto& [name, list] : mhw.at("weights", "the weights file").as_object("\"weights\"")) {
    const std::string what = "weights of \"" + name + "\"";
    std::vector<Entry> entries;
    for (const JsonValue& pair : list.as_array(what)) {
      const std::vector<JsonValue>& items = pair.as_array(what + " entry");
      if (items.size() != 2) pair.fail(what + " has an entry of " + std::to_string(items.size()) + " numbers; expected [vertex, weight]");
      const int v = items[0].as_int(what + " vertex");
      const double w = items[1].as_number(what + " weight");
      if (v < 0 || v >= static_cast<int>(body_index.size()))
        pair.fail(what + " names vertex " + std::to_string(v) + "; expected an index below " + std::to_string(body_index.size()));
      if (!(w >= 0.0) || !std::isfinite(w)) pair.fail(what + " has a negative or non-finite weight; expected a weight >= 0");
      const int b = body_index[static_cast<std::size_t>(v)];
      if (b >= 0 && w > 0.0) entries.push_back({b, w});
    }
    bones.emplace_back(name, std::move(entries));
  }

  VertexWeights weights(static_cast<std::size_t>(body_count));
  for (const auto& [name, entries] : bones) {
    const auto found = joint_of_bone.find(name);
    if (found == joint_of_bone.end()) continue;
    for (int joint : found->second)
      for (const Entry& e : entries) add_weight(weights[static_cast<std::size_t>(e.vertex)], joint, e.weight);
  }
  // Default bones no rig bone lists (face, jaw, breasts, eyes, the last
  // thumb joint): MakeHuman hands their weights to the nearest listed
  // ancestor in its default skeleton, which is not among our files; the
  // rig bone whose weights overlap theirs most on the same vertices stands
  // in for it (jaw and face -> Head, breasts -> Spine, thumb tip -> thumb).
  std::vector<std::pair<const std::vector<Entry>*, int>> extra;
  for (const auto& [name, entries] : bones) {
    if (joint_of_bone.count(name)) continue;
    std::map<int, double> overlap;
    for (const Entry& e : entries)
      for (const auto& [joint, w] : weights[static_cast<std::size_t>(e.vertex)]) overlap[joint] += e.weight * w;
    int best = -1;
    double best_score = 0.0;
    for (const auto& [joint, score] : overlap) {
      if (score > best_score) {
        best = joint;
        best_score = score;
      }
    }
    if (best >= 0) extra.emplace_back(&entries, best);
  }
  for (const auto& [entries, joint] : extra)
    for (const Entry& e : *entries) add_weight(weights[static_cast<std::size_t>(e.vertex)], joint, e.weight);

  for (auto& list : weights) {
    double total = 0.0;
    for (const auto& entry : list) total += entry.second;
    if (!(total > 0.0)) {
      list.assign(1, {fallback_joint, 1.0});
      continue;
    }
    for (auto& entry : list) entry.second /= total;
    std::sort(list.begin(), list.end());
  }
  return weights;
}

// ---------------------------------------------------------------------------
// Binding: rest corrections and the T-pose mesh.

constexpr double kCoincident = 1e-9;  ///< metres: joints closer than this coincide

struct Binding {
  std::vector<Matrix3d> correction;  ///< per joint: global rotation mesh -> rest space
  std::vector<Vector3d> head;        ///< per joint: mesh position of the bone's head (metres, aligned)
  std::vector<Vector3d> pivot;       ///< per joint: the corrected head (joint_rest)
};

/// The rest correction of every joint, parents first. A bone takes its
/// parent's correction composed with the smallest rotation turning its
/// (parent-corrected) mesh direction onto the skeleton's rest direction
/// towards the child that direction is closest to (an End Site counts).
/// Bones keep their parent's correction when the skeleton gives them no
/// direction: every child coincides with them (Hips, Spine1, the hands), or
/// they are one of several branches leaving their parent's joint (the hip,
/// lower back, neck, shoulder, finger and thumb branches; in CMU they leave
/// at the parent's point, in DAZ's skeleton a little apart) -- their rest
/// directions describe where the capture subject's branches leave the
/// pelvis, chest or hand, not a pose, and aligning them bends the pelvis
/// and chest out of shape (the CMU hip branch is 36 deg off the mesh's, the
/// DAZ buttock bone points backwards). The root keeps the identity: the mesh
/// already faces +Z with Y up, as the skeleton does.
Binding bind_skeleton(const Skeleton& skeleton, const Pose& rest, const std::vector<Vector3d>& heads,
                      const std::vector<Vector3d>& tails, const std::vector<bool>& has_bone) {
  const std::size_t n = skeleton.joints.size();
  std::vector<std::vector<int>> children(n);
  for (std::size_t j = 0; j < n; ++j)
    if (skeleton.joints[j].parent >= 0) children[static_cast<std::size_t>(skeleton.joints[j].parent)].push_back(static_cast<int>(j));

  Binding binding;
  binding.correction.assign(n, Matrix3d::Identity());
  binding.head = heads;
  binding.pivot.assign(n, Vector3d::Zero());
  for (std::size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    const Vector3d rest_j = rest.position(static_cast<int>(j));
    if (parent < 0) {
      binding.pivot[j] = has_bone[j] ? heads[j] : rest_j;
      continue;
    }
    const auto p = static_cast<std::size_t>(parent);
    const Matrix3d& inherited = binding.correction[p];
    binding.correction[j] = inherited;
    if (!has_bone[j]) {
      // End Sites (and joints the rig has no bone for) follow the skeleton's offset.
      binding.pivot[j] = binding.pivot[p] + (rest_j - rest.position(parent));
      continue;
    }
    binding.pivot[j] = binding.pivot[p] + inherited * (heads[j] - heads[p]);

    const bool branch = children[p].size() > 1;
    const Vector3d mesh_direction = inherited * (tails[j] - heads[j]);
    if (branch || mesh_direction.norm() <= kCoincident) continue;
    Vector3d best = Vector3d::Zero();
    double best_cos = -2.0;
    for (int c : children[j]) {
      const Vector3d offset = rest.position(c) - rest_j;
      if (offset.norm() <= kCoincident) continue;
      const double cos_angle = offset.normalized().dot(mesh_direction.normalized());
      if (cos_angle > best_cos) {
        best_cos = cos_angle;
        best = offset;
      }
    }
    if (best_cos < -1.5) continue;  // no child away from the joint: no direction
    const Matrix3d turn = Eigen::Quaterniond::FromTwoVectors(mesh_direction, best).toRotationMatrix();
    binding.correction[j] = turn * inherited;
  }
  return binding;
}

// ---------------------------------------------------------------------------
// MeshBody geometry helpers.

/// Which part of a triangle is closest: its interior, a vertex or an edge
/// (edge k runs from corner k to corner k+1).
enum Feature : int { kFace = 0, kVertex0 = 1, kVertex1 = 2, kVertex2 = 3, kEdge0 = 4, kEdge1 = 5, kEdge2 = 6 };

struct TrianglePoint {
  Vector3d point;
  double b0, b1, b2;  ///< barycentric coordinates of point
  int feature;
};

/// Closest point of triangle (a, b, c) to p, with the feature it lies on
/// (Ericson, Real-Time Collision Detection, 5.1.5: Voronoi regions tested
/// by signs of dot products, so the feature is consistent with the point).
TrianglePoint closest_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, 1.0, 0.0, 0.0, kVertex0};
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, 0.0, 1.0, 0.0, kVertex1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, 1.0 - v, v, 0.0, kEdge0};
  }
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, 0.0, 0.0, 1.0, kVertex2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, 1.0 - w, 0.0, w, kEdge2};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), 0.0, 1.0 - w, w, kEdge1};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // A degenerate (zero-area) triangle that no region above claimed: its
    // closest point lies on one of its edges.
    TrianglePoint best{a, 1.0, 0.0, 0.0, kVertex0};
    double best_d2 = std::numeric_limits<double>::infinity();
    const Vector3d corners[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Vector3d& s = corners[k];
      const Vector3d e = corners[(k + 1) % 3] - s;
      const double len2 = e.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((p - s).dot(e) / len2, 0.0, 1.0) : 0.0;
      const Vector3d q = s + t * e;
      const double d2q = (p - q).squaredNorm();
      if (d2q < best_d2) {
        best_d2 = d2q;
        double bary[3] = {0.0, 0.0, 0.0};
        bary[k] = 1.0 - t;
        bary[(k + 1) % 3] = t;
        best = {q, bary[0], bary[1], bary[2], kEdge0 + k};
      }
    }
    return best;
  }
  const double v = vb / sum, w = vc / sum;
  return {a + ab * v + ac * w, 1.0 - v - w, v, w, kFace};
}

}  // namespace

MakeHumanOptions makehuman_files(const std::string& folder) {
  MakeHumanOptions files;
  files.base_obj = folder + "/base.obj";
  files.skeleton_file = folder + "/rigs/cmu_mb.mhskel";
  files.weights_file = folder + "/rigs/default_weights.mhw";
  return files;
}

// ---------------------------------------------------------------------------
// load_makehuman_body

SkinnedBody load_makehuman_body(const MakeHumanOptions& files, const Skeleton& skeleton) {
  constexpr double kMetresPerUnit = 0.1;  // base.obj is in decimetres
  const ObjData obj = read_obj_group(files.base_obj, "body");
  std::vector<Vector3d> all_vertices = obj.vertices;
  for (Vector3d& v : all_vertices) v *= kMetresPerUnit;

  const JsonValue rig = read_json(files.skeleton_file);
  const JsonValue mhw = read_json(files.weights_file);
  const std::map<std::string, Vector3d> joints = rig_joints(rig, all_vertices);
  const std::map<std::string, RigBone> bones = rig_bones(rig, joints);

  // Rig bone <-> skeleton joint, by name. A joint the rig has no bone for
  // (a DAZ skeleton's eyes and finger links) carries no skin and follows
  // its parent; a bone the skeleton has no joint for (DAZ has no Spine,
  // Neck1 or toes) hands its skin to its nearest ancestor that has one.
  const std::size_t n = skeleton.joints.size();
  if (n == 0) throw InputError(files.skeleton_file + ": the skeleton to bind to has no joints; expected a CMU skeleton");
  std::vector<const RigBone*> bone_of(n, nullptr);
  std::map<std::string, int> joint_of_rig_bone;
  for (std::size_t j = 0; j < n; ++j) {
    if (skeleton.joints[j].end_site) continue;
    const auto found = bones.find(rig_name(skeleton.joints[j].name));
    if (found == bones.end()) continue;
    bone_of[j] = &found->second;
    joint_of_rig_bone[found->first] = static_cast<int>(j);
  }
  if (!bone_of[0]) {
    std::string root_bone;
    for (const auto& [name, bone] : bones)
      if (bone.parent.empty()) root_bone = name;
    throw InputError(files.skeleton_file + ": the skeleton's root joint \"" + skeleton.joints[0].name +
                     "\" has no bone in the rig; expected the rig's root \"" + root_bone +
                     "\" (the CMU MotionBuilder names; rename the motion's joints onto them)");
  }
  // Each rig bone's skin goes to its own joint or its nearest ancestor's.
  const auto joint_taking = [&](const std::string& bone_name) {
    std::string at = bone_name;
    for (std::size_t guard = 0; guard <= bones.size(); ++guard) {
      const auto joint = joint_of_rig_bone.find(at);
      if (joint != joint_of_rig_bone.end()) return joint->second;
      const auto bone = bones.find(at);
      if (bone == bones.end() || bone->second.parent.empty()) break;
      at = bone->second.parent;
    }
    return 0;  // no bound ancestor (a second root): the skeleton's root
  };

  // Align: the mesh's hip joints' midpoint on the skeleton's (leg lengths
  // agree within 1 %, so the feet meet the skeleton's ground; the two Hips
  // joints do not: the CMU one sits 9.8 cm above its hip joints, MakeHuman's
  // 2.4 cm). Without both hip joints, the roots are aligned.
  const Pose rest = rest_pose(skeleton);
  const int left_hip = skeleton.find("LeftUpLeg"), right_hip = skeleton.find("RightUpLeg");
  const int root = 0;
  Vector3d offset;
  if (left_hip >= 0 && right_hip >= 0 && bone_of[static_cast<std::size_t>(left_hip)] && bone_of[static_cast<std::size_t>(right_hip)]) {
    const Vector3d mesh_mid = 0.5 * (joints.at(bone_of[static_cast<std::size_t>(left_hip)]->head) +
                                     joints.at(bone_of[static_cast<std::size_t>(right_hip)]->head));
    offset = 0.5 * (rest.position(left_hip) + rest.position(right_hip)) - mesh_mid;
  } else {
    offset = rest.position(root) - joints.at(bone_of[root] ? bone_of[root]->head : bones.begin()->second.head);
  }

  std::vector<Vector3d> heads(n, Vector3d::Zero()), tails(n, Vector3d::Zero());
  std::vector<bool> has_bone(n, false);
  for (std::size_t j = 0; j < n; ++j) {
    if (!bone_of[j]) continue;
    has_bone[j] = true;
    heads[j] = joints.at(bone_of[j]->head) + offset;
    tails[j] = joints.at(bone_of[j]->tail) + offset;
  }
  const Binding binding = bind_skeleton(skeleton, rest, heads, tails, has_bone);

  // Body vertices: those the group's faces use, in file order.
  std::vector<int> body_index(all_vertices.size(), -1);
  for (const auto& face : obj.group_faces)
    for (int v : face) body_index[static_cast<std::size_t>(v)] = 0;
  int body_count = 0;
  for (int& index : body_index)
    if (index == 0) index = body_count++;

  SkinnedBody body;
  body.obj_offset = offset;
  for (const auto& face : obj.group_faces) {
    // Quads (and larger polygons) as fans from their first corner.
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      body.triangles.emplace_back(body_index[static_cast<std::size_t>(face[0])], body_index[static_cast<std::size_t>(face[k])],
                                  body_index[static_cast<std::size_t>(face[k + 1])]);
    }
  }

  std::map<std::string, std::vector<int>> joint_of_bone;
  for (std::size_t j = 0; j < n; ++j)
    if (bone_of[j])
      for (const std::string& name : bone_of[j]->weight_bones) joint_of_bone[name].push_back(static_cast<int>(j));
  for (const auto& [name, bone] : bones) {
    if (joint_of_rig_bone.count(name)) continue;
    const int j = joint_taking(name);
    for (const std::string& weight_bone : bone.weight_bones) joint_of_bone[weight_bone].push_back(j);
  }
  const int hips = skeleton.find("Hips");
  body.weights = map_weights(mhw, joint_of_bone, body_index, body_count, hips >= 0 ? hips : root);

  body.rest_vertices.resize(body_count, 3);
  for (std::size_t v = 0; v < all_vertices.size(); ++v) {
    const int b = body_index[v];
    if (b < 0) continue;
    const Vector3d x = all_vertices[v] + offset;
    Vector3d bound_x = Vector3d::Zero();
    for (const auto& [joint, w] : body.weights[static_cast<std::size_t>(b)]) {
      const auto j = static_cast<std::size_t>(joint);
      bound_x += w * (binding.pivot[j] + binding.correction[j] * (x - binding.head[j]));
    }
    body.rest_vertices.row(b) = bound_x.transpose();
  }
  body.joint_rest = binding.pivot;
  // The input pose's joints: the rest pivots carried back through the
  // corrections along the chain, so that skinning the input in the rest
  // pose gives exactly the bound rest_vertices above.
  body.rest_correction = binding.correction;
  body.input_joints.assign(n, Vector3d::Zero());
  for (std::size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent < 0) {
      body.input_joints[j] = binding.pivot[j];
      continue;
    }
    const auto p = static_cast<std::size_t>(parent);
    body.input_joints[j] =
        body.input_joints[p] + binding.correction[p].transpose() * (binding.pivot[j] - binding.pivot[p]);
  }
  body.input_vertices.resize(body_count, 3);
  for (std::size_t v = 0; v < all_vertices.size(); ++v)
    if (body_index[v] >= 0) body.input_vertices.row(body_index[v]) = (all_vertices[v] + offset).transpose();
  return body;
}

// ---------------------------------------------------------------------------
// skin

namespace {

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
  const Eigen::MatrixX3d& source = source_vertices(body);
  source_normal_.reserve(body.triangles.size());
  const auto row = [&](int v) { return Vector3d(source.row(v).transpose()); };
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

// ---------------------------------------------------------------------------
// MeshBody
//
// Our own BVH, not CGAL's AABB tree: CGAL's tree cannot be refit, so the
// body would be rebuilt every step. Measured on the 26,756-triangle body in
// a walk (Release, one thread of a shared 2-core Xeon VM): CGAL 5.5
// AABB_tree build + accelerate_distance_queries 22 ms (10 ms without the
// kd-tree), ours refit 0.3 ms (build once ~30 ms); closest point for points
// 0-1 cm from the body ~4 us ours vs ~6 us CGAL, 1-5 cm 7 vs 9 us, 5-15 cm
// 8-9 vs 12 us. The surface-area heuristic's splits (instead of medians)
// then took points within 3 mm from 2.7-3.2 to 2.2 us, within 3 cm from 5.0
// to 4.0 us (walk frame 100, 20,000 points, same machine).

struct MeshBody::Impl {
  static constexpr int kLeafSize = 4;
  static constexpr int kStackSize = 96;
  static constexpr int kStackSize4 = 3 * kStackSize;  ///< a 4-wide node pushes up to 3 more than it pops, at half the binary depth
  static constexpr int kMaxSahDepth = 40;  ///< below this the build splits at medians (depth stays < 40 + log2 n < kStackSize)
  static constexpr int kMaxSweeps = 8;
  /// Beyond thickness, how far the bounded search looks (metres): only a
  /// cost trade-off (points farther than this outside are clear, deeper
  /// inside go to the unbounded search), never a change of result.
  static constexpr double kMargin = 0.05;
  /// Beyond this distance from the nearest seen triangle, while some are
  /// left out, the side comes from the whole mesh (inside_whole_mesh),
  /// metres: well outside the thickness layer, where pushes are decided.
  static constexpr double kWholeMeshSideBeyond = 0.01;
  /// A resolve's search looks twice this far (metres) beyond the nearest
  /// surface for triangles the point is behind, so it vouches for the
  /// point's side at most this far (SurfaceNearby::flip).
  static constexpr double kFlipReach = 0.0025;

  /// An internal node holding both children's boxes (one 64-byte line
  /// decides both), stored as floats rounded outwards: a box can only grow,
  /// so pruning stays conservative and results exact, at half the memory.
  struct Node {
    float lo[2][3], hi[2][3];
    int index[2] = {-1, -1};  ///< child k: node index if internal, first triangle if a leaf, -1 if none
    int count[2] = {0, 0};    ///< child k: triangles in the leaf, 0 if internal (or none)
  };

  struct Closest {
    double d2 = std::numeric_limits<double>::infinity();
    int triangle = -1;
    TrianglePoint at{Vector3d::Zero(), 0.0, 0.0, 0.0, kFace};
  };

  struct Contact {
    double distance = 0.0;  ///< signed, negative inside
    Vector3d normal{0, 1, 0};
    int triangle = -1;
    double b0 = 0, b1 = 0, b2 = 0;
  };

  /// Every seen triangle within `radius` of `centre`, as a search found
  /// them: the later searches of the same resolve that stay inside that
  /// ball read them instead of the tree. Empty (radius 0) when there were
  /// more than fit.
  struct Candidates {
    static constexpr int kCapacity = 96;
    int items[kCapacity];
    int count = 0;
    Vector3d centre{0, 0, 0};
    double radius = 0.0;
    /// Whether they hold every triangle within sqrt(search2) of p.
    bool cover(const Vector3d& p, double search2) const {
      return radius > 0.0 && (p - centre).norm() + std::sqrt(search2) <= radius;
    }
  };

  std::vector<Node> nodes;
  /// Per node, its children's boxes over both of the last two poses (what
  /// each subtree swept through between the last two updates, if its
  /// vertices moved in straight lines), rounded outwards as Node's.
  struct SweptBoxes {
    float lo[2][3], hi[2][3];
  };
  std::vector<SweptBoxes> swept;
  /// Four boxes, per axis (an empty one: lo +inf, hi -inf, never near).
  struct Boxes4 {
    float lo[3][4], hi[3][4];
  };
  /// The same tree with every other level skipped, for the proximity
  /// searches: a node holds its grandchildren's boxes (or a child's, where
  /// that child is a leaf), axis by axis, so one pass over four lanes
  /// measures all of them: half the levels and a quarter of the branches.
  /// Segment walks use the binary tree (with its swept boxes).
  struct alignas(64) Node4 {
    Boxes4 boxes;  ///< each child's box
    int index[4];  ///< child k: Node4 index if internal, first triangle if a leaf, -1 if none
    int count[4];  ///< child k: triangles in the leaf, 0 if internal (or none)
  };
  std::vector<Node4> nodes4;
  /// Per leaf, its triangles' boxes in the current pose, rounded outwards,
  /// four side by side, so a visited leaf tests them together (one pass
  /// over four lanes, as a node's children) instead of one after another;
  /// per triangle (leaf order), its box's place there: 4 * block + lane.
  std::vector<Boxes4> leaf_boxes;
  std::vector<int> box_slot;
  /// Per Node4 child, the binary node and side whose child box it copies
  /// at each refit ({-1, 0}: none).
  std::vector<std::array<std::pair<int, int>, 4>> source4;
  std::vector<Eigen::Vector3i> triangles;      ///< in leaf order
  std::vector<int> leaf_of_input;              ///< per triangle in construction order, its leaf-order index
  std::vector<char> ignored;                   ///< per triangle (leaf order): unseen in this pose (turned over)
  std::vector<int> ignored_list;               ///< the ignored triangles (leaf order): a few dozen on a walking body
  std::vector<char> on_rim;                    ///< per triangle (leaf order): seen, with a corner on an ignored one
  std::vector<int> rim_list;                   ///< the triangles on_rim marks
  bool any_ignored = false;
  std::vector<std::array<int, 3>> neighbours;  ///< triangle across edge k
  std::vector<int> ring_start;                 ///< per vertex, its first entry in ring (one past the end: the next vertex's)
  std::vector<std::pair<int, int>> ring;       ///< (triangle, corner) around each vertex
  std::vector<Vector3d> x, x_previous;         ///< vertex positions now and at the previous update (in number_vertices_by_leaf's order)
  std::vector<int> input_vertex;               ///< per vertex, its row in the input (empty: the input's order)
  Vector3d root_lo{0, 0, 0}, root_hi{0, 0, 0};  ///< the whole mesh's box
  double thickness = 0.0, friction = 0.0;
  unsigned long long serial = 0;  ///< counts update() calls: a memo is only good for the pose it was made in
  double reach2 = 0.0;        ///< (thickness + margin)^2
  double normal_floor = 0.0;  ///< below this distance the pseudo-normal, not p - c, is the normal

  static void require_finite(const Eigen::MatrixX3d& vertices) {
    for (Eigen::Index v = 0; v < vertices.rows(); ++v)
      if (!vertices.row(v).allFinite())
        throw ArgumentError("MeshBody: vertex " + std::to_string(v) + " is not finite; expected finite positions");
  }

  void set_positions(const Eigen::MatrixX3d& vertices) {
    x.resize(static_cast<std::size_t>(vertices.rows()));
    for (std::size_t v = 0; v < x.size(); ++v)
      x[v] = vertices.row(input_vertex.empty() ? static_cast<Eigen::Index>(v) : input_vertex[v]).transpose();
  }

  /// Renumbers the vertices in the order the triangles (in leaf order)
  /// first use them, the unused ones last: a leaf's corners then lie
  /// together in x, not scattered over the input's order.
  void number_vertices_by_leaf() {
    std::vector<int> internal(x.size(), -1);
    input_vertex.clear();
    input_vertex.reserve(x.size());
    for (Eigen::Vector3i& tri : triangles)
      for (int k = 0; k < 3; ++k) {
        int& to = internal[static_cast<std::size_t>(tri(k))];
        if (to < 0) {
          to = static_cast<int>(input_vertex.size());
          input_vertex.push_back(tri(k));
        }
        tri(k) = to;
      }
    for (std::size_t v = 0; v < internal.size(); ++v)
      if (internal[v] < 0) input_vertex.push_back(static_cast<int>(v));
    std::vector<Vector3d> reordered(x.size());
    for (std::size_t v = 0; v < x.size(); ++v) reordered[v] = x[static_cast<std::size_t>(input_vertex[v])];
    x = std::move(reordered);
  }

  /// Builds the subtree of order[begin, end) and returns it as a child
  /// (index, count): a leaf of at most kLeafSize triangles, or a node.
  /// A triangle's box, and the box of a set of them.
  struct Box {
    Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity());
    Vector3d hi = Vector3d::Constant(-std::numeric_limits<double>::infinity());
    void add(const Box& b) {
      lo = lo.cwiseMin(b.lo);
      hi = hi.cwiseMax(b.hi);
    }
    double half_area() const {
      const Vector3d e = (hi - lo).cwiseMax(0.0);
      return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
    }
  };

  /// Builds the subtree of order[begin, end) and returns it as a child
  /// (index, count): a leaf of at most kLeafSize triangles, or a node. The
  /// split is the surface-area heuristic's best of 16 bins per axis (the
  /// expected number of boxes a query opens), falling back to the median
  /// along the widest axis when no bin split separates the triangles or
  /// the tree grows deep (the query's stack is fixed).
  std::pair<int, int> build(std::vector<int>& order, const std::vector<Vector3d>& centroid,
                            const std::vector<Box>& box, int begin, int end, int depth) {
    if (end - begin <= kLeafSize) return {begin, end - begin};
    const auto at = [&](int i) { return static_cast<std::size_t>(order[static_cast<std::size_t>(i)]); };
    Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int i = begin; i < end; ++i) {
      lo = lo.cwiseMin(centroid[at(i)]);
      hi = hi.cwiseMax(centroid[at(i)]);
    }
    constexpr int kBins = 16;
    int best_axis = -1, best_split = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    const auto bin_of = [&](std::size_t t, int axis) {
      const double extent = hi(axis) - lo(axis);
      return std::min(kBins - 1, static_cast<int>(kBins * (centroid[t](axis) - lo(axis)) / extent));
    };
    for (int axis = 0; axis < 3 && depth < kMaxSahDepth; ++axis) {
      if (!(hi(axis) - lo(axis) > 0.0)) continue;
      Box bins[kBins];
      int counts[kBins] = {0};
      for (int i = begin; i < end; ++i) {
        const int b = bin_of(at(i), axis);
        bins[b].add(box[at(i)]);
        ++counts[b];
      }
      // Right-to-left areas and counts, then one left-to-right sweep.
      double right_area[kBins];
      int right_count[kBins];
      Box right;
      int count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        right.add(bins[b]);
        count += counts[b];
        right_area[b] = right.half_area();
        right_count[b] = count;
      }
      Box left;
      count = 0;
      for (int split = 1; split < kBins; ++split) {
        left.add(bins[split - 1]);
        count += counts[split - 1];
        if (count == 0 || right_count[split] == 0) continue;
        const double cost = left.half_area() * count + right_area[split] * right_count[split];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_split = split;
        }
      }
    }
    int mid = 0;
    if (best_axis >= 0) {
      mid = static_cast<int>(std::partition(order.begin() + begin, order.begin() + end,
                                            [&](int t) { return bin_of(static_cast<std::size_t>(t), best_axis) < best_split; }) -
                             order.begin());
    }
    if (best_axis < 0 || mid == begin || mid == end) {
      int axis = 0;
      (hi - lo).maxCoeff(&axis);
      mid = begin + (end - begin) / 2;
      std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](int a, int b) {
        return centroid[static_cast<std::size_t>(a)](axis) < centroid[static_cast<std::size_t>(b)](axis);
      });
    }
    const int index = static_cast<int>(nodes.size());
    nodes.emplace_back();
    const std::pair<int, int> left = build(order, centroid, box, begin, mid, depth + 1);
    const std::pair<int, int> right = build(order, centroid, box, mid, end, depth + 1);
    Node& node = nodes[static_cast<std::size_t>(index)];
    node.index[0] = left.first;
    node.count[0] = left.second;
    node.index[1] = right.first;
    node.count[1] = right.second;
    return {index, 0};
  }

  /// Makes the Node4 of binary node b (and, recursively, of the binary
  /// nodes below it at every other level); returns its index. Called once
  /// the binary tree is built.
  int build4(int b) {
    const int index = static_cast<int>(nodes4.size());
    nodes4.emplace_back();
    source4.emplace_back();
    int slot = 0;
    const auto place = [&](int node, int k) {
      const Node& n = nodes[static_cast<std::size_t>(node)];
      source4[static_cast<std::size_t>(index)][static_cast<std::size_t>(slot)] = {node, k};
      nodes4[static_cast<std::size_t>(index)].count[slot] = n.count[k];
      nodes4[static_cast<std::size_t>(index)].index[slot] = n.index[k];
      const int at = slot++;
      if (n.count[k] > 0) {
        for (int lane = 0; lane < n.count[k]; ++lane)
          box_slot[static_cast<std::size_t>(n.index[k] + lane)] = 4 * static_cast<int>(leaf_boxes.size()) + lane;
        leaf_boxes.push_back(empty_boxes4());
      } else {
        const int child = build4(n.index[k]);  // after this nodes4 may have moved
        nodes4[static_cast<std::size_t>(index)].index[at] = child;
      }
    };
    for (int k = 0; k < 2; ++k) {
      const Node& n = nodes[static_cast<std::size_t>(b)];
      if (n.count[k] == 0 && n.index[k] < 0) continue;
      if (n.count[k] > 0) {
        place(b, k);
        continue;
      }
      const int c = n.index[k];
      for (int k2 = 0; k2 < 2; ++k2) {
        const Node& m = nodes[static_cast<std::size_t>(c)];
        if (m.count[k2] == 0 && m.index[k2] < 0) continue;
        place(c, k2);
      }
    }
    for (; slot < 4; ++slot) {
      source4[static_cast<std::size_t>(index)][static_cast<std::size_t>(slot)] = {-1, 0};
      nodes4[static_cast<std::size_t>(index)].index[slot] = -1;
      nodes4[static_cast<std::size_t>(index)].count[slot] = 0;
    }
    return index;
  }

  static Boxes4 empty_boxes4() {
    Boxes4 b;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 4; ++c) {
        b.lo[a][c] = std::numeric_limits<float>::infinity();
        b.hi[a][c] = -std::numeric_limits<float>::infinity();
      }
    return b;
  }

  /// Copies the binary tree's refit boxes into nodes4.
  void refit4() {
    for (std::size_t i = 0; i < nodes4.size(); ++i) {
      Node4& node = nodes4[i];
      for (int slot = 0; slot < 4; ++slot) {
        const auto [b, k] = source4[i][static_cast<std::size_t>(slot)];
        for (int a = 0; a < 3; ++a) {
          node.boxes.lo[a][slot] = b < 0 ? std::numeric_limits<float>::infinity() : nodes[static_cast<std::size_t>(b)].lo[k][a];
          node.boxes.hi[a][slot] = b < 0 ? -std::numeric_limits<float>::infinity() : nodes[static_cast<std::size_t>(b)].hi[k][a];
        }
      }
    }
  }

  // Outward by 4e-7 relative before the conversion, which rounds by at most
  // 6e-8 relative: the float always lies on the safe side (branch-free; the
  // boxes grow by 0.4 micrometre per metre).
  static float round_down(double v) { return static_cast<float>(v - (std::abs(v) * 4e-7 + 1e-30)); }
  static float round_up(double v) { return static_cast<float>(v + (std::abs(v) * 4e-7 + 1e-30)); }

  /// Children after parents in `nodes`, so one backward pass refits: O(n).
  /// `first`: no earlier pose (x_previous is x), so the swept boxes are
  /// the boxes.
  void refit(bool first = false) {
    swept.resize(nodes.size());
    for (std::size_t i = nodes.size(); i-- > 0;) {
      Node& node = nodes[i];
      SweptBoxes& sweep = swept[i];
      for (int k = 0; k < 2; ++k) {
        if (node.count[k] == 0 && node.index[k] < 0) {
          // No child (a root holding a single leaf): a box nothing is near.
          for (int a = 0; a < 3; ++a) {
            node.lo[k][a] = sweep.lo[k][a] = std::numeric_limits<float>::infinity();
            node.hi[k][a] = sweep.hi[k][a] = -std::numeric_limits<float>::infinity();
          }
          continue;
        }
        Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        if (node.count[k] > 0) {
          for (int t = node.index[k]; t < node.index[k] + node.count[k]; ++t) {
            Vector3d triangle_lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), triangle_hi = -triangle_lo;
            for (int c = 0; c < 3; ++c) {
              const Vector3d& q = corner(t, c);
              triangle_lo = triangle_lo.cwiseMin(q);
              triangle_hi = triangle_hi.cwiseMax(q);
            }
            const int slot = box_slot[static_cast<std::size_t>(t)];
            Boxes4& block = leaf_boxes[static_cast<std::size_t>(slot >> 2)];
            for (int a = 0; a < 3; ++a) {
              block.lo[a][slot & 3] = round_down(triangle_lo(a));
              block.hi[a][slot & 3] = round_up(triangle_hi(a));
            }
            lo = lo.cwiseMin(triangle_lo);
            hi = hi.cwiseMax(triangle_hi);
          }
        } else {
          const Node& child = nodes[static_cast<std::size_t>(node.index[k])];
          for (int a = 0; a < 3; ++a) {
            // Float to double is exact: the union of the child's boxes.
            lo(a) = std::min(child.lo[0][a], child.lo[1][a]);
            hi(a) = std::max(child.hi[0][a], child.hi[1][a]);
          }
        }
        // The box over both poses is the union of this box and the last:
        // rounding outwards is monotonic, so these are the floats that
        // rounding the union of both poses' corners (or of the children's
        // swept boxes) gives.
        for (int a = 0; a < 3; ++a) {
          const float new_lo = round_down(lo(a)), new_hi = round_up(hi(a));
          sweep.lo[k][a] = first ? new_lo : std::min(node.lo[k][a], new_lo);
          sweep.hi[k][a] = first ? new_hi : std::max(node.hi[k][a], new_hi);
          node.lo[k][a] = new_lo;
          node.hi[k][a] = new_hi;
        }
      }
    }
    refit4();
    root_lo = Vector3d::Constant(std::numeric_limits<double>::infinity());
    root_hi = -root_lo;
    for (int k = 0; k < 2; ++k)
      for (int a = 0; a < 3; ++a) {
        root_lo(a) = std::min(root_lo(a), static_cast<double>(nodes[0].lo[k][a]));
        root_hi(a) = std::max(root_hi(a), static_cast<double>(nodes[0].hi[k][a]));
      }
  }

  const Vector3d& corner(int t, int k) const {
    return x[static_cast<std::size_t>(triangles[static_cast<std::size_t>(t)](k))];
  }

  /// Unit normal of triangle t (zero when it is degenerate).
  Vector3d face_normal(int t) const {
    const Vector3d n = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
    const double length = n.norm();
    return length > 0.0 ? Vector3d(n / length) : Vector3d::Zero();
  }

  double root_distance2(const Vector3d& p) const {
    const Vector3d e = (root_lo - p).cwiseMax(p - root_hi).cwiseMax(0.0);
    return e.squaredNorm();
  }

  bool inside_root(const Vector3d& p) const {
    return (p.array() >= root_lo.array()).all() && (p.array() <= root_hi.array()).all();
  }

  /// Tests seen triangle t against the closest so far (`best`, its squared
  /// distance, and `out`); its own box first, which rejects most.
  void consider(const Vector3d& p, int t, double& best, Closest& out) const {
    consider(p, t, triangle_box_distance2(p, t), best, out);
  }
  /// The same with t's box distance `box2` already known.
  void consider(const Vector3d& p, int t, double box2, double& best, Closest& out) const {
    if (!(box2 < best)) return;
    const TrianglePoint at = closest_on_triangle(p, corner(t, 0), corner(t, 1), corner(t, 2));
    const double d2 = (p - at.point).squaredNorm();
    if (d2 < best) {
      best = d2;
      out.d2 = d2;
      out.triangle = t;
      out.at = at;
    }
  }

  /// The four children's squared distances from p (0 inside), in double
  /// (the boxes' floats are exact in it): per axis the gap below or above
  /// the box, squared and summed in axis order, two lanes at a time.
  static void box_distances4(const Boxes4& node, const Vector3d& p, double d[4]) {
#if defined(__SSE2__)
    const __m128d zero = _mm_setzero_pd();
    for (int h = 0; h < 4; h += 2) {
      __m128d sum = zero;
      for (int a = 0; a < 3; ++a) {
        const __m128d at = _mm_set1_pd(p(a));
        const __m128d lo = _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&node.lo[a][h]))));
        const __m128d hi = _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&node.hi[a][h]))));
        const __m128d e = _mm_max_pd(zero, _mm_max_pd(_mm_sub_pd(lo, at), _mm_sub_pd(at, hi)));
        sum = _mm_add_pd(sum, _mm_mul_pd(e, e));
      }
      _mm_storeu_pd(d + h, sum);
    }
#else
    for (int c = 0; c < 4; ++c) d[c] = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 4; ++c) {
        const double below = static_cast<double>(node.lo[a][c]) - p(a);
        const double above = p(a) - static_cast<double>(node.hi[a][c]);
        const double e = std::max(0.0, std::max(below, above));
        d[c] += e * e;
      }
#endif
  }

  /// triangle_box_distance2(p, t) of the leaf's triangles, t from `first`
  /// (the leaf's first triangle) on, together.
  void leaf_box_distances(int first, const Vector3d& p, double d[4]) const {
    box_distances4(leaf_boxes[static_cast<std::size_t>(box_slot[static_cast<std::size_t>(first)] >> 2)], p, d);
  }

  /// Visits the leaves whose box lies nearer to p than sqrt(limit()) (a
  /// bound that may shrink as they are visited), nearer child first, each
  /// leaf as visit(first, count), walking the 4-wide tree; inner nodes wait
  /// on a fixed stack, the nearer on top. No allocation. (Against the
  /// binary tree: the shared skirt refined twice on 07_06, 1.3 million
  /// first-round resolves replayed from a recorded run, 0.87 us each
  /// against 1.23, the same answers but for which of two triangles meeting
  /// at a closest point is named, in 1,752 of them.)
  template <typename Limit, typename Visit>
  void leaves_near(const Vector3d& p, Limit limit, Visit visit) const {
    struct Item {
      int node;
      double d2;
    };
    Item stack[kStackSize4];
    int top = 0;
    const double root_d2 = root_distance2(p);
    if (!(root_d2 < limit())) return;
    stack[top++] = {0, root_d2};
    while (top > 0) {
      const Item item = stack[--top];
      if (!(item.d2 < limit())) continue;
      const Node4& node = nodes4[static_cast<std::size_t>(item.node)];
      double d[4];
      box_distances4(node.boxes, p, d);
      // The children within the bound, nearest first (insertion: few are):
      // leaves visited in that order (the bound may shrink as they are),
      // inner nodes pushed farthest first.
      const double bound = limit();
      int order[4], n = 0;
      for (int c = 0; c < 4; ++c) {
        if (!(d[c] < bound)) continue;
        int k = n++;
        for (; k > 0 && d[c] < d[order[k - 1]]; --k) order[k] = order[k - 1];
        order[k] = c;
      }
      for (int i = 0; i < n; ++i) {
        const int c = order[i];
        if (node.count[c] > 0 && d[c] < limit()) visit(node.index[c], node.count[c]);
      }
      for (int i = n; i-- > 0;) {
        const int c = order[i];
        if (node.count[c] == 0 && node.index[c] >= 0 && d[c] < limit()) stack[top++] = {node.index[c], d[c]};
      }
    }
  }

  /// Closest seen triangle to p closer than sqrt(max_d2); false when none is.
  bool closest(const Vector3d& p, double max_d2, Closest& out) const {
    double best = max_d2;
    leaves_near(p, [&] { return best; }, [&](int first, int count) {
      double box2[4];
      leaf_box_distances(first, p, box2);
      for (int t = first; t < first + count; ++t)
        if (!(any_ignored && ignored[static_cast<std::size_t>(t)])) consider(p, t, box2[t - first], best, out);
    });
    return out.triangle >= 0;
  }

  /// closest(p, max_d2, out), and also the distance to the nearest other
  /// triangle whose plane p is behind, where that is within `margin` of
  /// the nearest's distance (`behind`: that distance, or the nearest's plus
  /// margin when none is; unchanged when there is no nearest). A point
  /// inside by a triangle's closest feature is behind the plane of a
  /// triangle through that feature, no farther away; where skinning drives
  /// one part of the body into another (the thighs, a hand into the hip) p
  /// can be in front of its nearest triangle and inside the other part,
  /// and moving a little then makes the other part's surface the nearest:
  /// its side flips. `out` may hold a first candidate (its d2 the bound).
  bool closest_and_behind(const Vector3d& p, double max_d2, double margin, Closest& out, double& behind,
                          Candidates* candidates = nullptr) const {
    struct Behind {
      double d2 = std::numeric_limits<double>::infinity();
      int triangle = -1;
    } first, second;  // the two nearest triangles p is behind (one may be the nearest itself)
    double best = out.triangle >= 0 ? out.d2 : max_d2;
    const auto limit_of = [&](double b) {
      const double r = std::sqrt(b) + margin;
      return r * r;
    };
    double limit2 = limit_of(best);
    bool overflow = false;
    if (candidates) candidates->count = 0;
    const auto visit = [&](int t, double box2) {
      if (any_ignored && ignored[static_cast<std::size_t>(t)]) return;
      if (!(box2 < limit2)) return;
      if (candidates) {
        if (candidates->count < Candidates::kCapacity) candidates->items[candidates->count++] = t;
        else overflow = true;
      }
      const Vector3d a = corner(t, 0);
      const bool is_behind = (p - a).dot((corner(t, 1) - a).cross(corner(t, 2) - a)) < 0.0;
      if (!(box2 < best) && !is_behind) return;
      const TrianglePoint at = closest_on_triangle(p, a, corner(t, 1), corner(t, 2));
      const double d2 = (p - at.point).squaredNorm();
      if (is_behind && d2 < second.d2 && t != first.triangle) {
        if (d2 < first.d2) {
          second = first;
          first = {d2, t};
        } else {
          second = {d2, t};
        }
      }
      if (d2 < best) {
        best = d2;
        limit2 = limit_of(best);
        out.d2 = d2;
        out.triangle = t;
        out.at = at;
      }
    };
    leaves_near(p, [&] { return limit2; }, [&](int leaf, int count) {
      double box2[4];
      leaf_box_distances(leaf, p, box2);
      for (int t = leaf; t < leaf + count; ++t) visit(t, box2[t - leaf]);
    });
    if (candidates) {
      // Everything pruned lay beyond the limit when it was pruned, and the
      // limit only shrank: the list holds every triangle within it.
      candidates->centre = p;
      candidates->radius = overflow ? 0.0 : std::sqrt(limit2);
    }
    if (out.triangle < 0) return false;
    const Behind& other = first.triangle != out.triangle ? first : second;
    behind = std::min(std::sqrt(other.d2), std::sqrt(best) + margin);
    return true;
  }

  /// The angle-weighted pseudo-normal (Baerentzen and Aanaes 2005) of the
  /// feature of triangle t a closest point lies on, not normalised: the face
  /// normal, the sum of the two face normals at an edge, the sum of the
  /// incident face normals weighted by their angles at a vertex. Formed here
  /// from the current positions rather than stored per update: refits stay
  /// O(n) bounding boxes only, and vertex features are a small share of the
  /// queries.
  Vector3d pseudo_normal(int t, int feature) const {
    const auto ti = static_cast<std::size_t>(t);
    if (feature == kFace) return face_normal(t);
    if (feature >= kEdge0) {
      const int across = neighbours[ti][static_cast<std::size_t>(feature - kEdge0)];
      if (any_ignored && ignored[static_cast<std::size_t>(across)]) return face_normal(t);
      return face_normal(t) + face_normal(across);
    }
    const auto v = static_cast<std::size_t>(triangles[ti](feature - kVertex0));
    Vector3d sum = Vector3d::Zero();
    for (int r = ring_start[v]; r < ring_start[v + 1]; ++r) {
      const auto [u, k] = ring[static_cast<std::size_t>(r)];
      if (any_ignored && ignored[static_cast<std::size_t>(u)]) continue;
      const Vector3d e1 = corner(u, (k + 1) % 3) - corner(u, k);
      const Vector3d e2 = corner(u, (k + 2) % 3) - corner(u, k);
      const Vector3d n = e1.cross(e2);
      const double length = n.norm();
      if (length > 0.0) sum += std::atan2(length, e1.dot(e2)) * (n / length);
    }
    return sum;
  }

  Contact signed_contact(const Vector3d& p, const Closest& c) const {
    Contact contact;
    const Vector3d diff = p - c.at.point;
    const double distance = std::sqrt(c.d2);
    Vector3d pseudo = pseudo_normal(c.triangle, c.at.feature);
    if (!(pseudo.squaredNorm() > 0.0)) pseudo = face_normal(c.triangle);
    bool inside = diff.dot(pseudo) < 0.0;
    // With turned triangles left out the seen surface is open, and a point
    // a few centimetres from it can be nearest to a triangle whose side is
    // the wrong one (on 08_03 a point 29 mm inside the leg was called 22
    // mm outside): there the whole closed mesh decides. Nearer in, it
    // vetoes "inside" where the nearest is on the rim of the hole they
    // leave: above the hole a point outside is behind the rim's side (the
    // shared skirt refined twice on 07_03: a point outside the body,
    // winding number 0, was called 7 mm inside the groin's fold). Not the
    // other way: in the pocket a fold leaves (behind a bent knee) the
    // parity says inside where the seen surface, which the turned skin was
    // left out of so as not to push cloth into the leg, says outside (the
    // walk table's trousers on 02_01: 3 runs then ended 4 mm "inside").
    if (any_ignored && (distance > kWholeMeshSideBeyond || (inside && on_rim[static_cast<std::size_t>(c.triangle)])))
      inside = inside_whole_mesh(p);
    contact.distance = inside ? -distance : distance;
    // The outward normal is the distance field's gradient, (p - c) / |p - c|
    // (signed), so a push along it lands exactly at the new distance; on the
    // surface itself that direction is noise, and the pseudo-normal serves.
    if (distance > normal_floor) contact.normal = (inside ? -diff : diff) / distance;
    else contact.normal = pseudo.squaredNorm() > 0.0 ? pseudo.normalized() : Vector3d::UnitY();
    contact.triangle = c.triangle;
    contact.b0 = c.at.b0;
    contact.b1 = c.at.b1;
    contact.b2 = c.at.b2;
    return contact;
  }

  /// The contact of p if a triangle is closer than sqrt(search2), or, with
  /// `deep`, if p is inside: false means p is outside and at least that far.
  bool contact(const Vector3d& p, double search2, bool deep, Contact& out) const {
    Closest c;
    if (closest(p, search2, c)) {
      out = signed_contact(p, c);
      return true;
    }
    // Nothing within reach: outside (no contact), or deep inside. Only a
    // point inside the root box can be inside; search without bound.
    if (!deep || !inside_root(p)) return false;
    if (!closest(p, std::numeric_limits<double>::infinity(), c)) return false;
    out = signed_contact(p, c);
    return out.distance < 0.0;
  }

  /// Squared distance from p to the bounding box of triangle t (0 inside):
  /// branch-free, and a fraction of the exact test's cost.
  double triangle_box_distance2(const Vector3d& p, int t) const {
    const int slot = box_slot[static_cast<std::size_t>(t)];
    const Boxes4& block = leaf_boxes[static_cast<std::size_t>(slot >> 2)];
    double box2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double below = static_cast<double>(block.lo[k][slot & 3]) - p(k);
      const double above = p(k) - static_cast<double>(block.hi[k][slot & 3]);
      const double e = std::max(0.0, std::max(below, above));
      box2 += e * e;
    }
    return box2;
  }

  /// Whether segment a-b meets the box [lo, hi] (slab test).
  static bool segment_meets_box(const Vector3d& a, const Vector3d& d, const float lo[3], const float hi[3]) {
    double enter = 0.0, leave = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double l = lo[k], h = hi[k];
      if (d(k) == 0.0) {
        if (a(k) < l || a(k) > h) return false;
        continue;
      }
      double t0 = (l - a(k)) / d(k), t1 = (h - a(k)) / d(k);
      if (t0 > t1) std::swap(t0, t1);
      enter = std::max(enter, t0);
      leave = std::min(leave, t1);
      if (enter > leave) return false;
    }
    return true;
  }

  /// Visits the leaves whose box meets the segment a + t d, t in [0, 1]:
  /// their current boxes, or with `over_last_two` their boxes over the last
  /// two poses. `visit(first, count)` (the leaf's triangles) returns false
  /// to stop; the result is false when it stopped.
  template <typename Visit>
  bool leaves_on_segment(const Vector3d& a, const Vector3d& d, bool over_last_two, Visit visit) const {
    int stack[kStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const auto i = static_cast<std::size_t>(stack[--top]);
      const Node& node = nodes[i];
      for (int k = 0; k < 2; ++k) {
        if (node.count[k] == 0 && node.index[k] < 0) continue;
        const float* lo = over_last_two ? swept[i].lo[k] : node.lo[k];
        const float* hi = over_last_two ? swept[i].hi[k] : node.hi[k];
        if (!segment_meets_box(a, d, lo, hi)) continue;
        if (node.count[k] == 0) stack[top++] = node.index[k];
        else if (!visit(node.index[k], node.count[k])) return false;
      }
    }
    return true;
  }

  /// Whether no triangle can have crossed the segment a-b since the last
  /// update but one: no leaf's swept box meets it. A point that moved along
  /// it while the surface moved (straight) between those poses then stayed
  /// on its side. Conservative: a false "no" only costs a query.
  bool segment_clear(const Vector3d& a, const Vector3d& b) const {
    return leaves_on_segment(a, b - a, true, [](int, int) { return false; });
  }

  /// Whether p is inside the closed mesh, every triangle counted (the
  /// ignored ones too): the parity of a ray's crossings, the ray in a
  /// direction no face or edge of a body is likely to be aligned with.
  /// The parity of a closed surface's crossings (self-intersecting too) is
  /// the same along every ray, so the ray leaves by the root box's nearest
  /// face: out of a leg through its front or back, not up through the torso
  /// (a third of the boxes to open on a walking body).
  bool inside_whole_mesh(const Vector3d& p) const {
    if (!inside_root(p)) return false;
    int axis = 0;
    double sign = 1.0, reach = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (p(k) - root_lo(k) < reach) {
        reach = p(k) - root_lo(k);
        axis = k;
        sign = -1.0;
      }
      if (root_hi(k) - p(k) < reach) {
        reach = root_hi(k) - p(k);
        axis = k;
        sign = 1.0;
      }
    }
    // Skewed off the axis (fixed, irrational-looking slopes); the axis part
    // ends a millimetre beyond the face, outside the box.
    Vector3d d(0.3170, 0.5918, 0.7412);
    d(axis) = sign;
    d *= reach + 1e-3;
    int crossings = 0;
    leaves_on_segment(p, d, false, [&](int first, int count) {
      for (int t = first; t < first + count; ++t) {
        SegmentHit hit;
        if (segment_meets_triangle(p, d, t, hit) && hit.s > 0.0) ++crossings;
      }
      return true;
    });
    return crossings % 2 == 1;
  }

  /// Where the segment a + s d, s in [0, 1], meets triangle t (Moller-
  /// Trumbore): its parameter s and barycentrics u, v (of corners 1 and 2).
  struct SegmentHit {
    double s = 0.0, u = 0.0, v = 0.0;
  };
  bool segment_meets_triangle(const Vector3d& a, const Vector3d& d, int t, SegmentHit& hit) const {
    const Vector3d e1 = corner(t, 1) - corner(t, 0), e2 = corner(t, 2) - corner(t, 0);
    const Vector3d pv = d.cross(e2);
    const double det = e1.dot(pv);
    if (det == 0.0) return false;
    const Vector3d tv = a - corner(t, 0);
    hit.u = tv.dot(pv) / det;
    if (hit.u < 0.0 || hit.u > 1.0) return false;
    const Vector3d qv = tv.cross(e1);
    hit.v = d.dot(qv) / det;
    if (hit.v < 0.0 || hit.u + hit.v > 1.0) return false;
    hit.s = e2.dot(qv) / det;
    return hit.s >= 0.0 && hit.s <= 1.0;
  }

  /// Where segment a-b first enters the surface (in the current pose),
  /// coming from a: the first triangle it crosses against that triangle's
  /// outward normal. `out`: that triangle, the crossing's barycentrics and
  /// the triangle's unit normal (distance 0). False when the segment
  /// enters nowhere.
  bool first_entry(const Vector3d& a, const Vector3d& b, Contact& out) const {
    const Vector3d d = b - a;
    double best = std::numeric_limits<double>::infinity();
    // One-sided: only crossings into the body.
    leaves_on_segment(a, d, false, [&](int first, int count) {
      for (int t = first; t < first + count; ++t) {
        if (any_ignored && ignored[static_cast<std::size_t>(t)]) continue;
        const Vector3d n = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
        SegmentHit hit;
        if (!(d.dot(n) < 0.0) || !segment_meets_triangle(a, d, t, hit) || hit.s >= best) continue;
        best = hit.s;
        out.triangle = t;
        out.b0 = 1.0 - hit.u - hit.v;
        out.b1 = hit.u;
        out.b2 = hit.v;
        out.normal = n.normalized();
      }
      return true;
    });
    if (!(best <= 1.0)) return false;
    out.distance = 0.0;
    return true;
  }

  /// The point of a contact's triangle at its barycentrics.
  Vector3d surface_point(const Contact& c) const {
    return c.b0 * corner(c.triangle, 0) + c.b1 * corner(c.triangle, 1) + c.b2 * corner(c.triangle, 2);
  }

  /// Whether an ignored (turned) triangle lies within sqrt(radius2) of p:
  /// there the seen surface is open, and a side read off it may be wrong.
  bool near_fold(const Vector3d& p, double radius2) const {
    for (int t : ignored_list)
      if (triangle_box_distance2(p, t) < radius2) return true;
    return false;
  }

  /// Whether memo says its point was left outside in this pose or the one
  /// before, with a side that may be carried: then that side still holds at
  /// a point the way to which no surface crossed (segment_clear).
  bool recently_outside(const ContactMemo* memo) const {
    return memo && memo->owner == this && memo->radius > 0.0 && memo->outside && memo->sided &&
           (memo->serial == serial || memo->serial + 1 == serial);
  }

  /// The contact of p with the seen triangle nearest to it within `reach`
  /// beyond the thickness, or, with nothing that near, the contact of p
  /// deep inside; false when p is outside and nothing is that near. The
  /// same answer as contact(p, (thickness + reach)^2, true, out); the memo
  /// only makes it cheaper: its nearest triangle starts the search with a
  /// bound, and with nothing within reach its carried side (a way no
  /// surface crossed) stands for the unbounded search. `behind`, if
  /// given, receives closest_and_behind's distance for a contact found
  /// within reach (the depth for one deep inside).
  bool nearest_contact(const Vector3d& p, double reach, const ContactMemo* memo, Contact& out,
                       double* behind = nullptr, Candidates* candidates = nullptr) const {
    const double near2 = (thickness + reach) * (thickness + reach);
    Closest c;
    if (memo && memo->owner == this && memo->nearest >= 0 &&
        static_cast<std::size_t>(memo->nearest) < triangles.size() &&
        !(any_ignored && ignored[static_cast<std::size_t>(memo->nearest)])) {
      const int t = memo->nearest;
      const TrianglePoint at = closest_on_triangle(p, corner(t, 0), corner(t, 1), corner(t, 2));
      const double d2 = (p - at.point).squaredNorm();
      if (d2 < near2) {
        c.d2 = d2;
        c.triangle = t;
        c.at = at;
      }
    }
    // The search finds any triangle nearer than the memo's, which stays
    // the answer when none is.
    double behind_distance = 0.0;
    const bool found = behind ? closest_and_behind(p, near2, 2.0 * kFlipReach, c, behind_distance, candidates)
                              : (closest(p, c.triangle >= 0 ? c.d2 : near2, c) || c.triangle >= 0);
    if (found) {
      out = signed_contact(p, c);
      if (behind) *behind = behind_distance;
      return true;
    }
    if (recently_outside(memo) && segment_clear(memo->centre, p)) return false;
    if (!inside_root(p) || !closest(p, std::numeric_limits<double>::infinity(), c)) return false;
    out = signed_contact(p, c);
    if (behind) *behind = -out.distance;  // inside: no side to vouch for
    return out.distance < 0.0;
  }

  /// What the memo keeps of a point left at p with nearest seen triangle
  /// `nearest` (-1: none within reach), outside or not.
  void remember(const Vector3d& p, int nearest, bool outside, double reach, ContactMemo* memo) const {
    if (!memo) return;
    memo->items.clear();
    memo->nearest = nearest;
    memo->centre = p;
    memo->radius = thickness + reach;
    memo->outside = outside;
    // A side is carried only from where nothing seen was near (so it came
    // from the tree's whole search or a carried side, not from one nearby
    // triangle, which where skinning drives one part into another can be
    // the wrong part's) and no fold is near (the seen surface is open there).
    memo->sided = nearest < 0 && !(any_ignored && near_fold(p, memo->radius * memo->radius));
    memo->owner = this;
    memo->serial = serial;
  }

  /// Pushes p out to thickness along the distance's gradient, searching
  /// within sqrt(search2). A push out of one side of a crease (armpit,
  /// crotch) can land within thickness of the other, so it repeats, as
  /// resolve_point does between colliders; after a push p is exactly
  /// thickness outside its closest point, so later sweeps only search that
  /// far. In a gap narrower than twice the thickness (between toes or
  /// fingers) no place is clear of both sides and the pushes alternate: then
  /// the place seen farthest out is kept. `largest` takes the largest push;
  /// `last` (if given) the contact of the last push kept.
  /// contact(p, search2, false, out), from `candidates` when they cover
  /// that ball.
  bool contact_near(const Vector3d& p, double search2, const Candidates* candidates, Contact& out) const {
    if (!candidates || !candidates->cover(p, search2)) return contact(p, search2, false, out);
    Closest c;
    double best = search2;
    for (int k = 0; k < candidates->count; ++k) consider(p, candidates->items[k], best, c);
    if (c.triangle < 0) return false;
    out = signed_contact(p, c);
    return true;
  }

  void project(Vector3d& p, double search2, double& largest, Contact* last = nullptr,
               const Candidates* candidates = nullptr) const {
    Vector3d best_p = p;
    double best_distance = -std::numeric_limits<double>::infinity();
    Contact best_contact;
    const double near2 = thickness * thickness;
    for (int sweep = 0; sweep <= kMaxSweeps; ++sweep) {
      Contact c;
      if (!contact_near(p, sweep == 0 ? search2 : near2, candidates, c)) return;
      const double gap = c.distance - thickness;
      if (!(gap < -1e-12)) return;  // round-off short of thickness is clear: no endless re-pushes
      if (c.distance > best_distance) {
        best_distance = c.distance;
        best_p = p;
        best_contact = c;
      }
      if (sweep == kMaxSweeps) break;
      p += -gap * c.normal;
      largest = std::max(largest, -gap);
      if (last) *last = c;
    }
    p = best_p;
    if (last) *last = best_contact;
  }

  Vector3d surface_motion(const Contact& c) const {
    const Eigen::Vector3i& tri = triangles[static_cast<std::size_t>(c.triangle)];
    Vector3d motion = Vector3d::Zero();
    const double b[3] = {c.b0, c.b1, c.b2};
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(tri(k));
      motion += b[k] * (x[v] - x_previous[v]);
    }
    return motion;
  }
};

MeshBody::MeshBody(const Eigen::MatrixX3d& vertices, std::vector<Eigen::Vector3i> triangles, double thickness,
                   double friction)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (!(std::isfinite(thickness) && thickness >= 0.0))
    throw ArgumentError("MeshBody: thickness must be a finite number >= 0 (got " + std::to_string(thickness) + ")");
  if (!(std::isfinite(friction) && friction >= 0.0))
    throw ArgumentError("MeshBody: friction must be a finite number >= 0 (got " + std::to_string(friction) + ")");
  if (triangles.empty()) throw ArgumentError("MeshBody: no triangles; expected a closed triangle mesh");
  m.thickness = thickness;
  m.friction = friction;
  m.reach2 = (thickness + Impl::kMargin) * (thickness + Impl::kMargin);
  Impl::require_finite(vertices);
  m.set_positions(vertices);
  const int vertex_count = static_cast<int>(vertices.rows());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (triangles[t](k) < 0 || triangles[t](k) >= vertex_count)
        throw ArgumentError("MeshBody: triangle " + std::to_string(t) + " names vertex " + std::to_string(triangles[t](k)) +
                            "; expected an index below " + std::to_string(vertex_count));
    }
  }

  // The tree: surface-area-heuristic splits (built once, on the first
  // pose), depth-first node order (left child next, parents before
  // children, so a reverse pass refits), triangles stored in leaf order.
  std::vector<Vector3d> centroid(triangles.size());
  std::vector<Impl::Box> boxes(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    centroid[t] = (m.x[static_cast<std::size_t>(triangles[t](0))] + m.x[static_cast<std::size_t>(triangles[t](1))] +
                   m.x[static_cast<std::size_t>(triangles[t](2))]) / 3.0;
    for (int k = 0; k < 3; ++k) boxes[t].add({m.x[static_cast<std::size_t>(triangles[t](k))], m.x[static_cast<std::size_t>(triangles[t](k))]});
  }
  std::vector<int> order(triangles.size());
  for (std::size_t t = 0; t < order.size(); ++t) order[t] = static_cast<int>(t);
  m.nodes.reserve(2 * triangles.size() / Impl::kLeafSize + 2);
  const std::pair<int, int> top = m.build(order, centroid, boxes, 0, static_cast<int>(order.size()), 0);
  if (top.second > 0) {
    // Few enough triangles for one leaf: a root node holding it alone.
    m.nodes.emplace_back();
    m.nodes[0].index[0] = top.first;
    m.nodes[0].count[0] = top.second;
  }
  m.triangles.resize(triangles.size());
  m.leaf_of_input.resize(triangles.size());
  for (std::size_t t = 0; t < order.size(); ++t) {
    m.triangles[t] = triangles[static_cast<std::size_t>(order[t])];
    m.leaf_of_input[static_cast<std::size_t>(order[t])] = static_cast<int>(t);
  }
  m.ignored.assign(triangles.size(), 0);
  m.on_rim.assign(triangles.size(), 0);

  // Neighbours across each edge: the mesh must be closed and consistently
  // oriented (each directed edge once, its reverse once).
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(3 * m.triangles.size());
  auto key = [](int a, int b) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b); };
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[t](k), b = m.triangles[t]((k + 1) % 3);
      if (!directed.emplace(key(a, b), static_cast<int>(3 * t + static_cast<std::size_t>(k))).second) {
        throw ArgumentError("MeshBody: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                            ") is used twice in the same direction; expected a consistently oriented 2-manifold mesh");
      }
    }
  }
  m.neighbours.resize(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[t](k), b = m.triangles[t]((k + 1) % 3);
      const auto found = directed.find(key(b, a));
      if (found == directed.end()) {
        throw ArgumentError("MeshBody: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                            ") has a triangle on one side only; expected a closed mesh");
      }
      m.neighbours[t][static_cast<std::size_t>(k)] = found->second / 3;
    }
  }
  m.number_vertices_by_leaf();  // after the checks above, whose messages name the input's vertices

  m.ring_start.assign(m.x.size() + 1, 0);
  for (const Eigen::Vector3i& tri : m.triangles)
    for (int k = 0; k < 3; ++k) ++m.ring_start[static_cast<std::size_t>(tri(k)) + 1];
  for (std::size_t v = 0; v < m.x.size(); ++v) m.ring_start[v + 1] += m.ring_start[v];
  m.ring.resize(3 * m.triangles.size());
  std::vector<int> fill(m.ring_start.begin(), m.ring_start.end() - 1);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      m.ring[static_cast<std::size_t>(fill[static_cast<std::size_t>(m.triangles[t](k))]++)] = {static_cast<int>(t), k};

  m.nodes4.reserve(m.nodes.size());
  m.box_slot.assign(m.triangles.size(), -1);
  m.build4(0);
  m.x_previous = m.x;
  m.refit(/*first=*/true);
  double volume = 0.0;
  for (const Eigen::Vector3i& tri : m.triangles)
    volume += m.x[static_cast<std::size_t>(tri(0))].dot(m.x[static_cast<std::size_t>(tri(1))].cross(m.x[static_cast<std::size_t>(tri(2))]));
  if (!(volume > 0.0))
    throw ArgumentError("MeshBody: the triangles enclose a negative volume; expected them ordered counter-clockwise seen from outside");
  const double diagonal = (m.root_hi - m.root_lo).norm();
  m.normal_floor = 1e-10 * std::max(1.0, diagonal);
}

MeshBody::~MeshBody() = default;

void MeshBody::update(const Eigen::MatrixX3d& vertices, const std::vector<char>& ignored) {
  Impl& m = *impl_;
  if (vertices.rows() != static_cast<Eigen::Index>(m.x.size())) {
    throw ArgumentError("MeshBody::update: " + std::to_string(vertices.rows()) + " vertices; expected " +
                        std::to_string(m.x.size()) + " (the count the body was built with)");
  }
  if (!ignored.empty() && ignored.size() != m.triangles.size())
    throw ArgumentError("MeshBody::update: " + std::to_string(ignored.size()) + " ignore flags; expected one per triangle (" +
                        std::to_string(m.triangles.size()) + ")");
  m.any_ignored = false;
  std::fill(m.ignored.begin(), m.ignored.end(), 0);
  m.ignored_list.clear();
  for (std::size_t t = 0; t < ignored.size(); ++t)
    if (ignored[t]) {
      m.ignored[static_cast<std::size_t>(m.leaf_of_input[t])] = 1;
      m.ignored_list.push_back(m.leaf_of_input[t]);
      m.any_ignored = true;
    }
  for (int t : m.rim_list) m.on_rim[static_cast<std::size_t>(t)] = 0;
  m.rim_list.clear();
  for (int t : m.ignored_list)
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(m.triangles[static_cast<std::size_t>(t)](k));
      for (int r = m.ring_start[v]; r < m.ring_start[v + 1]; ++r) {
        const auto u = static_cast<std::size_t>(m.ring[static_cast<std::size_t>(r)].first);
        if (m.ignored[u] || m.on_rim[u]) continue;
        m.on_rim[u] = 1;
        m.rim_list.push_back(static_cast<int>(u));
      }
    }
  Impl::require_finite(vertices);
  ++m.serial;
  std::swap(m.x, m.x_previous);
  m.set_positions(vertices);
  m.refit();
}

double MeshBody::resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction,
                         ContactMemo* memo, SurfaceNearby* nearby) const {
  const Impl& m = *impl_;
  // The nearest seen triangle within reach (the memo's from the last
  // resolve starts the search), or the contact deep inside.
  Impl::Contact c;
  double behind = 0.0;  // how far the nearest triangle p is behind is (when near)
  const Vector3d searched = position;
  Impl::Candidates candidates;  // what that search saw, for the searches after a push
  const bool near = m.nearest_contact(position, kNearbyReach, memo, c, nearby ? &behind : nullptr, &candidates);
  if (!near || !(c.distance - m.thickness < 0.0)) {
    if (nearby) {
      nearby->clearance = near ? c.distance - m.thickness : kNearbyReach;
      nearby->has_plane = near;
      nearby->normal = c.normal;
      nearby->point = position - nearby->clearance * c.normal;
      // Its side holds while the nearest triangle it is behind stays farther.
      nearby->flip = near ? 0.5 * (behind - c.distance) : std::numeric_limits<double>::infinity();
    }
    m.remember(position, near ? c.triangle : -1, true, kNearbyReach, memo);
    return 0.0;
  }
  // Where the point ends: thickness off its last push's surface.
  const auto finish = [&](const Impl::Contact& last, double largest) {
    if (nearby) {
      nearby->clearance = 0.0;
      nearby->has_plane = true;
      nearby->normal = last.normal;
      nearby->point = position;
      // Now thickness off its surface, and the triangles it was behind at
      // most as much nearer as it moved.
      nearby->flip = std::max(0.0, 0.5 * (behind - (position - searched).norm() - m.thickness));
    }
    m.remember(position, last.triangle, true, kNearbyReach, memo);
    return largest;
  };
  // Inside, the nearest surface may be the far side of a limb that moved
  // more than half its width through the point this step (a shin swinging
  // at 3 m/s moves 25 mm per 1/120 s step): pushed there, cloth ends on
  // both sides of the limb and tears. The point's way relative to the
  // surface (from where it started, carried along by the surface, to here)
  // says where it entered, and it goes back out there: the limb carries it
  // from where it met it. Not when that place is inside another part of
  // the body (where the skin passes into itself, as the thighs do), nor
  // when the way enters nowhere (the point started inside): then the
  // nearest surface, as below.
  if (c.distance < 0.0) {
    Impl::Contact entry, there;
    if (m.first_entry(start + m.surface_motion(c), position, entry)) {
      const Vector3d out = m.surface_point(entry) + m.thickness * entry.normal;
      // The entry triangle lies within thickness of `out`, so the closest
      // one does too: searching no farther finds the same one, sooner.
      const double within = m.thickness + 1e-9;
      if (!(m.contact(out, within * within, true, there) && there.distance < 0.0)) {
        double largest = (out - position).norm();
        position = out;
        m.project(position, m.thickness * m.thickness, largest, &entry);
        return finish(entry, largest);
      }
    }
  }
  const double gap = c.distance - m.thickness;
  // As resolve_point: out to thickness along the normal, then Coulomb
  // friction on the step's tangential displacement, here relative to the
  // surface (which moved by its vertices' displacement since the last
  // update).
  const double correction = -gap;
  position += correction * c.normal;
  double largest = correction;
  if (!friction) {
    m.project(position, m.thickness * m.thickness, largest, &c, &candidates);
    return finish(c, largest);
  }
  const Vector3d step = position - start - m.surface_motion(c);
  const Vector3d tangential = step - c.normal * c.normal.dot(step);
  const double slide = tangential.norm();
  const double grip = m.friction * correction;
  const Vector3d move = slide <= grip ? Vector3d(-tangential) : Vector3d(-tangential * (grip / slide));
  position += move;
  // The point is now thickness outside its closest point, moved along the
  // surface by `move`: only a triangle nearer than thickness plus the move
  // can still hold it (the other side of a crease, or the surface it slid
  // along); pushes from there on are frictionless.
  const double reach = m.thickness + move.norm();
  m.project(position, reach * reach, largest, &c, &candidates);
  return finish(c, largest);
}

double MeshBody::penetration(const Eigen::Vector3d& p) const {
  Impl::Contact c;
  if (!impl_->contact(p, impl_->reach2, true, c)) return 0.0;
  return std::max(0.0, impl_->thickness - c.distance);
}

double MeshBody::depth(const Eigen::Vector3d& p) const {
  Impl::Contact c;
  if (!impl_->contact(p, impl_->reach2, true, c)) return 0.0;
  return std::max(0.0, -c.distance);
}

MeshBody::SurfacePoint MeshBody::nearest_point(const Eigen::Vector3d& p) const {
  const Impl& m = *impl_;
  Impl::Closest c;
  m.closest(p, std::numeric_limits<double>::infinity(), c);
  SurfacePoint out;
  if (c.triangle < 0) return out;
  const double b[3] = {c.at.b0, c.at.b1, c.at.b2};
  for (int k = 0; k < 3; ++k) {
    const int v = m.triangles[static_cast<std::size_t>(c.triangle)](k);
    out.vertices[static_cast<std::size_t>(k)] = m.input_vertex.empty() ? v : m.input_vertex[static_cast<std::size_t>(v)];
    out.weights[static_cast<std::size_t>(k)] = b[k];
  }
  out.distance = std::sqrt(c.d2);
  return out;
}

SurfaceQuery MeshBody::query(const Eigen::Vector3d& p) const {
  Impl::Closest c;
  impl_->closest(p, std::numeric_limits<double>::infinity(), c);
  const Impl::Contact contact = impl_->signed_contact(p, c);
  SurfaceQuery out;
  out.distance = contact.distance;
  out.normal = contact.normal;
  return out;
}

}  // namespace mrcloth
