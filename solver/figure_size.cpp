#include "figure_size.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace mrcloth {
namespace {

std::string metres(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f m", value);  // the host keeps LC_NUMERIC "C" (main.cpp)
  return text;
}

/// Each leg's hip and ankle joints, by CMU names.
constexpr std::pair<const char*, const char*> kLegs[] = {{"LeftUpLeg", "LeftFoot"}, {"RightUpLeg", "RightFoot"}};

}  // namespace

double leg_length(const Skeleton& skeleton, const std::vector<Eigen::Vector3d>& joints) {
  double sum = 0.0;
  int legs = 0;
  for (const auto& [hip, ankle] : kLegs) {
    const int h = skeleton.find(hip), a = skeleton.find(ankle);
    if (h < 0 || a < 0 || static_cast<std::size_t>(std::max(h, a)) >= joints.size()) continue;
    sum += (joints[static_cast<std::size_t>(h)] - joints[static_cast<std::size_t>(a)]).norm();
    ++legs;
  }
  return legs > 0 ? sum / legs : 0.0;
}

FigureScale figure_scale(const Skeleton& skeleton, double body_legs) {
  const Pose rest = rest_pose(skeleton);
  std::vector<Eigen::Vector3d> joints;
  joints.reserve(rest.global.size());
  for (const auto& transform : rest.global) joints.push_back(transform.translation());
  FigureScale scale;
  scale.legs = leg_length(skeleton, joints);
  for (const auto& [hip, ankle] : kLegs)
    scale.measured = scale.measured || (skeleton.find(hip) >= 0 && skeleton.find(ankle) >= 0);
  scale.against_body = body_legs > 0.0;
  scale.expected = scale.against_body ? body_legs : kReferenceLegs;
  return scale;
}

bool plausible(const FigureScale& scale) {
  const double factor = scale.factor();
  if (scale.against_body) return factor <= kBodyFactorLimit && factor >= 1.0 / kBodyFactorLimit;
  return factor >= kReferenceFactorLow && factor <= kReferenceFactorHigh;
}

std::string describe(const FigureScale& scale) {
  char factor[32];
  std::snprintf(factor, sizeof factor, scale.factor() >= 10.0 ? "%.0f" : "%.2g", scale.factor());
  return "the figure's legs are " + metres(scale.legs) + " long (hip to ankle in its rest pose), " + factor +
         " times " + (scale.against_body ? "the MakeHuman body's " : "an adult's ") + metres(scale.expected);
}

}  // namespace mrcloth
