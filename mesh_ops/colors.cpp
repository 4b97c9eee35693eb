#include "colors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace mrcloth {

std::array<unsigned char, 3> sequential_color(double t) {
  // Matplotlib's viridis at 9 evenly spaced stops, linearly interpolated.
  static constexpr std::array<std::array<double, 3>, 9> kStops{{
      {68, 1, 84}, {71, 44, 122}, {59, 81, 139}, {44, 113, 142}, {33, 144, 141},
      {39, 173, 129}, {92, 200, 99}, {170, 220, 50}, {253, 231, 37},
  }};
  if (!(t > 0.0)) t = 0.0;  // also NaN
  if (t > 1.0) t = 1.0;
  const double at = t * (kStops.size() - 1);
  const std::size_t i = std::min(kStops.size() - 2, static_cast<std::size_t>(at));
  const double f = at - static_cast<double>(i);
  std::array<unsigned char, 3> rgb{};
  for (std::size_t c = 0; c < 3; ++c)
    rgb[c] = static_cast<unsigned char>(std::lround(kStops[i][c] + f * (kStops[i + 1][c] - kStops[i][c])));
  return rgb;
}

std::array<unsigned char, 3> palette_color(int value) {
  // Tableau 10 (matplotlib "tab10") without its grey, which is kept for
  // values <= 0 (unpainted / not a level). Qualitative and well separated;
  // value 1 is blue, 2 orange, 3 green, 4 red, ... 9 cyan; past 9, see below.
  static constexpr std::array<std::array<unsigned char, 3>, 9> kPalette{{
      {31, 119, 180},   // blue
      {255, 127, 14},   // orange
      {44, 160, 44},    // green
      {214, 39, 40},    // red
      {148, 103, 189},  // purple
      {140, 86, 75},    // brown
      {227, 119, 194},  // pink
      {188, 189, 34},   // olive
      {23, 190, 207},   // cyan
  }};
  if (value <= 0) return {127, 127, 127};
  if (value <= static_cast<int>(kPalette.size())) return kPalette[static_cast<std::size_t>(value - 1)];
  // Past 9 the colours wrapped (mode 10 drew as mode 1, in the legend too):
  // hues a golden-ratio turn apart, so neighbouring values differ most, at
  // two saturations and three brightnesses; every value up to kLargestMode
  // has its own colour (tested), none grey.
  const int k = value - static_cast<int>(kPalette.size()) - 1;
  const double hue = 6.0 * std::fmod(0.07 + 0.6180339887498949 * k, 1.0);
  static constexpr std::array<double, 2> kSaturation{0.8, 0.5};
  static constexpr std::array<double, 3> kBrightness{0.9, 0.7, 0.5};
  const double v = kBrightness[static_cast<std::size_t>((k / 2) % 3)];
  const double c = v * kSaturation[static_cast<std::size_t>(k % 2)];
  const double x = c * (1.0 - std::abs(std::fmod(hue, 2.0) - 1.0)), m = v - c;
  const int sector = std::min(5, static_cast<int>(hue));
  const std::array<std::array<double, 3>, 6> rgb{{{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}}};
  std::array<unsigned char, 3> colour{};
  for (std::size_t i = 0; i < 3; ++i)
    colour[i] = static_cast<unsigned char>(std::lround(255.0 * (rgb[static_cast<std::size_t>(sector)][i] + m)));
  return colour;
}

}  // namespace mrcloth
