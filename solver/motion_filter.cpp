#include "motion_filter.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mrcloth {
namespace {

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

/// Adds whole turns to each value so that consecutive ones differ by at most half a turn.
void unwrap_degrees(std::vector<double>& values) {
  for (std::size_t f = 1; f < values.size(); ++f)
    values[f] -= 360.0 * std::round((values[f] - values[f - 1]) / 360.0);
}

/// `values` filtered by the symmetric weights, the ends continued by point reflection.
std::vector<double> filtered(const std::vector<double>& values, const std::vector<double>& w) {
  const auto n = static_cast<long>(values.size());
  const auto at = [&](long f) {
    // Point reflection through the end frame: x(-k) = 2 x(0) - x(k).
    if (f < 0) return 2.0 * values.front() - values[static_cast<std::size_t>(std::min(-f, n - 1))];
    if (f >= n) return 2.0 * values.back() - values[static_cast<std::size_t>(std::max(2 * (n - 1) - f, 0L))];
    return values[static_cast<std::size_t>(f)];
  };
  const auto radius = static_cast<long>(w.size()) - 1;
  std::vector<double> out(values.size());
  for (long f = 0; f < n; ++f) {
    double sum = w[0] * values[static_cast<std::size_t>(f)];
    for (long k = 1; k <= radius; ++k) sum += w[static_cast<std::size_t>(k)] * (at(f - k) + at(f + k));
    out[static_cast<std::size_t>(f)] = sum;
  }
  return out;
}

}  // namespace

void smooth_motion(Motion& motion, double sigma_seconds, int first_frame) {
  const long rows = motion.frames.rows() - std::max(first_frame, 0);
  if (!(sigma_seconds > 0.0) || rows < 2) return;
  const std::vector<double> w = gaussian_weights(sigma_seconds / motion.frame_time);
  std::vector<Channel> kinds(static_cast<std::size_t>(motion.frames.cols()), Channel::x_position);
  for (const Joint& joint : motion.skeleton.joints)
    for (std::size_t k = 0; k < joint.channels.size(); ++k)
      kinds[static_cast<std::size_t>(joint.first_channel) + k] = joint.channels[k];
  const Eigen::Index first = motion.frames.rows() - rows;
  std::vector<double> values(static_cast<std::size_t>(rows));
  for (Eigen::Index c = 0; c < motion.frames.cols(); ++c) {
    for (long f = 0; f < rows; ++f) values[static_cast<std::size_t>(f)] = motion.frames(first + f, c);
    if (!is_position(kinds[static_cast<std::size_t>(c)])) unwrap_degrees(values);
    const std::vector<double> out = filtered(values, w);
    for (long f = 0; f < rows; ++f) motion.frames(first + f, c) = out[static_cast<std::size_t>(f)];
  }
}

}  // namespace mrcloth
