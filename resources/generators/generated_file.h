#pragma once
// What the resource generators share: exact, locale-proof number text and
// writing a file so it is either complete or absent. Standard library only,
// so the generators do not depend on the code their output tests.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace mrcloth::generators {

/// Fixed six decimals (micrometres), with -0 printed as 0 so the text is
/// byte-identical on every platform.
inline std::string format_coordinate(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6f", value);
  std::string text = buffer;
  if (text == "-0.000000") text = "0.000000";
  return text;
}

/// Writes `text` to a temporary file beside `path` and renames it into
/// place, so an interrupted run never leaves a truncated file behind.
inline void write_atomically(const std::string& text, const std::filesystem::path& path) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text;
    file.close();
    if (!file) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error("cannot write " + temporary.string());
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error("cannot rename " + temporary.string() + " to " + path.string());
  }
}

}  // namespace mrcloth::generators
