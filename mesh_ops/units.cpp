#include "units.h"

#include "errors.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace mrcloth {
namespace {

// Names are matched case-insensitively; the first spelling of each scale is
// the one the error message advertises.
constexpr std::array<std::pair<const char*, double>, 10> kUnits{{
    {"m", 1.0},
    {"metres", 1.0},
    {"meters", 1.0},
    {"metre", 1.0},
    {"meter", 1.0},
    {"dm", 0.1},
    {"cm", 0.01},
    {"mm", 0.001},
    {"inch", 0.0254},
    {"in", 0.0254},
}};

std::string to_lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

double metres_per_unit(const std::string& unit) {
  const std::string key = to_lower(unit);
  for (const auto& [name, metres] : kUnits) {
    if (key == name) return metres;
  }
  throw ArgumentError("unknown unit '" + unit +
                      "'; expected one of m, dm, cm, mm, inch (also metres, meters, metre, meter, in)");
}

}  // namespace mrcloth
