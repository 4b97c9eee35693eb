#pragma once
// OpenMesh 9's OBJ, OFF and PLY readers parse coordinates as float, which
// would cost garments about seven significant digits. The text formats are
// therefore scanned once more here, in double precision; the scan also sees
// what the OBJ reader hides (it drops vertices it cannot parse and quietly
// removes repeated corners), so those files fail with the real reason.
#include "errors.h"
#include "garment_formats.h"
#include "quad_mesh.h"

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace mrcloth {

/// The first face the file gets wrong, in file order (0-based).
struct FaceProblem {
  long face = -1;
  std::string text;  ///< starts with "face <n>"
  bool found() const { return face >= 0; }
};

/// Whichever of `a` and `b` comes first in file order (the one found, when
/// only one is).
FaceProblem earlier(const FaceProblem& a, const FaceProblem& b);

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

/// Scans the file `path` as `format` (OBJ, OFF or PLY) in double precision,
/// ready for OpenMesh's reader; a scan not understood (keep OpenMesh's
/// coordinates) for OM or a file that cannot be opened. Throws InputError
/// naming `path` (and the line, or in binary data the element) for what
/// OpenMesh's reader would misread, hang or abort on, or a coordinate that
/// is not a finite number within single precision's range.
TextScan scan_text(const std::string& path, Format format);

/// OpenMesh's OFF reader reads a stream as laid out like the last file it
/// checked by name (binary, colours, normals: it learns a layout only from
/// a file's first line, and only when given a file name): an ASCII OFF
/// handed over as text after a binary one was read as binary. So it checks
/// a scratch file holding `text`'s first line before it reads `text`; where
/// no scratch file can be written, the file `path` itself (whose first line
/// says the same unless comments or blank lines come before it).
void set_off_layout(const std::string& path, const std::string& text);

/// True when the scan read the same vertices OpenMesh did, up to float rounding.
/// `scan`: scan_text's of the file OpenMesh read into `mesh`.
bool scan_matches(const TextScan& scan, const QuadMesh& mesh);

}  // namespace mrcloth
