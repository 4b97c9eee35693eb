#pragma once
// Writing a file so that it either appears complete or not at all.
#include <functional>
#include <string>

namespace mrcloth {

/// Calls `write(temporary_path)` for a hidden temporary file beside `path`
/// whose name ends in `extension` (writers that choose a format by extension
/// need it), then renames it to `path`. If `write` returns false or throws,
/// or the rename fails, the temporary file is removed and nothing appears at
/// `path`; an existing file there is replaced only on success.
/// Throws OutputError naming `path` (exceptions from `write` pass through).
void write_file_atomically(const std::string& path, const std::string& extension,
                           const std::function<bool(const std::string& temporary_path)>& write);

}  // namespace mrcloth
