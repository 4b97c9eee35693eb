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

}  // namespace

double metres_per_unit(const std::string& unit) {
  const std::string key = ascii_lower(unit);
  for (const auto& [name, metres] : kUnits) {
    if (key == name) return metres;
  }
  throw ArgumentError("unknown unit '" + unit +
                      "'; expected one of m, dm, cm, mm, inch (also metres, meters, metre, meter, in)");
}

std::string ascii_lower(std::string text) {
  for (char& c : text)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return text;
}

}  // namespace mrcloth
