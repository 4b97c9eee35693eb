#include "garment_formats.h"

#include "units.h"

#include <filesystem>
#include <optional>
#include <string>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

}  // namespace

std::string lower_extension(const std::string& path) { return ascii_lower(fs::path(path).extension().string()); }

std::optional<Format> format_of(const std::string& extension) {
  if (extension == ".obj") return Format::obj;
  if (extension == ".off") return Format::off;
  if (extension == ".ply") return Format::ply;
  if (extension == ".om") return Format::om;
  return std::nullopt;
}

const char* format_name(Format format) {
  switch (format) {
    case Format::obj: return "OBJ";
    case Format::off: return "OFF";
    case Format::ply: return "PLY";
    case Format::om: return "OpenMesh OM";
  }
  return "?";
}

std::string shown_extension(const std::string& extension) {
  return extension.empty() ? std::string("none") : "'" + extension + "'";
}

std::string face_label(long face) { return "face " + std::to_string(face); }

}  // namespace mrcloth
