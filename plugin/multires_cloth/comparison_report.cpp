#include "comparison_report.h"

#include <QVariantList>

namespace mrcloth {

QVariantMap comparisonReportMap(int source, int reference, const ComparisonReport& report, double milliseconds) {
  QVariantList rms, p95;
  for (const DistanceStats& d : report.per_frame) {
    rms << d.rms;
    p95 << d.p95;
  }
  return {{QStringLiteral("operation"), QStringLiteral("compareResults")},
          {QStringLiteral("source"), source},
          {QStringLiteral("reference"), reference},
          {QStringLiteral("frames"), report.frames},
          {QStringLiteral("points"), report.points},
          {QStringLiteral("regionMode"), report.region_mode},
          {QStringLiteral("regionPoints"), report.region_points},
          {QStringLiteral("meanRms"), report.mean_rms},
          {QStringLiteral("meanP95"), report.mean_p95},
          {QStringLiteral("maxDistance"), report.max_distance},
          {QStringLiteral("wrinkleKept"), report.wrinkle_kept},
          {QStringLiteral("wrinkleKeptRegion"), report.wrinkle_kept_region},
          {QStringLiteral("wrinkleError"), report.wrinkle_error},
          {QStringLiteral("wrinkleErrorRegion"), report.wrinkle_error_region},
          {QStringLiteral("rmsPerFrame"), rms},
          {QStringLiteral("p95PerFrame"), p95},
          {QStringLiteral("cancelled"), report.cancelled},
          {QStringLiteral("milliseconds"), milliseconds}};
}

QString comparisonOutcomeLine(const QString& model, const QString& reference, const ComparisonReport& report) {
  if (report.cancelled)
    return QStringLiteral("compareResults: %1 against %2 cancelled after %3 frames").arg(model, reference).arg(report.frames);
  return QStringLiteral("compareResults: %1 against %2 over %3 frames: RMS %4 mm, p95 %5 mm, max %6 mm; "
                        "wrinkle energy kept %7 % (mode-%8 region: %9 %), error %10 (region %11)")
      .arg(model, reference).arg(report.frames)
      .arg(1000.0 * report.mean_rms, 0, 'f', 2).arg(1000.0 * report.mean_p95, 0, 'f', 2)
      .arg(1000.0 * report.max_distance, 0, 'f', 2).arg(100.0 * report.wrinkle_kept, 0, 'f', 1)
      .arg(report.region_mode).arg(100.0 * report.wrinkle_kept_region, 0, 'f', 1)
      .arg(report.wrinkle_error, 0, 'f', 3).arg(report.wrinkle_error_region, 0, 'f', 3);
}

}  // namespace mrcloth
