#include "run_report.h"

#include <QFileInfo>

#include <algorithm>

namespace mrcloth {

QVariantMap runOutputsReportMap(const QString& slot, int source, const SimulationRequest& request,
                                const RunOutputs& outputs) {
  QVariantMap map{{QStringLiteral("operation"), slot},
                  {QStringLiteral("source"), source},
                  {QStringLiteral("material"), QString::fromStdString(request.dynamics.material.name)},
                  {QStringLiteral("objFiles"), outputs.obj_files},
                  {QStringLiteral("restMesh"), outputs.rest_mesh}};
  if (outputs.result > 0) map.insert(QStringLiteral("resultId"), outputs.result);
  return map;
}

QVariantMap characterRunReportMap(const CharacterRequest& wanted, const ClipChanges& changes, const QVariantMap& fit,
                                  const GarmentClearance& clearance, const RunOutputs& outputs) {
  QVariantMap joints;
  for (const auto& [from, to] : changes.renamed) joints.insert(QString::fromStdString(from), QString::fromStdString(to));
  QVariantMap map{{QStringLiteral("jointsRenamed"), joints},
                  {QStringLiteral("axesTurned"), QString::fromStdString(changes.turned.describe())},
                  {QStringLiteral("garmentCleared"),
                   QVariantMap{{QStringLiteral("vertices"), clearance.moved},
                               {QStringLiteral("largestMove"), clearance.largest_move}}}};
  if (!fit.isEmpty()) map.insert(QStringLiteral("fit"), fit);
  if (!outputs.body_mesh.isEmpty())
    map.insert({{QStringLiteral("bodyCache"), wanted.bodyOutput}, {QStringLiteral("bodyMesh"), outputs.body_mesh}});
  return map;
}

std::vector<LogLine> simulationOutcomeLines(int source, const SimulationRequest& request,
                                            const SimulationReport& report) {
  std::vector<LogLine> lines;
  const SimulationOptions& settings = request.simulation;
  if (report.initial_penetration > 0.0)
    lines.push_back({LOGWARN, QStringLiteral("simulate: the cloth starts %1 mm inside a collider (or its thickness); "
                                             "it is pushed out on the first step, which stretches it: move the "
                                             "colliders or the garment so they start apart")
                                  .arg(1000.0 * report.initial_penetration, 0, 'f', 1)});
  const QString pinned_warning = pinnedDepthWarning(QStringLiteral("simulate"), report, request);
  if (!pinned_warning.isEmpty()) lines.push_back({LOGWARN, pinned_warning});
  if (report.cancelled)
    lines.push_back({LOGWARN, QStringLiteral("simulate: cancelled after %1 of %2 frames; nothing was written")
                                  .arg(report.frames).arg(settings.frames)});
  else if (report.non_finite)
    lines.push_back({LOGWARN, QStringLiteral("simulate: the simulation became non-finite (NaN or infinity) in frame %1 "
                                             "of %2; nothing was written (try more substeps or a softer material)")
                                  .arg(report.frames + 1).arg(settings.frames)});
  else
    lines.push_back({LOGINFO, QStringLiteral("simulate: object %1: %2 frames, %3 steps, %4 ms/frame (dynamics %5, "
                                             "collision %6), %7, %8%9")
                                  .arg(source).arg(report.frames).arg(report.steps)
                                  .arg(report.mean_frame.total_ms(), 0, 'f', 2)
                                  .arg(report.mean_frame.dynamics_ms, 0, 'f', 2)
                                  .arg(report.mean_frame.collision_ms, 0, 'f', 2).arg(stretchSummary(report))
                                  .arg(penetrationSummary(report))
                                  .arg(report.cache_path.empty()
                                           ? QString()
                                           : QStringLiteral(" -> ") + QString::fromStdString(report.cache_path))});
  return lines;
}

std::vector<LogLine> characterOutcomeLines(const QString& slot, int source, const SimulationRequest& request,
                                           const CharacterRequest& wanted, const CharacterRunReport& report,
                                           const CharacterRunOptions& run, const QString& rest_mesh) {
  std::vector<LogLine> lines;
  const SimulationReport& motion_report = report.motion;
  // Like the fit, where the pins go is the garment's and the motion's, the
  // same for every refinement of one garment (the pipeline says it once).
  const QString pinned_warning = pinnedDepthWarning(slot, motion_report, request);
  if (!pinned_warning.isEmpty() && request.character->fitWarning) lines.push_back({LOGWARN, pinned_warning});
  // Where the garment starts is its own and the body's, the same for every
  // refinement of it, so it is said with the fit (the pipeline: once per
  // motion; the report has initialPenetration either way). Capsules are
  // shrunk to the garment and the skinned mesh clears it before the run,
  // so what is left is cloth modelled within the thickness (the MakeHuman
  // trousers on fitted capsules: 4.3 mm, 0.3 mm past a capsule): said with
  // both depths rather than as a misplacement.
  const double initial = report.preroll.initial_penetration, thickness = wanted.setup.thickness;
  if (initial > 1e-6 && request.character->fitWarning)  // clearing leaves round-off
    lines.push_back({LOGWARN, QStringLiteral("%1: in the rest pose the cloth starts %2 mm inside the body's surface and "
                                             "its %3 mm thickness (%4 mm past the surface); it is pushed out on the "
                                             "first step")
                                  .arg(slot).arg(1000.0 * initial, 0, 'f', 1).arg(1000.0 * thickness, 0, 'f', 1)
                                  .arg(1000.0 * std::max(0.0, initial - thickness), 0, 'f', 1)});
  if (report.preroll.cancelled)
    lines.push_back({LOGWARN, QStringLiteral("%1: cancelled during the pre-roll, after %2 of its %3 frames; nothing "
                                             "was written")
                                  .arg(slot).arg(report.preroll.frames).arg(preroll_frame_count(run))});
  else if (motion_report.cancelled)
    lines.push_back({LOGWARN, QStringLiteral("%1: cancelled after %2 of %3 frames; nothing was written")
                                  .arg(slot).arg(motion_report.frames).arg(run.frames)});
  else if (motion_report.non_finite)
    lines.push_back({LOGWARN, QStringLiteral("%1: the simulation became non-finite (NaN or infinity) %2; nothing was "
                                             "written (try a higher stepRate, a longer preroll or a softer material)")
                                  .arg(slot)
                                  .arg(report.preroll.non_finite ? QStringLiteral("during the pre-roll")
                                                                 : QStringLiteral("in frame %1 of %2")
                                                                       .arg(motion_report.frames + 1).arg(run.frames))});
  else
    lines.push_back({LOGINFO, QStringLiteral("%1: object %2 on %3: pre-roll %4 frames, %5 frames, %6 ms/frame "
                                             "(dynamics %7, collision %8), %9, %10, max waist error %11 m%12%13")
                                  .arg(slot).arg(source).arg(QFileInfo(wanted.motionPath).fileName())
                                  .arg(report.preroll.frames).arg(motion_report.frames)
                                  .arg(motion_report.mean_frame.total_ms(), 0, 'f', 2)
                                  .arg(motion_report.mean_frame.dynamics_ms, 0, 'f', 2)
                                  .arg(motion_report.mean_frame.collision_ms, 0, 'f', 2)
                                  .arg(stretchSummary(motion_report))
                                  .arg(penetrationSummary(motion_report))
                                  .arg(report.max_waist_error, 0, 'g', 3)
                                  .arg(motion_report.cache_path.empty()
                                           ? QString()
                                           : QStringLiteral(" -> ") + QString::fromStdString(motion_report.cache_path))
                                  .arg(rest_mesh.isEmpty() ? QString() : QStringLiteral(" + ") + rest_mesh)});
  return lines;
}

}  // namespace mrcloth
