#pragma once
// What compareResults says and reports: its log line and the report object
// a script gets back. The measures are the solver's (result_comparison.h).
#include "solver/result_comparison.h"

#include <QString>
#include <QVariantMap>

namespace mrcloth {

/// The report of compareResults: operation, source and reference (the two
/// objects' ids), frames, points, regionMode, regionPoints, meanRms,
/// meanP95, maxDistance (metres), wrinkleKept, wrinkleKeptRegion,
/// wrinkleError, wrinkleErrorRegion (ratios), rmsPerFrame and p95PerFrame
/// (metres), cancelled, milliseconds (the whole call's).
QVariantMap comparisonReportMap(int source, int reference, const ComparisonReport& report, double milliseconds);

/// compareResults' log line: `model` and `reference` as the log names
/// them; a cancelled comparison says how far it got, not its numbers (they
/// cover only the frames it reached).
QString comparisonOutcomeLine(const QString& model, const QString& reference, const ComparisonReport& report);

}  // namespace mrcloth
