// The solver's readers given thousands of seeded edits of valid files
// (tests/input_mutations.h): BVH motions, PC2 caches (three ways of reading
// them), the OBJ meshes beside caches, JSON, and the MakeHuman body's rig,
// weights and mesh (the shared data's, when present). Each edit is either
// read, and what comes back holds the reader's promises, or refused with
// InputError naming the file (and the line, for the line-oriented text
// formats). Anything else fails, with the input kept for replay.
#include "mesh_ops/errors.h"
#include "solver/body_skinned_mesh.h"
#include "solver/json_lite.h"
#include "solver/point_cache.h"
#include "solver/skeleton.h"
#include "input_mutations.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool all_finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// ---- BVH -------------------------------------------------------------------

/// Three joints in two chains under a root with every channel, channel
/// orders of several kinds, a joint with position channels, End Sites and
/// five frames.
std::string valid_bvh() {
  return "HIERARCHY\n"
         "ROOT Hips\n"
         "{\n"
         "\tOFFSET 0.00 0.00 0.00\n"
         "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
         "\tJOINT Spine\n"
         "\t{\n"
         "\t\tOFFSET 0.00 5.21 0.10\n"
         "\t\tCHANNELS 3 Yrotation Xrotation Zrotation\n"
         "\t\tJOINT Head\n"
         "\t\t{\n"
         "\t\t\tOFFSET 0.00 4.50 0.00\n"
         "\t\t\tCHANNELS 4 Xposition Xrotation Zrotation Yrotation\n"
         "\t\t\tEnd Site\n"
         "\t\t\t{\n"
         "\t\t\t\tOFFSET 0.00 1.50 0.00\n"
         "\t\t\t}\n"
         "\t\t}\n"
         "\t}\n"
         "\tJOINT LeftUpLeg\n"
         "\t{\n"
         "\t\tOFFSET 1.50 -0.50 0.00\n"
         "\t\tCHANNELS 2 Zrotation Xrotation\n"
         "\t\tEnd Site\n"
         "\t\t{\n"
         "\t\t\tOFFSET 0.00 -7.50 0.00\n"
         "\t\t}\n"
         "\t}\n"
         "}\n"
         "MOTION\n"
         "Frames: 5\n"
         "Frame Time: 0.008333\n"
         "1.0 17.5 -2.0 3.5 -10.0 2.0 12.0 -4.5 1.0 0.25 8.0 -3.0 4.5 20.0 -15.0\n"
         "1.5 17.4 -1.0 4.0 -9.5 2.5 11.0 -4.0 1.5 0.30 7.5 -2.5 4.0 25.0 -12.5\n"
         "2.0 17.3 0.0 4.5 -9.0 3.0 10.0 -3.5 2.0 0.35 7.0 -2.0 3.5 30.0 -10.0\n"
         "2.5 17.2 1.0 5.0 -8.5 3.5 9.0 -3.0 2.5 0.40 6.5 -1.5 3.0 35.0 -7.5\n"
         "3.0 17.1 2.0 5.5 -8.0 4.0 8.0 -2.5 3.0 0.45 6.0 -1.0 2.5 40.0 -5.0\n";
}

/// What read_bvh promises of a motion it returns, and forward kinematics
/// of it: joints in parent-first order with unique names, a frame table as
/// wide as the channels, finite numbers, a positive frame time, and poses
/// at any time with finite transforms whose bones (joints without position
/// channels) keep their offsets' lengths.
void expect_sound_motion(const Motion& motion, const std::string& input) {
  const Skeleton& skeleton = motion.skeleton;
  ASSERT_FALSE(skeleton.joints.empty()) << input;
  std::set<std::string> names;
  int channels = 0;
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    ASSERT_LT(joint.parent, static_cast<int>(j)) << input;
    ASSERT_TRUE(names.insert(joint.name).second) << "joint name " << joint.name << " twice\n" << input;
    ASSERT_TRUE(all_finite(joint.offset)) << joint.name << "\n" << input;
    ASSERT_EQ(joint.first_channel, channels) << joint.name << "\n" << input;
    channels += static_cast<int>(joint.channels.size());
  }
  ASSERT_EQ(skeleton.channel_count(), channels);
  ASSERT_EQ(motion.frames.cols(), channels) << input;
  ASSERT_GE(motion.frames.rows(), 1) << input;
  ASSERT_TRUE(motion.frames.allFinite()) << input;
  ASSERT_TRUE(std::isfinite(motion.frame_time) && motion.frame_time > 0.0) << input;
  for (const double time : {0.0, 0.5 * motion.frame_time, motion.duration()}) {
    const Pose pose = pose_at(motion, time);
    ASSERT_EQ(pose.global.size(), skeleton.joints.size());
    for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
      const Joint& joint = skeleton.joints[j];
      ASSERT_TRUE(pose.global[j].matrix().allFinite()) << joint.name << " at " << time << " s\n" << input;
      bool moves = false;
      for (const Channel c : joint.channels) moves |= is_position(c);
      if (joint.parent < 0 || moves) continue;
      const Eigen::Vector3d at = pose.position(static_cast<int>(j)), parent_at = pose.position(joint.parent);
      // Round-off relative to the numbers summed (a 1e19 m offset above
      // leaves nothing of a 0.15 m bone).
      const double magnitude = at.norm() + parent_at.norm() + joint.offset.norm();
      ASSERT_NEAR((at - parent_at).norm(), joint.offset.norm(), 1e-12 * std::max(1.0, magnitude))
          << joint.name << " at " << time << " s\n" << input;
    }
  }
}

TEST(BvhMutations, TextEditsReadSoundOrAreRefusedNamingTheFileAndLine) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("solver_input_mutation_test", "bvh");
  const std::string valid = valid_bvh();
  test::write_bytes(dir / "valid.bvh", valid);
  const Motion reference = read_bvh((dir / "valid.bvh").string(), {0.1, false});
  ASSERT_EQ(reference.skeleton.joints.size(), 6u);
  ASSERT_EQ(reference.frames.rows(), 5);
  expect_sound_motion(reference, valid);

  const auto read = [](const std::string& path, const std::string& input) {
    expect_sound_motion(read_bvh(path, {0.1, false}), input);
  };
  const std::string alphabet = "HIERARCHYROOTJOINTEndSiteOFFSETCHANNELSXYZpositionrotationMOTIONFrames:{}\n\t -.0123456789";
  const test::SweepTally tally =
      test::sweep_reader(dir, ".bvh", valid, test::TextMutator(21, alphabet), 2000, test::Naming::file_and_line, read);
  EXPECT_GT(tally.read, 100);
  EXPECT_GT(tally.refused, 500);
  // With the first frame skipped, as a CMU clip is read.
  const test::SweepTally skipping = test::sweep_reader(
      dir, ".bvh", valid, test::TextMutator(22, alphabet), 500, test::Naming::file_and_line,
      [](const std::string& path, const std::string& input) {
        expect_sound_motion(read_bvh(path, {0.1, true}), input);
      });
  EXPECT_GT(skipping.read, 20);
  EXPECT_GT(skipping.refused, 100);
}

// ---- PC2 -------------------------------------------------------------------

/// A cache of 5 points over 4 frames, written by Pc2Writer.
std::string valid_pc2(const fs::path& dir) {
  const fs::path path = dir / "valid.pc2";
  Pc2Writer writer(path.string(), 5, 3.0, 1.0);
  for (int f = 0; f < 4; ++f) {
    FramePositions frame(5, 3);
    for (int v = 0; v < 5; ++v) frame.row(v) << 0.1 * v, 1.0 - 0.05 * f, 0.01 * v * f;
    writer.add_frame(frame);
  }
  writer.finish();
  return read_text(path.string());
}

/// read_pc2, Pc2Reader (frame and finite_frame) and read_pc2_frame agree
/// on every frame of a cache they read, to the bit; finite_frame returns
/// finite positions or refuses naming the file.
void expect_consistent_cache(const std::string& path, const std::string& input) {
  const PointCache cache = read_pc2(path);
  ASSERT_GT(cache.num_points, 0);
  Pc2Reader reader(path);
  ASSERT_EQ(reader.num_points(), cache.num_points);
  ASSERT_EQ(reader.num_frames(), static_cast<int>(cache.frames.size()));
  ASSERT_EQ(static_cast<double>(reader.start_frame()), cache.start_frame);
  for (int f = 0; f < reader.num_frames(); ++f) {
    const FramePositions& whole = cache.frames[static_cast<std::size_t>(f)];
    ASSERT_EQ(whole.rows(), cache.num_points);
    const FramePositions streamed = reader.frame(f);
    const FramePositions single = read_pc2_frame(path, f);
    // Bitwise, NaN included: the three read the same bytes.
    ASSERT_EQ(std::memcmp(streamed.data(), whole.data(), sizeof(double) * static_cast<std::size_t>(whole.size())), 0)
        << "frame " << f;
    ASSERT_EQ(std::memcmp(single.data(), whole.data(), sizeof(double) * static_cast<std::size_t>(whole.size())), 0)
        << "frame " << f;
    try {
      ASSERT_TRUE(reader.finite_frame(f).allFinite()) << "frame " << f;
    } catch (const InputError& error) {
      ASSERT_FALSE(whole.allFinite()) << error.what();
      ASSERT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
  }
  (void)input;
}

TEST(Pc2Mutations, ByteEditsReadTheSameThreeWaysOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("solver_input_mutation_test", "pc2");
  const std::string valid = valid_pc2(dir);
  ASSERT_EQ(valid.size(), 32u + 4u * 5u * 12u);
  expect_consistent_cache((dir / "valid.pc2").string(), "");
  // Edits anywhere (mostly refused by the header's sizes), and edits of the
  // positions alone, behind an intact header (read, NaN and all).
  const test::SweepTally whole = test::sweep_reader(dir, ".pc2", valid, test::ByteMutator(23), 1000,
                                                    test::Naming::file, expect_consistent_cache);
  const test::SweepTally data = test::sweep_reader(dir, ".pc2", valid, test::ByteMutator(24, 32), 1000,
                                                   test::Naming::file, expect_consistent_cache);
  EXPECT_GT(whole.refused, 500);
  EXPECT_GT(data.read, 100);
}

// ---- the OBJ beside a cache ------------------------------------------------

TEST(ObjMeshMutations, TextEditsReadInRangeOrAreRefusedNamingTheFile) {
  test::bound_memory();
  const fs::path dir = test::fresh_folder("solver_input_mutation_test", "obj");
  FramePositions positions(6, 3);
  for (int v = 0; v < 6; ++v) positions.row(v) << 0.1 * (v % 3), 0.1 * (v / 3), 0.0;
  write_obj((dir / "valid.obj").string(), positions, {{0, 1, 4, 3}, {1, 2, 5, 4}},
            {{{0, 0}, {0.5, 0}, {0.5, 1}, {0, 1}}, {{0.5, 0}, {1, 0}, {1, 1}, {0.5, 1}}});
  const std::string valid = read_text((dir / "valid.obj").string()) + "f -3 -2 -1\n";
  const auto read = [](const std::string& path, const std::string& input) {
    const ObjMesh mesh = read_obj(path);
    ASSERT_GT(mesh.positions.rows(), 0) << input;
    ASSERT_FALSE(mesh.faces.empty()) << input;
    for (const auto& face : mesh.faces) {
      ASSERT_GE(face.size(), 3u) << input;
      for (const int v : face) ASSERT_TRUE(v >= 0 && v < mesh.positions.rows()) << v << "\n" << input;
    }
  };
  test::write_bytes(dir / "valid.obj", valid);
  read((dir / "valid.obj").string(), valid);
  ASSERT_EQ(read_obj((dir / "valid.obj").string()).faces.size(), 3u);
  const test::SweepTally tally =
      test::sweep_reader(dir, ".obj", valid, test::TextMutator(25, "vtf/ #\n-.0123456789e"), 2000, test::Naming::file, read);
  EXPECT_GT(tally.read, 200);
  EXPECT_GT(tally.refused, 200);
}

// ---- JSON ------------------------------------------------------------------

/// A rig-like JSON text with every kind of value, escapes and nesting.
std::string valid_json() {
  return "{\n"
         "  \"name\": \"cmu \\\"mb\\\" \\u00e9\\ud83d\\ude00\\n\",\n"
         "  \"version\": 110,\n"
         "  \"scale\": -1.25e-2,\n"
         "  \"tags\": [\"a\", \"b\\/c\", \"\\t\"],\n"
         "  \"bones\": {\n"
         "    \"Hips\": {\"head\": \"hips\", \"tail\": \"spine\", \"parent\": null, \"roll\": 0.0, \"flag\": true},\n"
         "    \"Spine\": {\"head\": \"spine\", \"tail\": \"neck\", \"parent\": \"Hips\", \"roll\": 12.5, \"flag\": false,\n"
         "              \"weights_reference\": [\"spine01\", \"spine02\"]}\n"
         "  },\n"
         "  \"weights\": {\"Hips\": [[0, 0.5], [1, 1.0], [2, 0.125]], \"Spine\": [[3, 1e0], [4, 0.75E+0]]},\n"
         "  \"empty\": [[], {}]\n"
         "}\n";
}

/// What parse_json promises of a value it returns: lines within the text,
/// finite numbers, unique keys, the source it was given.
void expect_sound_json(const JsonValue& value, int lines, const std::string& source) {
  ASSERT_TRUE(value.line() >= 1 && value.line() <= lines) << value.line();
  ASSERT_EQ(value.source(), source);
  if (value.is_number()) {
    ASSERT_TRUE(std::isfinite(value.as_number()));
  }
  if (value.is_array()) {
    for (const JsonValue& item : value.as_array()) expect_sound_json(item, lines, source);
  }
  if (value.is_object()) {
    std::set<std::string> keys;
    for (const auto& [key, member] : value.as_object()) {
      ASSERT_TRUE(keys.insert(key).second) << "key " << key << " twice";
      ASSERT_EQ(value.find(key), &member);
      expect_sound_json(member, lines, source);
    }
  }
}

TEST(JsonMutations, TextEditsParseSoundOrAreRefusedNamingTheSourceAndLine) {
  const fs::path dir = test::fresh_folder("solver_input_mutation_test", "json");
  const std::string valid = valid_json();
  const auto read = [](const std::string& path, const std::string& input) {
    const int lines = 1 + static_cast<int>(std::count(input.begin(), input.end(), '\n'));
    const JsonValue value = parse_json(input, path);
    expect_sound_json(value, lines, path);
    // read_json reads the same file to the same values.
    const JsonValue again = read_json(path);
    ASSERT_EQ(again.kind(), value.kind());
  };
  test::write_bytes(dir / "valid.json", valid);
  read((dir / "valid.json").string(), valid);
  const test::SweepTally tally = test::sweep_reader(dir, ".json", valid,
                                                    test::TextMutator(26, "{}[]\":,\\u0123456789abcdefEtrunlsx \n.-+"),
                                                    3000, test::Naming::file_and_line, read);
  EXPECT_GT(tally.read, 100);
  EXPECT_GT(tally.refused, 1000);
}

// ---- the MakeHuman body (shared data) --------------------------------------

bool have_makehuman() {
  return fs::exists(test::shared_data("bodies/makehuman/base.obj")) &&
         fs::exists(test::shared_data("bodies/makehuman/rigs/cmu_mb.mhskel")) &&
         fs::exists(test::shared_data("bodies/makehuman/rigs/default_weights.mhw")) &&
         fs::exists(test::shared_data("motions/cmu_mb/07_06.bvh"));
}

std::string makehuman_absent() {
  return "shared data absent under " + test::shared_data("") +
         " (set MRCLOTH_SHARED_DATA to the folder with bodies/makehuman and motions/cmu_mb)";
}

/// What load_makehuman_body promises of a body it returns: finite rest and
/// input vertices, triangles in range, each vertex's weights on skeleton
/// joints summing to 1, and the rest pose skinning to the rest vertices.
void expect_sound_body(const SkinnedBody& body, const Skeleton& skeleton) {
  ASSERT_GT(body.rest_vertices.rows(), 0);
  ASSERT_TRUE(body.rest_vertices.allFinite());
  ASSERT_TRUE(body.input_vertices.allFinite());
  const auto count = static_cast<int>(body.rest_vertices.rows());
  ASSERT_FALSE(body.triangles.empty());
  for (const Eigen::Vector3i& t : body.triangles)
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(t[c] >= 0 && t[c] < count) << t.transpose();
  ASSERT_EQ(body.weights.size(), static_cast<std::size_t>(count));
  for (std::size_t v = 0; v < body.weights.size(); ++v) {
    double sum = 0.0;
    for (const auto& [joint, w] : body.weights[v]) {
      ASSERT_TRUE(joint >= 0 && joint < static_cast<int>(skeleton.joints.size())) << "vertex " << v;
      ASSERT_TRUE(std::isfinite(w)) << "vertex " << v;
      sum += w;
    }
    ASSERT_NEAR(sum, 1.0, 1e-9) << "vertex " << v;
  }
  const Eigen::MatrixX3d rest = skin(body, skeleton, rest_pose(skeleton));
  ASSERT_TRUE(rest.allFinite());
  // Round-off relative to the body's extent (an edit may put a vertex far off).
  ASSERT_LE((rest - body.rest_vertices).cwiseAbs().maxCoeff(),
            1e-12 * std::max(1.0, body.rest_vertices.cwiseAbs().maxCoeff()));
}

/// Sweeps edits of one of the MakeHuman files (`which` picks it from the
/// options), the other two as shared.
template <class Mutator>
test::SweepTally sweep_makehuman_file(const std::string& name, std::string MakeHumanOptions::*which,
                                      Mutator mutate, int count, test::Naming naming) {
  const Motion walk = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {0.056444, true});
  const MakeHumanOptions shared = makehuman_files(test::shared_data("bodies/makehuman"));
  const fs::path dir = test::fresh_folder("solver_input_mutation_test", name);
  const std::string valid = read_text(shared.*which);
  const std::string suffix = fs::path(shared.*which).extension().string();
  return test::sweep_reader(dir, suffix, valid, std::move(mutate), count, naming,
                            [&](const std::string& path, const std::string&) {
                              MakeHumanOptions files = shared;
                              files.*which = path;
                              expect_sound_body(load_makehuman_body(files, walk.skeleton), walk.skeleton);
                            });
}

TEST(MakeHumanMutations, RigEditsBindSoundOrAreRefusedNamingTheFile) {
  if (!have_makehuman()) {
    GTEST_SKIP() << makehuman_absent();
  }
  test::bound_memory();
  const test::SweepTally tally = sweep_makehuman_file(
      "mhskel", &MakeHumanOptions::skeleton_file, test::TextMutator(27, "{}[]\":,headtilprnwgsjo \n.-0123456789"), 300,
      test::Naming::file);
  EXPECT_GT(tally.read, 10);
  EXPECT_GT(tally.refused, 30);
}

TEST(MakeHumanMutations, WeightEditsBindSoundOrAreRefusedNamingTheFile) {
  if (!have_makehuman()) {
    GTEST_SKIP() << makehuman_absent();
  }
  test::bound_memory();
  const test::SweepTally tally = sweep_makehuman_file(
      "mhw", &MakeHumanOptions::weights_file, test::TextMutator(28, "{}[]\":,weightsbo \n.-0123456789e"), 300,
      test::Naming::file);
  EXPECT_GT(tally.read, 10);
  EXPECT_GT(tally.refused, 30);
}

TEST(MakeHumanMutations, MeshEditsBindSoundOrAreRefusedNamingTheFile) {
  if (!have_makehuman()) {
    GTEST_SKIP() << makehuman_absent();
  }
  test::bound_memory();
  const test::SweepTally tally = sweep_makehuman_file(
      "base_obj", &MakeHumanOptions::base_obj, test::TextMutator(29, "vtfg/ #\nbodyhelper-.0123456789e"), 200,
      test::Naming::file);
  EXPECT_GT(tally.read, 10);
  EXPECT_GT(tally.refused, 20);
}

}  // namespace
}  // namespace mrcloth
