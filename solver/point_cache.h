#pragma once
// Point caches: PC2 (the format Blender's Mesh Cache modifier, Maya and
// Marvelous Designer read) and OBJ sequences. Written atomically: a cache
// appears at its path only when complete.
//
// PC2 layout (little-endian): char[12] "POINTCACHE2\0", int32 version (1),
// int32 numPoints, float32 startFrame, float32 sampleRate, int32 numSamples,
// then numSamples x numPoints x float32[3] positions.
#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace mrcloth {

/// Positions of one frame: #points x 3, metres.
using FramePositions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Streams frames to a PC2 file. Frames go to a temporary file; `finish()`
/// patches the sample count and renames it into place. Destroying an
/// unfinished writer (error, cancel) removes the temporary file, so nothing
/// half-written is left behind.
class Pc2Writer {
 public:
  /// path: target file; num_points > 0; start_frame and sample_rate
  /// (frames between samples, usually 1) go into the header.
  Pc2Writer(const std::string& path, int num_points, double start_frame = 0.0, double sample_rate = 1.0);
  ~Pc2Writer();
  Pc2Writer(const Pc2Writer&) = delete;
  Pc2Writer& operator=(const Pc2Writer&) = delete;

  /// Appends one frame (num_points x 3). Throws ArgumentError on a size
  /// mismatch, OutputError on a write failure.
  void add_frame(const FramePositions& positions);
  /// Completes the file and renames it into place. Throws OutputError.
  void finish();
  int frames_written() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct PointCache {
  int num_points = 0;
  double start_frame = 0.0;
  double sample_rate = 1.0;
  std::vector<FramePositions> frames;  ///< each num_points x 3 (float precision in the file)
};

/// Reads a whole PC2 file. Throws InputError naming the file and the problem
/// (bad signature, version, sizes not matching the file length).
PointCache read_pc2(const std::string& path);

/// Reads one frame without loading the rest.
FramePositions read_pc2_frame(const std::string& path, int frame);

/// Streams a PC2 file frame by frame with the file kept open: memory for
/// one frame, whatever the cache's length (for analysis of long caches).
/// The header is checked on opening (InputError as read_pc2).
class Pc2Reader {
 public:
  explicit Pc2Reader(const std::string& path);
  ~Pc2Reader();
  Pc2Reader(const Pc2Reader&) = delete;
  Pc2Reader& operator=(const Pc2Reader&) = delete;

  int num_points() const;
  int num_frames() const;
  double start_frame() const;
  double sample_rate() const;
  const std::string& path() const;
  /// Frame `frame` (0-based, < num_frames()), num_points x 3. Sequential
  /// reads do not seek. Throws ArgumentError out of range, InputError when
  /// the file cannot be read.
  FramePositions frame(int frame);
  /// frame(frame), and InputError naming the file, the frame and the first
  /// point that is not finite (NaN or infinite), for readers that would
  /// otherwise write, draw or measure it.
  FramePositions finite_frame(int frame);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Texture coordinates per polygon corner (as the polygons' vertex lists),
/// or empty for none.
using FaceUVs = std::vector<std::vector<Eigen::Vector2d>>;

/// Frame `index` of an OBJ sequence of `count` frames: "<prefix>_0007.obj",
/// at least four digits so that the files sort by name, more when the
/// sequence needs them.
std::string obj_sequence_path(const std::string& prefix, std::size_t index, std::size_t count);

/// Writes `frames` as an OBJ sequence `<prefix>_0000.obj`, ... sharing the
/// faces of `faces` (each a vertex-index polygon, 0-based) and their corners'
/// texture coordinates `uvs` (written as vt, if given). Every file is
/// written atomically; frames an earlier, longer sequence of the same
/// prefix left after these are removed. Returns the paths written. Throws ArgumentError for
/// frames of unequal sizes, a face naming a missing vertex, or uvs not
/// shaped as the faces.
std::vector<std::string> write_obj_sequence(const std::string& prefix, const std::vector<FramePositions>& frames,
                                            const std::vector<std::vector<int>>& faces, const FaceUVs& uvs = {});

/// Writes one OBJ mesh (positions #points x 3, faces as 0-based vertex-index
/// polygons, their corners' texture coordinates if given) atomically: the
/// rest mesh beside a cache. Throws OutputError.
void write_obj(const std::string& path, const FramePositions& positions, const std::vector<std::vector<int>>& faces,
               const FaceUVs& uvs = {});

/// An OBJ file's vertices and polygons (what write_obj writes).
struct ObjMesh {
  FramePositions positions;               ///< #points x 3
  std::vector<std::vector<int>> faces;    ///< 0-based vertex indices
};

/// Reads the `v` and `f` lines of an OBJ file (face corners may be written
/// v, v/t, v//n or v/t/n; negative indices count from the end); other lines
/// are ignored. Throws InputError naming the file and line for a malformed
/// or out-of-range entry, and the file when it has no vertex or no face.
ObjMesh read_obj(const std::string& path);

}  // namespace mrcloth
