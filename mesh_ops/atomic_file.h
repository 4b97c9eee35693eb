#pragma once
// Writing a file so that it either appears complete or not at all.
#include <functional>
#include <string>
#include <vector>

namespace mrcloth {

/// Throws OutputError naming `path` unless its folder exists and `path`
/// (where its symbolic links lead) is nothing yet, or a regular file that
/// is not read-only and that this user may change: the checks every writer
/// makes before any work. A device or pipe (/dev/stdout, a FIFO) would be
/// replaced by a regular file; a read-only file is taken as one not to be
/// replaced, and another user's as not this user's to replace (a rename
/// needs only the folder's permission).
void require_writable_target(const std::string& path);

/// The file a write to `path` replaces: `path` itself, or the file its
/// symbolic links lead to (the links stay links; a dangling one gets its
/// file).
std::string write_target(const std::string& path);

/// Renames the finished `temporary` (from temporary_path_beside(path, ...))
/// onto write_target(path), giving it the permissions of the file it
/// replaces (never set-user or set-group-id) and, where this user may (root),
/// its owner. Throws OutputError naming `path`.
void replace_with_temporary(const std::string& temporary, const std::string& path);

/// Calls `write(temporary_path)` for a hidden temporary file beside `path`
/// whose name ends in `extension` (writers that choose a format by extension
/// need it), then renames it to `path`. If `write` returns false or throws,
/// or the rename fails, the temporary file is removed and nothing appears at
/// `path`; an existing file there is replaced only on success.
/// Throws OutputError naming `path` (exceptions from `write` pass through).
void write_file_atomically(const std::string& path, const std::string& extension,
                           const std::function<bool(const std::string& temporary_path)>& write);

/// A file written now and put in place later, with another output: a rest
/// mesh staged before its cache is finished is renamed into place right
/// after it (no room needed then), so a full disk cannot leave a new cache
/// beside an earlier run's rest mesh. Never committed, the temporary goes.
class StagedFile {
 public:
  /// Calls `write(temporary)`, a writer that writes a whole file at the
  /// path it is given (any of mrcloth's writers; `extension` ends the
  /// temporary's name, for writers choosing their format by it). Throws
  /// OutputError naming `path`, or what `write` throws; nothing is left.
  StagedFile(const std::string& path, const std::string& extension,
             const std::function<void(const std::string& temporary_path)>& write);
  ~StagedFile();
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  /// Puts the file at its path (replace_with_temporary); once.
  void commit();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string temporary_;
  bool committed_ = false;
};

/// A fresh name for a hidden temporary file beside `path` ending in
/// `extension` (".name.tmp-<random>-<n><extension>", both numbers in hex,
/// in write_target(path)'s folder, so the rename onto it stays within one
/// file system). Only the name: nothing
/// is created. For writers that stream into the file themselves and rename it
/// when done (see write_file_atomically for the one-call version).
std::string temporary_path_beside(const std::string& path, const std::string& extension);

/// Whether `file_name` (a name, no folder) has the form temporary_path_beside
/// gives: a temporary a writer left when its process was killed mid-write.
bool is_temporary_name(const std::string& file_name);

/// Removes every file in `folder` (not in its subfolders, which may be
/// other runs' outputs) whose name is_temporary_name; returns their paths.
/// Only for a folder no other process writes into now (a live writer's
/// temporary would go too). Throws OutputError naming a file that cannot
/// be removed.
std::vector<std::string> remove_temporaries_in(const std::string& folder);

}  // namespace mrcloth
