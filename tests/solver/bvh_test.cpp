// read_bvh / write_bvh: the real CMU clips, malformed files with exact line
// numbers, robustness against garbage, and write-then-read round trips.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mesh_ops/errors.h"
#include "solver/skeleton.h"
#include "test_meshes.h"

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

constexpr double kCmuScale = 0.056444;

/// A fresh, empty folder per test.
fs::path empty_folder(const std::string& name) { return test::fresh_folder("bvh_test", name); }

std::string write_text(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  return path.string();
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

std::vector<std::string> folder_contents(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  return names;
}

// ---- the real clips ------------------------------------------------------

struct Clip {
  const char* file;
  int joints;  ///< ROOT + JOINT, End Sites excluded
  int frames;  ///< README table
  double scale;
};

const Clip kClips[] = {
    {"motions/cmu_mb/07_06.bvh", 31, 418, kCmuScale},
    {"motions/cmu_mb/07_03.bvh", 31, 416, kCmuScale},
    {"motions/cmu_mb/08_03.bvh", 31, 354, kCmuScale},
    {"motions/cmu_mb/02_01.bvh", 31, 344, kCmuScale},
    {"motions/cmu_mb/13_29_squats_f3760-4580.bvh", 31, 822, kCmuScale},
    {"motions/cmu_mb/09_01.bvh", 31, 149, kCmuScale},
    {"motions/cmu_daz/16_15_daz.bvh", 43, 472, 0.01},
};

bool have_motions() { return fs::exists(test::shared_data("motions")); }

#define SKIP_WITHOUT_SHARED_DATA()                                       \
  if (!have_motions())                                                   \
  GTEST_SKIP() << "shared data absent: " << test::shared_data("motions") \
               << " (set MRCLOTH_SHARED_DATA to the folder with motions/cmu_mb and motions/cmu_daz)"

/// Independent counts from the raw text: ROOT/JOINT/End keywords and the "Frames:" value.
struct RawCounts {
  int joints = 0;
  int end_sites = 0;
  int frames = -1;
  int channels = 0;
};

RawCounts raw_counts(const std::string& path) {
  std::ifstream in(path);
  RawCounts counts;
  std::string word, previous;
  while (in >> word) {
    if (word == "ROOT" || word == "JOINT") ++counts.joints;
    if (word == "End") ++counts.end_sites;
    if (previous == "CHANNELS") counts.channels += std::stoi(word);
    if (word == "Frames:") {
      in >> counts.frames;
      break;
    }
    previous = word;
  }
  return counts;
}

int non_end_site_joints(const Skeleton& skeleton) {
  return static_cast<int>(std::count_if(skeleton.joints.begin(), skeleton.joints.end(),
                                        [](const Joint& joint) { return !joint.end_site; }));
}

TEST(BvhRead, EveryClipHasTheDocumentedJointsFramesAndFrameTime) {
  SKIP_WITHOUT_SHARED_DATA();
  for (const Clip& clip : kClips) {
    SCOPED_TRACE(clip.file);
    const std::string path = test::shared_data(clip.file);
    const RawCounts raw = raw_counts(path);
    ASSERT_EQ(raw.joints, clip.joints) << "the raw ROOT/JOINT count disagrees with the table";
    ASSERT_EQ(raw.frames, clip.frames) << "the file's Frames: line disagrees with the README table";

    const Motion motion = read_bvh(path, {clip.scale, false});
    EXPECT_EQ(non_end_site_joints(motion.skeleton), clip.joints);
    EXPECT_EQ(non_end_site_joints(motion.skeleton), raw.joints);
    EXPECT_EQ(static_cast<int>(motion.skeleton.joints.size()), raw.joints + raw.end_sites);
    EXPECT_EQ(motion.frames.rows(), clip.frames);
    EXPECT_EQ(motion.frames.cols(), raw.channels);
    EXPECT_EQ(motion.skeleton.channel_count(), raw.channels);
    EXPECT_NEAR(motion.frame_time, 1.0 / 120.0, 1e-6);
    EXPECT_NEAR(motion.duration(), (clip.frames - 1) * motion.frame_time, 1e-12);

    const Motion skipped = read_bvh(path, {clip.scale, true});
    EXPECT_EQ(skipped.frames.rows(), clip.frames - 1);
    EXPECT_EQ(skipped.frames.row(0), motion.frames.row(1));
    EXPECT_EQ(skipped.frames.row(clip.frames - 2), motion.frames.row(clip.frames - 1));
  }
}

// Scaling a motion read in file units gives, to the bit, what reading it
// with that scale gives: offsets and position channels, nothing else.
TEST(BvhRead, ScalingAfterReadingIsReadingWithTheScale) {
  SKIP_WITHOUT_SHARED_DATA();
  for (const char* clip : {"motions/cmu_mb/07_06.bvh", "motions/cmu_daz/16_15_daz.bvh"}) {
    const double scale = std::string(clip).find("daz") != std::string::npos ? 0.01 : kCmuScale;
    Motion scaled = read_bvh(test::shared_data(clip), {1.0, false});
    scale_motion(scaled, scale);
    const Motion read = read_bvh(test::shared_data(clip), {scale, false});
    EXPECT_TRUE(scaled.frames == read.frames) << clip;
    ASSERT_EQ(scaled.skeleton.joints.size(), read.skeleton.joints.size());
    for (std::size_t j = 0; j < read.skeleton.joints.size(); ++j)
      EXPECT_TRUE(scaled.skeleton.joints[j].offset == read.skeleton.joints[j].offset) << clip << " joint " << j;
  }
}

TEST(BvhRead, CmuLayoutNamesChannelsAndScale) {
  SKIP_WITHOUT_SHARED_DATA();
  const Motion motion = read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, false});
  const Skeleton& skeleton = motion.skeleton;
  ASSERT_EQ(non_end_site_joints(skeleton), 31);
  EXPECT_EQ(skeleton.joints[0].name, "Hips");
  EXPECT_EQ(skeleton.joints[0].parent, -1);
  EXPECT_EQ(skeleton.joints[0].channels,
            (std::vector<Channel>{Channel::x_position, Channel::y_position, Channel::z_position, Channel::z_rotation,
                                  Channel::y_rotation, Channel::x_rotation}));
  const std::vector<Channel> zyx{Channel::z_rotation, Channel::y_rotation, Channel::x_rotation};
  int columns = 0;
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    EXPECT_LT(joint.parent, static_cast<int>(j));
    EXPECT_EQ(joint.first_channel, columns) << joint.name;
    columns += static_cast<int>(joint.channels.size());
    if (joint.end_site) {
      EXPECT_TRUE(joint.channels.empty());
      EXPECT_EQ(joint.name, skeleton.joints[joint.parent].name + "_end");
    } else if (j > 0) {
      EXPECT_EQ(joint.channels, zyx) << joint.name;
    }
  }
  for (const char* name : {"LHipJoint", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "LowerBack", "Spine",
                           "Spine1", "Neck", "Neck1", "Head", "LeftShoulder", "LeftArm", "LeftForeArm", "LeftHand"})
    EXPECT_GE(skeleton.find(name), 0) << name;
  EXPECT_EQ(skeleton.find("NoSuchJoint"), -1);
  EXPECT_EQ(skeleton.find("LeftToeBase_end"), skeleton.find("LeftToeBase") + 1);

  // Line 12 "OFFSET 1.85590 -1.73949 0.84976" (LeftUpLeg) and frame 0 "7.5514 15.923 -40.3324 ...", scaled.
  const Joint& up_leg = skeleton.joints[skeleton.find("LeftUpLeg")];
  EXPECT_NEAR(up_leg.offset.x(), 1.85590 * kCmuScale, 1e-15);
  EXPECT_NEAR(up_leg.offset.y(), -1.73949 * kCmuScale, 1e-15);
  EXPECT_NEAR(motion.frames(0, 0), 7.5514 * kCmuScale, 1e-15);
  EXPECT_NEAR(motion.frames(0, 1), 15.923 * kCmuScale, 1e-15);
  EXPECT_NEAR(motion.frames(0, 2), -40.3324 * kCmuScale, 1e-15);
  EXPECT_EQ(motion.frames(0, 9), -21.0) << "angles are not scaled";
}

TEST(BvhRead, DazClipHasZxyChannels) {
  SKIP_WITHOUT_SHARED_DATA();
  const Motion motion = read_bvh(test::shared_data("motions/cmu_daz/16_15_daz.bvh"), {0.01, false});
  ASSERT_EQ(non_end_site_joints(motion.skeleton), 43);
  EXPECT_EQ(motion.skeleton.joints[0].name, "hip");
  const Joint& abdomen = motion.skeleton.joints[motion.skeleton.find("abdomen")];
  EXPECT_EQ(abdomen.channels, (std::vector<Channel>{Channel::z_rotation, Channel::x_rotation, Channel::y_rotation}));
  EXPECT_NEAR(abdomen.offset.y(), 0.206881, 1e-12);
  EXPECT_NEAR(motion.frames(0, 1), 0.850114, 1e-12);
}

// ---- malformed files ------------------------------------------------------

/// A valid two-joint file; the comments give line numbers used below.
std::vector<std::string> small_lines() {
  return {
      "HIERARCHY",                                                                 // 1
      "ROOT Hips",                                                                 // 2
      "{",                                                                         // 3
      "\tOFFSET 0 0 0",                                                            // 4
      "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation",  // 5
      "\tJOINT Spine",                                                             // 6
      "\t{",                                                                       // 7
      "\t\tOFFSET 0 1 0",                                                          // 8
      "\t\tCHANNELS 3 Zrotation Xrotation Yrotation",                              // 9
      "\t\tEnd Site",                                                              // 10
      "\t\t{",                                                                     // 11
      "\t\t\tOFFSET 0 0.5 0",                                                      // 12
      "\t\t}",                                                                     // 13
      "\t}",                                                                       // 14
      "}",                                                                         // 15
      "MOTION",                                                                    // 16
      "Frames: 3",                                                                 // 17
      "Frame Time: 0.0083333",                                                     // 18
      "1 2 3 10 20 30 40 50 60",                                                   // 19
      "1.5 2.5 3.5 11 21 31 41 51 61",                                             // 20
      "2 3 4 12 22 32 42 52 62",                                                   // 21
  };
}

struct Malformed {
  const char* name;
  std::vector<std::string> lines;
  int line;              ///< the line the message must name
  const char* contains;  ///< another piece the message must contain ("" for none)
};

std::vector<Malformed> malformed_variants() {
  std::vector<Malformed> cases;
  const auto edit = [](int line, const std::string& text) {
    std::vector<std::string> lines = small_lines();
    lines[line - 1] = text;
    return lines;
  };
  auto erase = [](int line) {
    std::vector<std::string> lines = small_lines();
    lines.erase(lines.begin() + (line - 1));
    return lines;
  };
  auto insert = [](int before, const std::string& text) {
    std::vector<std::string> lines = small_lines();
    lines.insert(lines.begin() + (before - 1), text);
    return lines;
  };
  // Braces: the last '}' missing names the line where the root's '{' opened.
  cases.push_back({"missing_last_brace", erase(15), 3, "'}'"});
  cases.push_back({"missing_inner_brace", erase(14), 3, "'}'"});
  cases.push_back({"extra_brace", insert(16, "}"), 16, "'}'"});
  cases.push_back({"missing_open_brace", erase(7), 7, "'{'"});
  {
    std::vector<std::string> lines = small_lines();
    lines.resize(14);  // ends inside the root
    cases.push_back({"ends_inside_root", lines, 3, "'}'"});
  }
  // CHANNELS whose count does not match the names listed.
  cases.push_back({"channel_count_too_big", edit(9, "\t\tCHANNELS 4 Zrotation Xrotation Yrotation"), 9, "CHANNELS"});
  cases.push_back({"channel_count_too_small", edit(9, "\t\tCHANNELS 2 Zrotation Xrotation Yrotation"), 9, "CHANNELS"});
  cases.push_back({"channel_count_root",
                   edit(5, "\tCHANNELS 5 Xposition Yposition Zposition Zrotation Yrotation Xrotation"), 5, "CHANNELS"});
  cases.push_back({"unknown_channel", edit(9, "\t\tCHANNELS 3 Zrotation Xrot Yrotation"), 9, "'Xrot'"});
  cases.push_back({"channel_twice", edit(9, "\t\tCHANNELS 3 Zrotation Xrotation Zrotation"), 9, "'Zrotation' listed twice"});
  {
    // One channel name too many, on a line of its own after the CHANNELS line.
    std::vector<std::string> lines = small_lines();
    lines[8] = "\t\tCHANNELS 2 Zrotation Xrotation";
    lines.insert(lines.begin() + 9, "\t\tYrotation");
    cases.push_back({"channel_after_the_list", lines, 9, "CHANNELS declares 2 channels but lists more"});
  }
  cases.push_back({"channel_case", edit(9, "\t\tCHANNELS 3 zrotation Xrotation Yrotation"), 9, "'zrotation'"});
  cases.push_back(
      {"channel_count_non_numeric", edit(9, "\t\tCHANNELS three Zrotation Xrotation Yrotation"), 9, "'three'"});
  // Non-numeric values.
  cases.push_back({"non_numeric_value", edit(20, "1.5 2.5 3.5 11 21 abc 41 51 61"), 20, "'abc'"});
  cases.push_back({"non_numeric_last_value", edit(21, "2 3 4 12 22 32 42 52 6x2"), 21, "'6x2'"});
  cases.push_back({"nan_value", edit(19, "1 2 3 nan 20 30 40 50 60"), 19, "non-finite value 'nan'"});
  cases.push_back({"overflowing_value", edit(19, "1 2 3 1e999 20 30 40 50 60"), 19, "'1e999'"});
  cases.push_back({"non_numeric_offset", edit(8, "\t\tOFFSET 0 one 0"), 8, "'one'"});
  cases.push_back({"short_offset", edit(8, "\t\tOFFSET 0 1"), 8, "OFFSET"});
  // Truncated motion names the last line; extra values name the first extra one.
  cases.push_back({"truncated_row", edit(21, "2 3 4 12 22 32 42 52"), 21, "26 values"});
  {
    std::vector<std::string> lines = small_lines();
    lines.pop_back();
    cases.push_back({"missing_row", lines, 20, "27 values"});
  }
  {
    std::vector<std::string> lines = small_lines();
    lines.resize(18);
    cases.push_back({"no_motion_data", lines, 18, "27 values"});
  }
  cases.push_back({"extra_value", edit(21, "2 3 4 12 22 32 42 52 62 72"), 21, "'72'"});
  // A short row within the data is named, not the end of the file; short
  // then long by one would shift a frame's channels.
  cases.push_back({"short_middle_row", edit(20, "1.5 2.5 3.5 11 21 31 41 51"), 20, "a row of 8 values"});
  {
    std::vector<std::string> lines = edit(20, "1.5 2.5 3.5 11 21 31 41 51");
    lines[20] = "61 2 3 4 12 22 32 42 52 62";
    cases.push_back({"short_then_long_row", lines, 20, "9 values per row"});
  }
  {
    std::vector<std::string> lines = small_lines();
    lines.push_back("3 4 5 13 23 33 43 53 63");
    cases.push_back({"extra_row", lines, 22, "'3'"});
  }
  // Frames and Frame Time.
  cases.push_back({"zero_frame_time", edit(18, "Frame Time: 0"), 18, "frame time"});
  cases.push_back({"negative_frame_time", edit(18, "Frame Time: -0.0083333"), 18, "frame time"});
  cases.push_back({"absurd_frame_time", edit(18, "Frame Time: 1e300"), 18, "at most 60 seconds per frame"});
  cases.push_back({"tiny_frame_time", edit(18, "Frame Time: 1e-300"), 18,
                   "frame time 1e-300 s; expected at least 0.00001 seconds per frame"});
  cases.push_back({"non_numeric_frame_time", edit(18, "Frame Time: fast"), 18, "'fast'"});
  cases.push_back({"zero_frames", edit(17, "Frames: 0"), 17, "frame count"});
  cases.push_back({"negative_frames", edit(17, "Frames: -3"), 17, "frame count"});
  cases.push_back({"fractional_frames", edit(17, "Frames: 2.5"), 17, "frame count '2.5' is not written as a whole number"});
  cases.push_back({"decimal_frames", edit(17, "Frames: 40.0"), 17, "frame count '40.0' is not written as a whole number"});
  cases.push_back({"exponent_frames", edit(17, "Frames: 1e3"), 17, "frame count '1e3' is not written as a whole number"});
  cases.push_back({"letter_frames", edit(17, "Frames: E"), 17, "non-numeric frame count 'E'"});
  cases.push_back({"word_frames", edit(17, "Frames: many"), 17, "non-numeric frame count 'many'"});
  cases.push_back({"huge_frames", edit(17, "Frames: 99999999999"), 17, "frame count"});
  cases.push_back({"missing_frame_time", erase(18), 18, "Frame Time"});
  // Unknown keywords.
  cases.push_back({"unknown_keyword_in_joint", edit(8, "\t\tOFFSETS 0 1 0"), 8, "'OFFSETS'"});
  cases.push_back({"unknown_keyword_inserted", insert(10, "\t\tROTATION 90"), 10, "'ROTATION'"});
  cases.push_back({"unknown_keyword_top", insert(16, "SKELETON"), 16, "'SKELETON'"});
  cases.push_back({"no_hierarchy", edit(1, "HIERARCHIE"), 1, "HIERARCHY"});
  cases.push_back({"joint_without_name", edit(6, "\tJOINT"), 6, "name"});
  cases.push_back({"channels_in_end_site", insert(12, "\t\t\tCHANNELS 1 Xrotation"), 12, "End Site"});
  cases.push_back({"duplicate_name", edit(6, "\tJOINT Hips"), 6, "'Hips'"});
  return cases;
}

TEST(BvhRead, PositionChannelsAreAbsoluteByDefaultOrAddedToTheOffset) {
  // The root rests 0.9 up and its channels say where it is (Blender and
  // MotionBuilder write this); Spine has 6 channels, 1 up from the root.
  std::vector<std::string> lines = small_lines();
  lines[3] = "\tOFFSET 0 0.9 0";
  lines[8] = "\t\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation";
  lines.resize(16);
  lines.insert(lines.end(), {"Frames: 1", "Frame Time: 0.01", "0.5 1 0 0 0 0 0 1.25 0 0 0 0"});
  const fs::path dir = empty_folder("positions");
  const std::string path = write_text(dir, "absolute.bvh", join_lines(lines));
  const Pose absolute = frame_pose(read_bvh(path), 0);
  EXPECT_NEAR((absolute.position(0) - Eigen::Vector3d(0.5, 1.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((absolute.position(1) - Eigen::Vector3d(0.5, 2.25, 0.0)).norm(), 0.0, 1e-12);
  BvhReadOptions relative_options;
  relative_options.position_channels = PositionChannels::relative;
  const Pose relative = frame_pose(read_bvh(path, relative_options), 0);
  EXPECT_NEAR((relative.position(0) - Eigen::Vector3d(0.5, 1.9, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((relative.position(1) - Eigen::Vector3d(0.5, 4.15, 0.0)).norm(), 0.0, 1e-12);
  // Written back, the channels are absolute again: the same poses.
  const std::string again = (dir / "again.bvh").string();
  write_bvh(again, read_bvh(path));
  const Pose reread = frame_pose(read_bvh(again), 0);
  for (int j = 0; j < 2; ++j) EXPECT_NEAR((reread.position(j) - absolute.position(j)).norm(), 0.0, 1e-12);
}

TEST(BvhRead, AJointNamedLikeAnEndSiteKeepsItsName) {
  // The End Site of Spine would be called "Spine_end"; a later joint of that
  // name is the file's own, and the End Site gives way.
  std::vector<std::string> lines = small_lines();
  lines.insert(lines.begin() + 13, {"\t\tJOINT Spine_end", "\t\t{", "\t\t\tOFFSET 0 0.2 0",
                                    "\t\t\tCHANNELS 1 Zrotation", "\t\t}"});
  for (int row = 0; row < 3; ++row) lines[static_cast<std::size_t>(23 + row)] += " 5";
  const fs::path dir = empty_folder("end_site_name");
  const Motion motion = read_bvh(write_text(dir, "named.bvh", join_lines(lines)));
  const int joint = motion.skeleton.find("Spine_end");
  ASSERT_GE(joint, 0);
  EXPECT_FALSE(motion.skeleton.joints[static_cast<std::size_t>(joint)].end_site);
  const int site = motion.skeleton.find("Spine_end2");
  ASSERT_GE(site, 0);
  EXPECT_TRUE(motion.skeleton.joints[static_cast<std::size_t>(site)].end_site);
  EXPECT_EQ(motion.frames(2, 9), 5.0);
}

TEST(BvhRead, MalformedFilesNameTheFileAndTheLine) {
  const fs::path dir = empty_folder("malformed");
  // The valid base parses (otherwise every case below fails for nothing).
  const Motion base = read_bvh(write_text(dir, "valid.bvh", join_lines(small_lines())));
  ASSERT_EQ(base.skeleton.joints.size(), 3u);
  ASSERT_EQ(base.frames.rows(), 3);
  ASSERT_EQ(base.frames.cols(), 9);

  // With LF, CRLF and lone CR (classic Mac OS) line ends alike: a CR-only
  // file was one line to the reader, every error on line 1 and a row short
  // by one value then long by one read with its channels shifted.
  for (const char* line_end : {"\n", "\r\n", "\r"}) {
    for (const Malformed& variant : malformed_variants()) {
      SCOPED_TRACE(std::string(variant.name) + (line_end[0] == '\n' ? "" : line_end[1] ? " (CRLF)" : " (CR)"));
      std::string text;
      for (const std::string& line : variant.lines) text += line + line_end;
      const std::string path = write_text(dir, std::string(variant.name) + ".bvh", text);
      try {
        read_bvh(path);
        ADD_FAILURE() << "no InputError for " << variant.name;
      } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind(path + ":" + std::to_string(variant.line) + ": ", 0), 0u) << message;
        EXPECT_NE(message.find("; expected "), std::string::npos) << message;
        EXPECT_NE(message.find(variant.contains), std::string::npos) << message;
      }
    }
  }
}

TEST(BvhRead, SkippingTheOnlyFrameIsAnError) {
  const fs::path dir = empty_folder("skip_only");
  std::vector<std::string> lines = small_lines();
  lines[16] = "Frames: 1";
  lines.resize(19);
  const std::string path = write_text(dir, "one.bvh", join_lines(lines));
  EXPECT_EQ(read_bvh(path).frames.rows(), 1);
  try {
    read_bvh(path, {1.0, true});
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(path + ":17:"), std::string::npos) << error.what();
  }
}

TEST(BvhRead, MissingFileNamesThePath) {
  const std::string path = (empty_folder("missing") / "no_such.bvh").string();
  try {
    read_bvh(path);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind(path + ": ", 0), 0u) << error.what();
  }
  EXPECT_THROW(read_bvh(path, {0.0, false}), ArgumentError);
}

TEST(BvhRead, EmptyAndBinaryGarbageAreInputErrors) {
  const fs::path dir = empty_folder("garbage");
  EXPECT_THROW(read_bvh(write_text(dir, "empty.bvh", "")), InputError);
  EXPECT_THROW(read_bvh(write_text(dir, "blank.bvh", "\n\n   \n")), InputError);
  std::string binary;
  std::mt19937 rng(7);
  for (int k = 0; k < 4096; ++k) binary += static_cast<char>(rng() & 0xFF);
  EXPECT_THROW(read_bvh(write_text(dir, "binary.bvh", binary)), InputError);
  // Nesting 200000 joints deep must not exhaust the stack.
  std::string deep = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\n";
  for (int k = 0; k < 200000; ++k) deep += "JOINT j" + std::to_string(k) + " {\nOFFSET 0 0 0\n";
  EXPECT_THROW(read_bvh(write_text(dir, "deep.bvh", deep)), InputError);
}

/// Every prefix and many random byte edits of a valid file either parse or throw InputError.
TEST(BvhRead, TruncationsAndMutationsNeverCrash) {
  const fs::path dir = empty_folder("fuzz");
  const std::string text = join_lines(small_lines());
  const std::string path = (dir / "fuzz.bvh").string();
  int parsed = 0, rejected = 0;
  const auto attempt = [&](const std::string& content) {
    write_text(dir, "fuzz.bvh", content);
    try {
      const Motion motion = read_bvh(path);
      EXPECT_EQ(motion.frames.cols(), motion.skeleton.channel_count());
      EXPECT_GE(motion.frames.rows(), 1);
      ++parsed;
    } catch (const InputError& error) {
      EXPECT_EQ(std::string(error.what()).rfind(path + ":", 0), 0u) << error.what();
      ++rejected;
    }
  };
  for (std::size_t length = 0; length < text.size(); ++length) attempt(text.substr(0, length));
  std::mt19937 rng(2024);
  const std::string alphabet = "{}:0123456789.-+eE \t\nXYZpositionrtaJOINTEndSiteROOTMOTIONFramesTime\x01\xff";
  for (int k = 0; k < 1500; ++k) {
    std::string mutated = text;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % mutated.size();
      switch (rng() % 3) {
        case 0:
          mutated[at] = alphabet[rng() % alphabet.size()];
          break;
        case 1:
          mutated.erase(at, 1 + rng() % 4);
          break;
        default:
          mutated.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
      }
    }
    attempt(mutated);
  }
  EXPECT_GT(parsed, 0);
  EXPECT_GT(rejected, 0);
}

TEST(BvhRead, LenientLayouts) {
  const fs::path dir = empty_folder("lenient");
  // Rows wrapped across lines, CRLF line ends, braces on the keyword line,
  // "Frames:3" without a space, a name with a space, one with a ':' (as
  // Mixamo's), a position channel in the middle of the rotations, a joint
  // without CHANNELS.
  const std::string text =
      "HIERARCHY\r\nROOT Hips {\r\n OFFSET 0 0 0\r\n CHANNELS 4 Zrotation Xposition Yrotation Xrotation\r\n"
      " JOINT Left Arm {\r\n  OFFSET 1 0 0\r\n  JOINT mixamorig:Hand {\r\n   OFFSET 1 0 0\r\n   CHANNELS 1 Yrotation\r\n"
      "   End Site { OFFSET 0 1 0 }\r\n  }\r\n }\r\n}\r\nMOTION\r\nFrames:3\r\nFrame Time:\t0.1\r\n"
      "1 2\r\n3 4 5\r\n6 7 8 9 10\r\n+11 12 13 14e0 1.5e1\r\n";
  const Motion motion = read_bvh(write_text(dir, "lenient.bvh", text), {2.0, false});
  ASSERT_EQ(motion.skeleton.joints.size(), 4u);
  EXPECT_EQ(motion.skeleton.joints[1].name, "Left Arm");
  EXPECT_TRUE(motion.skeleton.joints[1].channels.empty());
  EXPECT_EQ(motion.skeleton.joints[2].first_channel, 4);
  EXPECT_EQ(motion.skeleton.joints[2].name, "mixamorig:Hand") << "a ':' inside a name stays";
  EXPECT_EQ(motion.skeleton.joints[3].name, "mixamorig:Hand_end");
  EXPECT_EQ(motion.skeleton.joints[2].offset, Eigen::Vector3d(2, 0, 0));
  ASSERT_EQ(motion.frames.rows(), 3);
  ASSERT_EQ(motion.frames.cols(), 5);
  // Column 1 is Xposition: scaled by 2; the others are angles.
  EXPECT_EQ(motion.frames.row(0), (Eigen::RowVectorXd(5) << 1, 2 * 2.0, 3, 4, 5).finished());
  EXPECT_EQ(motion.frames.row(1), (Eigen::RowVectorXd(5) << 6, 7 * 2.0, 8, 9, 10).finished());
  EXPECT_EQ(motion.frames.row(2), (Eigen::RowVectorXd(5) << 11, 12 * 2.0, 13, 14, 15).finished());
}

TEST(BvhRead, SeveralRootsKeepTheirChannelColumns) {
  const fs::path dir = empty_folder("two_roots");
  const std::string text =
      "HIERARCHY\nROOT A\n{\n\tOFFSET 1 0 0\n\tCHANNELS 2 Xposition Zrotation\n\tEnd Site\n\t{\n\t\tOFFSET 0 1 "
      "0\n\t}\n}\n"
      "ROOT B\n{\n\tOFFSET 0 0 1\n\tCHANNELS 1 Yrotation\n\tEnd Site\n\t{\n\t\tOFFSET 0 1 0\n\t}\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.5\n1 2 3\n4 5 6\n";
  const Motion motion = read_bvh(write_text(dir, "two.bvh", text));
  ASSERT_EQ(motion.skeleton.joints.size(), 4u);
  EXPECT_EQ(motion.skeleton.joints[2].name, "B");
  EXPECT_EQ(motion.skeleton.joints[2].parent, -1);
  EXPECT_EQ(motion.skeleton.joints[2].first_channel, 2);
  EXPECT_EQ(motion.frames(1, 2), 6.0);
  const std::string out = (dir / "out.bvh").string();
  write_bvh(out, motion);
  const Motion again = read_bvh(out);
  EXPECT_EQ(again.frames, motion.frames);
  EXPECT_EQ(again.skeleton.joints[3].name, "B_end");
}

TEST(BvhRead, ChannelColumnsFollowTheOrderOfTheChannelsLines) {
  const fs::path dir = empty_folder("late_channels");
  // The root's CHANNELS line comes after its child's block: its column is 1.
  const std::string text =
      "HIERARCHY\nROOT A\n{\n\tOFFSET 0 0 0\n\tJOINT B\n\t{\n\t\tOFFSET 1 0 0\n\t\tCHANNELS 1 Xrotation\n"
      "\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 1 0\n\t\t}\n\t}\n\tCHANNELS 1 Zrotation\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.5\n90 30\n";
  const Motion motion = read_bvh(write_text(dir, "late.bvh", text));
  EXPECT_EQ(motion.skeleton.joints[0].first_channel, 1);
  EXPECT_EQ(motion.skeleton.joints[1].first_channel, 0);
  // Written in the usual layout (CHANNELS first), the values move with their joints.
  const std::string out = (dir / "out.bvh").string();
  write_bvh(out, motion);
  const Motion again = read_bvh(out);
  EXPECT_EQ(again.skeleton.joints[0].first_channel, 0);
  EXPECT_EQ(again.frames, (Eigen::MatrixXd(1, 2) << 30, 90).finished());
}

// ---- writing --------------------------------------------------------------

void expect_same_motion(const Motion& a, const Motion& b) {
  ASSERT_EQ(a.skeleton.joints.size(), b.skeleton.joints.size());
  for (std::size_t j = 0; j < a.skeleton.joints.size(); ++j) {
    const Joint& x = a.skeleton.joints[j];
    const Joint& y = b.skeleton.joints[j];
    SCOPED_TRACE(x.name);
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.parent, y.parent);
    EXPECT_EQ(x.end_site, y.end_site);
    EXPECT_EQ(x.channels, y.channels);
    EXPECT_EQ(x.first_channel, y.first_channel);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(x.offset[k], y.offset[k], 1e-9 * std::max(1.0, std::abs(x.offset[k])));
  }
  EXPECT_NEAR(a.frame_time, b.frame_time, 1e-9 * a.frame_time);
  ASSERT_EQ(a.frames.rows(), b.frames.rows());
  ASSERT_EQ(a.frames.cols(), b.frames.cols());
  double worst = 0.0;
  for (Eigen::Index r = 0; r < a.frames.rows(); ++r)
    for (Eigen::Index c = 0; c < a.frames.cols(); ++c)
      worst = std::max(worst, std::abs(a.frames(r, c) - b.frames(r, c)) / std::max(1e-3, std::abs(a.frames(r, c))));
  EXPECT_LE(worst, 1e-6);
}

TEST(BvhWrite, RoundTripsTheSmallFile) {
  const fs::path dir = empty_folder("round_trip_small");
  const Motion motion = read_bvh(write_text(dir, "in.bvh", join_lines(small_lines())), {0.01, false});
  const std::string out = (dir / "out.bvh").string();
  write_bvh(out, motion, 0.01);
  const Motion again = read_bvh(out, {0.01, false});
  expect_same_motion(motion, again);
  EXPECT_EQ(again.frames, motion.frames) << "12 significant digits reproduce these values exactly";
  // The file is standard: tabs, "Frames:" and "Frame Time:".
  std::ifstream in(out);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(
      text.find(
          "ROOT Hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
          "\tJOINT Spine\n\t{\n\t\tOFFSET 0 1 0\n"),
      std::string::npos)
      << text;
  EXPECT_NE(
      text.find("\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 0.5 0\n\t\t}\n\t}\n}\nMOTION\nFrames: 3\nFrame Time: 0.0083333\n"
                "1 2 3 10 20 30 40 50 60\n"),
      std::string::npos)
      << text;
  EXPECT_EQ(folder_contents(dir).size(), 2u) << "no temporary file is left";
}

TEST(BvhWrite, RoundTripsTheRealClips) {
  SKIP_WITHOUT_SHARED_DATA();
  const fs::path dir = empty_folder("round_trip_real");
  for (const Clip& clip : {kClips[0], kClips[6]}) {
    SCOPED_TRACE(clip.file);
    const Motion motion = read_bvh(test::shared_data(clip.file), {clip.scale, false});
    const std::string out = (dir / "out.bvh").string();
    write_bvh(out, motion, clip.scale);
    expect_same_motion(motion, read_bvh(out, {clip.scale, false}));
    // Another scale on the way out and back gives the same metres.
    write_bvh(out, motion, 1.0);
    expect_same_motion(motion, read_bvh(out, {1.0, false}));
  }
}

TEST(BvhWrite, RejectsInconsistentMotionsAndWritesNothing) {
  const fs::path dir = empty_folder("write_errors");
  const Motion motion = read_bvh(write_text(dir, "in.bvh", join_lines(small_lines())));
  const std::string out = (dir / "out.bvh").string();

  Motion wrong_columns = motion;
  wrong_columns.frames.conservativeResize(Eigen::NoChange, 8);
  EXPECT_THROW(write_bvh(out, wrong_columns), ArgumentError);
  Motion no_frames = motion;
  no_frames.frames.resize(0, 9);
  EXPECT_THROW(write_bvh(out, no_frames), ArgumentError);
  Motion bad_time = motion;
  bad_time.frame_time = 0.0;
  EXPECT_THROW(write_bvh(out, bad_time), ArgumentError);
  Motion non_finite = motion;
  non_finite.frames(1, 4) = std::nan("");
  EXPECT_THROW(write_bvh(out, non_finite), ArgumentError);
  Motion bad_name = motion;
  bad_name.skeleton.joints[1].name = "Sp{ine";
  EXPECT_THROW(write_bvh(out, bad_name), ArgumentError);
  EXPECT_THROW(write_bvh(out, motion, 0.0), ArgumentError);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(folder_contents(dir).size(), 1u);
}

}  // namespace
}  // namespace mrcloth
