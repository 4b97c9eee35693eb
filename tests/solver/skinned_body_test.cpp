// The skinned MakeHuman body (loading, rest correction, skinning) on the real
// data, and MeshBody (BVH closest point, pseudo-normal sign, resolve,
// friction) against brute force on the body. The waist: skinned_waist_test.cpp;
// malformed body files: skinned_body_files_test.cpp.
#include "solver/body_skinned_mesh.h"
#include "solver/mesh_body.h"

#include "solver/character_setup.h"
#include "solver/character_sim.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "solver/colliders.h"
#include "solver/joint_names.h"
#include "mesh_oracles.h"
#include "skinned_body_fixture.h"
#include "test_meshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>
#include <array>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;
using Eigen::Vector3i;
using test::brute_distance;
using test::expect_matches_brute_force;
using test::have_body;
using test::icosphere;
using test::kCmuScale;
using test::Mesh;
using test::sample_points;
using test::SkinnedBodyTest;
using test::winding_number;

constexpr double kPi = 3.14159265358979323846;

// ---- the MakeHuman body ----------------------------------------------------------

/// The body's vertices as in base.obj (the first 13380 'v' lines), in metres
/// and moved by the body's obj_offset: the input mesh, before correction.
Eigen::MatrixX3d input_mesh(const SkinnedBody& body) {
  std::ifstream in(test::shared_data("bodies/makehuman/base.obj"));
  Eigen::MatrixX3d out(body.rest_vertices.rows(), 3);
  std::string line;
  Eigen::Index row = 0;
  while (row < out.rows() && std::getline(in, line)) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream words(line.substr(2));
    words.imbue(std::locale::classic());
    Vector3d v;
    words >> v.x() >> v.y() >> v.z();
    out.row(row++) = (0.1 * v + body.obj_offset).transpose();
  }
  return out;
}

TEST_F(SkinnedBodyTest, LoadsTheBodyGroupWithNormalisedWeights) {
  SKIP_WITHOUT_BODY();
  const SkinnedBody& body = *body_;
  ASSERT_EQ(body.rest_vertices.rows(), 13380) << "group body is vertices 0-13379";
  ASSERT_EQ(body.triangles.size(), 26756u) << "13378 quads, two triangles each";
  std::vector<int> used(13380, 0);
  for (const Vector3i& t : body.triangles)
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(t(k), 0);
      ASSERT_LT(t(k), 13380);
      used[static_cast<std::size_t>(t(k))] = 1;
    }
  EXPECT_EQ(std::count(used.begin(), used.end(), 1), 13380) << "every body vertex is used by a triangle";
  EXPECT_TRUE(body.rest_vertices.allFinite());
  ASSERT_EQ(body.weights.size(), 13380u);
  ASSERT_EQ(body.joint_rest.size(), skeleton().joints.size());
  int multi = 0;
  for (std::size_t v = 0; v < body.weights.size(); ++v) {
    double sum = 0.0;
    ASSERT_FALSE(body.weights[v].empty()) << "vertex " << v;
    for (const auto& [j, w] : body.weights[v]) {
      ASSERT_GE(j, 0);
      ASSERT_LT(j, static_cast<int>(skeleton().joints.size()));
      ASSERT_FALSE(skeleton().joints[static_cast<std::size_t>(j)].end_site);
      ASSERT_GT(w, 0.0);
      sum += w;
    }
    ASSERT_NEAR(sum, 1.0, 1e-12) << "vertex " << v;
    multi += body.weights[v].size() > 1;
  }
  EXPECT_GT(multi, 5000) << "weights blend across joints";
  // Face and hands are carried by the head and hand bones, not left at the hips.
  const int hips = joint("Hips");
  int on_hips = 0;
  for (const auto& list : body.weights) on_hips += list.size() == 1 && list[0].first == hips;
  EXPECT_EQ(on_hips, 0) << "every vertex has weights of its own: none falls back to Hips alone";
  EXPECT_GT(dominated_by(joint("Head"), 0.99).size(), 2000u) << "the face moves with the head";
  EXPECT_GT(dominated_by(joint("LeftHandIndex1"), 0.5).size(), 100u) << "fingers are bound to the finger bone";
}

// Each triangle corner keeps the texture coordinate its quad's corner has
// in base.obj (read here independently: the 'vt' lines and the body
// group's faces, split from their first corner as the loader splits them).
TEST_F(SkinnedBodyTest, CarriesTheFilesTextureCoordinatesPerTriangleCorner) {
  SKIP_WITHOUT_BODY();
  std::ifstream in(test::shared_data("bodies/makehuman/base.obj"));
  std::vector<Eigen::Vector2d> texcoords;
  std::vector<std::array<Eigen::Vector2d, 3>> expected;
  bool in_body = false;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "vt") {
      Eigen::Vector2d uv;
      words >> uv.x() >> uv.y();
      texcoords.push_back(uv);
    } else if (tag == "g") {
      std::string name;
      words >> name;
      in_body = name == "body";
    } else if (tag == "f" && in_body) {
      std::vector<Eigen::Vector2d> corners;
      for (std::string corner; words >> corner;)
        corners.push_back(texcoords[static_cast<std::size_t>(std::stol(corner.substr(corner.find('/') + 1)) - 1)]);
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) expected.push_back({corners[0], corners[k], corners[k + 1]});
    }
  }
  ASSERT_EQ(expected.size(), body_->triangles.size());
  ASSERT_EQ(body_->triangle_uvs.size(), body_->triangles.size());
  for (std::size_t t = 0; t < expected.size(); ++t)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(body_->triangle_uvs[t][k], expected[t][k]) << "triangle " << t;
  // The body made for collisions (hands capped) has none of its own; drawn,
  // it carries these: a kept triangle its own, a cap the UVs its rim
  // vertices have, the cap's centre its triangle's first rim vertex's.
  SkinnedBody cut = without_hands(*body_, skeleton());
  EXPECT_TRUE(cut.triangle_uvs.empty());
  carry_uvs(*body_, cut);
  ASSERT_EQ(cut.triangle_uvs.size(), cut.triangles.size());
  std::map<std::array<int, 3>, std::size_t> original;
  for (std::size_t t = 0; t < body_->triangles.size(); ++t)
    original[{body_->triangles[t][0], body_->triangles[t][1], body_->triangles[t][2]}] = t;
  std::size_t kept = 0, capped = 0;
  for (std::size_t t = 0; t < cut.triangles.size(); ++t) {
    const Vector3i& c = cut.triangles[t];
    if (const auto found = original.find({c[0], c[1], c[2]}); found != original.end()) {
      ++kept;
      for (int k = 0; k < 3; ++k) ASSERT_EQ(cut.triangle_uvs[t][k], body_->triangle_uvs[found->second][k]) << t;
      continue;
    }
    ++capped;
    ASSERT_GE(c[2], static_cast<int>(body_->rest_vertices.rows())) << "a cap's third corner is its centre";
    EXPECT_EQ(cut.triangle_uvs[t][2], cut.triangle_uvs[t][0]) << "the centre takes its first rim vertex's UV";
  }
  EXPECT_GT(kept, 20000u);
  EXPECT_GT(capped, 20u);
}

TEST_F(SkinnedBodyTest, RestPoseReproducesRestVertices) {
  SKIP_WITHOUT_BODY();
  const Eigen::MatrixX3d posed = skin(*body_, skeleton(), rest_pose(skeleton()));
  ASSERT_EQ(posed.rows(), body_->rest_vertices.rows());
  EXPECT_LE((posed - body_->rest_vertices).cwiseAbs().maxCoeff(), 1e-12);
}

/// The mesh's own pose (MakeHuman's A-pose) reproduces base.obj exactly:
/// garments modelled on it start where they were modelled.
TEST_F(SkinnedBodyTest, MeshPoseReproducesTheInputMesh) {
  SKIP_WITHOUT_BODY();
  const Eigen::MatrixX3d input = input_mesh(*body_);
  ASSERT_EQ(body_->input_vertices.rows(), input.rows());
  EXPECT_LE((body_->input_vertices - input).cwiseAbs().maxCoeff(), 1e-12);
  const Pose pose = mesh_pose(*body_, skeleton());
  const Eigen::MatrixX3d posed = skin(*body_, skeleton(), pose);
  EXPECT_LE((posed - input).cwiseAbs().maxCoeff(), 1e-12);
  // A real pose of the skeleton: its bones keep their lengths, the root stays.
  const Pose rest = rest_pose(skeleton());
  EXPECT_EQ(pose.position(0), rest.position(0));
  for (std::size_t j = 1; j < skeleton().joints.size(); ++j) {
    const int parent = skeleton().joints[j].parent;
    EXPECT_NEAR((pose.position(static_cast<int>(j)) - pose.position(parent)).norm(),
                (rest.position(static_cast<int>(j)) - rest.position(parent)).norm(), 1e-12);
  }
  // The A-pose: the arms hang well below the T-pose's horizontal ones.
  for (const char* hand : {"LeftHand", "RightHand"})
    EXPECT_LT(pose.position(joint(hand)).y(), rest.position(joint(hand)).y() - 0.2) << hand;
  // Poses between mesh_pose and the rest pose blend smoothly (the pre-roll).
  const Eigen::MatrixX3d half = skin(*body_, skeleton(), blend_poses(skeleton(), pose, rest, 0.5));
  EXPECT_TRUE(half.allFinite());
}

TEST_F(SkinnedBodyTest, BonesAreTurnedRigidlyOntoTheSkeletonsRestDirections) {
  SKIP_WITHOUT_BODY();
  const Pose rest = rest_pose(skeleton());
  // The body's bone chain runs along the skeleton's rest directions (with
  // the mesh's own lengths).
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"LeftUpLeg", "LeftLeg"}, {"LeftLeg", "LeftFoot"}, {"RightUpLeg", "RightLeg"}, {"RightLeg", "RightFoot"},
           {"LeftArm", "LeftForeArm"}, {"LeftForeArm", "LeftHand"}, {"RightArm", "RightForeArm"}, {"Spine", "Spine1"}}) {
    const Vector3d body_bone = body_->joint_rest[static_cast<std::size_t>(joint(to))] - body_->joint_rest[static_cast<std::size_t>(joint(from))];
    const Vector3d skeleton_bone = rest.position(joint(to)) - rest.position(joint(from));
    EXPECT_LT(body_bone.normalized().cross(skeleton_bone.normalized()).norm(), 1e-9) << from << " -> " << to;
    EXPECT_GT(body_bone.dot(skeleton_bone), 0.0) << from << " -> " << to;
    EXPECT_NEAR(body_bone.norm(), skeleton_bone.norm(), 0.35 * skeleton_bone.norm()) << "similar proportions " << from;
  }
  // Vertices bound to one bone alone move rigidly: distances among them keep.
  const Eigen::MatrixX3d input = input_mesh(*body_);
  for (const std::string name : {"LeftLeg", "LeftForeArm", "Head"}) {
    const std::vector<Eigen::Index> rigid = dominated_by(joint(name), 1.0 - 1e-12);
    ASSERT_GT(rigid.size(), 10u) << name;
    for (std::size_t i = 0; i + 1 < rigid.size(); i += 7) {
      const Eigen::Index a = rigid[i], b = rigid[(i * 13 + 5) % rigid.size()];
      EXPECT_NEAR((body_->rest_vertices.row(a) - body_->rest_vertices.row(b)).norm(), (input.row(a) - input.row(b)).norm(), 1e-12)
          << name;
    }
  }
}

/// The rotation angle (degrees) that takes the input mesh's vertices rigidly
/// bound to `name` to their rest position (from three of them).
double correction_angle(const Eigen::MatrixX3d& input, const SkinnedBody& body, const std::vector<Eigen::Index>& rigid) {
  auto frame = [&](const Eigen::MatrixX3d& x) {
    const Vector3d a = x.row(rigid.front()).transpose();
    const Vector3d b = x.row(rigid[rigid.size() / 2]).transpose();
    const Vector3d c = x.row(rigid.back()).transpose();
    const Vector3d e1 = (b - a).normalized();
    const Vector3d e2 = (c - a - e1 * e1.dot(c - a)).normalized();
    Eigen::Matrix3d f;
    f << e1, e2, e1.cross(e2);
    return f;
  };
  const Eigen::Matrix3d r = frame(body.rest_vertices) * frame(input).transpose();
  return std::acos(std::clamp((r.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / kPi;
}

TEST_F(SkinnedBodyTest, ArmsRiseToHorizontalLegsTurnLittle) {
  SKIP_WITHOUT_BODY();
  const Eigen::MatrixX3d input = input_mesh(*body_);
  for (const std::string side : {"Left", "Right"}) {
    const std::string hand_name = side + "Hand";
    const Vector3d shoulder = body_->joint_rest[static_cast<std::size_t>(joint(side + "Arm"))];
    const std::vector<Eigen::Index> hand = dominated_by(joint(hand_name), 0.5);
    ASSERT_GT(hand.size(), 20u);
    double rest_y = 0.0, input_y = 0.0;
    for (Eigen::Index v : hand) {
      rest_y += body_->rest_vertices(v, 1) / static_cast<double>(hand.size());
      input_y += input(v, 1) / static_cast<double>(hand.size());
    }
    EXPECT_NEAR(rest_y, shoulder.y(), 0.05) << hand_name << ": the hand is at shoulder height in T-pose";
    EXPECT_LT(input_y, shoulder.y() - 0.25) << hand_name << ": in the input A-pose it hangs well below";
  }
  // The A-pose arm turns by about 50 degrees; the legs by much less (the
  // CMU rest pose spreads the legs 20 degrees and the mesh stands with its
  // feet apart, so not zero).
  const double forearm = correction_angle(input, *body_, dominated_by(joint("LeftForeArm"), 1.0 - 1e-12));
  const double shin = correction_angle(input, *body_, dominated_by(joint("LeftLeg"), 1.0 - 1e-12));
  const double thigh = correction_angle(input, *body_, dominated_by(joint("LeftUpLeg"), 1.0 - 1e-12));
  EXPECT_GT(forearm, 40.0);
  EXPECT_LT(shin, 25.0);
  EXPECT_LT(thigh, 25.0);
  // Frame 0 of a CMU clip is its own T-pose with the legs brought together:
  // there the body's legs stand close to the input mesh's.
  const Pose t_pose = frame_pose(*motion_, 0);
  const Eigen::MatrixX3d posed = skin(*body_, skeleton(), t_pose);
  const Vector3d root_shift = t_pose.position(0) - rest_pose(skeleton()).position(0);
  double shin_worst = 0.0;
  for (Eigen::Index v : dominated_by(joint("LeftLeg"), 0.9))
    shin_worst = std::max(shin_worst, (posed.row(v).transpose() - root_shift - input.row(v).transpose()).norm());
  EXPECT_LT(shin_worst, 0.15) << "left shin at frame 0 vs the input mesh";
  std::cout << "[ info ] correction angles: forearm " << forearm << " deg, thigh " << thigh << " deg, shin " << shin
            << " deg; frame-0 shin vs input mesh: " << shin_worst << " m\n";
}

TEST_F(SkinnedBodyTest, WalkFramesAreFiniteWithFeetOnTheGround) {
  SKIP_WITHOUT_BODY();
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  std::vector<int> feet;
  for (std::size_t j = 0; j < walk.skeleton.joints.size(); ++j) {
    const std::string& name = walk.skeleton.joints[j].name;
    if (name.find("Foot") != std::string::npos || name.find("Toe") != std::string::npos) feet.push_back(static_cast<int>(j));
  }
  ASSERT_GE(feet.size(), 4u);
  for (int frame : {0, 60, 120, 200, 300, static_cast<int>(walk.frames.rows()) - 1}) {
    const Pose pose = frame_pose(walk, frame);
    const Eigen::MatrixX3d x = skin(*body_, walk.skeleton, pose);
    ASSERT_TRUE(x.allFinite()) << "frame " << frame;
    double feet_low = std::numeric_limits<double>::infinity();
    for (int j : feet) feet_low = std::min(feet_low, pose.position(j).y());
    EXPECT_NEAR(x.col(1).minCoeff(), feet_low, 0.10) << "frame " << frame;
    // Rigid bones stay rigid through the motion.
    const std::vector<Eigen::Index> shin = dominated_by(joint("LeftLeg"), 1.0 - 1e-12);
    EXPECT_NEAR((x.row(shin.front()) - x.row(shin.back())).norm(),
                (body_->rest_vertices.row(shin.front()) - body_->rest_vertices.row(shin.back())).norm(), 1e-12);
  }
}

TEST_F(SkinnedBodyTest, ProportionedPosePutsJointsWhereSkinningPutsThem) {
  // A "body" made of the body's own rest joints, each weighted to its
  // parent (a root to itself), skins to exactly where proportioned_pose
  // puts the joints: capsules posed by it follow the skinned mesh's limbs.
  SKIP_WITHOUT_BODY();
  const std::size_t n = skeleton().joints.size();
  ASSERT_EQ(body_->joint_rest.size(), n);
  SkinnedBody joints;
  joints.rest_vertices.resize(static_cast<Eigen::Index>(n), 3);
  joints.weights.resize(n);
  joints.joint_rest = body_->joint_rest;
  for (std::size_t j = 0; j < n; ++j) {
    joints.rest_vertices.row(static_cast<Eigen::Index>(j)) = body_->joint_rest[j].transpose();
    const int parent = skeleton().joints[j].parent;
    joints.weights[j] = {{parent < 0 ? static_cast<int>(j) : parent, 1.0}};
  }
  const Pose rest = rest_pose(skeleton());
  const Pose at_rest = proportioned_pose(skeleton(), body_->joint_rest, rest);
  for (std::size_t j = 0; j < n; ++j)
    EXPECT_LT((at_rest.position(static_cast<int>(j)) - body_->joint_rest[j]).norm(), 1e-12) << skeleton().joints[j].name;
  for (int frame : {0, 75, 150, 300}) {
    const Pose pose = frame_pose(*motion_, frame);
    const Pose proportioned = proportioned_pose(skeleton(), body_->joint_rest, pose);
    const Eigen::MatrixX3d skinned = skin(joints, skeleton(), pose);
    for (std::size_t j = 0; j < n; ++j) {
      EXPECT_LT((proportioned.position(static_cast<int>(j)) - skinned.row(static_cast<Eigen::Index>(j)).transpose()).norm(), 1e-12)
          << skeleton().joints[j].name << " frame " << frame;
      EXPECT_LT((proportioned.global[j].linear() - pose.global[j].linear()).norm(), 1e-15);
    }
  }
  // Without a body's joints the pose is the skeleton's own.
  const Pose same = proportioned_pose(skeleton(), {}, frame_pose(*motion_, 75));
  EXPECT_LT((same.position(5) - frame_pose(*motion_, 75).position(5)).norm(), 1e-15);
}

/// The largest weight's joint of each vertex.
std::vector<int> dominant_joints(const SkinnedBody& body) {
  std::vector<int> out;
  for (const auto& list : body.weights) {
    out.push_back(std::max_element(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.second < b.second; })->first);
  }
  return out;
}

TEST_F(SkinnedBodyTest, MeshBodyOnTheBodyMatchesBruteForce) {
  SKIP_WITHOUT_BODY();
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  const std::vector<int> dominant = dominant_joints(*body_);
  auto part_of = [&](std::size_t v, std::initializer_list<const char*> parts) {
    const std::string& name = skeleton().joints[static_cast<std::size_t>(dominant[v])].name;
    for (const char* part : parts)
      if (name.find(part) != std::string::npos) return true;
    return false;
  };
  Mesh mesh{body_->rest_vertices, body_->triangles};
  MeshBody body(mesh.vertices, mesh.triangles, 0.004, 0.3);
  std::mt19937 rng(5);
  // The sample leaves out, with 10 cm around them: the hands, feet and head,
  // whose fingers, toes, lips and ears lie closer together than twice the
  // thickness (no place is clear of both sides); and when walking, the arms,
  // which the skinning folds into the chest's sides at the armpits (the
  // surface crosses itself there and inside has no single meaning).
  auto check = [&](const std::string& label, std::initializer_list<const char*> left_out) {
    std::vector<int> excluded(dominant.size(), 0);
    for (std::size_t v = 0; v < dominant.size(); ++v) excluded[v] = part_of(v, left_out);
    Mesh region;
    region.vertices = mesh.vertices;
    for (const Vector3i& t : mesh.triangles)
      if (!excluded[static_cast<std::size_t>(t(0))] && !excluded[static_cast<std::size_t>(t(1))] && !excluded[static_cast<std::size_t>(t(2))])
        region.triangles.push_back(t);
    auto clear = [&](const Vector3d& p) {
      for (std::size_t v = 0; v < excluded.size(); ++v)
        if (excluded[v] && (mesh.vertex(static_cast<int>(v)) - p).norm() < 0.1) return false;
      return true;
    };
    std::vector<Vector3d> points;
    for (const Vector3d& p : sample_points(region, rng, 240, 0.08))
      if (clear(p)) points.push_back(p);
    // Deep inside, beyond the search margin: 9 cm in from trunk vertices.
    std::vector<Vector3d> normal(dominant.size(), Vector3d::Zero());
    for (const Vector3i& t : mesh.triangles) {
      const Vector3d n = (mesh.vertex(t(1)) - mesh.vertex(t(0))).cross(mesh.vertex(t(2)) - mesh.vertex(t(0)));
      for (int k = 0; k < 3; ++k) normal[static_cast<std::size_t>(t(k))] += n;
    }
    int deep = 0;
    for (std::size_t v = 0; v < dominant.size(); v += 97) {
      if (!part_of(v, {"Hips", "LowerBack", "Spine"})) continue;
      const Vector3d p = mesh.vertex(static_cast<int>(v)) - 0.09 * normal[v].normalized();
      if (brute_distance(mesh, p) < 0.06 || winding_number(mesh, p) < 0.5 || !clear(p)) continue;
      ++deep;
      EXPECT_GT(body.penetration(p), 0.06) << label << ": found although beyond the search margin";
      points.push_back(p);
    }
    EXPECT_GE(deep, 5) << label;
    ASSERT_GT(points.size(), 100u) << label;
    expect_matches_brute_force(body, mesh, points, label);
    // Resolved points end clear of the surface by the thickness, except in
    // the crotch's crease, narrower there than twice the thickness: pushes
    // from its two sides alternate and leave the point short, not inside.
    int short_of_thickness = 0;
    for (const Vector3d& p : points) {
      Vector3d q = p;
      body.resolve(p, q);
      const double d = body.query(q).distance;
      ASSERT_GE(d, 0.0) << label << " from (" << p.transpose() << ")";
      short_of_thickness += d < 0.004 - 1e-12;
    }
    EXPECT_LE(short_of_thickness, static_cast<int>(points.size()) / 100) << label;
  };
  check("T-pose body", {"Hand", "Thumb", "Finger", "Foot", "Toe", "Head"});
  // One step of the walk, as in a simulation (friction sees the surface's
  // motion over the step).
  body.update(skin(*body_, walk.skeleton, frame_pose(walk, 149)));
  mesh.vertices = skin(*body_, walk.skeleton, frame_pose(walk, 150));
  body.update(mesh.vertices);
  check("walking body", {"Hand", "Thumb", "Finger", "Foot", "Toe", "Head", "Arm", "Shoulder"});
}

// Linear blend skinning folds the skin where a joint bends far from the
// pose the mesh was modelled in (behind a bent knee, the armpit, between
// fingers): the folded triangles face into the body. turned_triangles finds
// them (none in the mesh's own pose), and a MeshBody that ignores them says
// inside or outside near the legs' folds as the generalized winding number
// of the whole surface does (the oracle: >= 0.5 inside, robust where the
// surface crosses itself) more often than one that does not.
TEST_F(SkinnedBodyTest, TurnedTrianglesAreTheSkinFoldedBehindBentJoints) {
  SKIP_WITHOUT_BODY();
  const Pose own = mesh_pose(*body_, skeleton());
  const std::vector<char> none = turned_triangles(*body_, skeleton(), own, skin(*body_, skeleton(), own));
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0) << "the mesh's own pose folds nothing";
  const std::vector<int> dominant = dominant_joints(*body_);
  const auto on_a_leg = [&](const Vector3i& tri) {
    const std::string& name = skeleton().joints[static_cast<std::size_t>(dominant[static_cast<std::size_t>(tri(0))])].name;
    return name == "Hips" || name.find("UpLeg") != std::string::npos || name == "LeftLeg" || name == "RightLeg";
  };
  const auto leg_folds = [&](const std::vector<char>& flags) {
    int n = 0;
    for (std::size_t t = 0; t < flags.size(); ++t) n += flags[t] && on_a_leg(body_->triangles[t]);
    return n;
  };
  // The walk's frame with the most folded leg skin.
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  int worst_frame = 0, worst = -1;
  for (int frame = 0; frame < walk.frames.rows(); frame += 2) {
    const Pose pose = frame_pose(walk, frame);
    const int folds = leg_folds(turned_triangles(*body_, skeleton(), pose, skin(*body_, skeleton(), pose)));
    if (folds > worst) std::tie(worst, worst_frame) = std::make_pair(folds, frame);
  }
  const Pose pose = frame_pose(walk, worst_frame);
  const Mesh mesh{skin(*body_, skeleton(), pose), body_->triangles};
  const std::vector<char> turned = turned_triangles(*body_, skeleton(), pose, mesh.vertices);
  ASSERT_GT(worst, 0) << "no leg skin folded in a walk; the test proves nothing";
  ASSERT_LT(std::count(turned.begin(), turned.end(), 1), static_cast<long>(mesh.triangles.size()) / 100) << "folds are local";
  MeshBody with(mesh.vertices, mesh.triangles, 0.004, 0.3), without(mesh.vertices, mesh.triangles, 0.004, 0.3);
  with.update(mesh.vertices, turned);
  // Points within 2 cm of the folded triangles, off their planes.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  int points = 0, agree_with = 0, agree_without = 0;
  for (std::size_t t = 0; t < turned.size(); ++t) {
    if (!turned[t] || !on_a_leg(mesh.triangles[t])) continue;
    const Vector3i& tri = mesh.triangles[t];
    const Vector3d centre = (mesh.vertex(tri(0)) + mesh.vertex(tri(1)) + mesh.vertex(tri(2))) / 3.0;
    for (int k = 0; k < 12; ++k) {
      const Vector3d p = centre + Vector3d(u(rng), u(rng), u(rng));
      const double d = with.query(p).distance;
      if (std::abs(d) < 1e-3) continue;  // on the surface: no side to compare
      const bool inside = winding_number(mesh, p) >= 0.5;
      ++points;
      agree_with += (d < 0.0) == inside;
      agree_without += (without.query(p).distance < 0.0) == inside;
    }
  }
  std::printf("frame %d: %d leg triangles turned; near them %d points, inside/outside as the winding number: "
              "%d ignoring them, %d with them\n",
              worst_frame, worst, points, agree_with, agree_without);
  ASSERT_GT(points, 30);
  EXPECT_GT(agree_with, agree_without) << "ignoring the folded skin should agree with the oracle more often";
  // Where the legs' skin folds the surface crosses itself and the nearest
  // surface cannot always tell (measured: 161 of 180 against 155 of 180).
  EXPECT_GE(agree_with, points * 85 / 100);
}

// turned_triangles' test on every triangle, those whose corners follow one
// joint alone included (which it skips): the oracle.
std::vector<char> turned_by_testing_every_triangle(const SkinnedBody& body, const Skeleton& skeleton,
                                                   const Pose& pose, const Eigen::MatrixX3d& posed) {
  const Pose rest = rest_pose(skeleton);
  std::vector<Eigen::Matrix3d> turn(skeleton.joints.size());
  for (std::size_t j = 0; j < turn.size(); ++j) {
    turn[j] = pose.global[j].linear() * rest.global[j].linear().transpose();
    if (body.input_vertices.rows() > 0) turn[j] = turn[j] * body.rest_correction[j];
  }
  const Eigen::MatrixX3d& source = body.input_vertices.rows() > 0 ? body.input_vertices : body.rest_vertices;
  std::vector<char> turned(body.triangles.size(), 0);
  for (std::size_t t = 0; t < body.triangles.size(); ++t) {
    const Vector3i& tri = body.triangles[t];
    Eigen::Matrix3d blend = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k)
      for (const auto& [joint, w] : body.weights[static_cast<std::size_t>(tri(k))]) blend += w * turn[static_cast<std::size_t>(joint)];
    const auto at = [](const Eigen::MatrixX3d& x, int v) { return Vector3d(x.row(v).transpose()); };
    const Vector3d source_normal = (at(source, tri(1)) - at(source, tri(0))).cross(at(source, tri(2)) - at(source, tri(0)));
    const Vector3d normal = (at(posed, tri(1)) - at(posed, tri(0))).cross(at(posed, tri(2)) - at(posed, tri(0)));
    turned[t] = normal.dot(blend * source_normal) < 0.0 ? 1 : 0;
  }
  return turned;
}

// A posed body keeps one TurnedTriangles from step to step: its flags in
// each pose of a walk are the one-shot function's (the kept buffers carry
// nothing from one pose to the next), folds included, and those of testing
// every triangle (the ones it skips, moved by one joint alone, never turn).
TEST_F(SkinnedBodyTest, TurnedTrianglesKeptAcrossPosesFlagWhatTheOneShotTestFlags) {
  SKIP_WITHOUT_BODY();
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  TurnedTriangles kept(*body_);
  long folded = 0;
  for (int frame = 0; frame < walk.frames.rows(); frame += 7) {
    const Pose pose = frame_pose(walk, frame);
    const Eigen::MatrixX3d posed = skin(*body_, skeleton(), pose);
    const std::vector<char> fresh = turned_triangles(*body_, skeleton(), pose, posed);
    ASSERT_EQ(kept(skeleton(), pose, posed), fresh) << "frame " << frame;
    ASSERT_EQ(fresh, turned_by_testing_every_triangle(*body_, skeleton(), pose, posed)) << "frame " << frame;
    folded += std::count(fresh.begin(), fresh.end(), 1);
  }
  EXPECT_GT(folded, 0) << "no pose of the walk folds any skin; the comparison proves little";
  const Pose bad = frame_pose(walk, 0);
  EXPECT_THROW(kept(skeleton(), bad, Eigen::MatrixX3d::Zero(3, 3)), ArgumentError);
}

// More than 1 cm from the seen skin, with folded triangles left out, a
// point's side is the parity of the whole surface's crossings along a ray
// (MeshBody takes the shortest way out of the body's box). On the walking
// body, self-intersecting where the thighs meet, that parity is the winding
// number's (an integer off the surface) modulo 2, whichever ray is taken:
// the oracle, at points all over the body's box and inside the limbs.
TEST_F(SkinnedBodyTest, FarFromTheSeenSkinTheSideIsTheWholeBodysParity) {
  SKIP_WITHOUT_BODY();
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, true});
  const Pose pose = frame_pose(walk, 150);
  const Mesh mesh{skin(*body_, skeleton(), pose), body_->triangles};
  const std::vector<char> turned = turned_triangles(*body_, skeleton(), pose, mesh.vertices);
  ASSERT_GT(std::count(turned.begin(), turned.end(), 1), 0) << "nothing folded: the whole-mesh side is never asked";
  MeshBody body(mesh.vertices, mesh.triangles, 0.004, 0.3);
  body.update(mesh.vertices, turned);
  std::vector<Vector3d> points;
  Vector3d lo = mesh.vertices.colwise().minCoeff().transpose(), hi = mesh.vertices.colwise().maxCoeff().transpose();
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 300; ++k)
    points.push_back(lo + Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(hi - lo));
  // Inside the limbs and trunk: 2-6 cm in from every 41st vertex.
  std::vector<Vector3d> normal(static_cast<std::size_t>(mesh.vertices.rows()), Vector3d::Zero());
  for (const Vector3i& t : mesh.triangles) {
    const Vector3d n = (mesh.vertex(t(1)) - mesh.vertex(t(0))).cross(mesh.vertex(t(2)) - mesh.vertex(t(0)));
    for (int k = 0; k < 3; ++k) normal[static_cast<std::size_t>(t(k))] += n;
  }
  for (std::size_t v = 0; v < normal.size(); v += 41)
    points.push_back(mesh.vertex(static_cast<int>(v)) - (0.02 + 0.04 * unit(rng)) * normal[v].normalized());
  int inside = 0, outside = 0;
  for (const Vector3d& p : points) {
    const double d = body.query(p).distance;
    if (!(std::abs(d) > 0.011)) continue;  // near the seen skin its pseudo-normals decide
    const long winding = std::lround(winding_number(mesh, p));
    const bool odd = winding % 2 != 0;
    EXPECT_EQ(d < 0.0, odd) << "(" << p.transpose() << "): " << d << " m from the seen skin, winding number " << winding;
    (d < 0.0 ? inside : outside) += 1;
  }
  EXPECT_GE(inside, 30);
  EXPECT_GE(outside, 100);
}

TEST_F(SkinnedBodyTest, WithoutHandsTheBodyStaysClosedAndSkinsAsBefore) {
  SKIP_WITHOUT_BODY();
  const SkinnedBody& body = *body_;
  const std::vector<int> hand = hand_vertices(body, skeleton());
  const auto hand_count = std::count_if(hand.begin(), hand.end(), [](int h) { return h >= 0; });
  EXPECT_GT(hand_count, 2000) << "both hands, fingers and thumbs";
  EXPECT_LT(hand_count, 4000) << "and no forearm";
  const SkinnedBody cut = without_hands(body, skeleton());
  ASSERT_EQ(cut.rest_vertices.rows(), body.rest_vertices.rows() + 2) << "one cap vertex per wrist";
  ASSERT_EQ(cut.input_vertices.rows(), cut.rest_vertices.rows());
  ASSERT_EQ(cut.weights.size(), static_cast<std::size_t>(cut.rest_vertices.rows()));
  std::size_t kept = 0;
  for (const Vector3i& t : body.triangles) kept += hand[t[0]] < 0 && hand[t[1]] < 0 && hand[t[2]] < 0;
  std::size_t caps = 0;
  for (const Vector3i& t : cut.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_FALSE(t[k] < static_cast<int>(hand.size()) && hand[static_cast<std::size_t>(t[k])] >= 0) << "a hand vertex is left";
    }
    caps += t[2] >= static_cast<int>(body.rest_vertices.rows());
  }
  EXPECT_EQ(cut.triangles.size(), kept + caps) << "the kept triangles and the caps, nothing else";
  EXPECT_GT(caps, 20u) << "each wrist's opening goes round the wrist";
  // Closed and consistently oriented, enclosing a positive volume: MeshBody
  // refuses anything else.
  EXPECT_NO_THROW(MeshBody(cut.rest_vertices, cut.triangles));
  for (Eigen::Index v = body.rest_vertices.rows(); v < cut.rest_vertices.rows(); ++v) {
    double sum = 0.0;
    for (const auto& [j, w] : cut.weights[static_cast<std::size_t>(v)]) sum += w;
    EXPECT_NEAR(sum, 1.0, 1e-12) << "cap vertex " << v;
  }
  // The cap vertices skin like every other vertex: in the rest pose to
  // their rest position, in the mesh's pose to their input position; the
  // kept vertices exactly as in the whole body.
  const Eigen::MatrixX3d rest = skin(cut, skeleton(), rest_pose(skeleton()));
  EXPECT_LE((rest - cut.rest_vertices).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::MatrixX3d own = skin(cut, skeleton(), mesh_pose(cut, skeleton()));
  EXPECT_LE((own - cut.input_vertices).cwiseAbs().maxCoeff(), 1e-12);
  const Pose walking = pose_at(*motion_, 1.0);
  const Eigen::MatrixX3d whole = skin(body, skeleton(), walking), without = skin(cut, skeleton(), walking);
  EXPECT_EQ((whole - without.topRows(whole.rows())).cwiseAbs().maxCoeff(), 0.0);
}

TEST_F(SkinnedBodyTest, MittensSitInTheHandsAndTurnWithThem) {
  SKIP_WITHOUT_BODY();
  const std::vector<BoneCapsule> mittens = hand_mitten_capsules(skeleton(), *body_);
  ASSERT_EQ(mittens.size(), 2u);
  const std::vector<int> hand = hand_vertices(*body_, skeleton());
  const Pose rest = proportioned_pose(skeleton(), body_->joint_rest, rest_pose(skeleton()));
  for (const BoneCapsule& mitten : mittens) {
    const std::string& name = skeleton().joints[static_cast<std::size_t>(mitten.joint)].name;
    EXPECT_TRUE(name == "LeftHand" || name == "RightHand") << name;
    EXPECT_GT(mitten.radius_head, 0.01) << name;
    EXPECT_LT(mitten.radius_head, 0.04) << name << ": about half a palm wide";
    // A third or more of the hand's vertices lie within the capsule in the
    // rest pose (as thick as their median distance from its axis, over the
    // middle 90 % of the hand's length).
    CapsuleRig rig;
    rig.bones = {mitten};
    const Collider capsule = posed_capsules(rig, rest)[0];
    int mine = 0, within = 0;
    for (std::size_t v = 0; v < hand.size(); ++v) {
      if (hand[v] != mitten.joint) continue;
      const Vector3d p = body_->rest_vertices.row(static_cast<Eigen::Index>(v)).transpose();
      ++mine;
      within += query_surface(capsule, p).distance <= 1e-9;
    }
    EXPECT_GT(mine, 1000) << name;
    EXPECT_GE(within, mine / 3) << name;  // measured 38 %: the median distance, over the hand's middle 90 %
    EXPECT_LE(within, mine * 9 / 10) << name << ": the spread fingers stay partly outside";
  }
  // Posed, a mitten keeps its place in the hand: its ends stay where the
  // hand joint's frame carries them.
  const Pose walking = pose_at(*motion_, 1.0);
  CapsuleRig rig;
  rig.bones = mittens;
  const std::vector<Collider> posed = posed_capsules(rig, walking);
  for (std::size_t k = 0; k < mittens.size(); ++k) {
    const auto& c = std::get<CapsuleCollider>(posed[k].shape);
    const Eigen::Isometry3d& frame = walking.global[static_cast<std::size_t>(mittens[k].joint)];
    EXPECT_LE((c.a - (frame.translation() + frame.linear() * mittens[k].shift_head)).norm(), 1e-12);
    EXPECT_LE((c.b - (frame.translation() + frame.linear() * mittens[k].shift_tail)).norm(), 1e-12);
  }
}

TEST(WithoutHands, ABodyWithoutHandsIsUnchangedAndATornCutIsRefused) {
  // A sphere on a skeleton of a root and one hand: with no vertex on the
  // hand nothing is cut; with two opposite vertices on it the cut leaves
  // two openings for one hand, which is refused with its count; with one,
  // its five triangles go and a five-triangle cap closes the opening.
  Skeleton skeleton;
  skeleton.joints.resize(2);
  skeleton.joints[0].name = "Hips";
  skeleton.joints[1].name = "LeftHand";
  skeleton.joints[1].parent = 0;
  const Mesh sphere = icosphere(1);
  SkinnedBody body;
  body.rest_vertices = sphere.vertices;
  body.triangles = sphere.triangles;
  body.weights.assign(static_cast<std::size_t>(sphere.vertices.rows()), {{0, 1.0}});
  const SkinnedBody same = without_hands(body, skeleton);
  EXPECT_EQ(same.triangles, body.triangles);
  EXPECT_EQ(same.rest_vertices, body.rest_vertices);
  ASSERT_EQ((body.rest_vertices.row(0) + body.rest_vertices.row(3)).norm(), 0.0) << "vertices 0 and 3 are opposite";
  body.weights[0] = {{1, 0.75}, {0, 0.25}};
  body.weights[3] = {{1, 0.6}, {0, 0.4}};
  try {
    without_hands(body, skeleton);
    ADD_FAILURE() << "two openings for one hand were accepted";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("leaves 2 openings; expected one per hand (1)"), std::string::npos) << e.what();
  }
  body.weights[3] = {{0, 1.0}};
  const SkinnedBody cut = without_hands(body, skeleton);
  const Eigen::Index n = body.rest_vertices.rows();
  ASSERT_EQ(cut.rest_vertices.rows(), n + 1);
  EXPECT_EQ(cut.triangles.size(), body.triangles.size()) << "five triangles cut, five in the cap";
  Eigen::RowVector3d ring = Eigen::RowVector3d::Zero();
  int neighbours = 0;
  for (const Vector3i& t : body.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] == 0) {
        ring += body.rest_vertices.row(t[(k + 1) % 3]);
        ++neighbours;
      }
  ASSERT_EQ(neighbours, 5);
  EXPECT_LE((cut.rest_vertices.row(n) - ring / 5.0).norm(), 1e-15) << "the cap's centre: the opening's centroid";
  for (const Vector3i& t : cut.triangles) EXPECT_TRUE(t[0] != 0 && t[1] != 0 && t[2] != 0);
  ASSERT_EQ(cut.weights.size(), static_cast<std::size_t>(n + 1));
  EXPECT_EQ(cut.weights[static_cast<std::size_t>(n)], (std::vector<std::pair<int, double>>{{0, 1.0}}));
  EXPECT_NO_THROW(MeshBody(cut.rest_vertices, cut.triangles)) << "closed, consistently oriented, outward";
}

// ---- another skeleton: CMU 16_15 in its DAZ-friendly conversion ------------

/// Edges of the body stretched or shortened by more than 25 % between the
/// input mesh and `posed`, counted by the joint that dominates their first
/// vertex.
std::map<std::string, int> distorted_edges(const SkinnedBody& body, const Skeleton& skeleton, const Eigen::MatrixX3d& posed) {
  std::map<std::string, int> out;
  for (const Vector3i& t : body.triangles)
    for (int k = 0; k < 3; ++k) {
      const int i = t(k), j = t((k + 1) % 3);
      const double rest = (body.input_vertices.row(i) - body.input_vertices.row(j)).norm();
      const double now = (posed.row(i) - posed.row(j)).norm();
      if (!(std::abs(now / rest - 1.0) > 0.25)) continue;
      int top = -1;
      double top_weight = 0.0;
      for (const auto& [joint, w] : body.weights[static_cast<std::size_t>(i)])
        if (w > top_weight) {
          top = joint;
          top_weight = w;
        }
      ++out[skeleton.joints[static_cast<std::size_t>(top)].name];
    }
  return out;
}

TEST(SkinnedBodyOtherSkeleton, TheDazClipBindsOnceItsJointsAreRenamed) {
  const std::string clip = test::shared_data("motions/cmu_daz/16_15_daz.bvh");
  if (!have_body() || !fs::exists(clip)) GTEST_SKIP() << "shared data absent under " << test::shared_data("");
  Motion motion = read_bvh(clip, {0.01, false});
  const MakeHumanOptions files = makehuman_files(test::shared_data("bodies/makehuman"));
  // As the file names them, no joint is a rig bone: refused, naming the way out.
  try {
    load_makehuman_body(files, motion.skeleton);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("root joint \"hip\" has no bone in the rig; expected the rig's root \"Hips\""),
              std::string::npos) << e.what();
  }
  rename_joints(motion.skeleton, cmu_renaming(motion.skeleton));
  const Skeleton& skeleton = motion.skeleton;
  const SkinnedBody body = load_makehuman_body(files, skeleton);
  ASSERT_EQ(body.rest_vertices.rows(), 13380);
  // Skinning reproduces the bound rest mesh and, in the mesh's own pose, base.obj.
  EXPECT_LE((skin(body, skeleton, rest_pose(skeleton)) - body.rest_vertices).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::MatrixX3d input = input_mesh(body);
  EXPECT_LE((body.input_vertices - input).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((skin(body, skeleton, mesh_pose(body, skeleton)) - input).cwiseAbs().maxCoeff(), 1e-12);
  // Weights: normalised, and only on joints the rig has a bone for (the
  // eyes and finger links have none); the skin of the rig's bones DAZ lacks
  // (Spine, Neck1, the toes, the fingers) went to their nearest ancestors.
  std::map<std::string, int> dominated;
  for (const auto& list : body.weights) {
    double sum = 0.0, top_weight = 0.0;
    int top = -1;
    for (const auto& [joint, w] : list) {
      const std::string& name = skeleton.joints[static_cast<std::size_t>(joint)].name;
      EXPECT_TRUE(name != "leftEye" && name != "rightEye" && name.find("Index") == std::string::npos &&
                  name.find("Thumb") == std::string::npos)
          << name << " carries skin";
      sum += w;
      if (w > top_weight) {
        top = joint;
        top_weight = w;
      }
    }
    ASSERT_NEAR(sum, 1.0, 1e-12);
    ++dominated[skeleton.joints[static_cast<std::size_t>(top)].name];
  }
  EXPECT_GT(dominated["LeftHand"], 300) << "the hand carries its fingers";
  EXPECT_GT(dominated["LeftFoot"], 200) << "the foot carries its toes";
  EXPECT_GT(dominated["LowerBack"], 300) << "the lower back carries the spine";
  EXPECT_GT(dominated["Head"], 2000);
  // The pelvis keeps its shape in the rest pose: DAZ's hip branches (the
  // buttocks, 9 cm from the hip joint) keep the hip's correction, as CMU's
  // (at the hip joint) do. Turned onto their bones, which point backwards,
  // they twisted the hips: 730 edges of the pelvis and thighs beyond 25 %
  // instead of 12.
  const std::map<std::string, int> distorted = distorted_edges(body, skeleton, body.rest_vertices);
  int hips = 0;
  for (const char* name : {"Hips", "LHipJoint", "RHipJoint", "LeftUpLeg", "RightUpLeg"})
    hips += distorted.count(name) ? distorted.at(name) : 0;
  EXPECT_LE(hips, 60);
}

TEST_F(SkinnedBodyTest, ThePosedBodysDepthIsItsMeshsOrItsBridgesAsDepthsSays) {
  SKIP_WITHOUT_BODY();
  // The skinned body as a run collides with it (make_character: the mesh,
  // the leg bridges and the mittens), posed at walk frames: around its
  // skin, depth() and penetration() agree with depths() to the bit, and
  // some points are inside.
  const QuadMesh skirt = load_garment(test::shared_data("garments/makehuman/skirthelper.obj"), {"dm"}).mesh;
  CharacterSetup setup;
  setup.body = CharacterBodyKind::mesh;
  setup.makehuman = makehuman_files(test::shared_data("bodies/makehuman"));
  setup.place = GarmentPlacement::makehuman;
  const Character character = make_character(*motion_, setup, skirt);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> offset(-0.015, 0.015);
  int inside = 0, points = 0;
  for (const int frame : {40, 160, 300}) {
    const Pose pose = frame_pose(*character.motion, frame);
    character.body->set_pose(pose);
    const CollisionScene& scene = character.body->scene();
    const BodySurface surface = character.body->surface(pose);
    for (Eigen::Index v = 0; v < surface.vertices.rows(); v += 37, ++points) {
      const Vector3d p = surface.vertices.row(v).transpose() + Vector3d(offset(rng), offset(rng), offset(rng));
      const PointDepths both = scene.depths(p);
      ASSERT_EQ(scene.depth(p), both.depth) << "frame " << frame << ", near body vertex " << v;
      ASSERT_EQ(scene.penetration(p), both.penetration) << "frame " << frame << ", near body vertex " << v;
      inside += both.depth > 0.0;
    }
  }
  EXPECT_GT(inside, points / 10) << "of " << points;
  EXPECT_LT(inside, points) << "of " << points;
}

TEST(SkinnedBodyParts, PartsThatDoNotMatchAreRefusedNamingTheCall) {
  // A two-joint chain and a three-vertex body: each part whose count does
  // not match the body's vertices or the skeleton's joints is refused by
  // every call that reads it, the message naming the call and the counts.
  Skeleton skeleton;
  for (int k = 0; k < 2; ++k) {
    Joint j;
    j.name = k == 0 ? "Hips" : "Spine";
    j.parent = k - 1;
    j.offset = {0.0, 0.1 * k, 0.0};
    j.channels = {Channel::z_rotation, Channel::x_rotation, Channel::y_rotation};
    j.first_channel = 3 * k;
    skeleton.joints.push_back(j);
  }
  SkinnedBody good;
  good.rest_vertices = Eigen::MatrixX3d::Identity(3, 3);
  good.triangles = {Vector3i(0, 1, 2)};
  good.weights = {{{0, 1.0}}, {{1, 1.0}}, {{0, 0.5}, {1, 0.5}}};
  const Pose rest = rest_pose(skeleton);
  ASSERT_NO_THROW(skin(good, skeleton, rest));
  const auto expect_refused = [&](const SkinnedBody& body, const std::string& part) {
    for (const auto& [call, run] : std::vector<std::pair<std::string, std::function<void()>>>{
             {"skin", [&] { skin(body, skeleton, rest); }},
             {"mesh_pose", [&] { mesh_pose(body, skeleton); }},
             {"turned_triangles", [&] { turned_triangles(body, skeleton, rest, good.rest_vertices); }}}) {
      try {
        run();
        ADD_FAILURE() << call << " took " << part;
      } catch (const ArgumentError& error) {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind(call + ": the body", 0), 0u) << message;
        EXPECT_NE(message.find(part), std::string::npos) << message;
      }
    }
  };
  SkinnedBody weights = good;
  weights.weights.pop_back();
  expect_refused(weights, "2 weight lists for 3 vertices");
  SkinnedBody pivots = good;
  pivots.joint_rest = {Vector3d::Zero()};
  expect_refused(pivots, "1 joint pivots; expected 2");
  SkinnedBody input = good;
  input.input_vertices = Eigen::MatrixX3d::Zero(2, 3);
  input.input_joints.assign(2, Vector3d::Zero());
  input.rest_correction.assign(2, Eigen::Matrix3d::Identity());
  expect_refused(input, "input mesh (2 vertices, 2 joints, 2 corrections) does not match its 3 vertices");
  // Only turned_triangles reads the triangles.
  SkinnedBody corner = good;
  corner.triangles = {Vector3i(0, 1, 7)};
  EXPECT_NO_THROW(skin(corner, skeleton, rest));
  try {
    turned_triangles(corner, skeleton, rest, good.rest_vertices);
    ADD_FAILURE() << "turned_triangles took a triangle naming vertex 7";
  } catch (const ArgumentError& error) {
    EXPECT_STREQ(error.what(), "turned_triangles: the body's triangle 0 names vertex 7; expected an index below 3");
  }
}

}  // namespace
}  // namespace mrcloth
