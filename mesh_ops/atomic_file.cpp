#include "atomic_file.h"

#include "errors.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <regex>
#include <sstream>
#include <system_error>

#include <sys/stat.h>
#include <unistd.h>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

/// The longest file name (bytes) the usual file systems take (ext4, XFS,
/// tmpfs: NAME_MAX).
constexpr std::size_t kLongestName = 255;

/// At most `bytes` bytes of UTF-8 `name`, cut before a whole character.
std::string utf8_prefix(const std::string& name, std::size_t bytes) {
  if (name.size() <= bytes) return name;
  std::size_t end = bytes;
  while (end > 0 && (static_cast<unsigned char>(name[end]) & 0xC0) == 0x80) --end;
  return name.substr(0, end);
}

/// "dir/.name.tmp-<random>.om": beside the target so the final rename stays
/// within one file system, hidden, and ending in the real extension because
/// OpenMesh chooses its writer by extension. The target's name is shortened
/// where the whole would pass kLongestName: any name the target may have,
/// its temporary may too.
fs::path temporary_path(const fs::path& target, const std::string& extension) {
  static std::atomic<unsigned> counter{0};
  std::random_device entropy;
  for (int attempt = 0;; ++attempt) {
    std::ostringstream suffix;
    suffix << ".tmp-" << std::hex << entropy() << '-' << counter++ << extension;
    const std::string tail = suffix.str();
    const std::size_t room = kLongestName > tail.size() + 1 ? kLongestName - tail.size() - 1 : 0;
    std::ostringstream name;
    name << '.' << utf8_prefix(target.filename().string(), room) << tail;
    fs::path candidate = target.parent_path() / name.str();
    std::error_code error;
    if (!fs::exists(candidate, error) || attempt > 100) return candidate;
  }
}

/// Why a writer that reports only failure could not write `file` (it has
/// been removed): the system's reason for refusing to create it, or, where
/// it can be created, most likely a full disk.
std::string why_unwritable(const fs::path& file) {
  std::FILE* probe = std::fopen(file.c_str(), "wb");
  if (!probe) return std::strerror(errno);
  std::fclose(probe);
  std::error_code ignored;
  fs::remove(file, ignored);
  return "it could be created, so most likely the disk is full";
}

}  // namespace

std::string write_target(const std::string& path) {
  fs::path target(path);
  std::error_code error;
  // A bounded walk: a loop of links ends at its 40th (the kernel's own limit).
  for (int link = 0; link < 40 && fs::is_symlink(fs::symlink_status(target, error)); ++link) {
    const fs::path to = fs::read_symlink(target, error);
    if (error) break;
    // From the link's folder as the system finds it: joining every hop's
    // relative path grew past PATH_MAX on a chain of long links.
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code unresolved;
    const fs::path resolved = fs::weakly_canonical(folder, unresolved);
    target = to.is_absolute() ? to : (unresolved ? folder : resolved) / to;
  }
  return target.string();
}

void require_writable_target(const std::string& path) {
  const fs::path target(write_target(path));
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code error;
  if (!fs::is_directory(folder, error))
    throw OutputError(with_path(path, "cannot write file (folder '" + folder.string() + "' " +
                                          (fs::exists(folder, error) ? "is a file, not a folder)" : "does not exist)")));
  const fs::file_status status = fs::status(target, error);
  if (error && error != std::errc::no_such_file_or_directory)  // a loop of links, a folder not searchable
    throw OutputError(with_path(path, "cannot write file (" + error.message() + ")"));
  if (fs::is_directory(status)) throw OutputError(with_path(path, "cannot write file (it is a folder)"));
  if (!fs::exists(status)) return;
  if (!fs::is_regular_file(status))
    throw OutputError(with_path(path, "cannot write file (it is a device, pipe or socket, not a regular file; expected "
                                      "the path of a file to write)"));
  constexpr fs::perms writable = fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write;
  if ((status.permissions() & writable) == fs::perms::none)
    throw OutputError(with_path(path, "cannot write file (it is read-only; make it writable to replace it)"));
  // Renaming over a file needs only its folder's permission: another user's
  // file in a shared folder was replaced where `echo >>` is refused.
  if (access(target.c_str(), W_OK) != 0 && errno == EACCES)
    throw OutputError(with_path(path, "cannot write file (this user may not change it)"));
}

void replace_with_temporary(const std::string& temporary, const std::string& path) {
  const fs::path target(write_target(path));
  std::error_code error;
  const fs::file_status replaced = fs::status(target, error);
  if (fs::is_regular_file(replaced)) {
    // The replaced file's owner where this user may give it (root), and its
    // permissions, but never set-user or set-group-id onto a file written here.
    struct stat owner {};
    if (stat(target.c_str(), &owner) == 0) {
      // Where this user may not give it away (not root), the file is this
      // user's now, as any editor's save makes it.
      [[maybe_unused]] const int given = chown(temporary.c_str(), owner.st_uid, owner.st_gid);
    }
    fs::permissions(temporary, replaced.permissions() & ~(fs::perms::set_uid | fs::perms::set_gid), error);
  }
  fs::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw OutputError(with_path(path, "cannot write file (" + error.message() + ")"));
  }
}

/// Runs `write` on a temporary file and renames it to `path` only when it
/// succeeded; on any failure the temporary file is removed.
void write_file_atomically(const std::string& path, const std::string& extension,
                      const std::function<bool(const std::string&)>& write) {
  require_writable_target(path);
  std::error_code error;
  const fs::path temporary = temporary_path(fs::path(write_target(path)), extension);
  bool written = false;
  try {
    written = write(temporary.string());
  } catch (...) {
    fs::remove(temporary, error);
    throw;
  }
  if (!written) {
    fs::remove(temporary, error);
    throw OutputError(with_path(path, "cannot write file (writing '" + temporary.filename().string() + "' failed: " +
                                          why_unwritable(temporary) + ")"));
  }
  replace_with_temporary(temporary.string(), path);
}

StagedFile::StagedFile(const std::string& path, const std::string& extension,
                       const std::function<void(const std::string&)>& write)
    : path_(path), temporary_(temporary_path_beside(path, extension)) {
  require_writable_target(path);
  const auto remove_temporary = [&] {
    std::error_code ignored;
    fs::remove(temporary_, ignored);
  };
  try {
    write(temporary_);
  } catch (const OutputError& error) {
    remove_temporary();
    // Named by the file the user asked for, not its temporary.
    const std::string what = error.what(), named = temporary_ + ": ";
    throw OutputError(what.rfind(named, 0) == 0 ? with_path(path_, what.substr(named.size())) : what);
  } catch (...) {
    remove_temporary();
    throw;
  }
}

StagedFile::~StagedFile() {
  if (committed_ || temporary_.empty()) return;
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

void StagedFile::commit() {
  if (committed_) return;
  replace_with_temporary(temporary_, path_);
  committed_ = true;
}

std::string temporary_path_beside(const std::string& path, const std::string& extension) {
  return temporary_path(fs::path(write_target(path)), extension).string();
}

bool is_temporary_name(const std::string& file_name) {
  // temporary_path's ".<name>.tmp-<entropy>-<counter><extension>", both numbers in hex.
  static const std::regex form(R"(^\..*\.tmp-[0-9a-f]{1,8}-[0-9a-f]+(\.[A-Za-z0-9]+)?$)");
  return std::regex_match(file_name, form);
}

std::vector<std::string> remove_temporaries_in(const std::string& folder) {
  std::vector<std::string> removed;
  std::error_code error;
  if (!fs::is_directory(folder, error)) return removed;
  std::vector<fs::path> found;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
    if (it->is_regular_file(error) && is_temporary_name(it->path().filename().string())) found.push_back(it->path());
  if (error) throw OutputError(with_path(folder, "cannot list the folder (" + error.message() + ")"));
  for (const fs::path& file : found) {
    if (!fs::remove(file, error) && error)
      throw OutputError(with_path(file.string(), "cannot remove a leftover temporary file (" + error.message() + ")"));
    removed.push_back(file.string());
  }
  return removed;
}

}  // namespace mrcloth
