#include "analysis_options.h"

#include "mesh_ops/mode_layer.h"
#include "option_limits.h"
#include "plugin/core/script_values.h"

#include <QStringList>

#include <cstdint>

namespace mrcloth {

ModeRequest parseModeOptions(const QVariant& options) {
  const script::Options given(options, QStringLiteral("extractModes options"),
                              {QStringLiteral("clusters"), QStringLiteral("normalize"), QStringLiteral("seed"),
                               QStringLiteral("restarts"), QStringLiteral("skipFrames"), QStringLiteral("maxFrames")});
  ModeRequest request;
  ModeOptions& modes = request.modes;
  modes.modes = given.integerBetween(QStringLiteral("clusters"), modes.modes, 1, kLargestMode);
  modes.normalization = normalization_from_name(
      given.choice(QStringLiteral("normalize"), QStringLiteral("minmax"), {QStringLiteral("minmax"), QStringLiteral("zscore")})
          .toStdString());
  modes.seed = static_cast<std::uint64_t>(given.integerAtLeast(QStringLiteral("seed"), 1, 0));
  // Each restart is a whole k-means run (a step of the clustering job).
  modes.restarts = given.integerBetween(QStringLiteral("restarts"), modes.restarts, 1, options::kMostRestarts);
  CurvatureAnalysisOptions& analysis = request.analysis;
  analysis.skip_frames = given.integerAtLeast(QStringLiteral("skipFrames"), 0, 0);
  analysis.max_frames = given.has(QStringLiteral("maxFrames"))
                            ? given.integerAtLeast(QStringLiteral("maxFrames"), -1, 1)
                            : -1;
  return request;
}

ComparisonOptions parseComparisonOptions(const QVariant& options) {
  const script::Options given(options, QStringLiteral("compareResults options"),
                              {QStringLiteral("regionMode"), QStringLiteral("maxFrames")});
  ComparisonOptions settings;
  settings.region_mode = given.integerAtLeast(QStringLiteral("regionMode"), settings.region_mode, 1);
  settings.max_frames = given.integerAtLeast(QStringLiteral("maxFrames"), settings.max_frames, 1);
  return settings;
}

}  // namespace mrcloth
