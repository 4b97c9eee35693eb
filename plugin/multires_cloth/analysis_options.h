#pragma once
// The options of the analysis slots, extractModes and compareResults, read
// from a script's object and checked (script errors name the option).
#include "solver/deformation_modes.h"
#include "solver/instance_curvature.h"
#include "solver/result_comparison.h"

#include <QVariant>

namespace mrcloth {

/// What extractModes is asked for: the clustering and the frames analysed.
struct ModeRequest {
  ModeOptions modes;                   ///< clusters, normalize, seed, restarts
  CurvatureAnalysisOptions analysis;   ///< skipFrames, maxFrames
};

/// extractModes' `options` (an object, or undefined for the defaults).
ModeRequest parseModeOptions(const QVariant& options);

/// compareResults' `options`: regionMode, maxFrames.
ComparisonOptions parseComparisonOptions(const QVariant& options);

}  // namespace mrcloth
