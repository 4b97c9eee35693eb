#include "instance_curvature.h"

#include "mesh_ops/bend_partners.h"
#include "mesh_ops/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace mrcloth {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Below this x, 1 - sinc(x) and its derivative come from their series:
/// the closed forms cancel there.
constexpr double kSeriesBelow = 1.0;

/// d/dx (1 - sinc(x)) = (sin x - x cos x) / x^2 (> 0 on (0, pi]).
double one_minus_sinc_slope(double x) {
  if (x < kSeriesBelow) {
    // sum_n (-1)^(n+1) 2n x^(2n-1) / (2n+1)!, to n = 7 (error < 1e-13 at x = 1;
    // Newton only needs the slope roughly).
    const double y = x * x;
    return x * (1.0 / 3.0 + y * (-1.0 / 30.0 + y * (1.0 / 840.0 + y * (-1.0 / 45360.0 + y * (1.0 / 3991680.0 +
               y * (-1.0 / 518918400.0 + y * (1.0 / 93405312000.0)))))));
  }
  return (std::sin(x) - x * std::cos(x)) / (x * x);
}

}  // namespace

double one_minus_sinc(double x) {
  x = std::abs(x);
  if (x < kSeriesBelow) {
    // sum_n (-1)^(n+1) x^(2n) / (2n+1)!, to n = 10: the next term is below
    // 1e-19 of the sum for x < 1.
    const double y = x * x;
    constexpr double c[] = {1.0 / 6.0,           -1.0 / 120.0,          1.0 / 5040.0,
                            -1.0 / 362880.0,     1.0 / 39916800.0,      -1.0 / 6227020800.0,
                            1.0 / 1307674368000.0, -1.0 / 355687428096000.0, 1.0 / 121645100408832000.0,
                            -1.0 / 51090942171709440000.0};
    double sum = 0.0;
    for (int k = 9; k >= 0; --k) sum = sum * y + c[k];
    return sum * y;
  }
  return 1.0 - std::sin(x) / x;
}

double inverse_sinc(double ratio) {
  if (std::isnan(ratio)) throw ArgumentError("inverse_sinc: the ratio is NaN; expected a number");
  if (ratio >= 1.0) return 0.0;
  if (ratio <= 0.0) return kPi;
  // Solve 1 - sinc(x) = s with s = 1 - ratio (exact for ratio >= 0.5), so a
  // ratio within 1e-12 of 1 keeps its digits. Start from the series
  // s = x^2/6 - x^4/120 + x^6/5040 inverted to third order in s,
  // x^2 = 6 s + 9/5 s^2 + 288/350 s^3 (one or two Newton steps for cloth,
  // whose ratios are near 1); Newton, kept inside a
  // bracket that every step narrows (1 - sinc increases on [0, pi]).
  const double s = 1.0 - ratio;
  double lo = 0.0, hi = kPi;
  double x = std::min(kPi, std::sqrt(s * (6.0 + s * (1.8 + s * (288.0 / 350.0)))));
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double residual = one_minus_sinc(x) - s;
    if (residual == 0.0) return x;
    if (residual > 0.0) hi = x;
    else lo = x;
    const double step = residual / one_minus_sinc_slope(x);
    double next = x - step;
    if (!(next > lo && next < hi)) {
      next = 0.5 * (lo + hi);
    } else if (std::abs(step) <= 1e-9 * x) {
      // Newton converges quadratically here (1 - sinc is smooth, its slope
      // bounded away from 0 relative to x): the next error is ~1e-18 x.
      return next;
    }
    x = next;
    if (hi - lo <= 2.0 * std::numeric_limits<double>::epsilon() * hi) break;
  }
  return x;
}

double arc_curvature(double distance, double half_rest) {
  return inverse_sinc(distance / (2.0 * half_rest)) / half_rest;
}

CurvaturePairs curvature_pairs(const QuadMesh& mesh) {
  CurvaturePairs pairs;
  pairs.num_vertices = static_cast<int>(mesh.n_vertices());
  pairs.partners.assign(static_cast<std::size_t>(pairs.num_vertices), 0);
  for (const BendPair& pair : bend_pairs(mesh)) {
    const OpenMesh::Vec3d d = mesh.point(OpenMesh::VertexHandle(pair.i)) - mesh.point(OpenMesh::VertexHandle(pair.j));
    const double half = 0.5 * d.norm();
    if (!(half > 0.0) || !std::isfinite(half)) {
      throw ArgumentError("curvature_pairs: bend partners " + std::to_string(pair.i) + " and " + std::to_string(pair.j) +
                          " coincide at rest (or are not finite); expected distinct rest positions");
    }
    pairs.i.push_back(pair.i);
    pairs.j.push_back(pair.j);
    pairs.half_rest.push_back(half);
    ++pairs.partners[static_cast<std::size_t>(pair.i)];
    ++pairs.partners[static_cast<std::size_t>(pair.j)];
  }
  return pairs;
}

Eigen::VectorXd vertex_curvature(const CurvaturePairs& pairs, const FramePositions& frame) {
  if (frame.rows() != pairs.num_vertices) {
    throw ArgumentError("vertex_curvature: the frame has " + std::to_string(frame.rows()) + " points; expected " +
                        std::to_string(pairs.num_vertices) + " (the mesh's vertices)");
  }
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(pairs.num_vertices);
  for (std::size_t k = 0; k < pairs.i.size(); ++k) {
    const int i = pairs.i[k], j = pairs.j[k];
    const double distance = (frame.row(i) - frame.row(j)).norm();
    const double curvature = arc_curvature(distance, pairs.half_rest[k]);
    sum[i] += curvature;
    sum[j] += curvature;
  }
  for (int v = 0; v < pairs.num_vertices; ++v)
    if (pairs.partners[static_cast<std::size_t>(v)] > 0) sum[v] /= pairs.partners[static_cast<std::size_t>(v)];
  return sum;
}

CurvatureAccumulator::CurvatureAccumulator(int num_vertices)
    : mean_(Eigen::VectorXd::Zero(num_vertices)), squares_(Eigen::VectorXd::Zero(num_vertices)) {}

void CurvatureAccumulator::add(const Eigen::VectorXd& curvature) {
  if (curvature.size() != mean_.size()) {
    throw ArgumentError("CurvatureAccumulator: " + std::to_string(curvature.size()) + " values; expected " +
                        std::to_string(mean_.size()));
  }
  ++frames_;
  // Welford: no sum of squares minus squared sum, which cancels for a
  // vertex that bends about the same in every frame.
  const Eigen::VectorXd delta = curvature - mean_;
  mean_ += delta / frames_;
  squares_ += delta.cwiseProduct(curvature - mean_);
}

Eigen::VectorXd CurvatureAccumulator::deviation() const {
  if (frames_ == 0) return Eigen::VectorXd::Zero(mean_.size());
  return (squares_.cwiseMax(0.0) / frames_).cwiseSqrt();
}

CurvatureFeatures analyse_curvature(const std::string& pc2_path, const CurvaturePairs& pairs,
                                    const CurvatureAnalysisOptions& options, const AnalysisProgress& progress) {
  if (options.skip_frames < 0)
    throw ArgumentError("analyse_curvature: skip_frames must be >= 0 (got " + std::to_string(options.skip_frames) + ")");
  if (options.max_frames == 0 || options.max_frames < -1)
    throw ArgumentError("analyse_curvature: max_frames must be -1 (all) or >= 1 (got " +
                        std::to_string(options.max_frames) + ")");
  Pc2Reader cache(pc2_path);
  if (cache.num_points() != pairs.num_vertices) {
    throw InputError(pc2_path + ": the cache has " + std::to_string(cache.num_points()) + " points; expected " +
                     std::to_string(pairs.num_vertices) + " (the analysed mesh's vertices)");
  }
  int total = cache.num_frames() - options.skip_frames;
  if (options.max_frames > 0) total = std::min(total, options.max_frames);
  if (total <= 0) {
    throw ArgumentError(pc2_path + ": the cache has " + std::to_string(cache.num_frames()) + " frames; skipping " +
                        std::to_string(options.skip_frames) + " leaves none to analyse");
  }
  CurvatureAccumulator accumulator(pairs.num_vertices);
  CurvatureFeatures features;
  features.first_frame = options.skip_frames;
  for (int k = 0; k < total; ++k) {
    const int index = options.skip_frames + k;
    const FramePositions frame = cache.frame(index);
    for (Eigen::Index v = 0; v < frame.rows(); ++v) {
      if (!frame.row(v).allFinite())
        throw InputError(pc2_path + ": frame " + std::to_string(index) + ", point " + std::to_string(v) +
                         " is not finite; expected finite positions");
    }
    accumulator.add(vertex_curvature(pairs, frame));
    if (progress && !progress(k + 1, total)) {
      features.cancelled = true;
      break;
    }
  }
  features.frames = accumulator.frames();
  features.mean = accumulator.mean();
  features.deviation = accumulator.deviation();
  return features;
}

}  // namespace mrcloth
