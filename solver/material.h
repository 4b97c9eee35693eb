#pragma once
// Cloth material constants shared by the solver and the host.

namespace mrcloth {

/// Areal density used when none is given, in kg/m^2 (a light cotton, 150 g/m^2).
inline constexpr double kDefaultArealDensity = 0.15;

}  // namespace mrcloth
