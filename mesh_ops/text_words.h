#pragma once
// The words of a line of a text file, for the garment readers' own scans of
// the OBJ, OFF and PLY text they hand to OpenMesh.
#include <sstream>
#include <string>
#include <vector>

namespace mrcloth {

/// The words of `line` (one line, no line end), separated by any whitespace, in order.
inline std::vector<std::string> split_words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

}  // namespace mrcloth
