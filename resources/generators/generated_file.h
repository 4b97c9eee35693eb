#pragma once
// What the resource generators share: exact, locale-proof number text and
// writing a file so it is either complete or absent. Standard library only,
// so the generators do not depend on the code their output tests.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <ostream>
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

/// The OBJ body: `v x y z` per vertex (fields x, y, z) and `f a b c d` per
/// quad (0-based corner indices, written 1-based).
template <class Vertices, class Quads>
void write_obj_elements(std::ostream& out, const Vertices& vertices, const Quads& quads) {
  for (const auto& v : vertices)
    out << "v " << format_coordinate(v.x) << ' ' << format_coordinate(v.y) << ' ' << format_coordinate(v.z) << '\n';
  for (const auto& q : quads) out << "f " << q[0] + 1 << ' ' << q[1] + 1 << ' ' << q[2] + 1 << ' ' << q[3] + 1 << '\n';
}

/// A generator's main: `name <output.obj>` writes text() atomically; --help
/// prints the usage and `what`; failures print "name: message", exit 1.
template <class Text>
int generator_main(int argc, char** argv, const char* name, const char* what, Text&& text) {
  if (argc != 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::cerr << "usage: " << name << " <output.obj>\n" << what << '\n';
    return argc == 2 ? 0 : 2;
  }
  try {
    write_atomically(text(), argv[1]);
  } catch (const std::exception& e) {
    std::cerr << name << ": " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace mrcloth::generators
