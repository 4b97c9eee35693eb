#include "character_fit.h"

#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace mrcloth {

namespace {

bool arm_joint(const std::string& name) {
  for (const char* part : {"Shoulder", "Arm", "Hand", "Finger", "Thumb"})
    if (name.find(part) != std::string::npos) return true;
  return false;
}

/// Per joint, whether it is on an arm: named as an arm's joint, or below
/// one. A hand's finger joints count whatever their names (a DAZ
/// skeleton's lIndex1, lMid1, ... name no arm part); left out, the hands
/// hanging at the hips counted into a skirt's girth there.
std::vector<char> arm_joints(const Skeleton& skeleton) {
  std::vector<char> arm(skeleton.joints.size(), 0);
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j)
    for (int k = static_cast<int>(j); k >= 0 && !arm[j]; k = skeleton.joints[static_cast<std::size_t>(k)].parent)
      arm[j] = arm_joint(skeleton.joints[static_cast<std::size_t>(k)].name);
  return arm;
}

}  // namespace

std::vector<Eigen::Vector2i> polygon_edges(const std::vector<std::vector<int>>& polygons) {
  std::vector<Eigen::Vector2i> edges;
  for (const std::vector<int>& f : polygons)
    for (std::size_t k = 0; k < f.size(); ++k) edges.emplace_back(f[k], f[(k + 1) % f.size()]);
  return edges;
}

std::vector<char> vertices_off_arms(const PosedBody& body, const Skeleton& skeleton) {
  const Pose rest = rest_pose(skeleton);
  const BodySurface surface = body.surface(rest);
  const std::vector<char> on_arm = arm_joints(skeleton);
  std::vector<char> counted(static_cast<std::size_t>(surface.vertices.rows()), 1);
  for (Eigen::Index v = 0; v < surface.vertices.rows(); ++v) {
    const Eigen::Vector3d p = surface.vertices.row(v).transpose();
    double nearest = std::numeric_limits<double>::infinity();
    bool arm = false;
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
      const int parent = skeleton.joints[j].parent;
      if (parent < 0) continue;
      const double d = segment_distance(p, rest.position(parent), rest.position(static_cast<int>(j))).first;
      if (d < nearest) {
        nearest = d;
        arm = on_arm[j] != 0;
      }
    }
    counted[static_cast<std::size_t>(v)] = !arm;
  }
  return counted;
}

bool is_tube_garment(const QuadMesh& garment) { return boundary_loops(garment).size() == 2; }

HoopDemandOptions full_round_span(const QuadMesh& tube, const Eigen::MatrixX3d& points, HoopDemandOptions levels) {
  const std::vector<std::vector<int>> loops = boundary_loops(tube);
  if (loops.size() != 2 || !std::isnan(levels.top) || !std::isnan(levels.bottom)) return levels;
  const int up = levels.up_axis;
  const auto extent = [&](const std::vector<int>& loop) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const int v : loop) {
      low = std::min(low, points(v, up));
      high = std::max(high, points(v, up));
    }
    return std::make_pair(low, high);
  };
  auto upper = extent(loops[0]), lower = extent(loops[1]);
  if (upper.second < lower.second) std::swap(upper, lower);
  if (upper.first > lower.second) {  // else the loops overlap in height: the whole garment, as for any shape
    levels.top = upper.first;
    levels.bottom = lower.second;
  }
  return levels;
}

std::vector<HoopLevel> run_hoop_demand(const Motion& motion, const PosedBody& body, const CharacterRunOptions& options,
                                       const QuadMesh& garment, const HoopDemandOptions& levels, int max_samples) {
  if (max_samples < 1)
    throw ArgumentError("run_hoop_demand: " + std::to_string(max_samples) + " samples; expected at least 1");
  if (!is_tube_garment(garment)) return {};
  const int stride = std::max(1, (options.frames + max_samples - 1) / max_samples);
  Eigen::MatrixX3d rest(static_cast<Eigen::Index>(garment.n_vertices()), 3);
  for (const auto v : garment.vertices()) {
    const auto p = garment.point(v);
    rest.row(v.idx()) << p[0], p[1], p[2];
  }
  const int pelvis = motion.skeleton.find(options.pelvis_joint);
  if (pelvis < 0)
    throw ArgumentError("run_hoop_demand: the skeleton has no joint '" + options.pelvis_joint + "' (the pelvis)");
  const int up = levels.up_axis;
  const double pelvis_rest = reference_pose(motion, options).position(pelvis)(up);
  std::vector<Eigen::MatrixX3d> frames;
  std::vector<std::vector<int>> faces;
  for (int f = 0; f < options.frames; f += stride) {
    const Pose pose = character_pose(motion, options.preroll_seconds + (f + 1) / options.fps, options);
    BodySurface surface = body.surface(pose);
    surface.vertices.col(up).array() -= pose.position(pelvis)(up) - pelvis_rest;
    frames.push_back(std::move(surface.vertices));
    if (faces.empty()) faces = std::move(surface.faces);
  }
  std::vector<HoopLevel> out =
      hoop_demand(rest, polygon_edges(active_face_polygons(garment)), frames, polygon_edges(faces),
                  vertices_off_arms(body, motion.skeleton), full_round_span(garment, rest, levels));
  for (HoopLevel& level : out)
    if (level.frame >= 0) level.frame *= stride;  // the output frame, not the sample
  return out;
}

}  // namespace mrcloth
