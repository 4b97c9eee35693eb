#include "obj_tokens.h"

#include <charconv>

namespace mrcloth {

long resolve_obj_index(std::string_view text, long defined) {
  long index = 0;
  const auto [stop, error] = std::from_chars(text.data(), text.data() + text.size(), index);
  if (error != std::errc() || stop != text.data() + text.size() || index == 0) return -1;
  const long resolved = index > 0 ? index - 1 : defined + index;
  return resolved >= 0 && resolved < defined ? resolved : -1;
}

std::string_view obj_corner_texture(std::string_view corner) {
  const std::size_t slash = corner.find('/');
  if (slash == std::string_view::npos) return {};
  const std::string_view rest = corner.substr(slash + 1);
  return rest.substr(0, rest.find('/'));
}

}  // namespace mrcloth
