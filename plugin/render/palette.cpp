#include "plugin/render/palette.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mrcloth::render {

QColor categorical_color(int index) {
  static const std::array<QRgb, 10> colors{0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2, 0x59a14f,
                                           0xedc948, 0xb07aa1, 0xff9da7, 0x9c755f, 0xbab0ac};
  const int n = static_cast<int>(colors.size());
  return QColor(colors[static_cast<std::size_t>(((index % n) + n) % n)]);
}

QColor viridis(double t) {
  if (std::isnan(t)) return QColor(128, 128, 128);
  // Samples of matplotlib's viridis at t = 0, 0.125, ..., 1; linear in between.
  static const std::array<std::array<double, 3>, 9> samples{{{68, 1, 84},
                                                              {71, 44, 122},
                                                              {59, 81, 139},
                                                              {44, 113, 142},
                                                              {33, 144, 141},
                                                              {39, 173, 129},
                                                              {92, 200, 99},
                                                              {170, 220, 50},
                                                              {253, 231, 37}}};
  const double x = std::clamp(t, 0.0, 1.0) * (samples.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(x), samples.size() - 2);
  const double f = x - static_cast<double>(i);
  auto mix = [&](int c) { return static_cast<int>(std::lround(samples[i][c] * (1 - f) + samples[i + 1][c] * f)); };
  return QColor(mix(0), mix(1), mix(2));
}

}  // namespace mrcloth::render
