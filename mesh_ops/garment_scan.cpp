#include "garment_scan.h"

#include "errors.h"
#include "little_endian.h"
#include "obj_tokens.h"
#include "ply_layout.h"
#include "text_words.h"

#include <OpenMesh/Core/IO/reader/OFFReader.hh>

#include <algorithm>
#include <atomic>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <unistd.h>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

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
  const auto read_u32 = [&](std::size_t at) { return static_cast<std::uint32_t>(little_endian_at(text, at, 4)); };
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

/// An OFF file's non-blank lines as words, comments stripped, with their
/// line numbers; keeps the lines read as the text the reader gets.
class OffLines {
 public:
  explicit OffLines(const std::string& text) : in_(text) {}

  /// The next non-blank line's words (empty at the end of the file).
  std::vector<std::string> next_words() {
    for (std::string line; std::getline(in_, line);) {
      ++line_number_;
      line = strip_comment(line);
      std::vector<std::string> words = split_words(line);
      if (words.empty()) continue;
      cleaned_ += line;
      cleaned_ += '\n';
      return words;
    }
    return std::vector<std::string>{};
  }

  /// The line number of the words last returned (1-based).
  std::size_t line_number() const { return line_number_; }
  /// The lines read so far, for the reader.
  std::string& cleaned() { return cleaned_; }

 private:
  std::istringstream in_;
  std::size_t line_number_ = 0;
  std::string cleaned_;
};

/// The header word without its ST, C and N prefixes; refuses a word that is
/// no OFF variant (OpenMesh accepted "OFFX").
std::string off_variant(const std::string& path, const std::string& word) {
  std::string header = word;
  for (const char* prefix : {"ST", "C", "N"}) {
    if (header.rfind(prefix, 0) == 0) header.erase(0, std::string(prefix).size());
  }
  if (header != "OFF" && header != "4OFF" && header != "nOFF")
    throw InputError(with_path(path, "the file starts with '" + word +
                                         "'; expected OFF (or COFF, NOFF, STOFF, 4OFF, nOFF)"));
  return header;
}

/// The vertex and face counts of the header's `words` (its 'V F E' line,
/// at `line`). Without them OpenMesh's reader reserves for whatever its
/// variables held (tens of gigabytes were seen).
std::array<std::size_t, 2> off_counts(const std::string& path, const std::vector<std::string>& words, std::size_t line) {
  if (words.size() < 2)
    throw InputError(with_path(path, "the OFF header has no vertex and face counts" +
                                         (words.empty() ? std::string() : at_line(line)) +
                                         "; expected 'V F E' after OFF"));
  std::array<std::size_t, 2> counts{0, 0};  // vertices, faces
  for (int k = 0; k < 2; ++k) {
    const std::string& word = words[static_cast<std::size_t>(k)];
    const auto [stop, error] = std::from_chars(word.data(), word.data() + word.size(), counts[static_cast<std::size_t>(k)]);
    if (error != std::errc() || stop != word.data() + word.size())
      throw InputError(with_path(path, "the OFF header's " + std::string(k == 0 ? "vertex" : "face") + " count '" +
                                           word + "'" + at_line(line) + " is not a count; expected 'V F E'"));
  }
  return counts;
}

/// Refuses face `f` (its `words`, at `line`) unless it starts with its
/// corner count and lists at least that many numbers after it. OpenMesh
/// takes the first number as the corner count and reads that many indices
/// on, across lines: a huge count reserves memory without bound, a wrong
/// one reads the faces after it askew.
void check_off_face(const std::string& path, std::size_t f, const std::vector<std::string>& words, std::size_t line) {
  std::size_t corners = 0;
  const std::string& count = words[0];
  const auto [stop, error] = std::from_chars(count.data(), count.data() + count.size(), corners);
  if (error != std::errc() || stop != count.data() + count.size() || corners + 1 > words.size())
    throw InputError(with_path(path, face_label(static_cast<long>(f)) + at_line(line) + " starts with '" + count +
                                         "' and lists " + std::to_string(words.size() - 1) +
                                         " numbers after it; expected its corner count, then that many vertex "
                                         "indices (then, optionally, a colour)"));
}

/// Plain ASCII OFF, optionally with colours/normals/texture coordinates after
/// x y z (COFF, NOFF, STOFF...); binary OFF by scan_binary_off; 4OFF and nOFF
/// are left to OpenMesh (which refuses them).
/// Refuses a header OpenMesh would misread: a word that is no OFF variant
/// (it accepted "OFFX"), and counts more than the lines after it hold (it
/// would allocate for them, or read faces as vertices).
TextScan scan_off(const std::string& path, const std::string& text) {
  OffLines off(text);
  TextScan scan;
  std::vector<std::string> words = off.next_words();
  if (words.empty()) return scan;
  const std::string header = off_variant(path, words[0]);
  if (words.size() > 1 && words[1] == "BINARY") {
    if (off.line_number() != 1)
      throw InputError(with_path(path, "the 'OFF BINARY' line is line " + std::to_string(off.line_number()) +
                                       "; expected it first (OpenMesh's reader reads binary data after line 1)"));
    return scan_binary_off(path, words[0], text);
  }
  if (header != "OFF") return scan;
  const std::string magic = words[0];
  words.erase(words.begin());
  if (!words.empty()) {
    // Counts on the header's line: OpenMesh reads them only on their own.
    off.cleaned() = magic + "\n";
    for (const std::string& word : words) off.cleaned() += word + ' ';
    off.cleaned() += '\n';
  }
  if (words.empty()) words = off.next_words();
  const std::array<std::size_t, 2> counts = off_counts(path, words, off.line_number());
  const std::size_t header_line = off.line_number();
  std::vector<std::pair<std::size_t, std::vector<std::string>>> lines;  // (line number, words)
  for (std::vector<std::string> next = off.next_words(); !next.empty(); next = off.next_words())
    lines.emplace_back(off.line_number(), std::move(next));
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
    check_off_face(path, f, face_words, face_line);
  }
  scan.understood = true;
  scan.text_for_reader = std::move(off.cleaned());
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

}  // namespace

FaceProblem earlier(const FaceProblem& a, const FaceProblem& b) {
  if (!a.found()) return b;
  if (!b.found()) return a;
  return b.face < a.face ? b : a;
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

}  // namespace mrcloth
