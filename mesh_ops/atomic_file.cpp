#include "atomic_file.h"

#include "errors.h"

#include <atomic>
#include <filesystem>
#include <random>
#include <sstream>
#include <system_error>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

std::string with_path(const std::string& path, const std::string& problem) { return path + ": " + problem; }

/// "dir/.name.tmp-<random>.om": beside the target so the final rename stays
/// within one file system, hidden, and ending in the real extension because
/// OpenMesh chooses its writer by extension.
fs::path temporary_path(const fs::path& target, const std::string& extension) {
  static std::atomic<unsigned> counter{0};
  std::random_device entropy;
  for (int attempt = 0;; ++attempt) {
    std::ostringstream name;
    name << '.' << target.filename().string() << ".tmp-" << std::hex << entropy() << '-' << counter++
         << extension;
    fs::path candidate = target.parent_path() / name.str();
    std::error_code error;
    if (!fs::exists(candidate, error) || attempt > 100) return candidate;
  }
}

}  // namespace

void require_writable_target(const std::string& path) {
  const fs::path target(path);
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code error;
  if (!fs::is_directory(folder, error))
    throw OutputError(with_path(path, "cannot write file (folder '" + folder.string() + "' does not exist)"));
  if (fs::is_directory(target, error)) throw OutputError(with_path(path, "cannot write file (it is a folder)"));
}

/// Runs `write` on a temporary file and renames it to `path` only when it
/// succeeded; on any failure the temporary file is removed.
void write_file_atomically(const std::string& path, const std::string& extension,
                      const std::function<bool(const std::string&)>& write) {
  require_writable_target(path);
  const fs::path target(path);
  std::error_code error;
  const fs::path temporary = temporary_path(target, extension);
  bool written = false;
  try {
    written = write(temporary.string());
  } catch (...) {
    fs::remove(temporary, error);
    throw;
  }
  if (!written) {
    fs::remove(temporary, error);
    throw OutputError(with_path(path, "cannot write file (writing '" + temporary.filename().string() + "' failed)"));
  }
  fs::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw OutputError(with_path(path, "cannot write file (" + error.message() + ")"));
  }
}

std::string temporary_path_beside(const std::string& path, const std::string& extension) {
  return temporary_path(fs::path(path), extension).string();
}

}  // namespace mrcloth
