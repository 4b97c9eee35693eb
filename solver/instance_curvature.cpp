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

/// Below this x, 1 - sinc(x) comes from its series: the closed form
/// cancels there.
constexpr double kSeriesBelow = 1.0;

/// 1 - sinc(x) = sum_{n >= 1} kSeries[n - 1] x^(2n), kSeries[n - 1] =
/// (-1)^(n+1) / (2n+1)!; 15 terms reach 1e-17 at x = pi.
constexpr int kSeriesTerms = 15;
constexpr double kSeries[kSeriesTerms] = {
    1.0 / 6.0, -1.0 / 120.0, 1.0 / 5040.0, -1.0 / 362880.0, 1.0 / 39916800.0, -1.0 / 6227020800.0,
    1.0 / 1307674368000.0, -1.0 / 355687428096000.0, 1.0 / 121645100408832000.0, -1.0 / 51090942171709440000.0,
    1.0 / 25852016738884976640000.0, -1.0 / 15511210043330985984000000.0, 1.0 / 10888869450418352160768000000.0,
    -1.0 / 8841761993739701954543616000000.0, 1.0 / 8222838654177922817725562880000000.0};

/// 1 - sinc(x) and its slope (sin x - x cos x) / x^2 (> 0 on (0, pi]),
/// together, for a Newton step.
struct Residual {
  double value, slope;
};

Residual one_minus_sinc_with_slope(double x) {
  // Both from their Taylor series in y = x^2, to n = 15 over [0, pi]: no
  // trigonometry (the series' largest term at pi is 1.6, so round-off stays
  // at 1e-16), and for small x no cancellation either.
  const double y = x * x;
  double value = 0.0, slope = 0.0;
  // Below x = 1 ten terms already reach 1e-22 (most cloth bends gently).
  for (int n = x < 1.0 ? 10 : kSeriesTerms; n >= 1; --n) {
    value = value * y + kSeries[n - 1];
    slope = slope * y + 2.0 * n * kSeries[n - 1];
  }
  return {value * y, slope * x};
}

/// A start for Newton, within 2.1e-5 relative of sinc^-1(1 - s) over
/// (0, 1]: the series s = x^2/6 - x^4/120 + x^6/5040 inverted to third
/// order, x^2 = 6 s + 9/5 s^2 + 288/350 s^3, for small s; above, x / sqrt(s)
/// as a degree-10 polynomial in sqrt(s) (least squares on 400 Chebyshev
/// nodes, worst relative error 2.1e-5): x(sqrt(s)) is smooth on [0, 1].
double newton_start(double s) {
  if (s < 0.05) return std::sqrt(s * (6.0 + s * (1.8 + s * (288.0 / 350.0))));
  constexpr double c[] = {2.4495134132202683, -0.0053696992794620233, 0.56775591507207102, -2.8854577801989882,
                          21.166395298498067, -87.760712502664489,    222.68154296102318,  -349.23298579271255,
                          331.26900830025983, -174.25830375952387,    39.150141110811212};
  const double t = std::sqrt(s);
  double p = 0.0;
  for (int k = 10; k >= 0; --k) p = p * t + c[k];
  return std::min(kPi, p * t);
}

}  // namespace

double one_minus_sinc(double x) {
  x = std::abs(x);
  if (x >= kSeriesBelow) return 1.0 - std::sin(x) / x;
  // The series to n = 10: the next term is below 1e-19 of the sum for x < 1.
  const double y = x * x;
  double sum = 0.0;
  for (int n = 10; n >= 1; --n) sum = sum * y + kSeries[n - 1];
  return sum * y;
}

double inverse_sinc(double ratio) {
  if (std::isnan(ratio)) throw ArgumentError("inverse_sinc: the ratio is NaN; expected a number");
  if (ratio >= 1.0) return 0.0;
  if (ratio <= 0.0) return kPi;
  // Solve 1 - sinc(x) = s with s = 1 - ratio (exact for ratio >= 0.5), so a
  // ratio within 1e-12 of 1 keeps its digits: Newton from a start within
  // 2.1e-5 (two steps, one for the nearly straight pairs of most cloth), kept
  // inside a bracket that every step narrows (1 - sinc increases on [0, pi]).
  const double s = 1.0 - ratio;
  double lo = 0.0, hi = kPi;
  double x = newton_start(s);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Residual r = one_minus_sinc_with_slope(x);
    const double residual = r.value - s;
    if (residual == 0.0) return x;
    if (residual > 0.0) hi = x;
    else lo = x;
    const double step = residual / r.slope;
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

double median_pair_stretch(const CurvaturePairs& pairs, const FramePositions& frame) {
  if (pairs.i.empty()) return 1.0;
  std::vector<double> ratios(pairs.i.size());
  for (std::size_t k = 0; k < pairs.i.size(); ++k)
    ratios[k] = (frame.row(pairs.i[k]) - frame.row(pairs.j[k])).norm() / (2.0 * pairs.half_rest[k]);
  const auto middle = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
  std::nth_element(ratios.begin(), middle, ratios.end());
  return *middle;
}

double rounding_curvature(const CurvaturePairs& pairs, const FramePositions& frame) {
  if (pairs.half_rest.empty() || frame.rows() == 0) return 0.0;
  std::vector<double> lengths(pairs.half_rest.begin(), pairs.half_rest.end());
  const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  const double length = 2.0 * *middle;
  const double largest = frame.cwiseAbs().maxCoeff();
  constexpr double kHalfUlp = 6e-8;  // float32
  return 2.0 * std::sqrt(6.0 * kHalfUlp * largest / length) / length;
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
    const FramePositions frame = cache.finite_frame(index);
    if (k == 0) {
      features.first_frame_stretch = median_pair_stretch(pairs, frame);
      features.rounding_curvature = rounding_curvature(pairs, frame);
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
