#pragma once
// Ellipse helpers shared by the garment generators (standard library only).
#include <cmath>
#include <vector>

namespace mrcloth::generators {

inline constexpr double kEllipsePi = 3.14159265358979323846;

/// Perimeter of the ellipse with semi-axes a, b (Ramanujan's second
/// approximation; relative error below 1e-9 for our aspects).
inline double ellipse_perimeter(double a, double b) {
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  return kEllipsePi * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
}

/// Ellipse parameter angles of `count` points equally spaced in arc length,
/// starting at parameter 0. Equal arc spacing keeps the quads of one ring the
/// same width on the flat sides and at the front. Found by inverting a
/// finely sampled cumulative arc length (a, b only matter through b/a).
inline std::vector<double> equal_arc_angles(double a, double b, int count) {
  constexpr int kSamples = 4096;
  std::vector<double> length(kSamples + 1, 0.0);
  for (int i = 1; i <= kSamples; ++i) {
    const double t0 = 2.0 * kEllipsePi * (i - 1) / kSamples;
    const double t1 = 2.0 * kEllipsePi * i / kSamples;
    length[i] = length[i - 1] + std::hypot(a * (std::sin(t1) - std::sin(t0)), b * (std::cos(t1) - std::cos(t0)));
  }
  std::vector<double> angles(count);
  int i = 0;
  for (int k = 0; k < count; ++k) {
    const double target = length[kSamples] * k / count;
    while (length[i + 1] < target) ++i;
    const double f = (target - length[i]) / (length[i + 1] - length[i]);
    angles[k] = 2.0 * kEllipsePi * (i + f) / kSamples;
  }
  return angles;
}

}  // namespace mrcloth::generators
