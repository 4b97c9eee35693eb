#pragma once
// Vertex colours for values: the exports' (export_surface's color_by) and
// the previews' palette, one place so that both show a value alike.
#include <array>

namespace mrcloth {

/// Fixed, distinguishable colour for a mode or level value (RGB, 0..255).
std::array<unsigned char, 3> palette_color(int value);

/// Perceptually ordered colour for t in [0, 1] (viridis: dark purple at 0,
/// yellow at 1; clamped outside), RGB 0..255.
std::array<unsigned char, 3> sequential_color(double t);

}  // namespace mrcloth
