#include "point_cache.h"

#include "mesh_ops/atomic_file.h"
#include "mesh_ops/errors.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

// PC2 stores IEEE-754 binary32; the byte order is fixed below by explicit
// shifts, so the file is the same whatever the host's endianness.
static_assert(std::numeric_limits<float>::is_iec559 && sizeof(float) == 4, "PC2 positions are IEEE-754 float32");

constexpr std::array<char, 12> kSignature = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
constexpr std::int32_t kVersion = 1;
constexpr std::uint64_t kHeaderBytes = 32;
constexpr std::uint64_t kPointBytes = 12;  ///< float32 x, y, z
constexpr std::streamoff kSampleCountOffset = 28;

void put_u32(unsigned char* out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<unsigned char>(value >> (8 * i));
}

std::uint32_t get_u32(const unsigned char* in) {
  std::uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value |= std::uint32_t(in[i]) << (8 * i);
  return value;
}

void put_i32(unsigned char* out, std::int32_t value) { put_u32(out, static_cast<std::uint32_t>(value)); }
std::int32_t get_i32(const unsigned char* in) { return static_cast<std::int32_t>(get_u32(in)); }

void put_f32(unsigned char* out, float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  put_u32(out, bits);
}

float get_f32(const unsigned char* in) {
  const std::uint32_t bits = get_u32(in);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

struct Header {
  std::int32_t num_points = 0;
  float start_frame = 0.0f;
  float sample_rate = 1.0f;
  std::int32_t num_samples = 0;
};

std::array<unsigned char, kHeaderBytes> encode_header(const Header& header) {
  std::array<unsigned char, kHeaderBytes> bytes{};
  std::memcpy(bytes.data(), kSignature.data(), kSignature.size());
  put_i32(&bytes[12], kVersion);
  put_i32(&bytes[16], header.num_points);
  put_f32(&bytes[20], header.start_frame);
  put_f32(&bytes[24], header.sample_rate);
  put_i32(&bytes[28], header.num_samples);
  return bytes;
}

void encode_frame(const FramePositions& positions, std::vector<unsigned char>& bytes) {
  bytes.resize(static_cast<std::size_t>(positions.rows()) * kPointBytes);
  unsigned char* out = bytes.data();
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    for (int k = 0; k < 3; ++k, out += 4) put_f32(out, static_cast<float>(positions(i, k)));
  }
}

FramePositions decode_frame(const std::vector<unsigned char>& bytes, int num_points) {
  FramePositions positions(num_points, 3);
  const unsigned char* in = bytes.data();
  for (int i = 0; i < num_points; ++i) {
    for (int k = 0; k < 3; ++k, in += 4) positions(i, k) = get_f32(in);
  }
  return positions;
}

/// An open PC2 file whose header has been checked against its length, so
/// every frame the header promises can be read.
struct Pc2File {
  std::ifstream in;
  Header header;
};

std::uintmax_t file_size_or_throw(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(with_path(path, "cannot open file (" + missing_file_reason(path) + ")"));
  if (fs::is_directory(status)) throw InputError(with_path(path, "cannot open file (it is a folder)"));
  const std::uintmax_t size = fs::file_size(path, error);
  if (error) throw InputError(with_path(path, "cannot open file (" + error.message() + ")"));
  return size;
}

Header parse_header(const std::array<unsigned char, kHeaderBytes>& bytes, std::uintmax_t size,
                    const std::string& path) {
  if (std::memcmp(bytes.data(), kSignature.data(), kSignature.size()) != 0)
    throw InputError(with_path(path, "not a PC2 point cache (the file does not start with \"POINTCACHE2\\0\")"));
  const std::int32_t version = get_i32(&bytes[12]);
  if (version != kVersion)
    throw InputError(with_path(path, "unsupported PC2 version " + std::to_string(version) + " (expected 1)"));
  Header header;
  header.num_points = get_i32(&bytes[16]);
  header.start_frame = get_f32(&bytes[20]);
  header.sample_rate = get_f32(&bytes[24]);
  header.num_samples = get_i32(&bytes[28]);
  if (header.num_points <= 0)
    throw InputError(with_path(path, "the PC2 header has " + std::to_string(header.num_points) +
                                         " points per frame (expected > 0)"));
  if (header.num_samples < 0)
    throw InputError(with_path(path, "the PC2 header has " + std::to_string(header.num_samples) +
                                         " frames (expected >= 0)"));
  // Both counts are below 2^31, so the product fits comfortably in 64 bits.
  const std::uint64_t expected = kHeaderBytes + std::uint64_t(header.num_samples) *
                                                    std::uint64_t(header.num_points) * kPointBytes;
  if (size != expected) {
    throw InputError(with_path(path, "the file is " + std::to_string(size) + " bytes but its header's " +
                                         std::to_string(header.num_samples) + " frames of " +
                                         std::to_string(header.num_points) + " points need " +
                                         std::to_string(expected) + " bytes (truncated or corrupt)"));
  }
  return header;
}

Pc2File open_pc2(const std::string& path) {
  const std::uintmax_t size = file_size_or_throw(path);
  Pc2File file;
  file.in.open(path, std::ios::binary);
  if (!file.in) throw InputError(with_path(path, "cannot open file (it is not readable)"));
  if (size < kHeaderBytes) {
    throw InputError(with_path(path, "the file is " + std::to_string(size) +
                                         " bytes, shorter than the 32-byte PC2 header (truncated or not a PC2 file)"));
  }
  std::array<unsigned char, kHeaderBytes> bytes{};
  if (!file.in.read(reinterpret_cast<char*>(bytes.data()), bytes.size()))
    throw InputError(with_path(path, "cannot read the PC2 header"));
  file.header = parse_header(bytes, size, path);
  return file;
}

FramePositions read_frame(Pc2File& file, int frame, const std::string& path) {
  std::vector<unsigned char> bytes(static_cast<std::size_t>(file.header.num_points) * kPointBytes);
  if (!file.in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
    throw InputError(with_path(path, "cannot read frame " + std::to_string(frame)));
  return decode_frame(bytes, file.header.num_points);
}

/// Shortest decimal text with 9 significant digits (what a float32 needs to
/// round-trip, the precision the PC2 cache keeps too), independent of the C
/// locale, which a Qt host sets from the environment.
void append_number(std::string& out, double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 9);
  out.append(buffer, error == std::errc() ? end : buffer);
}

std::string obj_text(const FramePositions& positions, const std::vector<std::vector<int>>& faces, const FaceUVs& uvs) {
  std::string text;
  text.reserve(static_cast<std::size_t>(positions.rows()) * 40 + faces.size() * 24);
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    text += 'v';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append_number(text, positions(i, k));
    }
    text += '\n';
  }
  // One texture coordinate per face corner, in order (seams need nothing more).
  for (const auto& face : uvs)
    for (const Eigen::Vector2d& uv : face) {
      text += "vt ";
      append_number(text, uv.x());
      text += ' ';
      append_number(text, uv.y());
      text += '\n';
    }
  std::size_t texcoord = 0;
  for (const std::vector<int>& face : faces) {
    text += 'f';
    for (const int v : face) {
      text += ' ';
      text += std::to_string(v + 1);  // OBJ counts from 1
      if (!uvs.empty()) {
        text += '/';
        text += std::to_string(++texcoord);
      }
    }
    text += '\n';
  }
  return text;
}

void check_obj_sequence(const std::string& prefix, const std::vector<FramePositions>& frames,
                        const std::vector<std::vector<int>>& faces, const FaceUVs& uvs) {
  if (!uvs.empty()) {
    bool shaped = uvs.size() == faces.size();
    for (std::size_t f = 0; shaped && f < faces.size(); ++f) shaped = uvs[f].size() == faces[f].size();
    if (!shaped)
      throw ArgumentError(prefix + ": texture coordinates for " + std::to_string(uvs.size()) +
                          " faces, not one per corner of the " + std::to_string(faces.size()) + " faces");
  }
  const Eigen::Index points = frames.front().rows();
  for (std::size_t k = 1; k < frames.size(); ++k) {
    if (frames[k].rows() != points) {
      throw ArgumentError(prefix + ": frame " + std::to_string(k) + " has " + std::to_string(frames[k].rows()) +
                          " points but frame 0 has " + std::to_string(points));
    }
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].size() < 3)
      throw ArgumentError(prefix + ": face " + std::to_string(f) + " has " + std::to_string(faces[f].size()) +
                          " vertices (expected at least 3)");
    for (const int v : faces[f]) {
      if (v < 0 || v >= points)
        throw ArgumentError(prefix + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                            " but the frames have " + std::to_string(points) + " points");
    }
  }
}

}  // namespace

std::string obj_sequence_path(const std::string& prefix, std::size_t index, std::size_t count) {
  std::size_t width = 4;
  for (std::size_t last = count - 1; last >= 10000; last /= 10) ++width;
  std::string number = std::to_string(index);
  if (number.size() < width) number.insert(0, width - number.size(), '0');
  return prefix + "_" + number + ".obj";
}

// ---------------------------------------------------------------------------
// Pc2Writer

struct Pc2Writer::Impl {
  std::string path;
  std::string temporary;
  std::ofstream out;
  int num_points = 0;
  int frames = 0;
  bool finished = false;
  std::vector<unsigned char> buffer;

  /// Nothing half-written survives: an unfinished cache's temporary file is
  /// removed (also when the constructor throws after creating it).
  ~Impl() {
    if (finished || temporary.empty()) return;
    if (out.is_open()) out.close();
    std::error_code ignored;
    fs::remove(temporary, ignored);
  }

  void fail(const std::string& problem) {
    if (out.is_open()) out.close();
    throw OutputError(with_path(path, problem));
  }
};

Pc2Writer::Pc2Writer(const std::string& path, int num_points, double start_frame, double sample_rate)
    : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  impl.path = path;
  impl.num_points = num_points;
  if (num_points <= 0)
    throw ArgumentError(with_path(path, "a PC2 cache needs num_points > 0 (got " + std::to_string(num_points) + ")"));
  if (!std::isfinite(start_frame) || !std::isfinite(sample_rate))
    throw ArgumentError(with_path(path, "start_frame and sample_rate must be finite"));
  require_writable_target(path);

  impl.temporary = temporary_path_beside(path, ".pc2");
  impl.out.open(impl.temporary, std::ios::binary | std::ios::trunc);
  if (!impl.out)
    impl.fail("cannot write file (cannot create '" + fs::path(impl.temporary).filename().string() + "': " +
              std::strerror(errno) + ")");
  // The sample count stays 0 until finish(): a reader never trusts an
  // unfinished file, and finish() patches it in place.
  Header header;
  header.num_points = num_points;
  header.start_frame = static_cast<float>(start_frame);
  header.sample_rate = static_cast<float>(sample_rate);
  const auto bytes = encode_header(header);
  if (!impl.out.write(reinterpret_cast<const char*>(bytes.data()), bytes.size()))
    impl.fail("cannot write the PC2 header");
}

Pc2Writer::~Pc2Writer() = default;

void Pc2Writer::add_frame(const FramePositions& positions) {
  Impl& impl = *impl_;
  if (!impl.out.is_open())
    throw OutputError(with_path(impl.path, "cannot add a frame: the cache is already finished or has failed"));
  if (positions.rows() != impl.num_points) {
    throw ArgumentError(with_path(impl.path, "frame " + std::to_string(impl.frames) + " has " +
                                                 std::to_string(positions.rows()) + " points (expected " +
                                                 std::to_string(impl.num_points) + ")"));
  }
  if (impl.frames == std::numeric_limits<std::int32_t>::max())
    impl.fail("cannot add a frame: PC2 holds at most 2^31 - 1 frames");
  encode_frame(positions, impl.buffer);
  if (!impl.out.write(reinterpret_cast<const char*>(impl.buffer.data()),
                      static_cast<std::streamsize>(impl.buffer.size())))
    impl.fail("cannot write frame " + std::to_string(impl.frames) + " (disk full?)");
  ++impl.frames;
}

void Pc2Writer::finish() {
  Impl& impl = *impl_;
  if (!impl.out.is_open())
    throw OutputError(with_path(impl.path, "cannot finish: the cache is already finished or has failed"));
  unsigned char count[4];
  put_i32(count, impl.frames);
  impl.out.seekp(kSampleCountOffset);
  impl.out.write(reinterpret_cast<const char*>(count), sizeof count);
  impl.out.close();
  if (impl.out.fail()) throw OutputError(with_path(impl.path, "cannot write file (completing the PC2 header failed)"));
  replace_with_temporary(impl.temporary, impl.path);
  impl.finished = true;
}

int Pc2Writer::frames_written() const { return impl_->frames; }

// ---------------------------------------------------------------------------
// Reading

PointCache read_pc2(const std::string& path) {
  Pc2File file = open_pc2(path);
  PointCache cache;
  cache.num_points = file.header.num_points;
  cache.start_frame = file.header.start_frame;
  cache.sample_rate = file.header.sample_rate;
  cache.frames.reserve(static_cast<std::size_t>(file.header.num_samples));
  for (int k = 0; k < file.header.num_samples; ++k) cache.frames.push_back(read_frame(file, k, path));
  return cache;
}

FramePositions read_pc2_frame(const std::string& path, int frame) { return Pc2Reader(path).frame(frame); }

struct Pc2Reader::Impl {
  std::string path;
  Pc2File file;
  int next = 0;  ///< the frame the stream is positioned at
};

Pc2Reader::Pc2Reader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->file = open_pc2(path);
}

Pc2Reader::~Pc2Reader() = default;

int Pc2Reader::num_points() const { return impl_->file.header.num_points; }
int Pc2Reader::num_frames() const { return impl_->file.header.num_samples; }
double Pc2Reader::start_frame() const { return impl_->file.header.start_frame; }
double Pc2Reader::sample_rate() const { return impl_->file.header.sample_rate; }
const std::string& Pc2Reader::path() const { return impl_->path; }

FramePositions Pc2Reader::frame(int frame) {
  Impl& m = *impl_;
  if (frame < 0 || frame >= m.file.header.num_samples) {
    throw ArgumentError(with_path(m.path, "frame " + std::to_string(frame) + " is out of range (the cache has " +
                                              std::to_string(m.file.header.num_samples) + " frames)"));
  }
  if (frame != m.next) {
    const std::uint64_t offset =
        kHeaderBytes + std::uint64_t(frame) * std::uint64_t(m.file.header.num_points) * kPointBytes;
    m.file.in.clear();
    m.file.in.seekg(static_cast<std::streamoff>(offset));
  }
  FramePositions positions = read_frame(m.file, frame, m.path);
  m.next = frame + 1;
  return positions;
}

FramePositions Pc2Reader::finite_frame(int frame) {
  FramePositions positions = this->frame(frame);
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    if (!positions.row(v).allFinite())
      throw InputError(with_path(impl_->path, "frame " + std::to_string(frame) + ", point " + std::to_string(v) +
                                                  " is not finite; expected finite positions"));
  return positions;
}

// ---------------------------------------------------------------------------
// OBJ sequences

namespace {

/// The frames from `first` on that an earlier, longer sequence of `prefix`
/// left (at any of the widths a sequence numbers them with), up to the
/// first number none is there for: a DCC tool importing the sequence would
/// take them for this run's.
void remove_later_frames(const std::string& prefix, std::size_t first) {
  for (std::size_t k = first;; ++k) {
    bool found = false;
    const std::string digits = std::to_string(k);
    for (std::size_t width = std::max<std::size_t>(4, digits.size()); width <= std::max<std::size_t>(4, digits.size()) + 1;
         ++width) {
      const std::string path = prefix + "_" + std::string(width - std::min(width, digits.size()), '0') + digits + ".obj";
      std::error_code error;
      if (!std::filesystem::is_regular_file(path, error)) continue;
      found = true;
      if (!std::filesystem::remove(path, error) && error)
        throw OutputError(path + ": cannot remove a frame an earlier sequence left (" + error.message() + ")");
    }
    if (!found) return;
  }
}

}  // namespace

std::vector<std::string> write_obj_sequence(const std::string& prefix, const std::vector<FramePositions>& frames,
                                            const std::vector<std::vector<int>>& faces, const FaceUVs& uvs) {
  std::vector<std::string> paths;
  if (frames.empty()) return paths;
  check_obj_sequence(prefix, frames, faces, uvs);
  paths.reserve(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::string path = obj_sequence_path(prefix, k, frames.size());
    write_obj(path, frames[k], faces, uvs);
    paths.push_back(path);
  }
  remove_later_frames(prefix, frames.size());
  return paths;
}

void write_obj(const std::string& path, const FramePositions& positions, const std::vector<std::vector<int>>& faces,
               const FaceUVs& uvs) {
  check_obj_sequence(path, {positions}, faces, uvs);
  const std::string text = obj_text(positions, faces, uvs);
  write_file_atomically(path, ".obj", [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    return !out.fail();
  });
}

ObjMesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open");
  std::vector<Eigen::Vector3d> points;
  ObjMesh mesh;
  std::string line;
  int line_number = 0;
  const auto fail = [&](const std::string& what) {
    throw InputError(path + ":" + std::to_string(line_number) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      Eigen::Vector3d p;
      if (!(fields >> p.x() >> p.y() >> p.z())) fail("expected 'v x y z'");
      points.push_back(p);
    } else if (tag == "f") {
      std::vector<int> face;
      std::string corner;
      while (fields >> corner) {
        std::size_t used = 0;
        long index = 0;
        try {
          index = std::stol(corner, &used);
        } catch (const std::exception&) {
          fail("expected a vertex index, got '" + corner + "'");
        }
        if (used < corner.size() && corner[used] != '/') fail("expected a vertex index, got '" + corner + "'");
        const long count = static_cast<long>(points.size());
        const long zero_based = index > 0 ? index - 1 : count + index;
        if (index == 0 || zero_based < 0 || zero_based >= count)
          fail("vertex index " + std::to_string(index) + " out of range (" + std::to_string(count) +
               " vertices so far)");
        face.push_back(static_cast<int>(zero_based));
      }
      if (face.size() < 3) fail("a face needs at least 3 vertices");
      mesh.faces.push_back(std::move(face));
    }
  }
  // A binary file (a PC2 given for its OBJ) has no 'v' line to fail on.
  if (points.empty() || mesh.faces.empty())
    throw InputError(path + ": no " + std::string(points.empty() ? "'v' (vertex)" : "'f' (face)") +
                     " lines; expected an OBJ mesh");
  mesh.positions.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t k = 0; k < points.size(); ++k) mesh.positions.row(static_cast<Eigen::Index>(k)) = points[k].transpose();
  return mesh;
}

}  // namespace mrcloth
