#pragma once
// What the garment reader and the mesh writers share: the formats a path's
// extension names, how formats and faces are named in messages, and
// OpenMesh's own reports muted while it reads or writes.
#include <OpenMesh/Core/System/omstream.hh>

#include <optional>
#include <string>

namespace mrcloth {

/// The mesh formats mrcloth reads and writes, each named by its extension.
enum class Format { obj, off, ply, om };

/// ".obj" for "A/B.OBJ", "" when there is none.
std::string lower_extension(const std::string& path);

/// The format a lower-case `extension` (".obj", as lower_extension gives
/// it) names; nullopt for any other.
std::optional<Format> format_of(const std::string& extension);

/// The name of `format` in messages ("OBJ", "OpenMesh OM").
const char* format_name(Format format);

/// `extension` (".obj") quoted for a message, or "none" when it is empty.
std::string shown_extension(const std::string& extension);

/// "face <face>": `face` counted from 0, in the file's (the mesh's) order.
std::string face_label(long face);

/// OpenMesh reports to omerr()/omlog() itself; while one of our reads or
/// writes runs those reports are muted, because every problem the user must
/// see comes back as one of our exceptions instead.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : err_was_on_(::omerr().is_enabled()), log_was_on_(::omlog().is_enabled()) {
    ::omerr().flush();  // earlier, unrelated output still goes out
    ::omlog().flush();
    ::omerr().disable();
    ::omlog().disable();
  }
  ~QuietOpenMesh() {
    // A muted report without a final newline would otherwise sit in the
    // buffer and surface with the next unrelated message.
    ::omerr().flush();
    ::omlog().flush();
    if (err_was_on_) ::omerr().enable();
    if (log_was_on_) ::omlog().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  bool err_was_on_;
  bool log_was_on_;
};

}  // namespace mrcloth
