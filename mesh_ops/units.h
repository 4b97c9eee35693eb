#pragma once
#include <string>

namespace mrcloth {

/// Metres per input unit for a unit name: "m" (also "metres", "meters"), "dm",
/// "cm", "mm", "inch" (also "in"). Throws ArgumentError naming the unknown
/// unit and listing the accepted ones.
double metres_per_unit(const std::string& unit);

/// `text` with the ASCII letters A-Z lowered and every other byte kept: the
/// same in every locale (std::tolower follows the process's C locale, in
/// which a Turkish "INCH" lowers to "Inch").
std::string ascii_lower(std::string text);

}  // namespace mrcloth
