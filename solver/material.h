#pragma once
// Cloth materials: mass per area and the stiffness of the three spring sets.
#include <string>
#include <vector>

namespace mrcloth {

/// Areal density used when none is given, in kg/m^2 (a light cotton, 150 g/m^2).
inline constexpr double kDefaultArealDensity = 0.15;

/// Material constants. Spring stiffnesses are per spring, in N/m, for level-1
/// (coarse) springs; level L springs are scaled by eq. 1 (see DynamicsOptions).
/// For a square grid a stretch spring stiffness k equals the sheet's membrane
/// stiffness in N/m, independent of spacing, which is why N/m per spring is
/// a meaningful unit across resolutions.
struct Material {
  std::string name = "cotton";
  double areal_density = kDefaultArealDensity;  ///< kg/m^2
  double stretch_stiffness = 2000.0;            ///< N/m, springs along face edges
  double shear_stiffness = 200.0;               ///< N/m, springs along face diagonals
  double bend_stiffness = 0.5;                  ///< N/m, springs between bend partners
  double damping = 0.2;                         ///< 1/s, velocity damping (air drag-like, mass-proportional)
  double stretch_limit = 0.03;                  ///< target largest strain of a stretch spring after a step (0.03 = 3 %)
};

/// Presets: "cotton" (150 g/m^2), "denim" (400 g/m^2, stiffest), "silk"
/// (80 g/m^2, soft and light). Throws ArgumentError for an unknown name,
/// listing the known ones.
Material material_preset(const std::string& name);

/// Names accepted by material_preset.
std::vector<std::string> material_preset_names();

}  // namespace mrcloth
