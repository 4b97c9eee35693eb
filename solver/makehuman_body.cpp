// Reading MakeHuman's files into a SkinnedBody: the `body` group of
// base.obj, the .mhskel rig, the .mhw weights, each checked against the
// others, and the mesh bound to the BVH skeleton with the rest correction.
#include "makehuman_body.h"

#include "body_skinned_mesh.h"
#include "joint_names.h"
#include "json_lite.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/obj_tokens.h"
#include "mesh_ops/units.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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
  std::vector<Eigen::Vector2d> texcoords;     ///< every 'vt' line
  /// Per group face, its corners' 0-based texcoord indices; empty when some
  /// corner has none or a 'vt' could not be read (the body is drawn untextured).
  std::vector<std::vector<int>> group_face_uvs;
  std::vector<int> group_face_lines;  ///< per group face, its line in the file
  bool uvs_complete = true;
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
    } else if (words[0] == "vt") {
      Eigen::Vector2d uv = Eigen::Vector2d::Zero();
      for (int k = 0; k < 2 && static_cast<std::size_t>(k) + 1 < words.size(); ++k) {
        const std::string_view word = words[static_cast<std::size_t>(k) + 1];
        const auto result = std::from_chars(word.data(), word.data() + word.size(), uv(k));
        if (result.ec != std::errc() || result.ptr != word.data() + word.size()) obj.uvs_complete = false;
      }
      obj.texcoords.push_back(uv);
    } else if (words[0] == "g" || words[0] == "o") {
      in_group = std::find(words.begin() + 1, words.end(), group) != words.end();
    } else if (words[0] == "f" && in_group) {
      if (words.size() < 4) obj_error(path, line, "a face with fewer than 3 vertices", "f v1 v2 v3 ...");
      std::vector<int> face, face_uvs;
      for (std::size_t k = 1; k < words.size(); ++k) {
        const long uv = resolve_obj_index(obj_corner_texture(words[k]), static_cast<long>(obj.texcoords.size()));
        if (uv < 0) obj.uvs_complete = false;
        face_uvs.push_back(static_cast<int>(uv));
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
      obj.group_face_uvs.push_back(std::move(face_uvs));
      obj.group_face_lines.push_back(line);
    }
  }
  if (in.bad()) throw InputError(path + ": read error; expected a readable OBJ file");
  if (obj.group_faces.empty())
    throw InputError(path + ": no faces in group \"" + std::string(group) + "\"; expected the body as group \"" + std::string(group) + "\"");
  for (std::size_t f = 0; f < obj.group_faces.size(); ++f)
    for (int v : obj.group_faces[f])
      if (v >= static_cast<int>(obj.vertices.size()))
        obj_error(path, obj.group_face_lines[f], "face vertex " + std::to_string(v + 1) + " does not exist",
                  "an index <= " + std::to_string(obj.vertices.size()));
  return obj;
}

/// `value` printed by a printf `format` for one double ("%.2f").
std::string printed(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

/// The body group's height (its faces' vertices' extent along Y), in the
/// units of `points`.
double body_height(const ObjData& obj, const std::vector<Vector3d>& points) {
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const auto& face : obj.group_faces)
    for (int v : face) {
      low = std::min(low, points[static_cast<std::size_t>(v)].y());
      high = std::max(high, points[static_cast<std::size_t>(v)].y());
    }
  return high - low;
}

/// Refuses a body group not the height of a person (0.5-3 m) as read in
/// `files.metres_per_unit`: a body exported in centimetres and read as
/// MakeHuman's decimetres stands 16 m tall, and the clip's size check would
/// blame the clip. Suggests the units that give a height nearest 1.7 m.
void check_body_height(const MakeHumanOptions& files, double height) {
  constexpr double kLowest = 0.5, kTallest = 3.0, kTypical = 1.7;
  if (height >= kLowest && height <= kTallest) return;
  std::string suggestion;
  double best = std::numeric_limits<double>::infinity();
  for (const char* unit : {"m", "dm", "cm", "mm", "inch"}) {
    const double there = height / files.metres_per_unit * metres_per_unit(unit);
    const double error = std::abs(std::log(there / kTypical));
    if (height > 0.0 && error < best && there >= kLowest && there <= kTallest) {
      best = error;
      suggestion = std::string("; in \"") + unit + "\" it is " + printed("%.3g", there) + " m";
    }
  }
  throw InputError(files.base_obj + ": the body group is " + printed("%.3g", height) + " m tall read at " +
                   printed("%.3g", files.metres_per_unit) + " m per unit" +
                   (files.metres_per_unit == 0.1 ? std::string(" (decimetres, MakeHuman's units)") : std::string()) +
                   "; expected a person 0.5-3 m tall: give the file's units" + suggestion);
}

/// Refuses a body group that is not closed: every edge of its faces must be
/// shared by exactly two of them. Collision asks which side of the skin a
/// point is on, and a hole (faces deleted from the group) or a flap has no
/// inside; the later checks would say so only in their own terms.
void check_body_closed(const std::string& path, const ObjData& obj) {
  std::map<std::pair<int, int>, std::pair<int, std::size_t>> edges;  // (low, high) file vertex -> (faces, first face)
  for (std::size_t f = 0; f < obj.group_faces.size(); ++f) {
    const auto& face = obj.group_faces[f];
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int a = face[k], b = face[(k + 1) % face.size()];
      auto& entry = edges[{std::min(a, b), std::max(a, b)}];
      if (entry.first++ == 0) entry.second = f;
    }
  }
  std::size_t open = 0, crowded = 0;
  const std::pair<const std::pair<int, int>, std::pair<int, std::size_t>>* first = nullptr;
  for (const auto& edge : edges) {
    if (edge.second.first == 2) continue;
    (edge.second.first == 1 ? open : crowded) += 1;
    if (!first) first = &edge;
  }
  if (!first) return;
  const auto& [ends, use] = *first;
  std::string counts;
  if (open > 0) counts = std::to_string(open) + (open == 1 ? " edge has" : " edges have") + " a face on one side only";
  if (crowded > 0)
    counts += (counts.empty() ? "" : ", ") + std::to_string(crowded) + (crowded == 1 ? " edge has" : " edges have") +
              " more than two faces";
  throw InputError(path + ":" + std::to_string(obj.group_face_lines[use.second]) + ": the body group is not closed: " +
                   counts + " (the first: the edge from vertex " + std::to_string(ends.first + 1) + " to " +
                   std::to_string(ends.second + 1) + " of the face on this line)" +
                   "; expected MakeHuman's closed body, every edge between two faces (faces deleted from group "
                   "\"body\" leave holes the cloth cannot be kept out of)");
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
  // A parent the rig does not list leaves the bones below it without a
  // chain to the root (a bone deleted from the file): their skin would
  // turn about the wrong joints.
  for (const auto& [name, bone] : bones)
    if (!bone.parent.empty() && !bones.count(bone.parent))
      rig.at("bones", "the skeleton file").at(name, "\"bones\"")
          .fail("bone \"" + name + "\" names parent \"" + bone.parent +
                "\", which \"bones\" does not list; expected a listed bone (or null for the root)");
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
/// Body vertices without any weight follow `fallback_joint`; `unweighted`
/// receives them (body vertex indices). `mesh_path` names the base mesh in
/// messages about vertices it does not have.
VertexWeights map_weights(const JsonValue& mhw, const std::map<std::string, std::vector<int>>& joint_of_bone,
                          const std::vector<int>& body_index, int body_count, int fallback_joint,
                          std::vector<int>& unweighted, const std::string& mesh_path) {
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
        pair.fail(what + " names vertex " + std::to_string(v) + "; expected an index below " +
                  std::to_string(body_index.size()) + ", the vertex count of " + mesh_path +
                  " (weights of another mesh, or a mesh with vertices added or removed?)");
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
      unweighted.push_back(static_cast<int>(&list - weights.data()));
      list.assign(1, {fallback_joint, 1.0});
      continue;
    }
    for (auto& entry : list) entry.second /= total;
    std::sort(list.begin(), list.end());
  }
  return weights;
}

/// Refuses weights that do not belong to the mesh's vertex order (a .mhw or
/// .mhskel of another export, or a base.obj re-saved by a tool that
/// renumbers vertices): MakeHuman's skin keeps every vertex near a bone that
/// carries it (the shared body: all within 0.18 m of its 1.6 m), while
/// weights read against another order put most vertices far from theirs
/// (three quarters beyond 0.2 m) and the body would be torn apart by the
/// first pose. `heads`, `tails`: per joint, its rig bone in the same space
/// as `vertices` + `offset`; `height`: the body's (metres).
void check_weights_fit_mesh(const MakeHumanOptions& files, const std::vector<Vector3d>& vertices,
                            const std::vector<int>& body_index, const VertexWeights& weights,
                            const std::vector<Vector3d>& heads, const std::vector<Vector3d>& tails,
                            const std::vector<bool>& has_bone, const Vector3d& offset, const Skeleton& skeleton,
                            double height) {
  const double far = 0.2 * height;  // a fifth of the body's height
  std::size_t count = 0, beyond = 0;
  int first = -1, first_joint = -1;
  double first_distance = 0.0;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const int b = body_index[v];
    if (b < 0) continue;
    const Vector3d x = vertices[v] + offset;
    double nearest = std::numeric_limits<double>::infinity();
    int heaviest = -1;
    double heaviest_weight = 0.0;
    for (const auto& [joint, w] : weights[static_cast<std::size_t>(b)]) {
      const auto j = static_cast<std::size_t>(joint);
      if (!has_bone[j]) continue;
      const Vector3d d = tails[j] - heads[j];
      const double t = d.squaredNorm() > 0.0 ? std::clamp((x - heads[j]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, (x - heads[j] - t * d).norm());
      if (w > heaviest_weight) {
        heaviest_weight = w;
        heaviest = joint;
      }
    }
    if (heaviest < 0) continue;  // carried by joints without a bone: nothing to measure against
    ++count;
    if (!(nearest > far)) continue;
    if (++beyond == 1) {
      first = static_cast<int>(v);
      first_joint = heaviest;
      first_distance = nearest;
    }
  }
  // A few far vertices can be a real body's (a large belly); a tenth cannot.
  if (count == 0 || beyond * 10 <= count) return;
  throw InputError(files.weights_file + ": the weights do not fit the body's vertices: " +
                   printed("%.0f", 100.0 * static_cast<double>(beyond) / static_cast<double>(count)) +
                   " % of the body's vertices lie farther than " + printed("%.2f", far) +
                   " m (a fifth of its height) from every bone that carries them (the first: vertex " +
                   std::to_string(first + 1) + " of " + files.base_obj + " is " + printed("%.2f", first_distance) +
                   " m from the bones carrying it, mostly \"" +
                   skeleton.joints[static_cast<std::size_t>(first_joint)].name + "\", as " + files.skeleton_file +
                   " places them); expected the weights and rig of this base.obj, in its vertex order (files of one "
                   "MakeHuman export; a tool that re-saves the OBJ may renumber its vertices)");
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
      // End Sites (and joints the rig has no bone for) follow the skeleton's
      // offset; their mesh head is where that offset puts them, so a bone
      // below one (a rig without a bone for a joint mid-chain) keeps its
      // place on the mesh instead of measuring from the origin.
      binding.pivot[j] = binding.pivot[p] + (rest_j - rest.position(parent));
      binding.head[j] = binding.head[p] + inherited.transpose() * (rest_j - rest.position(parent));
      continue;
    }
    binding.pivot[j] = binding.pivot[p] + inherited * (heads[j] - binding.head[p]);

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

/// Rig bone <-> skeleton joint, by name. A joint the rig has no bone for
/// (a DAZ skeleton's eyes and finger links) carries no skin and follows
/// its parent; a bone the skeleton has no joint for (DAZ has no Spine,
/// Neck1 or toes) hands its skin to its nearest ancestor that has one.
struct RigMatch {
  std::vector<const RigBone*> bone_of;           ///< per skeleton joint: its rig bone, null if none
  std::map<std::string, int> joint_of_rig_bone;  ///< per rig bone with a joint: that joint
};

/// Matches `bones` (the rig's) to `skeleton`'s joints by name; InputError
/// naming `files`' rig when the root or a leg joint has no bone.
RigMatch match_rig_bones(const MakeHumanOptions& files, const Skeleton& skeleton,
                         const std::map<std::string, RigBone>& bones) {
  const std::size_t n = skeleton.joints.size();
  if (n == 0) throw InputError(files.skeleton_file + ": the skeleton to bind to has no joints; expected a CMU skeleton");
  RigMatch match;
  match.bone_of.assign(n, nullptr);
  for (std::size_t j = 0; j < n; ++j) {
    if (skeleton.joints[j].end_site) continue;
    const auto found = bones.find(rig_name(skeleton.joints[j].name));
    if (found == bones.end()) continue;
    match.bone_of[j] = &found->second;
    match.joint_of_rig_bone[found->first] = static_cast<int>(j);
  }
  if (!match.bone_of[0]) {
    std::string root_bone;
    for (const auto& [name, bone] : bones)
      if (bone.parent.empty()) root_bone = name;
    throw InputError(files.skeleton_file + ": the skeleton's root joint \"" + skeleton.joints[0].name +
                     "\" has no bone in the rig; expected the rig's root \"" + root_bone +
                     "\" (the CMU MotionBuilder names; rename the motion's joints onto them)");
  }
  // The legs move the garment: a leg joint of the skeleton the rig has no
  // bone for (a bone renamed in the .mhskel) would leave its skin to the
  // joint above, a thigh following the hip, and the hips unaligned.
  for (const char* leg : kCmuLegJoints) {
    const int j = skeleton.find(leg);
    if (j >= 0 && !match.bone_of[static_cast<std::size_t>(j)])
      throw InputError(files.skeleton_file + ": the rig has no bone \"" + leg +
                       "\" for the skeleton's joint of that name; expected a bone for each joint of the legs, named "
                       "as the skeleton's (the CMU MotionBuilder names): without it the skin of that part of the leg "
                       "would follow the joint above it");
  }
  return match;
}

/// The translation taking the mesh onto the skeleton: the mesh's hip
/// joints' midpoint on the skeleton's (leg lengths agree within 1 %, so the
/// feet meet the skeleton's ground; the two Hips joints do not: the CMU one
/// sits 9.8 cm above its hip joints, MakeHuman's 2.4 cm). Without both hip
/// joints, the roots are aligned. `joints`: the rig's joint positions (m).
Vector3d hip_alignment(const Skeleton& skeleton, const Pose& rest, const RigMatch& match,
                       const std::map<std::string, Vector3d>& joints, const std::map<std::string, RigBone>& bones) {
  const int left_hip = skeleton.find("LeftUpLeg"), right_hip = skeleton.find("RightUpLeg");
  const int root = 0;
  const auto& bone_of = match.bone_of;
  if (left_hip >= 0 && right_hip >= 0 && bone_of[static_cast<std::size_t>(left_hip)] && bone_of[static_cast<std::size_t>(right_hip)]) {
    const Vector3d mesh_mid = 0.5 * (joints.at(bone_of[static_cast<std::size_t>(left_hip)]->head) +
                                     joints.at(bone_of[static_cast<std::size_t>(right_hip)]->head));
    return 0.5 * (rest.position(left_hip) + rest.position(right_hip)) - mesh_mid;
  }
  return rest.position(root) - joints.at(bone_of[root] ? bone_of[root]->head : bones.begin()->second.head);
}

/// Per skin-weight bone of the .mhw, the joints taking its weights: those of
/// the rig bones listing it, a rig bone without a joint giving them to its
/// nearest ancestor's joint (the root's when it has none).
std::map<std::string, std::vector<int>> joints_of_weight_bones(const RigMatch& match,
                                                              const std::map<std::string, RigBone>& bones) {
  // Each rig bone's skin goes to its own joint or its nearest ancestor's.
  const auto joint_taking = [&](const std::string& bone_name) {
    std::string at = bone_name;
    for (std::size_t guard = 0; guard <= bones.size(); ++guard) {
      const auto joint = match.joint_of_rig_bone.find(at);
      if (joint != match.joint_of_rig_bone.end()) return joint->second;
      const auto bone = bones.find(at);
      if (bone == bones.end() || bone->second.parent.empty()) break;
      at = bone->second.parent;
    }
    return 0;  // no bound ancestor (a second root): the skeleton's root
  };
  std::map<std::string, std::vector<int>> joint_of_bone;
  for (std::size_t j = 0; j < match.bone_of.size(); ++j)
    if (match.bone_of[j])
      for (const std::string& name : match.bone_of[j]->weight_bones) joint_of_bone[name].push_back(static_cast<int>(j));
  for (const auto& [name, bone] : bones) {
    if (match.joint_of_rig_bone.count(name)) continue;
    const int j = joint_taking(name);
    for (const std::string& weight_bone : bone.weight_bones) joint_of_bone[weight_bone].push_back(j);
  }
  return joint_of_bone;
}

/// The body group's faces as triangles of `body` (quads and larger
/// polygons as fans from their first corner), with their texture
/// coordinates when the group has them all; `body_index`: per OBJ vertex,
/// its index in the body (-1: not in it).
void add_body_triangles(const ObjData& obj, const std::vector<int>& body_index, SkinnedBody& body) {
  for (std::size_t f = 0; f < obj.group_faces.size(); ++f) {
    const auto& face = obj.group_faces[f];
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      body.triangles.emplace_back(body_index[static_cast<std::size_t>(face[0])], body_index[static_cast<std::size_t>(face[k])],
                                  body_index[static_cast<std::size_t>(face[k + 1])]);
      if (obj.uvs_complete) {
        const auto& uv = obj.group_face_uvs[f];
        const auto at = [&](std::size_t corner) { return obj.texcoords[static_cast<std::size_t>(uv[corner])]; };
        body.triangle_uvs.push_back({at(0), at(k), at(k + 1)});
      }
    }
  }
}

/// The bound body's geometry from its weights and `binding`: the rest
/// vertices (in T-pose), the joints' rest pivots and corrections, and the
/// input pose (A-pose) joints and vertices skinning starts from.
/// `all_vertices`: the OBJ's (m, before `offset`); `body_index` as above.
void set_bound_geometry(const std::vector<Vector3d>& all_vertices, const std::vector<int>& body_index, int body_count,
                        const Vector3d& offset, const Binding& binding, const Skeleton& skeleton, SkinnedBody& body) {
  const std::size_t n = skeleton.joints.size();
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
  if (!(files.metres_per_unit > 0.0 && std::isfinite(files.metres_per_unit)))
    throw ArgumentError("load_makehuman_body: metres_per_unit must be a finite number > 0 (got " +
                        std::to_string(files.metres_per_unit) + ")");
  const ObjData obj = read_obj_group(files.base_obj, "body");
  std::vector<Vector3d> all_vertices = obj.vertices;
  for (Vector3d& v : all_vertices) v *= files.metres_per_unit;
  const double height = body_height(obj, all_vertices);
  check_body_height(files, height);
  check_body_closed(files.base_obj, obj);

  const JsonValue rig = read_json(files.skeleton_file);
  const JsonValue mhw = read_json(files.weights_file);
  const std::map<std::string, Vector3d> joints = rig_joints(rig, all_vertices);
  const std::map<std::string, RigBone> bones = rig_bones(rig, joints);
  const RigMatch match = match_rig_bones(files, skeleton, bones);
  const std::size_t n = skeleton.joints.size();

  const Pose rest = rest_pose(skeleton);
  const Vector3d offset = hip_alignment(skeleton, rest, match, joints, bones);
  std::vector<Vector3d> heads(n, Vector3d::Zero()), tails(n, Vector3d::Zero());
  std::vector<bool> has_bone(n, false);
  for (std::size_t j = 0; j < n; ++j) {
    if (!match.bone_of[j]) continue;
    has_bone[j] = true;
    heads[j] = joints.at(match.bone_of[j]->head) + offset;
    tails[j] = joints.at(match.bone_of[j]->tail) + offset;
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
  add_body_triangles(obj, body_index, body);

  const int hips = skeleton.find("Hips");
  const int root = 0;
  std::vector<int> unweighted;
  body.weights = map_weights(mhw, joints_of_weight_bones(match, bones), body_index, body_count,
                             hips >= 0 ? hips : root, unweighted, files.base_obj);
  // MakeHuman weighs every body vertex (the shared body: all 13,380); one
  // without weight would stand still in its A-pose while the clip walks.
  if (!unweighted.empty()) {
    int first = -1;
    for (std::size_t v = 0; v < body_index.size() && first < 0; ++v)
      if (body_index[v] == unweighted.front()) first = static_cast<int>(v);
    throw InputError(files.weights_file + ": " + std::to_string(unweighted.size()) + " of the body's " +
                     std::to_string(body_count) + " vertices have no weight (the first: vertex " +
                     std::to_string(first + 1) + " of " + files.base_obj +
                     "); expected weights for every vertex of the body group (a .mhw of another body or rig?)");
  }

  check_weights_fit_mesh(files, all_vertices, body_index, body.weights, heads, tails, has_bone, offset, skeleton,
                         height);
  set_bound_geometry(all_vertices, body_index, body_count, offset, binding, skeleton, body);
  return body;
}

}  // namespace mrcloth
