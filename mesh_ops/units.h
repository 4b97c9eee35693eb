#pragma once
#include <string>

namespace mrcloth {

/// Metres per input unit for a unit name: "m" (also "metres", "meters"), "dm",
/// "cm", "mm", "inch" (also "in"). Throws ArgumentError naming the unknown
/// unit and listing the accepted ones.
double metres_per_unit(const std::string& unit);

}  // namespace mrcloth
