#pragma once
// The one error style of mrcloth: typed exceptions at module boundaries,
// each message naming the file, line or element and what was expected.
#include <cstddef>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <string>

namespace mrcloth {

/// Base of every error mrcloth throws on purpose.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A file could not be read, or its contents are not what was expected.
struct InputError : Error {
  using Error::Error;
};

/// An argument is out of range or inconsistent with the mesh it refers to.
struct ArgumentError : Error {
  using Error::Error;
};

/// A file could not be written.
struct OutputError : Error {
  using Error::Error;
};

/// A number as messages print it: six significant digits, '.' whatever the
/// locale ("0.05", "1e+09").
inline std::string number_text(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << value;
  return out.str();
}

/// The form every message about a file takes: "<path>: <problem>".
inline std::string with_path(const std::string& path, const std::string& problem) { return path + ": " + problem; }

/// " (line N)", for a problem found on line N (1-based) of a text file.
inline std::string at_line(std::size_t line) { return " (line " + std::to_string(line) + ")"; }

/// Why a file named `path` (UTF-8) cannot be opened when it does not exist:
/// a name holding U+FFFD came from bytes that were not UTF-8 (a Latin-1
/// name, say), which Qt's scripts cannot name at all.
inline std::string missing_file_reason(const std::string& path) {
  if (path.find("\xEF\xBF\xBD") == std::string::npos) return "it does not exist";
  return "it does not exist; its name holds U+FFFD, the mark of bytes that were not UTF-8: a file whose name is "
         "not UTF-8 (Latin-1, say) cannot be named from a script, so rename it";
}

}  // namespace mrcloth
