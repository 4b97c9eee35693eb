#include "material.h"

#include "mesh_ops/errors.h"

namespace mrcloth {
namespace {

// Values are typical of mass-spring cloth models tuned to look like these
// fabrics at garment scale; the ratios (denim much stiffer in bending, silk
// light and floppy) matter more than the absolute numbers, because stretch is
// bounded by the strain limit anyway.
std::vector<Material> presets() {
  return {
      {"cotton", 0.15, 2000.0, 200.0, 0.5, 0.2, 0.03},
      {"denim", 0.40, 6000.0, 800.0, 3.0, 0.2, 0.03},
      {"silk", 0.08, 800.0, 60.0, 0.08, 0.3, 0.06},
  };
}

}  // namespace

Material material_preset(const std::string& name) {
  for (const Material& m : presets())
    if (m.name == name) return m;
  std::string known;
  for (const std::string& n : material_preset_names()) known += (known.empty() ? "" : ", ") + n;
  throw ArgumentError("unknown material preset '" + name + "' (known: " + known + ")");
}

std::vector<std::string> material_preset_names() {
  std::vector<std::string> names;
  for (const Material& m : presets()) names.push_back(m.name);
  return names;
}

}  // namespace mrcloth
