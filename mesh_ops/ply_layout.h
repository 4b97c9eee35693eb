#pragma once
// A PLY file checked before OpenMesh's PLY reader sees it. That reader reads
// its header word by word and never looks at a stream's fail state: a word
// it cannot convert (a version "infinity", a count "9ace" or "-1") leaves it
// looping for ever; a list length read from "-1" makes it push four billion
// corners; a comment before end_header shifts where it starts binary data.
// So the header is held to the PLY grammar, the data is walked the way the
// reader will walk it, and the reader is handed a copy of the file with a
// header it cannot misread.
#include <array>
#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <vector>

namespace mrcloth {

/// What a PLY file holds for the garment loader, once checked.
struct PlyScan {
  bool binary = false;
  /// ASCII only: each vertex's x, y, z as written (unparsed) and its line
  /// (1-based); each face's line.
  std::vector<std::array<std::string, 3>> coordinates;
  std::vector<std::size_t> vertex_lines, face_lines;
  /// The file again for OpenMesh's reader: the same elements, properties
  /// and data bytes under a header without comments or obj_info lines.
  std::string text_for_reader;
};

/// Reads `in` (the file `path`, opened in binary mode, at its start).
/// nullopt when its first line is not "ply" (OpenMesh's reader refuses such
/// a file by itself). Throws InputError naming the line (or, in binary
/// data, the element) that OpenMesh's reader would misread: a header line
/// outside the PLY grammar, a list other than the faces' vertex indices
/// (which the reader cannot skip), data that is not a number of its type,
/// a face whose corner count its data does not hold, data cut short.
std::optional<PlyScan> scan_ply_layout(const std::string& path, std::istream& in);

}  // namespace mrcloth
