#include "motion_filter.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace mrcloth {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

/// Gaussian weights w[0..radius] (w[k] for offsets +-k), summing to 1 over -radius..radius.
std::vector<double> gaussian_weights(double sigma_frames) {
  const int radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma_frames)));
  std::vector<double> w(static_cast<std::size_t>(radius) + 1);
  double sum = 0.0;
  for (int k = 0; k <= radius; ++k) {
    w[static_cast<std::size_t>(k)] = std::exp(-0.5 * (k / sigma_frames) * (k / sigma_frames));
    sum += (k == 0 ? 1.0 : 2.0) * w[static_cast<std::size_t>(k)];
  }
  for (double& weight : w) weight /= sum;
  return w;
}

/// The sequence x_0..x_{n-1} continued to -radius..n-1+radius by point
/// reflection through its end points, again and again for windows longer
/// than the sequence (so a constant rate continues exactly): x_{-k} =
/// reflect(x_0, x_k), x_{n-1+k} = reflect(x_{n-1}, x_{n-1-k}). Element i of
/// the result is x_{i - radius}.
template <class T>
std::vector<T> continued(const std::vector<T>& x, long radius, const std::function<T(const T&, const T&)>& reflect) {
  const auto n = static_cast<long>(x.size());
  const std::function<T(long)> at = [&](long f) -> T {
    if (n == 1 || (f >= 0 && f < n)) return x[static_cast<std::size_t>(std::clamp(f, 0L, n - 1))];
    if (f < 0) return reflect(x.front(), at(-f));
    return reflect(x.back(), at(2 * (n - 1) - f));
  };
  std::vector<T> out(static_cast<std::size_t>(n + 2 * radius));
  for (long i = 0; i < n + 2 * radius; ++i) out[static_cast<std::size_t>(i)] = at(i - radius);
  return out;
}

/// Adds whole turns to each value so that consecutive ones differ by at most half a turn.
void unwrap_degrees(std::vector<double>& values) {
  for (std::size_t f = 1; f < values.size(); ++f)
    values[f] -= 360.0 * std::round((values[f] - values[f - 1]) / 360.0);
}

/// `values` filtered by the symmetric weights, the ends continued by point reflection.
std::vector<double> filtered(const std::vector<double>& values, const std::vector<double>& w) {
  const auto radius = static_cast<long>(w.size()) - 1;
  const std::vector<double> x =
      continued<double>(values, radius, [](const double& end, const double& v) { return 2.0 * end - v; });
  std::vector<double> out(values.size());
  for (std::size_t f = 0; f < values.size(); ++f) {
    const std::size_t i = f + static_cast<std::size_t>(radius);
    double sum = w[0] * x[i];
    for (std::size_t k = 1; k < w.size(); ++k) sum += w[k] * (x[i - k] + x[i + k]);
    out[f] = sum;
  }
  return out;
}

int axis_of(Channel c) { return c == Channel::x_rotation ? 0 : c == Channel::y_rotation ? 1 : 2; }

/// The unit quaternions filtered by the symmetric weights (a weighted sum of
/// the signs aligned along the way, normalised), the ends continued by the
/// rotation's point reflection q0 q^-1 q0 (a constant angular velocity
/// continues, and is kept, exactly).
std::vector<Eigen::Quaterniond> filtered(const std::vector<Eigen::Quaterniond>& q, const std::vector<double>& w) {
  const auto radius = static_cast<long>(w.size()) - 1;
  std::vector<Eigen::Quaterniond> x = continued<Eigen::Quaterniond>(
      q, radius, [](const Eigen::Quaterniond& end, const Eigen::Quaterniond& v) { return end * v.conjugate() * end; });
  // Signs aligned along the whole continued sequence (q and -q are one rotation).
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i].dot(x[i - 1]) < 0.0) x[i].coeffs() = -x[i].coeffs();
  std::vector<Eigen::Quaterniond> out(q.size());
  for (std::size_t f = 0; f < q.size(); ++f) {
    const std::size_t i = f + static_cast<std::size_t>(radius);
    Eigen::Vector4d sum = w[0] * x[i].coeffs();
    for (std::size_t k = 1; k < w.size(); ++k) sum += w[k] * (x[i - k].coeffs() + x[i + k].coeffs());
    out[f].coeffs() = sum.normalized();
  }
  return out;
}

/// Of the two Euler triples of one rotation about three distinct axes,
/// (a, b, c) and (a + 180, 180 - b, c + 180), each angle moved by whole
/// turns toward `near`: the one nearer `near` (degrees).
std::array<double, 3> nearest_triple(const Eigen::Vector3d& radians, const std::array<double, 3>& near) {
  const auto toward = [](double angle, double target) { return angle - 360.0 * std::round((angle - target) / 360.0); };
  std::array<double, 3> best{}, other{};
  const std::array<double, 3> a = {radians[0] / kDegree, radians[1] / kDegree, radians[2] / kDegree};
  const std::array<double, 3> b = {a[0] + 180.0, 180.0 - a[1], a[2] + 180.0};
  double best_distance = 0.0, other_distance = 0.0;
  for (int k = 0; k < 3; ++k) {
    best[k] = toward(a[k], near[k]);
    other[k] = toward(b[k], near[k]);
    best_distance += std::abs(best[k] - near[k]);
    other_distance += std::abs(other[k] - near[k]);
  }
  return other_distance < best_distance ? other : best;
}

/// Smooths a joint's three rotation channels (columns, about axes), frames from `first`, as rotations.
void smooth_rotations(Motion& motion, const std::array<Eigen::Index, 3>& columns,
                      const std::array<int, 3>& axes, Eigen::Index first, const std::vector<double>& w) {
  const Eigen::Index rows = motion.frames.rows() - first;
  std::vector<Eigen::Quaterniond> q(static_cast<std::size_t>(rows));
  for (Eigen::Index f = 0; f < rows; ++f) {
    Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
    for (int k = 0; k < 3; ++k)
      r = r * Eigen::AngleAxisd(motion.frames(first + f, columns[k]) * kDegree, Eigen::Vector3d::Unit(axes[k]));
    q[static_cast<std::size_t>(f)] = r;
  }
  const std::vector<Eigen::Quaterniond> smoothed = filtered(q, w);
  for (Eigen::Index f = 0; f < rows; ++f) {
    const Eigen::Vector3d angles = smoothed[static_cast<std::size_t>(f)].toRotationMatrix().eulerAngles(axes[0], axes[1], axes[2]);
    const std::array<double, 3> near = {motion.frames(first + f, columns[0]), motion.frames(first + f, columns[1]),
                                        motion.frames(first + f, columns[2])};
    const std::array<double, 3> triple = nearest_triple(angles, near);
    for (int k = 0; k < 3; ++k) motion.frames(first + f, columns[k]) = triple[k];
  }
}

}  // namespace

void smooth_motion(Motion& motion, double sigma_seconds, int first_frame) {
  const long rows = motion.frames.rows() - std::max(first_frame, 0);
  if (!(sigma_seconds > 0.0) || rows < 2) return;
  const std::vector<double> w = gaussian_weights(sigma_seconds / motion.frame_time);
  const Eigen::Index first = motion.frames.rows() - rows;
  std::vector<double> values(static_cast<std::size_t>(rows));
  const auto smooth_column = [&](Eigen::Index c, bool angle) {
    for (long f = 0; f < rows; ++f) values[static_cast<std::size_t>(f)] = motion.frames(first + f, c);
    if (angle) unwrap_degrees(values);
    const std::vector<double> out = filtered(values, w);
    for (long f = 0; f < rows; ++f) motion.frames(first + f, c) = out[static_cast<std::size_t>(f)];
  };
  for (const Joint& joint : motion.skeleton.joints) {
    std::vector<Eigen::Index> rotation_columns;
    std::vector<int> rotation_axes;
    for (std::size_t k = 0; k < joint.channels.size(); ++k) {
      const Eigen::Index column = joint.first_channel + static_cast<Eigen::Index>(k);
      if (is_position(joint.channels[k])) {
        smooth_column(column, false);
      } else {
        rotation_columns.push_back(column);
        rotation_axes.push_back(axis_of(joint.channels[k]));
      }
    }
    const bool three_axes = rotation_axes.size() == 3 && rotation_axes[0] != rotation_axes[1] &&
                            rotation_axes[1] != rotation_axes[2] && rotation_axes[0] != rotation_axes[2];
    if (three_axes) {
      // As one rotation: its Euler angles may jump to the other triple of
      // the same rotation, which smoothing channel by channel would blur
      // into a pose that is neither.
      smooth_rotations(motion, {rotation_columns[0], rotation_columns[1], rotation_columns[2]},
                       {rotation_axes[0], rotation_axes[1], rotation_axes[2]}, first, w);
    } else {
      for (const Eigen::Index column : rotation_columns) smooth_column(column, true);
    }
  }
}

}  // namespace mrcloth
