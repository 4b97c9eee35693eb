#include "garment_io.h"
#include "mode_painting.h"

#include "atomic_file.h"
#include "errors.h"
#include "mode_layer.h"
#include "obj_tokens.h"
#include "quadtree_forest.h"
#include "texture_coords.h"
#include "om_structure.h"
#include "ply_layout.h"
#include "text_words.h"
#include "units.h"

// MeshIO.hh pulls in the reader and writer modules, which register
// themselves with the IOManager.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/IO/reader/OFFReader.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include <unistd.h>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;
using VertexHandle = OpenMesh::VertexHandle;

enum class Format { obj, off, ply, om };

/// ".obj" for "A/B.OBJ", "" when there is none.
std::string lower_extension(const std::string& path) { return ascii_lower(fs::path(path).extension().string()); }

std::optional<Format> format_of(const std::string& extension) {
  if (extension == ".obj") return Format::obj;
  if (extension == ".off") return Format::off;
  if (extension == ".ply") return Format::ply;
  if (extension == ".om") return Format::om;
  return std::nullopt;
}

const char* format_name(Format format) {
  switch (format) {
    case Format::obj: return "OBJ";
    case Format::off: return "OFF";
    case Format::ply: return "PLY";
    case Format::om: return "OpenMesh OM";
  }
  return "?";
}

std::string shown_extension(const std::string& extension) {
  return extension.empty() ? std::string("none") : "'" + extension + "'";
}

/// OpenMesh reports to omerr()/omlog() itself; while one of our reads or
/// writes runs those reports are muted, because every problem the user must
/// see comes back as one of our exceptions instead.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : err_was_on_(::omerr().is_enabled()), log_was_on_(::omlog().is_enabled()) {
    ::omerr().flush();  // earlier, unrelated output still goes out
    ::omlog().flush();
    ::omerr().disable();
    ::omlog().disable();
  }
  ~QuietOpenMesh() {
    // A muted report without a final newline would otherwise sit in the
    // buffer and surface with the next unrelated message.
    ::omerr().flush();
    ::omlog().flush();
    if (err_was_on_) ::omerr().enable();
    if (log_was_on_) ::omlog().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  bool err_was_on_;
  bool log_was_on_;
};

// ---------------------------------------------------------------------------
// Reading

/// The first face the file gets wrong, in file order (0-based).
struct FaceProblem {
  long face = -1;
  std::string text;  ///< starts with "face <n>"
  bool found() const { return face >= 0; }
};

FaceProblem earlier(const FaceProblem& a, const FaceProblem& b) {
  if (!a.found()) return b;
  if (!b.found()) return a;
  return b.face < a.face ? b : a;
}

std::string face_label(long face) { return "face " + std::to_string(face); }

/// Where each vertex and face of a text file stands (1-based line numbers,
/// in the file's order, which is the mesh's): messages about an element
/// found wrong after reading (the surface checks) name its line, so that
/// an index counted from 0 cannot be mistaken for OBJ's count from 1.
/// Empty (no lines named) for binary files and .om.
struct ElementLines {
  std::vector<std::size_t> vertex, face;

  std::string vertex_name(long v) const { return "vertex " + std::to_string(v) + line_of(vertex, v); }
  std::string face_name(long f) const { return face_label(f) + line_of(face, f); }

 private:
  static std::string line_of(const std::vector<std::size_t>& lines, long k) {
    return k >= 0 && static_cast<std::size_t>(k) < lines.size() ? at_line(lines[static_cast<std::size_t>(k)]) : "";
  }
};

/// Checks every face as the reader hands it over. ImporterT would log and
/// drop bad faces, and would silently duplicate the vertices of a face that
/// does not fit the manifold built so far; we want the read to fail instead.
/// Nothing is thrown from inside OpenMesh's reader: the first problem is
/// remembered and load_garment throws once the reader has returned.
class CheckingImporter : public OpenMesh::IO::ImporterT<QuadMesh> {
 public:
  /// `lines` (kept by reference: it must outlive the importer) names the
  /// file's lines in messages.
  CheckingImporter(QuadMesh& mesh, const ElementLines& lines) : ImporterT(mesh), target_(mesh), lines_(lines) {}

  using ImporterT::add_face;

  OpenMesh::FaceHandle add_face(const VHandles& corners) override {
    const long face = next_face_++;
    // Once the load is known to fail, later faces are skipped so the reader
    // can still run to its end.
    if (problem_.found()) return OpenMesh::FaceHandle();
    if (std::string issue = corner_issue(corners); !issue.empty()) {
      problem_ = {face, lines_.face_name(face) + issue};
      return OpenMesh::FaceHandle();
    }
    const OpenMesh::FaceHandle added = target_.add_face(corners);
    if (!added.is_valid()) problem_ = {face, lines_.face_name(face) + why_not_added(corners)};
    return added;
  }

  const FaceProblem& problem() const { return problem_; }

 private:
  /// Why the mesh refused a face whose corners are valid: the first of its
  /// edges that cannot join the faces read before it, named by its vertices.
  std::string why_not_added(const VHandles& corners) const {
    const std::string expected = "; expected an oriented 2-manifold quad mesh";
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const VertexHandle a = corners[k], b = corners[(k + 1) % corners.size()];
      const std::string edge = "edge from " + lines_.vertex_name(a.idx()) + " to " + lines_.vertex_name(b.idx());
      const auto along = target_.find_halfedge(a, b), against = target_.find_halfedge(b, a);
      if (along.is_valid() && !target_.is_boundary(along)) {
        if (against.is_valid() && !target_.is_boundary(against))
          return " would be a third face on its " + edge + expected;
        return " runs its " + edge + " the way " + lines_.face_name(target_.face_handle(along).idx()) +
               " does: one of them is wound the other way round (or the surface is one-sided, a Moebius strip)" +
               expected + " (faces wound alike, as seen from one side)";
      }
    }
    return " would join the faces before it only at a vertex (a bow-tie)" + expected;
  }

  std::string corner_issue(const VHandles& corners) const {
    if (corners.size() < 3)
      return " has only " + std::to_string(corners.size()) + " corners; expected at least 3";
    const int n_vertices = static_cast<int>(target_.n_vertices());
    for (const VertexHandle v : corners) {
      if (v.idx() < 0 || v.idx() >= n_vertices)
        return " refers to vertex " + std::to_string(v.idx()) + " (counted from 0), which does not exist (the file has " +
               std::to_string(n_vertices) + " vertices)";
    }
    for (std::size_t i = 0; i < corners.size(); ++i) {
      for (std::size_t j = i + 1; j < corners.size(); ++j) {
        if (corners[i] == corners[j])
          return " uses " + lines_.vertex_name(corners[i].idx()) + " more than once; expected distinct corners";
      }
    }
    return {};
  }

  QuadMesh& target_;
  const ElementLines& lines_;
  long next_face_ = 0;
  FaceProblem problem_;
};

// OpenMesh 9's OBJ, OFF and PLY readers parse coordinates as float, which
// would cost garments about seven significant digits. The text formats are
// therefore scanned once more here, in double precision; the scan also sees
// what the OBJ reader hides (it drops vertices it cannot parse and quietly
// removes repeated corners), so those files fail with the real reason.

/// What the double-precision scan learned about a text file.
struct TextScan {
  bool understood = false;              ///< false: keep OpenMesh's coordinates
  bool binary = false;                  ///< binary OFF/PLY: OpenMesh's values are all there is
  std::vector<OpenMesh::Vec3d> points;  ///< in file order, unscaled
  FaceProblem face_problem;             ///< OBJ only
  /// OBJ only: a face has a corner without a vertex index ("/2"), which
  /// OpenMesh's reader (built with assertions, as Debian's is) aborts the
  /// process on; face_problem (that face's or an earlier one's) is thrown
  /// before the reader runs.
  bool reader_would_abort = false;
  ElementLines lines;                   ///< OBJ and ASCII OFF: each vertex's and face's line
  /// OBJ only: the `vt` lines, and per face its corners' (vertex, texture
  /// coordinate) indices from 0 (-1: the corner names none); `uv_readable`
  /// false when a corner's texture index could not be read.
  std::vector<OpenMesh::Vec2d> texcoords;
  std::vector<std::vector<std::pair<long, long>>> face_corners;
  bool uv_readable = true;
  /// What OpenMesh reads instead of the file, if not empty: ASCII OFF
  /// without comments and blank lines (its OFF reader misreads a comment
  /// after the header as element counts: garbage counts, then garbage or
  /// very slow reads; counts moved off the magic word's line), or an OBJ
  /// without its byte-order mark (its OBJ reader drops the first line's
  /// vertex and shifts every face) and with continued lines joined.
  std::string text_for_reader;
};

std::string strip_comment(const std::string& line) { return line.substr(0, line.find('#')); }

/// A finite number from a whole token, independently of the C locale;
/// false when the token is not one.
bool parse_number(const std::string& token, double& value) {
  const char* begin = token.data();
  const char* end = token.data() + token.size();
  if (begin != end && *begin == '+') ++begin;  // from_chars does not take a plus sign
  const auto [stop, error] = std::from_chars(begin, end, value);
  return error == std::errc() && stop == end && std::isfinite(value);
}

/// Parses one coordinate independently of the C locale (a Qt host sets it
/// from the environment, and strtod would then expect a decimal comma).
double parse_coordinate(const std::string& path, const std::string& token, std::size_t vertex,
                        const std::string& where) {
  const char* begin = token.data();
  const char* end = token.data() + token.size();
  if (begin != end && *begin == '+') ++begin;  // from_chars does not take a plus sign
  double value = 0.0;
  const auto [stop, error] = std::from_chars(begin, end, value);
  const std::string vertex_text = "vertex " + std::to_string(vertex) + where;
  if (stop != end || (error != std::errc() && error != std::errc::result_out_of_range))
    throw InputError(with_path(path, vertex_text + " has a coordinate that is not a number ('" + token + "')"));
  if (error == std::errc::result_out_of_range) {
    // Underflow is harmless (the value is zero to double precision); overflow
    // is a coordinate we cannot represent.
    const bool negative_exponent = token.find("e-") != std::string::npos || token.find("E-") != std::string::npos;
    if (!negative_exponent)
      throw InputError(with_path(path, vertex_text + " has a non-finite coordinate (" + token +
                                           "); expected finite numbers"));
    value = 0.0;
  }
  if (!std::isfinite(value))
    throw InputError(
        with_path(path, vertex_text + " has a non-finite coordinate (" + token + "); expected finite numbers"));
  // OpenMesh's readers hold coordinates as float and drop a vertex beyond
  // its range, which shifts every later index.
  if (std::abs(value) > static_cast<double>(std::numeric_limits<float>::max()))
    throw InputError(with_path(path, vertex_text + " has a coordinate beyond single precision's range (" + token +
                                         "); expected |coordinate| < 3.4e38 (check the file's units)"));
  return value;
}

OpenMesh::Vec3d parse_point(const std::string& path, const std::vector<std::string>& words, std::size_t first,
                            std::size_t vertex, const std::string& where) {
  if (words.size() < first + 3)
    throw InputError(with_path(path, "vertex " + std::to_string(vertex) + where +
                                         " has fewer than 3 coordinates; expected x y z"));
  return {parse_coordinate(path, words[first], vertex, where), parse_coordinate(path, words[first + 1], vertex, where),
          parse_coordinate(path, words[first + 2], vertex, where)};
}

/// One OBJ face line checked the way CheckingImporter checks faces, but with
/// the file's own 1-based (or negative, relative) indices in the message.
std::string obj_face_issue(const std::vector<std::string>& words, long n_defined, const ElementLines& lines) {
  std::vector<long> corners;
  for (std::size_t k = 1; k < words.size(); ++k) {
    const std::string& word = words[k];
    const std::string index_text = word.substr(0, word.find('/'));
    long index = 0;
    const char* end = index_text.data() + index_text.size();
    const auto [stop, error] = std::from_chars(index_text.data(), end, index);
    if (error != std::errc() || stop != end) return " has a corner that is not a vertex index ('" + word + "')";
    const long resolved = index > 0 ? index - 1 : n_defined + index;
    if (index == 0 || resolved < 0 || resolved >= n_defined)
      return " refers to vertex " + index_text + ", which does not exist (" + std::to_string(n_defined) +
             " vertices are defined before it; OBJ indices start at 1)";
    corners.push_back(resolved);
  }
  if (corners.size() < 3) return " has only " + std::to_string(corners.size()) + " corners; expected at least 3";
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (std::size_t j = i + 1; j < corners.size(); ++j) {
      if (corners[i] == corners[j])
        return " uses " + lines.vertex_name(corners[i]) + " more than once; expected distinct corners";
    }
  }
  return {};
}

/// A face's corners as (vertex, texture coordinate) indices from 0, given
/// how many of each are defined before it; -1 where a corner names no
/// texture coordinate. A texture index that is not one of those defined
/// clears `readable` (the vertex indices are checked by obj_face_issue).
std::vector<std::pair<long, long>> obj_face_corners(const std::vector<std::string>& words, long n_vertices,
                                                    long n_texcoords, bool& readable) {
  std::vector<std::pair<long, long>> corners;
  for (std::size_t k = 1; k < words.size(); ++k) {
    const std::string_view word = words[k];
    const std::string_view texture = obj_corner_texture(word);
    const long texcoord = texture.empty() ? -1 : resolve_obj_index(texture, n_texcoords);
    if (!texture.empty() && texcoord < 0) readable = false;
    corners.emplace_back(resolve_obj_index(word.substr(0, word.find('/')), n_vertices), texcoord);
  }
  return corners;
}

TextScan scan_obj_lines(const std::string& path, std::istream& in) {
  TextScan scan;
  long n_faces = 0;
  std::size_t line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const std::vector<std::string> words = split_words(strip_comment(line));
    if (words.empty()) continue;
    if (words[0] == "v") {
      scan.points.push_back(parse_point(path, words, 1, scan.points.size(), at_line(line_number)));
      scan.lines.vertex.push_back(line_number);
    } else if (words[0] == "vt") {
      OpenMesh::Vec2d uv(0.0, 0.0);
      for (int c = 0; c < 2 && c + 1 < static_cast<int>(words.size()); ++c)
        if (!parse_number(words[static_cast<std::size_t>(c + 1)], uv[c])) scan.uv_readable = false;
      scan.texcoords.push_back(uv);
    } else if (words[0] == "f") {
      const long face = n_faces++;
      scan.lines.face.push_back(line_number);
      scan.face_corners.push_back(obj_face_corners(words, static_cast<long>(scan.points.size()),
                                                   static_cast<long>(scan.texcoords.size()), scan.uv_readable));
      for (std::size_t k = 1; k < words.size(); ++k)
        if (words[k].front() == '/') scan.reader_would_abort = true;
      if (scan.face_problem.found()) continue;
      if (std::string issue = obj_face_issue(words, static_cast<long>(scan.points.size()), scan.lines); !issue.empty())
        scan.face_problem = {face, face_label(face) + at_line(line_number) + issue};
    }
  }
  scan.understood = true;
  return scan;
}

/// An OBJ's text as OpenMesh's reader can take it, or "" when the file is
/// that already: without a byte-order mark (the reader would drop the first
/// line's vertex and shift every face) and with lines continued by a
/// trailing backslash joined (legal OBJ the reader does not know). A joined
/// line keeps the first line's number, and blank lines after it keep the
/// numbers of the lines below.
std::string obj_text_for_reader(const std::string& text) {
  const std::string byte_order_mark = "\xEF\xBB\xBF";
  const bool marked = text.rfind(byte_order_mark, 0) == 0;
  if (!marked && text.find("\\\n") == std::string::npos && text.find("\\\r\n") == std::string::npos) return {};
  std::istringstream in(marked ? text.substr(byte_order_mark.size()) : text);
  std::string out, logical;
  std::size_t joined = 0;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && line.back() == '\\') {
      logical += line.substr(0, line.size() - 1) + ' ';
      ++joined;
      continue;
    }
    out += logical + line + '\n';
    out.append(joined, '\n');
    logical.clear();
    joined = 0;
  }
  if (!logical.empty()) out += logical + '\n' + std::string(joined, '\n');
  return out;
}

/// Text that the line scan would read as one line or as no words at all:
/// refused with what it is (they read as "no vertices" or "no faces").
void require_line_text(const std::string& path, const std::string& text) {
  if (text.rfind("\xFF\xFE", 0) == 0 || text.rfind("\xFE\xFF", 0) == 0)
    throw InputError(with_path(path, "the file is UTF-16 text (it starts with a UTF-16 byte-order mark); expected "
                                     "UTF-8 or ASCII text (save it as UTF-8)"));
  if (text.find('\n') == std::string::npos && text.find('\r') != std::string::npos)
    throw InputError(with_path(path, "the file ends its lines with carriage returns alone (classic Mac OS); expected "
                                     "line ends LF or CR LF"));
}

TextScan scan_obj(const std::string& path, const std::string& text) {
  std::string reader_text = obj_text_for_reader(text);
  std::istringstream lines(reader_text.empty() ? text : reader_text);
  TextScan scan = scan_obj_lines(path, lines);
  scan.text_for_reader = std::move(reader_text);
  return scan;
}

/// OpenMesh's OFF reader reads a stream as laid out like the last file it
/// checked by name (binary, colours, normals: it learns a layout only from
/// a file's first line, and only when given a file name): an ASCII OFF
/// handed over as text after a binary one was read as binary. So it checks
/// a scratch file holding `text`'s first line before it reads `text`; where
/// no scratch file can be written, the file `path` itself (whose first line
/// says the same unless comments or blank lines come before it).
void set_off_layout(const std::string& path, const std::string& text) {
  static std::atomic<unsigned> serial{0};
  std::error_code error;
  const fs::path scratch = fs::temp_directory_path(error) / ("mrcloth-off-layout-" + std::to_string(::getpid()) +
                                                             "-" + std::to_string(serial++) + ".off");
  bool checked = false;
  if (!error) {
    std::ofstream out(scratch, std::ios::binary | std::ios::trunc);
    out << text.substr(0, text.find('\n') + 1);
    out.close();
    checked = out && OpenMesh::IO::OFFReader().can_u_read(scratch.string());
    fs::remove(scratch, error);
  }
  if (!checked) OpenMesh::IO::OFFReader().can_u_read(path);
}

/// Binary OFF as OpenMesh reads it: after the "OFF BINARY" line, little-
/// endian 32-bit vertex, face and edge counts, x y z floats per vertex,
/// and per face a 32-bit corner count and that many 32-bit vertex indices.
/// The reader trusts every count (a face count of 2^32 - 1 kept it reading
/// past the end of the file for minutes; a corner count as large pushes
/// billions of corners), so the data is walked first and each face's
/// corners checked against the bytes left and the vertex count. The
/// variants with normals, colours or texture coordinates (NOFF, COFF, STOFF
/// BINARY) are refused: their record sizes depend on the reader's options.
/// The reader gets the data under a header line it cannot misread.
TextScan scan_binary_off(const std::string& path, const std::string& magic, const std::string& text) {
  if (magic != "OFF")
    throw InputError(with_path(path, "binary " + magic + " (with normals, colours or texture coordinates) is not "
                                     "supported; expected 'OFF BINARY' with positions only, or an ASCII OFF"));
  const std::size_t line_end = text.find('\n');  // the first line held "OFF BINARY"
  if (line_end == std::string::npos)
    throw InputError(with_path(path, "the binary OFF has no line end after 'OFF BINARY'; expected the counts and data "
                                     "on the bytes after it"));
  const std::size_t data = line_end + 1;
  const auto read_u32 = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (int k = 0; k < 4; ++k) value |= std::uint32_t{static_cast<unsigned char>(text[at + k])} << (8 * k);
    return value;
  };
  const std::size_t size = text.size();
  if (size < data + 12)
    throw InputError(with_path(path, "the binary OFF ends before its vertex, face and edge counts; expected three "
                                     "32-bit counts after the 'OFF BINARY' line"));
  const std::uint64_t vertices = read_u32(data), faces = read_u32(data + 4);
  // At least 12 bytes per vertex and 4 per face (its corner count).
  const std::uint64_t least = 12 * vertices + 4 * faces;
  if (least > size - data - 12)
    throw InputError(with_path(path, "the binary OFF header declares " + std::to_string(vertices) + " vertices and " +
                                     std::to_string(faces) + " faces, which need at least " + std::to_string(least) +
                                     " bytes; " + std::to_string(size - data - 12) +
                                     " follow (truncated, or counts not little-endian as OpenMesh reads them)"));
  std::size_t at = data + 12 + 12 * vertices;
  for (std::uint64_t f = 0; f < faces; ++f) {
    if (size - at < 4)
      throw InputError(with_path(path, "the binary OFF ends at " + face_label(static_cast<long>(f)) + " of " +
                                       std::to_string(faces) + "; expected its corner count"));
    const std::uint64_t corners = read_u32(at);
    at += 4;
    if (corners < 3 || corners > (size - at) / 4)
      throw InputError(with_path(path, face_label(static_cast<long>(f)) + " (byte " + std::to_string(at - 4) +
                                       ") has corner count " + std::to_string(corners) + " and " +
                                       std::to_string((size - at) / 4) +
                                       " indices' bytes left; expected at least 3 corners and their indices"));
    for (std::uint64_t c = 0; c < corners; ++c, at += 4)
      if (read_u32(at) >= vertices)
        throw InputError(with_path(path, face_label(static_cast<long>(f)) + " names vertex " +
                                         std::to_string(read_u32(at)) + "; expected an index below " +
                                         std::to_string(vertices)));
  }
  TextScan scan;
  scan.binary = true;
  scan.text_for_reader = "OFF BINARY\n" + text.substr(data);
  return scan;
}

/// Plain ASCII OFF, optionally with colours/normals/texture coordinates after
/// x y z (COFF, NOFF, STOFF...); binary OFF by scan_binary_off; 4OFF and nOFF
/// are left to OpenMesh (which refuses them).
/// Refuses a header OpenMesh would misread: a word that is no OFF variant
/// (it accepted "OFFX"), and counts more than the lines after it hold (it
/// would allocate for them, or read faces as vertices).
TextScan scan_off(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  TextScan scan;
  std::size_t line_number = 0;
  std::string cleaned;
  auto next_words = [&]() {
    for (std::string line; std::getline(in, line);) {
      ++line_number;
      line = strip_comment(line);
      std::vector<std::string> words = split_words(line);
      if (words.empty()) continue;
      cleaned += line;
      cleaned += '\n';
      return words;
    }
    return std::vector<std::string>{};
  };
  std::vector<std::string> words = next_words();
  if (words.empty()) return scan;
  std::string header = words[0];
  for (const char* prefix : {"ST", "C", "N"}) {
    if (header.rfind(prefix, 0) == 0) header.erase(0, std::string(prefix).size());
  }
  if (header != "OFF" && header != "4OFF" && header != "nOFF")
    throw InputError(with_path(path, "the file starts with '" + words[0] +
                                         "'; expected OFF (or COFF, NOFF, STOFF, 4OFF, nOFF)"));
  if (words.size() > 1 && words[1] == "BINARY") {
    if (line_number != 1)
      throw InputError(with_path(path, "the 'OFF BINARY' line is line " + std::to_string(line_number) +
                                       "; expected it first (OpenMesh's reader reads binary data after line 1)"));
    return scan_binary_off(path, words[0], text);
  }
  if (header != "OFF") return scan;
  const std::string magic = words[0];
  words.erase(words.begin());
  if (!words.empty()) {
    // Counts on the header's line: OpenMesh reads them only on their own.
    cleaned = magic + "\n";
    for (const std::string& word : words) cleaned += word + ' ';
    cleaned += '\n';
  }
  if (words.empty()) words = next_words();
  // Without its counts OpenMesh's reader reserves for whatever its
  // variables held (tens of gigabytes were seen).
  if (words.size() < 2)
    throw InputError(with_path(path, "the OFF header has no vertex and face counts" +
                                         (words.empty() ? std::string() : at_line(line_number)) +
                                         "; expected 'V F E' after OFF"));
  std::size_t counts[2] = {0, 0};  // vertices, faces
  for (int k = 0; k < 2; ++k) {
    const std::string& word = words[static_cast<std::size_t>(k)];
    const auto [stop, error] = std::from_chars(word.data(), word.data() + word.size(), counts[k]);
    if (error != std::errc() || stop != word.data() + word.size())
      throw InputError(with_path(path, "the OFF header's " + std::string(k == 0 ? "vertex" : "face") + " count '" +
                                           word + "'" + at_line(line_number) + " is not a count; expected 'V F E'"));
  }
  const std::size_t header_line = line_number;
  std::vector<std::pair<std::size_t, std::vector<std::string>>> lines;  // (line number, words)
  for (std::vector<std::string> next = next_words(); !next.empty(); next = next_words())
    lines.emplace_back(line_number, std::move(next));
  if (lines.size() < counts[0] || lines.size() - counts[0] < counts[1])
    throw InputError(with_path(path, "the OFF header" + at_line(header_line) + " declares " +
                                         std::to_string(counts[0]) + " vertices and " + std::to_string(counts[1]) +
                                         " faces, but only " + std::to_string(lines.size()) +
                                         " lines of data follow; expected one line per vertex and per face"));
  for (std::size_t v = 0; v < counts[0]; ++v) {
    scan.points.push_back(parse_point(path, lines[v].second, 0, v, at_line(lines[v].first)));
    scan.lines.vertex.push_back(lines[v].first);
  }
  for (std::size_t f = 0; f < counts[1]; ++f) {
    const auto& [face_line, face_words] = lines[counts[0] + f];
    scan.lines.face.push_back(face_line);
    // OpenMesh takes the first number as the corner count and reads that
    // many indices on, across lines: a huge count reserves memory without
    // bound, a wrong one reads the faces after it askew.
    std::size_t corners = 0;
    const std::string& count = face_words[0];
    const auto [stop, error] = std::from_chars(count.data(), count.data() + count.size(), corners);
    if (error != std::errc() || stop != count.data() + count.size() || corners + 1 > face_words.size())
      throw InputError(with_path(path, face_label(static_cast<long>(f)) + at_line(face_line) + " starts with '" +
                                           count + "' and lists " + std::to_string(face_words.size() - 1) +
                                           " numbers after it; expected its corner count, then that many vertex "
                                           "indices (then, optionally, a colour)"));
  }
  scan.understood = true;
  scan.text_for_reader = std::move(cleaned);
  return scan;
}

/// PLY: checked by scan_ply_layout, whose copy of the file the reader gets.
TextScan scan_ply(const std::string& path, std::istream& in) {
  TextScan scan;
  std::optional<PlyScan> ply = scan_ply_layout(path, in);
  if (!ply) throw InputError(with_path(path, "the first line is not 'ply'; expected a PLY file"));
  scan.binary = ply->binary;
  scan.text_for_reader = std::move(ply->text_for_reader);
  if (scan.binary) return scan;
  for (std::size_t v = 0; v < ply->coordinates.size(); ++v) {
    const auto& xyz = ply->coordinates[v];
    scan.points.push_back(parse_point(path, {xyz[0], xyz[1], xyz[2]}, 0, v, at_line(ply->vertex_lines[v])));
  }
  scan.lines.vertex = std::move(ply->vertex_lines);
  scan.lines.face = std::move(ply->face_lines);
  scan.understood = true;
  return scan;
}

TextScan scan_text(const std::string& path, Format format) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  if (format == Format::ply) return scan_ply(path, in);
  if (format != Format::obj && format != Format::off) return {};
  // Both scans read lines (a binary OFF's header is a line too): the text
  // is read once and checked to be lines first.
  std::ostringstream whole;
  whole << in.rdbuf();
  const std::string text = whole.str();
  require_line_text(path, text);
  if (format == Format::obj) return scan_obj(path, text);
  return scan_off(path, text);
}

/// True when the scan read the same vertices OpenMesh did, up to float rounding.
bool scan_matches(const TextScan& scan, const QuadMesh& mesh) {
  if (!scan.understood || scan.points.size() != mesh.n_vertices()) return false;
  for (const auto v : mesh.vertices()) {
    const OpenMesh::Vec3d& precise = scan.points[static_cast<std::size_t>(v.idx())];
    const OpenMesh::Vec3d& single = mesh.point(v);
    for (int k = 0; k < 3; ++k) {
      const double tolerance = 1e-6 * std::max(std::abs(precise[k]), std::abs(single[k])) + 1e-37;
      if (!(std::abs(precise[k] - single[k]) <= tolerance)) return false;
    }
  }
  return true;
}

void require_input_file(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(with_path(path, "cannot open file (" + missing_file_reason(path) + ")"));
  if (fs::is_directory(status)) throw InputError(with_path(path, "cannot open file (it is a folder)"));
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw InputError(with_path(path, "cannot open file (it is not readable)"));
  if (probe.peek() == std::ifstream::traits_type::eof())
    throw InputError(with_path(path, "the file is empty; expected a quad mesh"));
}

/// Where a quad of split_into_quads came from: input face `face`, around
/// its vertex `corner` (between `previous` and `next` on that face), and
/// its own vertices (corner, the midpoint towards next, the centre, the
/// midpoint towards previous).
struct SplitQuad {
  int face = -1;
  int previous = -1, corner = -1, next = -1;
  std::array<int, 4> vertices{};
};

/// One midpoint split of every face: an n-gon becomes n quads around its
/// vertex centroid. Splitting the quads too keeps the result conforming.
/// Vertices: the input's (same indices), then one midpoint per edge in edge
/// order, then one centre per face in face order. `origins`, if given,
/// receives each new quad's origin, in face order.
QuadMesh split_into_quads(const QuadMesh& in, std::vector<SplitQuad>* origins = nullptr) {
  QuadMesh out;
  out.reserve(in.n_vertices() + in.n_edges() + in.n_faces(), 4 * in.n_edges(), 2 * in.n_edges());
  for (const auto v : in.vertices()) out.add_vertex(in.point(v));
  std::vector<VertexHandle> midpoint(in.n_edges());
  for (const auto e : in.edges())
    midpoint[static_cast<std::size_t>(e.idx())] = out.add_vertex(0.5 * (in.point(e.v0()) + in.point(e.v1())));
  std::vector<VertexHandle> centre(in.n_faces());
  for (const auto f : in.faces()) {
    OpenMesh::Vec3d sum(0.0, 0.0, 0.0);
    double n = 0.0;
    for (const auto v : f.vertices()) {
      sum += in.point(v);
      n += 1.0;
    }
    centre[static_cast<std::size_t>(f.idx())] = out.add_vertex(sum / n);
  }
  for (const auto f : in.faces()) {
    std::vector<OpenMesh::SmartHalfedgeHandle> sides(f.halfedges().begin(), f.halfedges().end());
    for (std::size_t i = 0; i < sides.size(); ++i) {
      const auto& incoming = sides[(i + sides.size() - 1) % sides.size()];
      const auto& outgoing = sides[i];
      const VertexHandle corner = outgoing.from();
      const VertexHandle corners[4] = {corner, midpoint[static_cast<std::size_t>(outgoing.edge().idx())],
                                       centre[static_cast<std::size_t>(f.idx())],
                                       midpoint[static_cast<std::size_t>(incoming.edge().idx())]};
      const OpenMesh::FaceHandle quad = out.add_face(corners[0], corners[1], corners[2], corners[3]);
      if (!quad.is_valid()) throw Error("split_into_quads: a quad of face " + std::to_string(f.idx()) + " was refused");
      if (origins)
        origins->push_back({f.idx(), incoming.from().idx(), corner.idx(), outgoing.to().idx(),
                            {corners[0].idx(), corners[1].idx(), corners[2].idx(), corners[3].idx()}});
    }
  }
  return out;
}

std::string plural(std::size_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

/// Makes an all-quad mesh of any mesh, with a warning when it had to split;
/// `origins` receives where each new quad came from (none when nothing was split).
void make_all_quad(QuadMesh& mesh, const std::string& path, std::vector<std::string>& warnings,
                   std::vector<SplitQuad>& origins) {
  std::size_t triangles = 0;
  std::size_t ngons = 0;
  for (const auto f : mesh.faces()) {
    const auto valence = f.valence();
    if (valence == 3) ++triangles;
    if (valence > 4) ++ngons;
  }
  if (triangles == 0 && ngons == 0) return;
  const std::size_t before = mesh.n_vertices();
  mesh = split_into_quads(mesh, &origins);
  warnings.push_back(with_path(
      path, plural(triangles, "triangle") + " and " + plural(ngons, "n-gon") +
                " (n > 4) found; every face was split into quads at its centre and edge midpoints, so the mesh "
                "now has " +
                std::to_string(mesh.n_vertices()) + " vertices instead of " + std::to_string(before) + " and " +
                std::to_string(mesh.n_faces()) + " faces"));
}

/// The OBJ's texture coordinates onto the new forest's records (record i is
/// face i, as init_forest makes them), when every corner of every face has
/// one and the faces are the file's; otherwise none, with a warning where
/// the file had some.
void read_texture_coords(const TextScan& scan, QuadMesh& mesh, std::size_t faces_read,
                         const std::vector<SplitQuad>& split, const std::string& path,
                         std::vector<std::string>& warnings) {
  if (scan.texcoords.empty()) return;
  const auto skip = [&](const std::string& why) {
    warnings.push_back(with_path(path, "its texture coordinates (vt) are not kept: " + why));
  };
  if (!scan.uv_readable) return skip("a vt line or a face's texture index could not be read");
  if (scan.face_corners.size() != faces_read) return skip("the file's faces could not be matched to the mesh's");
  // The UV file face `face` gives its corner at vertex `vertex` (false: none).
  const auto uv_at = [&](std::size_t face, int vertex, OpenMesh::Vec2d& uv) {
    const auto& corners = scan.face_corners[face];
    const auto found = std::find_if(corners.begin(), corners.end(), [&](const auto& c) { return c.first == vertex; });
    if (found == corners.end() || found->second < 0) return false;
    uv = scan.texcoords[static_cast<std::size_t>(found->second)];
    return true;
  };
  const auto& forest = quadtree(mesh);
  std::vector<RecordUV> uvs(forest.size());
  for (std::size_t i = 0; i < forest.size(); ++i) {
    // Per quad vertex, its UV: the file's, or (a quad of a split face) the
    // mean of its face's corners' at an edge midpoint or the centre, as its
    // position was made.
    std::array<std::pair<int, OpenMesh::Vec2d>, 4> known;
    bool complete = true;
    if (split.empty()) {
      for (int k = 0; k < 4; ++k) {
        const int v = forest[i].corners[static_cast<std::size_t>(k)];
        known[static_cast<std::size_t>(k)].first = v;
        complete = complete && uv_at(i, v, known[static_cast<std::size_t>(k)].second);
      }
    } else {
      const SplitQuad& q = split[i];
      const auto face = static_cast<std::size_t>(q.face);
      OpenMesh::Vec2d previous, corner, next, centre(0.0, 0.0);
      complete = uv_at(face, q.corner, corner) && uv_at(face, q.previous, previous) && uv_at(face, q.next, next);
      const auto& corners = scan.face_corners[face];
      for (const auto& c : corners) {
        OpenMesh::Vec2d uv;
        complete = complete && uv_at(face, static_cast<int>(c.first), uv);
        centre += uv / static_cast<double>(corners.size());
      }
      known = {{{q.vertices[0], corner}, {q.vertices[1], 0.5 * (corner + next)}, {q.vertices[2], centre},
                {q.vertices[3], 0.5 * (corner + previous)}}};
    }
    if (!complete)
      return skip("face " + std::to_string(split.empty() ? i : static_cast<std::size_t>(split[i].face)) +
                  " has a corner without one; expected one at every corner");
    for (int k = 0; k < 4; ++k) {
      const int v = forest[i].corners[static_cast<std::size_t>(k)];
      const auto at = std::find_if(known.begin(), known.end(), [&](const auto& entry) { return entry.first == v; });
      if (at == known.end()) return skip("the file's faces could not be matched to the mesh's");
      uvs[i].corner[static_cast<std::size_t>(k)] = at->second;
    }
  }
  set_record_uvs(mesh, std::move(uvs));
}

/// What the reader accepts but a garment cannot be: a vertex where two fans
/// of faces meet (a bow-tie, which the boundary loops and the waist would
/// pass twice), a vertex in no face (no mass: the solver refuses it), or a
/// face without area (the same: its corners coincide, lie on a line or
/// cross). Faces are named in file order, vertices by their index.
void check_garment_surface(const std::string& path, const QuadMesh& mesh, const ElementLines& lines) {
  for (const auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) {
      std::size_t loose = 0;
      for (const auto u : mesh.vertices()) loose += mesh.is_isolated(u) ? 1 : 0;
      throw InputError(with_path(path, lines.vertex_name(v.idx()) + " belongs to no face" +
                                           (loose > 1 ? " (nor do " + std::to_string(loose - 1) + " more)" : "") +
                                           "; expected every vertex in a face (delete loose vertices)"));
    }
    if (!mesh.is_manifold(v))
      throw InputError(with_path(path, lines.vertex_name(v.idx()) +
                                           " is non-manifold (two fans of faces meet only at it, a bow-tie); "
                                           "expected an oriented 2-manifold quad mesh"));
  }
  for (const auto f : mesh.faces()) {
    // Twice the polygon's vector area (Newell), against its longest edge:
    // zero up to round-off (exact zeros, underflow), not merely thin.
    OpenMesh::Vec3d twice_area(0, 0, 0);
    double longest2 = 0.0;
    for (const auto h : mesh.fh_range(f)) {
      const OpenMesh::Vec3d a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h));
      twice_area += OpenMesh::cross(a, b);
      longest2 = std::max(longest2, (b - a).sqrnorm());
    }
    if (!(twice_area.norm() > 1e-24 * longest2))
      throw InputError(with_path(path, lines.face_name(f.idx()) +
                                           " has no area (its corners coincide, lie on a line, or cross as a "
                                           "bow-tie); expected faces with area"));
  }
}

/// A warning when a face is concave (a dart: one corner turned inwards):
/// its bilinear split folds a child face over another, the surface
/// overlapping itself. Empty when every face is convex.
std::string concave_faces_warning(const std::string& path, const QuadMesh& mesh, const ElementLines& lines) {
  std::size_t concave = 0;
  int first_face = -1, first_corner = -1;
  for (const auto f : mesh.faces()) {
    std::vector<OpenMesh::Vec3d> p;
    for (const auto v : mesh.fv_range(f)) p.push_back(mesh.point(v));
    OpenMesh::Vec3d normal(0, 0, 0);  // Newell's
    for (std::size_t k = 0; k < p.size(); ++k) normal += OpenMesh::cross(p[k], p[(k + 1) % p.size()]);
    for (std::size_t k = 0; k < p.size(); ++k) {
      const OpenMesh::Vec3d& before = p[(k + p.size() - 1) % p.size()];
      const OpenMesh::Vec3d& after = p[(k + 1) % p.size()];
      // Turned against the face, beyond round-off (a T-node's corner, on a
      // straight edge, turns by nothing).
      const OpenMesh::Vec3d in = p[k] - before, out = after - p[k];
      if (OpenMesh::dot(OpenMesh::cross(in, out), normal) < -1e-9 * in.norm() * out.norm() * normal.norm()) {
        if (concave++ == 0) {
          first_face = f.idx();
          first_corner = static_cast<int>(k);
        }
        break;
      }
    }
  }
  if (concave == 0) return {};
  return with_path(path, lines.face_name(first_face) + " is concave at its corner " + std::to_string(first_corner) +
                             (concave > 1 ? " (and " + std::to_string(concave - 1) + " more faces are concave)" : "") +
                             ": refining it folds a child face over another; expected convex faces (split or "
                             "reshape darts)");
}

/// A warning when boundary vertices lie on one another (within a
/// millionth of the median edge): panels exported with their seams not
/// welded, which the simulation would let fall apart, only the pinned
/// piece staying up. Empty when there are none.
std::string unwelded_seams_warning(const std::string& path, const QuadMesh& mesh, const ElementLines& lines) {
  std::vector<std::pair<OpenMesh::Vec3d, int>> rim;
  for (const auto v : mesh.vertices())
    if (mesh.is_boundary(v)) rim.emplace_back(mesh.point(v), v.idx());
  std::vector<double> lengths;
  for (const auto e : mesh.edges()) lengths.push_back(mesh.calc_edge_length(e));
  if (rim.empty() || lengths.empty()) return {};
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  const double tolerance = 1e-6 * lengths[lengths.size() / 2];
  // Sorted along x, each vertex meets only those within the tolerance there.
  std::sort(rim.begin(), rim.end(), [](const auto& a, const auto& b) { return a.first[0] < b.first[0]; });
  std::size_t pairs = 0;
  int first_a = -1, first_b = -1;
  for (std::size_t i = 0; i < rim.size(); ++i)
    for (std::size_t j = i + 1; j < rim.size() && rim[j].first[0] - rim[i].first[0] <= tolerance; ++j)
      if ((rim[j].first - rim[i].first).norm() <= tolerance &&
          // Ends of one (very short) edge are no seam to weld: merging them would collapse faces.
          !mesh.find_halfedge(mesh.vertex_handle(static_cast<unsigned>(rim[i].second)),
                              mesh.vertex_handle(static_cast<unsigned>(rim[j].second))).is_valid()) {
        if (pairs++ == 0) std::tie(first_a, first_b) = std::minmax(rim[i].second, rim[j].second);
      }
  if (pairs == 0) return {};
  return with_path(path, std::to_string(pairs) + " pair" + (pairs > 1 ? "s" : "") +
                             " of boundary vertices lie on one another" + (pairs > 1 ? ", the first " : ": ") +
                             lines.vertex_name(first_a) + " on " + lines.vertex_name(first_b) +
                             ": seams that are not welded, along which the garment falls apart; weld them (merge "
                             "by distance) before simulating");
}

/// The refinement hierarchy of a `.om` file, checked before anything reads
/// it: a truncated or damaged file can hold records that point anywhere.
void check_stored_forest(const std::string& path, const QuadMesh& mesh) {
  const std::vector<QuadRecord>& forest = quadtree(mesh);
  const auto n = static_cast<std::int32_t>(forest.size());
  const auto n_vertices = static_cast<std::int32_t>(mesh.n_vertices());
  std::size_t active = 0;
  const auto corrupt = [&](std::size_t r, const std::string& what) {
    throw InputError(with_path(path, "the stored refinement hierarchy is damaged (record " + std::to_string(r) + " " +
                                         what + "); expected a .om file as mrcloth writes it, whole"));
  };
  for (std::size_t r = 0; r < forest.size(); ++r) {
    const QuadRecord& record = forest[r];
    if (record.level < 1 || (record.active != 0 && record.active != 1)) corrupt(r, "has level or state out of range");
    if ((record.parent < 0) != (record.level == 1) || record.parent >= n ||
        (record.parent >= 0 && forest[static_cast<std::size_t>(record.parent)].level != record.level - 1))
      corrupt(r, "has a parent out of place");
    const bool leaf = record.children[0] < 0;
    for (const std::int32_t child : record.children) {
      if ((child < 0) != leaf || child >= n ||
          (child >= 0 && forest[static_cast<std::size_t>(child)].parent != static_cast<std::int32_t>(r)))
        corrupt(r, "has a child out of place");
    }
    for (const std::int32_t corner : record.corners)
      if (corner < 0 || corner >= n_vertices) corrupt(r, "has a corner that is not a vertex");
    active += record.active ? 1 : 0;
  }
  if (active != mesh.n_faces())
    throw InputError(with_path(path, "the stored refinement hierarchy is damaged (" + std::to_string(active) +
                                         " active records for " + std::to_string(mesh.n_faces()) +
                                         " faces); expected a .om file as mrcloth writes it, whole"));
  const Layers layers = get_layers(mesh);
  std::vector<char> named(forest.size(), 0);
  for (const auto f : mesh.faces()) {
    const int r = mesh.property(layers.quad, f);
    if (r < 0 || r >= n || !forest[static_cast<std::size_t>(r)].active || named[static_cast<std::size_t>(r)]++)
      throw InputError(with_path(path, "the stored refinement hierarchy is damaged (" + face_label(f.idx()) +
                                           " names no active record, or one an earlier face names); expected a .om "
                                           "file as mrcloth writes it, whole"));
  }
  // The vertex layers later steps index by (a file saved before the
  // checksum, damaged inside, crashed objectInfo through them); eraseModes
  // copies the computed modes into the mode layer.
  OpenMesh::VPropHandleT<int> computed;
  const bool has_computed = mesh.get_property_handle(computed, layer::computed_mode);
  for (const auto v : mesh.vertices()) {
    const OpenMesh::Vec2i ends = mesh.property(layers.parents, v);
    const bool none = ends[0] == -1 && ends[1] == -1;
    // Refinement appends each midpoint after the ends of its edge: parents
    // with a larger index would be a cycle, which the polygons recurse along.
    const bool valid = ends[0] >= 0 && ends[0] < v.idx() && ends[1] >= 0 && ends[1] < v.idx() && ends[0] != ends[1];
    const int mode = mesh.property(layers.mode, v);
    const int computed_mode = has_computed ? mesh.property(computed, v) : 0;
    if (computed_mode < 0 || computed_mode > kLargestMode)
      throw InputError(with_path(path, "the stored layers are damaged (vertex " + std::to_string(v.idx()) +
                                           " has computed mode " + std::to_string(computed_mode) +
                                           "); expected a .om file as mrcloth writes it, whole"));
    if ((!none && !valid) || mode < 0 || mode > kLargestMode)
      throw InputError(with_path(path, "the stored layers are damaged (vertex " + std::to_string(v.idx()) +
                                           (none || valid ? " has mode " + std::to_string(mode)
                                                          : " names edge ends " + std::to_string(ends[0]) + ", " +
                                                                std::to_string(ends[1])) +
                                           "); expected a .om file as mrcloth writes it, whole"));
  }
  if (const int face = first_face_unlike_its_record(mesh); face >= 0)
    throw InputError(with_path(path, "the stored refinement hierarchy is damaged (" + face_label(face) +
                                         " is not the polygon or level of its record); expected a .om file as "
                                         "mrcloth writes it, whole"));
}

/// Where a .om file's checksum layer keeps its eight bytes: after the
/// chunk's name, its type's name (a length byte, then the text) and its
/// block size (4 bytes, which must be 8).
struct ChecksumPlace {
  bool present = false;  ///< the file names the layer (one written before it, or by another program, does not)
  bool damaged = false;  ///< named, but its frame is not as save_mesh writes it
  std::size_t offset = 0;
};
ChecksumPlace checksum_place(const std::string& bytes) {
  const std::string name = layer::checksum;
  const std::size_t at = bytes.find(name);
  if (at == std::string::npos) return {};
  const ChecksumPlace damaged{true, true, 0};
  if (at == 0 || static_cast<unsigned char>(bytes[at - 1]) != name.size()) return damaged;
  const std::size_t type_at = at + name.size();
  if (type_at >= bytes.size()) return damaged;
  const std::size_t size_at = type_at + 1 + static_cast<unsigned char>(bytes[type_at]);
  if (size_at + 4 + 8 > bytes.size()) return damaged;
  std::uint32_t block = 0;
  for (std::size_t k = 0; k < 4; ++k) block |= std::uint32_t{static_cast<unsigned char>(bytes[size_at + k])} << (8 * k);
  return block == 8 ? ChecksumPlace{true, false, size_at + 4} : damaged;
}

/// FNV-1a (64 bits) of `bytes` with the eight at `skip` taken as zero.
std::uint64_t file_checksum(const std::string& bytes, std::size_t skip) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    const unsigned char byte = (k >= skip && k < skip + 8) ? 0 : static_cast<unsigned char>(bytes[k]);
    hash = (hash ^ byte) * 1099511628211ull;
  }
  return hash;
}

/// A .om file with a checksum layer must match it (any byte changed or cut
/// off): checked before OpenMesh reads, whose reader asserts (aborting the
/// host) on some damaged chunks.
void check_om_checksum(const std::string& path, const std::string& bytes) {
  const ChecksumPlace place = checksum_place(bytes);
  if (!place.present) return;
  std::uint64_t stored = 0;
  if (!place.damaged)
    for (std::size_t k = 0; k < 8; ++k)
      stored |= std::uint64_t{static_cast<unsigned char>(bytes[place.offset + k])} << (8 * k);
  if (place.damaged || stored != file_checksum(bytes, place.offset))
    throw InputError(with_path(path, "the file is damaged or cut short (its bytes do not match the checksum mrcloth "
                                     "wrote into it); expected a .om file as mrcloth writes it, whole"));
}

/// An OM file cut short in its vertex or face chunks reads fewer elements
/// than its header counts (or garbage faces): refused before the faces are
/// looked at. The header: "OM", mesh kind, version, then the vertex, face
/// and edge counts as 32-bit integers in the writer's (little-endian) order.
void check_om_counts(const std::string& path, const std::string& bytes, const QuadMesh& mesh) {
  if (bytes.size() < 16 || bytes.compare(0, 2, "OM") != 0) return;  // the reader refused it already
  const auto count = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k) value |= std::uint32_t{static_cast<unsigned char>(bytes[at + k])} << (8 * k);
    return value;
  };
  const std::uint32_t vertices = count(4), faces = count(8);
  if (mesh.n_vertices() != vertices || mesh.n_faces() != faces)
    throw InputError(with_path(path, "the file is cut short or damaged (its header counts " + std::to_string(vertices) +
                                         " vertices and " + std::to_string(faces) + " faces; " +
                                         std::to_string(mesh.n_vertices()) + " and " + std::to_string(mesh.n_faces()) +
                                         " could be read); expected a whole .om file"));
  // OM files store the halfedge connectivity itself: one cut short (or
  // damaged) inside it reads as links that do not close up.
  const auto damaged = [&](const std::string& what) {
    throw InputError(with_path(path, "the file is cut short or damaged (" + what + "); expected a whole .om file"));
  };
  const auto valid = [](int index, std::size_t size) { return index >= 0 && static_cast<std::size_t>(index) < size; };
  for (const auto h : mesh.halfedges()) {
    const auto next = mesh.next_halfedge_handle(h), opposite = mesh.opposite_halfedge_handle(h);
    const auto to = mesh.to_vertex_handle(h);
    if (!valid(next.idx(), mesh.n_halfedges()) || !valid(to.idx(), mesh.n_vertices()) ||
        mesh.prev_halfedge_handle(next) != h || mesh.from_vertex_handle(opposite) != to ||
        mesh.face_handle(next) != mesh.face_handle(h) ||
        (!mesh.is_boundary(h) && !valid(mesh.face_handle(h).idx(), mesh.n_faces())))
      damaged("halfedge " + std::to_string(h.idx()) + " is not linked to its neighbours");
  }
  for (const auto f : mesh.faces()) {
    const auto first = mesh.halfedge_handle(f);
    if (!valid(first.idx(), mesh.n_halfedges()) || mesh.face_handle(first) != f)
      damaged("face " + std::to_string(f.idx()) + " names a halfedge not its own");
  }
  for (const auto v : mesh.vertices()) {
    const auto out = mesh.halfedge_handle(v);
    if (out.is_valid() && (!valid(out.idx(), mesh.n_halfedges()) || mesh.from_vertex_handle(out) != v))
      damaged("vertex " + std::to_string(v.idx()) + " names a halfedge not its own");
  }
}

/// The OM reader fills only layers that exist before it reads, so every
/// analysis layer was made first; those the file does not store (a mesh
/// saved before any analysis) are removed again, so that a save and load
/// adds no layers of zeros. An OM file stores each property's name as
/// plain text.
void drop_analysis_layers_not_stored(const std::string& bytes, QuadMesh& mesh) {
  const auto stored = [&](const char* name) { return bytes.find(name) != std::string::npos; };
  if (OpenMesh::VPropHandleT<int> handle; !stored(layer::computed_mode) && mesh.get_property_handle(handle, layer::computed_mode))
    mesh.remove_property(handle);
  for (const char* name : {layer::mean_curvature, layer::curvature_deviation})
    if (OpenMesh::VPropHandleT<double> handle; !stored(name) && mesh.get_property_handle(handle, name))
      mesh.remove_property(handle);
}

}  // namespace

LoadResult load_garment(const std::string& path, const LoadOptions& options) {
  const double scale = metres_per_unit(options.units);
  const std::string extension = lower_extension(path);
  const std::optional<Format> format = format_of(extension);
  // A folder, a missing or an empty file is that, whatever its name says.
  require_input_file(path);
  if (!format)
    throw InputError(with_path(path, "unknown mesh format (extension " + shown_extension(extension) +
                                         "); expected one of .obj, .off, .ply, .om"));

  const TextScan scan = *format == Format::om ? TextScan{} : scan_text(path, *format);

  LoadResult result;
  QuadMesh& mesh = result.mesh;
  // The OM reader fills a stored property only if the mesh already has one
  // with that name (and a matching size), so the layers must exist first.
  if (*format == Format::om) {
    ensure_layers(mesh);
    ensure_analysis_layers(mesh);
    ensure_record_uvs(mesh);
  }

  std::string om_bytes;
  if (*format == Format::om) {
    std::ifstream in(path, std::ios::binary);
    om_bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    check_om_checksum(path, om_bytes);
    check_om_structure(path, om_bytes);
  }

  // The reader would abort the process on this file: the scan's first face
  // problem is the message (the importer's manifold checks, which might
  // have named an earlier face, cannot run).
  if (scan.reader_would_abort) throw InputError(with_path(path, scan.face_problem.text));
  CheckingImporter importer(mesh, scan.lines);
  OpenMesh::IO::Options io_options;
  bool read = false;
  {
    QuietOpenMesh quiet;
    try {
      if (scan.text_for_reader.empty()) {
        read = OpenMesh::IO::IOManager().read(path, importer, io_options);
      } else {
        std::istringstream text(scan.text_for_reader);
        if (*format == Format::off) set_off_layout(path, scan.text_for_reader);
        read = OpenMesh::IO::IOManager().read(text, extension, importer, io_options);
      }
    } catch (const std::bad_alloc&) {
      // A binary header's counts misread (a big-endian OFF) or simply huge.
      throw InputError(with_path(path, std::string("cannot be read as ") + format_name(*format) +
                                           ": its header asks for more elements than memory holds; expected a valid " +
                                           extension + " mesh (binary OFF: little-endian, as OpenMesh reads it)"));
    }
  }
  if (*format == Format::om) check_om_counts(path, om_bytes, mesh);
  const FaceProblem problem = earlier(scan.face_problem, importer.problem());
  if (problem.found()) throw InputError(with_path(path, problem.text));
  if (!read)
    throw InputError(with_path(path, std::string("cannot be read as ") + format_name(*format) +
                                         " (OpenMesh rejected it); expected a valid " + extension + " mesh"));
  if (mesh.n_vertices() == 0) throw InputError(with_path(path, "the file has no vertices; expected a quad mesh"));
  if (mesh.n_faces() == 0) throw InputError(with_path(path, "the file has no faces; expected a quad mesh"));
  if (*format == Format::om) {
    const std::string& bytes = om_bytes;
    // save_mesh writes the forest last (ensure_layers): a file holding our
    // layers but no forest was cut short, and would load as a coarse garment.
    if (quadtree(mesh).empty() && bytes.find("mrcloth:") != std::string::npos)
      throw InputError(with_path(path, "the file is cut short (it holds mrcloth's layers but not the refinement "
                                       "hierarchy mrcloth writes last); expected a .om file as mrcloth writes "
                                       "it, whole"));
    drop_analysis_layers_not_stored(bytes, mesh);
  }

  const bool scanned = scan_matches(scan, mesh);
  if (scanned) {
    for (const auto v : mesh.vertices()) mesh.set_point(v, scan.points[static_cast<std::size_t>(v.idx())]);
  } else if (*format != Format::om && !scan.binary) {
    result.warnings.push_back(with_path(
        path, "the coordinates could not be re-read in double precision; they keep OpenMesh's single precision"));
  }
  for (const auto v : mesh.vertices()) {
    const OpenMesh::Vec3d& p = mesh.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InputError(with_path(path, "vertex " + std::to_string(v.idx()) +
                                           " has a non-finite coordinate; expected finite numbers"));
    mesh.set_point(v, p * scale);
  }

  // A refined mesh saved by save_mesh: its forest and layers are the truth.
  if (*format == Format::om && !quadtree(mesh).empty()) {
    check_stored_forest(path, mesh);
    // save_mesh writes metres; a scale makes another garment of it, whose
    // layers in metres (curvature, 1/m) no longer fit it.
    if (scale != 1.0 && checksum_place(om_bytes).present)
      result.warnings.push_back(with_path(
          path, "mrcloth saved this mesh in metres; units '" + options.units + "' scale it by " + number_text(scale) +
                    " (its curvature layers, in 1/m, are not rescaled): give units 'm' to load it as saved"));
    return result;
  }
  // Lines are named only where the scan saw the vertices OpenMesh read.
  const ElementLines no_lines;
  const ElementLines& lines = scanned ? scan.lines : no_lines;
  check_garment_surface(path, mesh, lines);
  if (std::string unwelded = unwelded_seams_warning(path, mesh, lines); !unwelded.empty())
    result.warnings.push_back(std::move(unwelded));
  if (std::string concave = concave_faces_warning(path, mesh, lines); !concave.empty())
    result.warnings.push_back(std::move(concave));

  const std::size_t faces_read = mesh.n_faces();
  std::vector<SplitQuad> split;
  make_all_quad(mesh, path, result.warnings, split);
  init_forest(mesh);
  read_texture_coords(scan, mesh, faces_read, split, path, result.warnings);
  return result;
}

// ---------------------------------------------------------------------------
// Writing

namespace {

/// Shortest text that reads back as exactly the same double.
std::string exact(double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc() ? std::string(buffer, end) : std::string("nan");
}

/// A polygon soup of the active surface, ready for the text writers.
struct Surface {
  std::vector<OpenMesh::Vec3d> points;
  std::vector<std::array<unsigned char, 3>> colors;  ///< one per point, or none
  std::vector<std::vector<int>> polygons;
  /// Per polygon, the texture coordinates of its corners (a vertex on a
  /// seam has one per side), or none.
  std::vector<std::vector<OpenMesh::Vec2d>> uvs;
};

Surface active_surface(const QuadMesh& mesh) {
  Surface surface;
  // Every vertex, deleted or not, so that a vertex's index is its line.
  surface.points.reserve(mesh.n_vertices());
  for (const auto v : mesh.all_vertices()) surface.points.push_back(mesh.point(v));
  surface.polygons.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {  // skips faces deleted but not yet collected
    std::vector<int> polygon;
    for (const auto v : f.vertices()) polygon.push_back(v.idx());
    surface.polygons.push_back(std::move(polygon));
  }
  surface.uvs = active_face_uvs(mesh);
  return surface;
}

double triangle_area(const OpenMesh::Vec3d& a, const OpenMesh::Vec3d& b, const OpenMesh::Vec3d& c) {
  return 0.5 * OpenMesh::cross(b - a, c - a).norm();
}

/// Fans every polygon into triangles. Hanging vertices lie on their edge, so
/// a fan from a corner next to one gives a zero-area sliver; the fan starts
/// at the corner whose smallest triangle is largest, and only when every
/// corner makes a sliver is the polygon fanned around an added centre point
/// (coloured like the polygon's first vertex). The choices are made on
/// `shape` (a point per surface point), so that every frame of one mesh,
/// chosen on its rest shape, gets the same triangles.
void triangulate(Surface& surface, const std::vector<OpenMesh::Vec3d>& shape) {
  std::vector<std::vector<int>> triangles;
  std::vector<std::vector<OpenMesh::Vec2d>> triangle_uvs;
  const bool textured = !surface.uvs.empty();
  for (std::size_t p = 0; p < surface.polygons.size(); ++p) {
    const std::vector<int>& polygon = surface.polygons[p];
    const std::size_t n = polygon.size();
    // The triangle of polygon corners i, j, k, with their texture coordinates.
    const auto add = [&](std::size_t i, std::size_t j, std::size_t k) {
      triangles.push_back({polygon[i], polygon[j], polygon[k]});
      if (textured) triangle_uvs.push_back({surface.uvs[p][i], surface.uvs[p][j], surface.uvs[p][k]});
    };
    if (n == 3) {
      add(0, 1, 2);
      continue;
    }
    double longest = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      longest = std::max(longest, (shape[polygon[(i + 1) % n]] - shape[polygon[i]]).norm());
    const double sliver = 1e-9 * longest * longest;
    std::size_t best_apex = 0;
    double best_smallest = -1.0;
    for (std::size_t apex = 0; apex < n; ++apex) {
      double smallest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 1; k + 1 < n; ++k) {
        smallest = std::min(smallest, triangle_area(shape[polygon[apex]], shape[polygon[(apex + k) % n]],
                                                    shape[polygon[(apex + k + 1) % n]]));
      }
      if (smallest > best_smallest) {
        best_smallest = smallest;
        best_apex = apex;
      }
    }
    if (best_smallest > sliver) {
      for (std::size_t k = 1; k + 1 < n; ++k) add(best_apex, (best_apex + k) % n, (best_apex + k + 1) % n);
      continue;
    }
    OpenMesh::Vec3d centre(0.0, 0.0, 0.0);
    for (const int v : polygon) centre += surface.points[static_cast<std::size_t>(v)];
    const int c = static_cast<int>(surface.points.size());
    surface.points.push_back(centre / static_cast<double>(n));
    if (!surface.colors.empty()) surface.colors.push_back(surface.colors[static_cast<std::size_t>(polygon[0])]);
    OpenMesh::Vec2d uv_centre(0.0, 0.0);
    if (textured)
      for (const OpenMesh::Vec2d& uv : surface.uvs[p]) uv_centre += uv / static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k) {
      triangles.push_back({polygon[k], polygon[(k + 1) % n], c});
      if (textured) triangle_uvs.push_back({surface.uvs[p][k], surface.uvs[p][(k + 1) % n], uv_centre});
    }
  }
  surface.polygons = std::move(triangles);
  surface.uvs = std::move(triangle_uvs);
}

void write_obj(std::ostream& out, const Surface& s) {
  out << "# mrcloth: " << s.points.size() << " vertices, " << s.polygons.size() << " faces\n";
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const OpenMesh::Vec3d& p = s.points[i];
    out << "v " << exact(p[0]) << ' ' << exact(p[1]) << ' ' << exact(p[2]);
    if (!s.colors.empty()) {
      // The common "v x y z r g b" extension, with channels in [0, 1].
      for (const unsigned char channel : s.colors[i]) out << ' ' << exact(channel / 255.0);
    }
    out << '\n';
  }
  // Texture coordinates one per polygon corner, in order: a seam needs
  // no special case.
  for (const auto& polygon : s.uvs)
    for (const OpenMesh::Vec2d& uv : polygon) out << "vt " << exact(uv[0]) << ' ' << exact(uv[1]) << '\n';
  std::size_t texcoord = 0;
  for (const std::vector<int>& polygon : s.polygons) {
    out << 'f';
    for (const int v : polygon) {
      out << ' ' << v + 1;
      if (!s.uvs.empty()) out << '/' << ++texcoord;
    }
    out << '\n';
  }
}

void write_off(std::ostream& out, const Surface& s) {
  out << "OFF\n" << s.points.size() << ' ' << s.polygons.size() << " 0\n";
  for (const OpenMesh::Vec3d& p : s.points) out << exact(p[0]) << ' ' << exact(p[1]) << ' ' << exact(p[2]) << '\n';
  for (const std::vector<int>& polygon : s.polygons) {
    out << polygon.size();
    for (const int v : polygon) out << ' ' << v;
    out << '\n';
  }
}

void write_ply(std::ostream& out, const Surface& s) {
  std::size_t widest = 0;
  for (const std::vector<int>& polygon : s.polygons) widest = std::max(widest, polygon.size());
  out << "ply\nformat ascii 1.0\ncomment written by mrcloth\nelement vertex " << s.points.size()
      << "\nproperty double x\nproperty double y\nproperty double z\n";
  if (!s.colors.empty()) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out << "element face " << s.polygons.size() << "\nproperty list " << (widest > 255 ? "int" : "uchar")
      << " int vertex_indices\nend_header\n";
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const OpenMesh::Vec3d& p = s.points[i];
    out << exact(p[0]) << ' ' << exact(p[1]) << ' ' << exact(p[2]);
    if (!s.colors.empty()) {
      for (const unsigned char channel : s.colors[i]) out << ' ' << static_cast<int>(channel);
    }
    out << '\n';
  }
  for (const std::vector<int>& polygon : s.polygons) {
    out << polygon.size();
    for (const int v : polygon) out << ' ' << v;
    out << '\n';
  }
}

bool write_text(const std::string& file, const Surface& surface, Format format) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) return false;
  out.imbue(std::locale::classic());
  switch (format) {
    case Format::obj: write_obj(out, surface); break;
    case Format::off: write_off(out, surface); break;
    case Format::ply: write_ply(out, surface); break;
    case Format::om: return false;
  }
  out.close();
  return !out.fail();
}

bool has_deleted_elements(const QuadMesh& mesh) {
  if (mesh.has_vertex_status()) {
    for (const auto v : mesh.all_vertices())
      if (mesh.status(v).deleted()) return true;
  }
  if (mesh.has_edge_status()) {
    for (const auto e : mesh.all_edges())
      if (mesh.status(e).deleted()) return true;
  }
  if (mesh.has_face_status()) {
    for (const auto f : mesh.all_faces())
      if (mesh.status(f).deleted()) return true;
  }
  return false;
}

/// Encodes in memory, then writes the bytes with our own checks: OpenMesh's
/// OM writer asserts that every write succeeded, so a full disk aborted the
/// host instead of failing the write.
bool write_om(const QuadMesh& mesh, const std::string& file) {
  QuietOpenMesh quiet;
  std::ostringstream encoded(std::ios::binary);
  // The OM writer stores deleted-but-not-collected elements as live ones.
  if (has_deleted_elements(mesh)) {
    QuadMesh compact = copy_mesh(mesh);
    compact.garbage_collection();
    if (!OpenMesh::IO::write_mesh(compact, encoded, ".om", OpenMesh::IO::Options::Binary)) return false;
  } else if (!OpenMesh::IO::write_mesh(mesh, encoded, ".om", OpenMesh::IO::Options::Binary)) {
    return false;
  }
  std::ofstream out(file, std::ios::binary);
  std::string bytes = std::move(encoded).str();
  // The checksum layer's eight bytes take the hash of all the others.
  if (const ChecksumPlace place = checksum_place(bytes); place.present && !place.damaged) {
    const std::uint64_t hash = file_checksum(bytes, place.offset);
    for (std::size_t k = 0; k < 8; ++k) bytes[place.offset + k] = static_cast<char>((hash >> (8 * k)) & 0xff);
  }
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  return !out.fail();
}

Format output_format(const std::string& path, bool om_allowed) {
  const std::string extension = lower_extension(path);
  const std::optional<Format> format = format_of(extension);
  const bool allowed = format && (*format == Format::obj || *format == Format::ply ||
                                  (om_allowed && (*format == Format::off || *format == Format::om)));
  if (!allowed) {
    throw ArgumentError(with_path(path, "unknown output format (extension " + shown_extension(extension) +
                                            "); expected one of " +
                                            (om_allowed ? ".om, .obj, .off, .ply" : ".obj, .ply")));
  }
  return *format;
}

}  // namespace

void save_mesh(const QuadMesh& mesh, const std::string& path) {
  const Format format = output_format(path, true);
  const std::string extension = lower_extension(path);
  if (format == Format::om) {
    write_file_atomically(path, extension, [&](const std::string& file) { return write_om(mesh, file); });
    return;
  }
  const Surface surface = active_surface(mesh);
  write_file_atomically(path, extension, [&](const std::string& file) { return write_text(file, surface, format); });
}

/// Per vertex, the finest level among the active faces around it, as the
/// previews colour faces: a coarse vertex inside a refined region is that
/// region's level (by the level that made it, it was a coarse speck there).
/// A vertex in no face keeps the level that made it.
std::vector<int> finest_face_levels(const QuadMesh& mesh) {
  std::vector<int> levels = vertex_levels(mesh);
  std::vector<int> finest(levels.size(), 0);
  const auto level = get_layers(mesh).level;
  for (const auto f : mesh.faces())
    for (const auto v : f.vertices()) {
      int& most = finest[static_cast<std::size_t>(v.idx())];
      most = std::max(most, mesh.property(level, f));
    }
  for (std::size_t v = 0; v < levels.size(); ++v)
    if (finest[v] > 0) levels[v] = finest[v];
  return levels;
}

void export_surface(const QuadMesh& mesh, const std::string& path, const ExportOptions& options) {
  const Format format = output_format(path, false);
  Surface surface = active_surface(mesh);
  if (options.color_by == ColorBy::level) {
    const std::vector<int> levels = finest_face_levels(mesh);
    for (std::size_t v = 0; v < surface.points.size(); ++v)
      surface.colors.push_back(palette_color(v < levels.size() ? levels[v] : 0));
  } else if (options.color_by == ColorBy::mode) {
    const auto mode = get_layers(mesh).mode;
    for (const auto v : mesh.all_vertices()) surface.colors.push_back(palette_color(mesh.property(mode, v)));
  } else if (options.color_by == ColorBy::curvature) {
    const std::vector<double> curvature = vertex_layer(mesh, layer::mean_curvature);
    const double largest = curvature.empty() ? 0.0 : *std::max_element(curvature.begin(), curvature.end());
    for (const double k : curvature) surface.colors.push_back(sequential_color(largest > 0.0 ? k / largest : 0.0));
  }
  if (options.triangulate) {
    const QuadMesh& shape = options.triangles_of ? *options.triangles_of : mesh;
    if (shape.n_vertices() != mesh.n_vertices() || shape.n_faces() != mesh.n_faces())
      throw ArgumentError("export_surface: the mesh to triangulate as has " + std::to_string(shape.n_vertices()) +
                          " vertices and " + std::to_string(shape.n_faces()) + " faces, the mesh exported " +
                          std::to_string(mesh.n_vertices()) + " and " + std::to_string(mesh.n_faces()) +
                          "; expected the same mesh at other positions");
    std::vector<OpenMesh::Vec3d> shape_points;
    shape_points.reserve(shape.n_vertices());
    for (const auto v : shape.all_vertices()) shape_points.push_back(shape.point(v));
    triangulate(surface, shape_points);
  }
  write_file_atomically(path, lower_extension(path),
                   [&](const std::string& file) { return write_text(file, surface, format); });
}

std::array<unsigned char, 3> sequential_color(double t) {
  // Matplotlib's viridis at 9 evenly spaced stops, linearly interpolated.
  static constexpr std::array<std::array<double, 3>, 9> kStops{{
      {68, 1, 84}, {71, 44, 122}, {59, 81, 139}, {44, 113, 142}, {33, 144, 141},
      {39, 173, 129}, {92, 200, 99}, {170, 220, 50}, {253, 231, 37},
  }};
  if (!(t > 0.0)) t = 0.0;  // also NaN
  if (t > 1.0) t = 1.0;
  const double at = t * (kStops.size() - 1);
  const std::size_t i = std::min(kStops.size() - 2, static_cast<std::size_t>(at));
  const double f = at - static_cast<double>(i);
  std::array<unsigned char, 3> rgb{};
  for (std::size_t c = 0; c < 3; ++c)
    rgb[c] = static_cast<unsigned char>(std::lround(kStops[i][c] + f * (kStops[i + 1][c] - kStops[i][c])));
  return rgb;
}

std::array<unsigned char, 3> palette_color(int value) {
  // Tableau 10 (matplotlib "tab10") without its grey, which is kept for
  // values <= 0 (unpainted / not a level). Qualitative and well separated;
  // value 1 is blue, 2 orange, 3 green, 4 red, ... 9 cyan; past 9, see below.
  static constexpr std::array<std::array<unsigned char, 3>, 9> kPalette{{
      {31, 119, 180},   // blue
      {255, 127, 14},   // orange
      {44, 160, 44},    // green
      {214, 39, 40},    // red
      {148, 103, 189},  // purple
      {140, 86, 75},    // brown
      {227, 119, 194},  // pink
      {188, 189, 34},   // olive
      {23, 190, 207},   // cyan
  }};
  if (value <= 0) return {127, 127, 127};
  if (value <= static_cast<int>(kPalette.size())) return kPalette[static_cast<std::size_t>(value - 1)];
  // Past 9 the colours wrapped (mode 10 drew as mode 1, in the legend too):
  // hues a golden-ratio turn apart, so neighbouring values differ most, at
  // two saturations and three brightnesses; every value up to kLargestMode
  // has its own colour (tested), none grey.
  const int k = value - static_cast<int>(kPalette.size()) - 1;
  const double hue = 6.0 * std::fmod(0.07 + 0.6180339887498949 * k, 1.0);
  static constexpr std::array<double, 2> kSaturation{0.8, 0.5};
  static constexpr std::array<double, 3> kBrightness{0.9, 0.7, 0.5};
  const double v = kBrightness[static_cast<std::size_t>((k / 2) % 3)];
  const double c = v * kSaturation[static_cast<std::size_t>(k % 2)];
  const double x = c * (1.0 - std::abs(std::fmod(hue, 2.0) - 1.0)), m = v - c;
  const int sector = std::min(5, static_cast<int>(hue));
  const std::array<std::array<double, 3>, 6> rgb{{{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}}};
  std::array<unsigned char, 3> colour{};
  for (std::size_t i = 0; i < 3; ++i)
    colour[i] = static_cast<unsigned char>(std::lround(255.0 * (rgb[static_cast<std::size_t>(sector)][i] + m)));
  return colour;
}

}  // namespace mrcloth
