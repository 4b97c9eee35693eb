#include "mode_report.h"

#include <QStringList>
#include <QVariantList>

namespace mrcloth {
namespace {

/// Below this many times the curvature float rounding alone gives
/// (CurvatureFeatures::rounding_curvature) a cache shows no bending (a still
/// 2 cm grid 100 m off: 0.02-0.06 1/m of noise modes against 4 of rounding;
/// a walking skirt's modes: 30-120 against about 1).
constexpr double kLeastBending = 2.0;

/// An h x 2 matrix (a mode per row) as a list of [mean curvature, deviation] pairs.
QVariantList rows(const Eigen::MatrixXd& matrix) {
  QVariantList list;
  for (Eigen::Index r = 0; r < matrix.rows(); ++r) list.append(QVariant(QVariantList{matrix(r, 0), matrix(r, 1)}));
  return list;
}

}  // namespace

std::vector<LogLine> curvatureCacheWarnings(const QString& path, const CurvatureFeatures& features) {
  std::vector<LogLine> lines;
  if (!(features.first_frame_stretch > 0.8 && features.first_frame_stretch < 1.25))
    lines.push_back({LOGWARN, QStringLiteral("extractModes: in frame %1 of %2 the mesh's neighbouring vertices lie %3 "
                                             "times their rest distance apart (median): a cache in other units, with "
                                             "its vertices in another order, or of another mesh of as many vertices? "
                                             "The curvature reads stretched pairs as flat")
                                  .arg(features.first_frame).arg(path).arg(features.first_frame_stretch, 0, 'g', 3)});
  const double most_bent = features.mean.size() ? features.mean.maxCoeff() : 0.0;
  if (most_bent < kLeastBending * features.rounding_curvature)
    lines.push_back({LOGWARN, QStringLiteral("extractModes: %1 shows no bending: the largest mean curvature is %2 1/m, "
                                             "what single-precision rounding of its positions alone gives (%3 1/m "
                                             "here); the modes would split noise (clusters: 1 says so)")
                                  .arg(path).arg(most_bent, 0, 'g', 3).arg(features.rounding_curvature, 0, 'g', 3)});
  return lines;
}

QVariantMap modeReportMap(int source, const QString& path, const CurvatureFeatures& features, int vertices,
                          const ModeOptions& modes, const ModeReport& report, double milliseconds) {
  QVariantList sizes;
  for (const int size : report.sizes) sizes.append(size);
  return {{QStringLiteral("operation"), QStringLiteral("extractModes")},
          {QStringLiteral("source"), source},
          {QStringLiteral("cache"), path},
          {QStringLiteral("frames"), features.frames},
          {QStringLiteral("firstFrame"), features.first_frame},
          {QStringLiteral("vertices"), vertices},
          {QStringLiteral("clusters"), modes.modes},
          {QStringLiteral("normalize"), QString::fromStdString(normalization_name(report.normalization))},
          {QStringLiteral("seed"), static_cast<qulonglong>(report.seed)},
          {QStringLiteral("restarts"), modes.restarts},
          {QStringLiteral("restartKept"), report.restart},
          {QStringLiteral("iterations"), report.iterations},
          {QStringLiteral("inertia"), report.inertia},
          {QStringLiteral("sizes"), sizes},
          {QStringLiteral("centroids"), rows(report.centroids)},
          {QStringLiteral("normalizedCentroids"), rows(report.normalized_centroids)},
          {QStringLiteral("offset"), QVariantList{report.offset[0], report.offset[1]}},
          {QStringLiteral("scale"), QVariantList{report.scale[0], report.scale[1]}},
          {QStringLiteral("maxMeanCurvature"), features.mean.size() ? features.mean.maxCoeff() : 0.0},
          {QStringLiteral("milliseconds"), milliseconds}};
}

QString modesFoundLine(const QString& object, const CurvatureFeatures& features, const ModeOptions& modes,
                       int vertices, const ModeReport& report) {
  QStringList counts;
  for (const int size : report.sizes) counts << QString::number(size);
  return QStringLiteral("extractModes: %1, %2 frames: %3 modes of %4 vertices (%5)")
      .arg(object).arg(features.frames).arg(modes.modes).arg(vertices).arg(counts.join(QStringLiteral(", ")));
}

}  // namespace mrcloth
