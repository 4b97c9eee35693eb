#include "solver/point_cache.h"

#include "mesh_ops/errors.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>

#include <sys/resource.h>

#include "test_meshes.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <locale>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

/// A fresh, empty folder per test, so "nothing else is left here" can be checked.
fs::path empty_folder(const std::string& name) { return test::fresh_folder("point_cache_test", name); }

std::vector<std::string> folder_contents(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  return names;
}

std::vector<unsigned char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::vector<FramePositions> random_frames(int frames, int points, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  std::vector<FramePositions> result;
  for (int k = 0; k < frames; ++k) {
    FramePositions positions(points, 3);
    for (int i = 0; i < points; ++i)
      for (int j = 0; j < 3; ++j) positions(i, j) = coordinate(rng);
    result.push_back(positions);
  }
  return result;
}

void write_pc2(const fs::path& path, const std::vector<FramePositions>& frames, double start = 0.0,
               double rate = 1.0) {
  Pc2Writer writer(path.string(), static_cast<int>(frames.front().rows()), start, rate);
  for (const FramePositions& frame : frames) writer.add_frame(frame);
  writer.finish();
}

/// Expects `call` to throw E whose message contains every one of `parts`.
template <typename E, typename F>
void expect_error(F&& call, const std::vector<std::string>& parts) {
  try {
    call();
    ADD_FAILURE() << "no error; expected one mentioning '" << parts.front() << "'";
  } catch (const E& error) {
    const std::string message = error.what();
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

// ---------------------------------------------------------------------------
// PC2

TEST(Pc2, RoundTripKeepsFloatPrecision) {
  const fs::path path = empty_folder("round_trip") / "cloth.pc2";
  const std::vector<FramePositions> frames = random_frames(3, 5, 1);
  write_pc2(path, frames, 12.0, 0.5);

  const PointCache cache = read_pc2(path.string());
  EXPECT_EQ(cache.num_points, 5);
  EXPECT_EQ(cache.start_frame, 12.0);
  EXPECT_EQ(cache.sample_rate, 0.5);
  ASSERT_EQ(cache.frames.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(cache.frames[k].rows(), 5);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_EQ(cache.frames[k](i, j), static_cast<double>(static_cast<float>(frames[k](i, j))))
            << "frame " << k << " point " << i << " coordinate " << j;
  }
}

TEST(Pc2, HeaderAndFirstPointAreByteExactLittleEndian) {
  const fs::path path = empty_folder("header") / "cloth.pc2";
  std::vector<FramePositions> frames = random_frames(3, 5, 2);
  frames[0].row(0) << 1.0, -2.0, 0.25;
  write_pc2(path, frames, 10.0, 0.5);

  const std::vector<unsigned char> bytes = read_bytes(path);
  ASSERT_EQ(bytes.size(), 32u + 3u * 5u * 12u);
  const std::vector<unsigned char> expected = {
      'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', 0,  // signature
      1, 0, 0, 0,                                                // version 1
      5, 0, 0, 0,                                                // numPoints
      0x00, 0x00, 0x20, 0x41,                                    // startFrame 10.0f
      0x00, 0x00, 0x00, 0x3F,                                    // sampleRate 0.5f
      3, 0, 0, 0,                                                // numSamples
      0x00, 0x00, 0x80, 0x3F,                                    // x = 1.0f
      0x00, 0x00, 0x00, 0xC0,                                    // y = -2.0f
      0x00, 0x00, 0x80, 0x3E};                                   // z = 0.25f
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(int(bytes[i]), int(expected[i])) << "byte " << i;
}

TEST(Pc2, EmptyCacheIsAValidHeaderOnlyFile) {
  const fs::path path = empty_folder("empty") / "cloth.pc2";
  Pc2Writer writer(path.string(), 7);
  writer.finish();
  EXPECT_EQ(fs::file_size(path), 32u);
  const PointCache cache = read_pc2(path.string());
  EXPECT_EQ(cache.num_points, 7);
  EXPECT_TRUE(cache.frames.empty());
}

TEST(Pc2, NothingAppearsBeforeFinish) {
  const fs::path dir = empty_folder("streaming");
  const fs::path path = dir / "cloth.pc2";
  Pc2Writer writer(path.string(), 5);
  for (const FramePositions& frame : random_frames(2, 5, 3)) writer.add_frame(frame);
  EXPECT_EQ(writer.frames_written(), 2);
  EXPECT_FALSE(fs::exists(path)) << "the cache appears only when complete";
  const std::vector<std::string> during = folder_contents(dir);
  ASSERT_EQ(during.size(), 1u);
  EXPECT_EQ(during[0].rfind(".cloth.pc2.tmp-", 0), 0u) << "a hidden temporary beside the target: " << during[0];
  writer.finish();
  EXPECT_EQ(folder_contents(dir), std::vector<std::string>{"cloth.pc2"});
  EXPECT_EQ(read_pc2(path.string()).frames.size(), 2u);
}

TEST(Pc2, CancelledWriterLeavesNothingBehind) {
  const fs::path dir = empty_folder("cancelled");
  {
    Pc2Writer writer(dir.string() + "/cloth.pc2", 5);
    for (const FramePositions& frame : random_frames(2, 5, 4)) writer.add_frame(frame);
  }
  EXPECT_TRUE(folder_contents(dir).empty()) << "neither the cache nor its temporary file";
}

TEST(Pc2, CancelledWriterKeepsAnExistingCache) {
  const fs::path dir = empty_folder("keeps_old");
  const fs::path path = dir / "cloth.pc2";
  write_pc2(path, random_frames(3, 5, 5));
  const std::vector<unsigned char> before = read_bytes(path);
  {
    Pc2Writer writer(path.string(), 4);
    writer.add_frame(random_frames(1, 4, 6).front());
  }
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_EQ(folder_contents(dir), std::vector<std::string>{"cloth.pc2"});
}

/// Files this process writes can grow to at most `bytes` while it lives
/// (RLIMIT_FSIZE, with SIGXFSZ ignored so a write past it fails with EFBIG
/// instead of ending the process): a disk that fills up mid-write.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit lowered = saved_;
    lowered.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lowered);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, old_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*old_handler_)(int) = SIG_DFL;
};

TEST(Pc2, AFullDiskMidWriteIsAnErrorNamingTheFrameAndLeavesTheOldCache) {
  const fs::path dir = empty_folder("full_disk");
  const fs::path path = dir / "cloth.pc2";
  write_pc2(path, random_frames(3, 5, 7));
  const std::vector<unsigned char> before = read_bytes(path);
  const std::vector<FramePositions> frames = random_frames(3, 5000, 8);  // 60,000 bytes a frame
  {
    const FileSizeLimit limit(100000);  // the header and one frame fit, not two
    Pc2Writer writer(path.string(), 5000);
    writer.add_frame(frames[0]);
    expect_error<OutputError>([&] { writer.add_frame(frames[1]); }, {"cloth.pc2", "cannot write frame 1"});
    expect_error<OutputError>([&] { writer.finish(); }, {"cloth.pc2", "failed"});
  }
  EXPECT_EQ(read_bytes(path), before) << "the cache from before is untouched";
  EXPECT_EQ(folder_contents(dir), std::vector<std::string>{"cloth.pc2"}) << "no temporary file is left";
}

TEST(Pc2, WriterRefusesBadArguments) {
  const fs::path dir = empty_folder("writer_errors");
  expect_error<ArgumentError>([&] { Pc2Writer writer((dir / "a.pc2").string(), 0); }, {"a.pc2", "num_points"});
  expect_error<OutputError>([&] { Pc2Writer writer((dir / "missing" / "a.pc2").string(), 3); },
                            {"a.pc2", "does not exist"});
  expect_error<OutputError>([&] { Pc2Writer writer(dir.string(), 3); }, {"folder"});

  Pc2Writer writer((dir / "b.pc2").string(), 3);
  expect_error<ArgumentError>([&] { writer.add_frame(FramePositions::Zero(4, 3)); }, {"b.pc2", "4 points", "3"});
  writer.add_frame(FramePositions::Zero(3, 3));
  writer.finish();
  expect_error<OutputError>([&] { writer.add_frame(FramePositions::Zero(3, 3)); }, {"b.pc2", "finished"});
  EXPECT_EQ(folder_contents(dir), std::vector<std::string>{"b.pc2"});
}

TEST(Pc2, ReadFrameEqualsTheWholeRead) {
  const fs::path path = empty_folder("read_frame") / "cloth.pc2";
  write_pc2(path, random_frames(4, 6, 7));
  const PointCache cache = read_pc2(path.string());
  for (int k = 0; k < 4; ++k) EXPECT_EQ(read_pc2_frame(path.string(), k), cache.frames[k]) << "frame " << k;
  expect_error<ArgumentError>([&] { read_pc2_frame(path.string(), 4); }, {"cloth.pc2", "frame 4", "4 frames"});
  expect_error<ArgumentError>([&] { read_pc2_frame(path.string(), -1); }, {"cloth.pc2", "frame -1"});
}

class Pc2Corrupt : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: ctest may run them in parallel.
    path_ = empty_folder(std::string("corrupt_") + ::testing::UnitTest::GetInstance()->current_test_info()->name()) /
            "cloth.pc2";
    write_pc2(path_, random_frames(3, 5, 8));
    bytes_ = read_bytes(path_);
  }
  /// Both readers refuse the file with an InputError mentioning `parts`.
  void expect_refused(const std::vector<std::string>& parts) {
    std::vector<std::string> with_name = parts;
    with_name.push_back(path_.string());
    expect_error<InputError>([&] { read_pc2(path_.string()); }, with_name);
    expect_error<InputError>([&] { read_pc2_frame(path_.string(), 0); }, with_name);
  }
  fs::path path_;
  std::vector<unsigned char> bytes_;
};

TEST_F(Pc2Corrupt, TruncatedFrames) {
  bytes_.pop_back();
  write_bytes(path_, bytes_);
  expect_refused({"211 bytes", "212 bytes", "truncated"});
}

TEST_F(Pc2Corrupt, TruncatedHeader) {
  bytes_.resize(20);
  write_bytes(path_, bytes_);
  expect_refused({"20 bytes", "header"});
}

TEST_F(Pc2Corrupt, ExtraBytes) {
  bytes_.push_back(0);
  write_bytes(path_, bytes_);
  expect_refused({"213 bytes", "212 bytes"});
}

TEST_F(Pc2Corrupt, BadSignature) {
  bytes_[5] = 'X';
  write_bytes(path_, bytes_);
  expect_refused({"POINTCACHE2", "not a PC2"});
}

TEST_F(Pc2Corrupt, WrongVersion) {
  bytes_[12] = 2;
  write_bytes(path_, bytes_);
  expect_refused({"version 2"});
}

TEST_F(Pc2Corrupt, NoPoints) {
  for (int i = 16; i < 20; ++i) bytes_[i] = 0;
  write_bytes(path_, bytes_);
  expect_refused({"0 points"});
}

TEST_F(Pc2Corrupt, SampleCountDisagreesWithLength) {
  bytes_[28] = 4;
  write_bytes(path_, bytes_);
  expect_refused({"4 frames", "272 bytes"});
}

TEST(Pc2, FiniteFrameNamesTheFirstPointThatIsNot) {
  const fs::path dir = empty_folder("finite_frame");
  std::vector<FramePositions> frames = random_frames(3, 5, 11);
  frames[1](2, 1) = std::numeric_limits<double>::quiet_NaN();
  frames[2](4, 0) = std::numeric_limits<double>::infinity();
  write_pc2(dir / "bad.pc2", frames);
  Pc2Reader reader((dir / "bad.pc2").string());
  EXPECT_TRUE(reader.finite_frame(0).allFinite());
  EXPECT_FALSE(reader.frame(1).allFinite()) << "frame() hands it over as it is";
  for (const auto& [frame, text] : {std::pair<int, std::string>{1, "bad.pc2: frame 1, point 2 is not finite"},
                                    std::pair<int, std::string>{2, "bad.pc2: frame 2, point 4 is not finite"}}) {
    try {
      reader.finite_frame(frame);
      ADD_FAILURE() << "frame " << frame << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  }
}

TEST(Pc2, MissingFileIsAnInputError) {
  const fs::path path = empty_folder("missing") / "nothing.pc2";
  expect_error<InputError>([&] { read_pc2(path.string()); }, {"nothing.pc2", "does not exist"});
}

// ---------------------------------------------------------------------------
// OBJ sequences

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ObjSequence, WritesNumberedFilesThatLoadBack) {
  const fs::path dir = empty_folder("obj");
  const std::string prefix = (dir / "cloth").string();
  std::vector<FramePositions> frames = random_frames(3, 5, 9);
  frames[1](2, 1) = 1e-7;  // small and large magnitudes keep their 9 digits
  frames[1](3, 0) = -12345.678912345;
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {1, 4, 2}};

  const std::vector<std::string> paths = write_obj_sequence(prefix, frames, faces);
  ASSERT_EQ(paths, (std::vector<std::string>{prefix + "_0000.obj", prefix + "_0001.obj", prefix + "_0002.obj"}));
  EXPECT_EQ(folder_contents(dir).size(), 3u) << "no temporary files left";

  for (int k = 0; k < 3; ++k) {
    const std::vector<std::string> lines = lines_of(paths[k]);
    ASSERT_EQ(lines.size(), 5u + 2u) << paths[k] << ": one line per vertex and per face";
    for (int i = 0; i < 5; ++i) {
      std::istringstream line(lines[i]);
      line.imbue(std::locale::classic());
      std::string tag;
      double x, y, z;
      ASSERT_TRUE(line >> tag >> x >> y >> z) << lines[i];
      EXPECT_EQ(tag, "v");
      const double parsed[3] = {x, y, z};
      for (int j = 0; j < 3; ++j) {
        const double value = frames[k](i, j);
        EXPECT_NEAR(parsed[j], value, 5e-9 * std::abs(value)) << "9 significant digits: " << lines[i];
      }
    }
    EXPECT_EQ(lines[5], "f 1 2 3 4");
    EXPECT_EQ(lines[6], "f 2 5 3");

    OpenMesh::PolyMesh_ArrayKernelT<> mesh;
    ASSERT_TRUE(OpenMesh::IO::read_mesh(mesh, paths[k])) << paths[k];
    EXPECT_EQ(mesh.n_vertices(), 5u);
    EXPECT_EQ(mesh.n_faces(), 2u);
    for (auto v : mesh.vertices())
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(mesh.point(v)[j], float(frames[k](v.idx(), j)), 1e-6 * (1 + std::abs(frames[k](v.idx(), j))));
  }
}

// Written again with fewer frames, a sequence leaves none of the earlier
// run's later frames (a DCC tool importing it took them for this run's);
// other files of the folder stay.
TEST(ObjSequence, FramesAnEarlierLongerSequenceLeftAreRemoved) {
  const fs::path dir = empty_folder("obj_shorter");
  const std::string prefix = (dir / "s").string();
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {1, 4, 2}};
  write_obj_sequence(prefix, random_frames(6, 5, 3), faces);
  std::ofstream(dir / "s_extra.obj") << "# not a frame\n";
  std::ofstream(dir / "s_0009.obj") << "# not after the last frame\n";
  std::ofstream(dir / "s_00006.obj") << "# a frame of a longer sequence's width\n";
  write_obj_sequence(prefix, random_frames(3, 5, 4), faces);
  std::vector<std::string> names = folder_contents(dir);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"s_0000.obj", "s_0001.obj", "s_0002.obj", "s_0009.obj", "s_extra.obj"}));
}

TEST(ObjSequence, TextureCoordinatesAreOnePerFaceCorner) {
  const fs::path dir = empty_folder("obj_uv");
  const std::vector<FramePositions> frames = random_frames(2, 5, 12);
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {1, 4, 2}};
  // Vertices 1 and 2 lie on a seam: another UV in the second face.
  const FaceUVs uvs = {{{0, 0}, {0.5, 0}, {0.5, 1}, {0, 1}}, {{0.75, 0}, {1, 0.5}, {0.75, 1}}};
  const std::vector<std::string> paths = write_obj_sequence((dir / "cloth").string(), frames, faces, uvs);
  for (const std::string& path : paths) {
    const std::vector<std::string> lines = lines_of(path);
    ASSERT_EQ(lines.size(), 5u + 7u + 2u) << path;
    EXPECT_EQ(lines[5], "vt 0 0");
    EXPECT_EQ(lines[6], "vt 0.5 0");
    EXPECT_EQ(lines[9], "vt 0.75 0");
    EXPECT_EQ(lines[11], "vt 0.75 1");
    EXPECT_EQ(lines[12], "f 1/1 2/2 3/3 4/4");
    EXPECT_EQ(lines[13], "f 2/5 5/6 3/7");
    EXPECT_EQ(read_obj(path).faces, faces) << "read back as the same polygons";
  }
  expect_error<ArgumentError>([&] { write_obj_sequence((dir / "bad").string(), frames, faces, {uvs[0]}); },
                              {"texture coordinates for 1 faces", "2 faces"});
  expect_error<ArgumentError>(
      [&] { write_obj_sequence((dir / "bad").string(), frames, faces, {uvs[0], {{0, 0}}}); },
      {"not one per corner"});
}

TEST(ObjSequence, MoreThan10000FramesWidenTheNumber) {
  const fs::path dir = empty_folder("obj_wide");
  const std::vector<FramePositions> frames(10001, FramePositions::Zero(1, 3));
  const std::vector<std::string> paths = write_obj_sequence((dir / "c").string(), frames, {});
  ASSERT_EQ(paths.size(), 10001u);
  EXPECT_EQ(fs::path(paths.front()).filename().string(), "c_00000.obj");
  EXPECT_EQ(fs::path(paths.back()).filename().string(), "c_10000.obj");
  EXPECT_EQ(lines_of(paths.back()), std::vector<std::string>{"v 0 0 0"});
  fs::remove_all(dir);
}

TEST(ObjSequence, RefusesInconsistentInputBeforeWritingAnything) {
  const fs::path dir = empty_folder("obj_errors");
  const std::string prefix = (dir / "cloth").string();
  std::vector<FramePositions> frames = random_frames(2, 4, 10);
  expect_error<ArgumentError>([&] { write_obj_sequence(prefix, frames, {{0, 1, 4}}); },
                              {"cloth", "face 0", "vertex 4"});
  expect_error<ArgumentError>([&] { write_obj_sequence(prefix, frames, {{0, 1, 2}, {0, 1}}); },
                              {"face 1", "2 vertices"});
  frames.push_back(FramePositions::Zero(3, 3));
  expect_error<ArgumentError>([&] { write_obj_sequence(prefix, frames, {}); }, {"frame 2", "3 points"});
  expect_error<OutputError>(
      [&] { write_obj_sequence((dir / "missing" / "cloth").string(), random_frames(1, 3, 11), {}); },
      {"does not exist"});
  EXPECT_TRUE(folder_contents(dir).empty());
  EXPECT_TRUE(write_obj_sequence(prefix, {}, {}).empty());
}

TEST(Obj, WriteThenReadGivesTheSamePolygons) {
  const fs::path dir = empty_folder("obj_round_trip");
  const FramePositions positions = random_frames(1, 6, 3).front();
  const std::vector<std::vector<int>> faces = {{0, 1, 2}, {2, 3, 4, 5}, {5, 4, 1}};
  const std::string path = (dir / "mesh.obj").string();
  write_obj(path, positions, faces);
  const ObjMesh read = read_obj(path);
  EXPECT_EQ(read.faces, faces);
  ASSERT_EQ(read.positions.rows(), 6);
  // write_obj keeps 9 significant digits: the float precision of the PC2 it goes with.
  EXPECT_LT((read.positions - positions).cwiseAbs().maxCoeff(), 1e-8 * positions.cwiseAbs().maxCoeff());
  EXPECT_EQ(folder_contents(dir), std::vector<std::string>{"mesh.obj"});
}

TEST(Obj, ReadsCornerFormsAndNegativeIndicesAndIgnoresOtherLines) {
  const fs::path dir = empty_folder("obj_forms");
  std::ofstream((dir / "forms.obj").string()) << "# comment\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\n"
                                                 "vt 0 0\nf 1/1/1 2//1 3/1\nf -3 -2 -1\n";
  const ObjMesh read = read_obj((dir / "forms.obj").string());
  EXPECT_EQ(read.faces, (std::vector<std::vector<int>>{{0, 1, 2}, {0, 1, 2}}));
  EXPECT_EQ(read.positions.rows(), 3);
}

TEST(Obj, MalformedLinesAreNamed) {
  const fs::path dir = empty_folder("obj_bad");
  const auto write = [&](const std::string& text) {
    std::ofstream((dir / "bad.obj").string()) << text;
    return (dir / "bad.obj").string();
  };
  expect_error<InputError>([&] { read_obj(write("v 0 0 0\nv 1 x 0\n")); }, {"bad.obj:2:", "v x y z"});
  expect_error<InputError>([&] { read_obj(write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")); },
                           {"bad.obj:4:", "vertex index 4 out of range"});
  expect_error<InputError>([&] { read_obj(write("v 0 0 0\nv 1 0 0\nf 1 2\n")); }, {"bad.obj:3:", "at least 3"});
  expect_error<InputError>([&] { read_obj(write("v 0 0 0\nf a b c\n")); }, {"bad.obj:2:", "'a'"});
  expect_error<InputError>([&] { read_obj((dir / "missing.obj").string()); }, {"missing.obj", "cannot open"});
  // A binary file (a PC2 given for its OBJ), or vertices without faces.
  expect_error<InputError>([&] { read_obj(write(std::string("POINTCACHE2\0\1\0\0\0", 16))); },
                           {"bad.obj: no 'v' (vertex) lines; expected an OBJ mesh"});
  expect_error<InputError>([&] { read_obj(write("v 0 0 0\nv 1 0 0\nv 0 1 0\n")); },
                           {"bad.obj: no 'f' (face) lines; expected an OBJ mesh"});
}

}  // namespace
}  // namespace mrcloth
