#pragma once
// Writing preview images so that a PNG either appears complete or not at
// all (a batch job interrupted mid-write must not leave a broken preview).
#include <QImage>

#include <string>

namespace mrcloth::render {

/// Writes `image` as PNG to `path` (UTF-8) through a temporary file that
/// replaces `path` only once complete (QSaveFile). Throws
/// std::runtime_error naming `path` and the reason when the image is null,
/// the folder is missing or not writable, or encoding fails; nothing is
/// left behind then, and an existing file at `path` is kept.
/// Needs no QGuiApplication.
void save_png(const QImage& image, const std::string& path);

}  // namespace mrcloth::render
