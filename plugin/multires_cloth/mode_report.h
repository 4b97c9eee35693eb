#pragma once
// What extractModes says and reports: the warnings about the cache the
// modes would be made of (log_line.h: the plugin emits them), its last log
// line and the report object a script gets back. The curvature and the
// clustering are the solver's.
#include "log_line.h"
#include "solver/deformation_modes.h"
#include "solver/instance_curvature.h"

#include <QString>
#include <QVariantMap>

#include <vector>

namespace mrcloth {

/// Warnings about a cache's curvature before it is clustered: a first
/// frame whose neighbours are not at their rest distance (other units,
/// another vertex order or another mesh), or no bending above float
/// rounding. `path` is the cache, `features` analyse_curvature's.
std::vector<LogLine> curvatureCacheWarnings(const QString& path, const CurvatureFeatures& features);

/// The report of extractModes: operation, source (`source`, the object's
/// id), cache (`path`), frames and firstFrame (`features`), vertices
/// (`vertices`, the mesh's), clusters and restarts (`modes`, as asked),
/// normalize, seed, restartKept, iterations, inertia, sizes, centroids,
/// normalizedCentroids, offset, scale (`report`, the clustering's),
/// maxMeanCurvature and milliseconds (`milliseconds`, the whole call's).
QVariantMap modeReportMap(int source, const QString& path, const CurvatureFeatures& features, int vertices,
                          const ModeOptions& modes, const ModeReport& report, double milliseconds);

/// extractModes' last log line: `object` (how the log names it), the
/// frames analysed (`features`), the modes asked for (`modes`), the mesh's
/// `vertices` and each mode's size (`report`).
QString modesFoundLine(const QString& object, const CurvatureFeatures& features, const ModeOptions& modes,
                       int vertices, const ModeReport& report);

}  // namespace mrcloth
