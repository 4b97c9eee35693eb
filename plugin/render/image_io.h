#pragma once
// Writing preview images so that a file either appears complete or not at
// all (a batch job interrupted mid-write must not leave a broken preview).
#include <QImage>

#include <string>

namespace mrcloth::render {

/// Writes `image` to `path` (UTF-8) in the format its suffix names, case
/// ignored: .png (also when there is no suffix), .jpg / .jpeg (quality 95),
/// .bmp or .ppm; the last three have no alpha, so a translucent image is
/// laid over white first. Through a temporary file that replaces `path`
/// only once complete (write_file_atomically). Throws std::invalid_argument
/// naming `path` when its suffix names another format, std::runtime_error
/// (an mrcloth::OutputError for the writing) naming it and the reason when
/// the image is null, the folder is missing or not writable, the disk is
/// full, or encoding fails; nothing is left behind then, and an existing
/// file at `path` is kept. Needs no QGuiApplication.
void save_image(const QImage& image, const std::string& path);

}  // namespace mrcloth::render
