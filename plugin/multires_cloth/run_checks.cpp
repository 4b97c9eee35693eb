#include "run_checks.h"

#include "solver/character_fit.h"

#include <QFileInfo>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrcloth {
namespace {

/// A PC2 cache keeps float32 positions: 24 bits, so a garment far from the
/// origin (1 km: 0.06 mm steps) loses its wrinkles in the file however well
/// it was simulated. Said where a step passes this many metres.
constexpr double kLargestCacheStep = 1e-4;

/// Above this (m/s) a joint of the legs moves between two frames of a clip
/// faster than any stride (fastest_leg_speed: the run 09_01's feet 8.2).
constexpr double kClipLegSpeedWarning = 10.0;

/// Above this (m/s^2) a clip's legs jitter (leg_jitter, the median of the
/// largest leg joint acceleration at a frame): the shared clips 10-32, the
/// run 09_01 64; 07_06 with Gaussian noise per frame on every joint angle
/// 150 (0.1 degrees), 355 (0.25), 710 (0.5: the shared trousers on the
/// skinned body stretched 89 % in one of two runs), 1420 (1: torn, 81-101
/// mm open). Smoothed by 0.01 s all of these held (9-10 %).
constexpr double kLegJitterWarning = 200.0;

/// Above this (m/s) a hip, knee or ankle moves too fast in the pre-roll
/// (preroll_leg_speed): trousers on CMU 07_06 held from 0.1 s (5.6 m/s)
/// and tore below 0.05 s (11 m/s and more).
constexpr double kPrerollLegSpeedWarning = 8.0;

}  // namespace

/// A warning for cloth-cloth contact on a mesh finer than its reach
/// (thickness + reach), empty otherwise: on the shared garments refined
/// twice it cost 7-8 times the body's collision and tore the skirt on
/// capsules (README, Known limits), so a run asking for it hears so before
/// it starts. Refined once (16-20 mm edges) they run whole.
QString selfContactWarning(const QString& slot, const QuadMesh& mesh, const SelfContactOptions& contact) {
  if (!(contact.thickness > 0.0) || mesh.n_edges() == 0) return {};
  double sum = 0.0;
  for (const auto edge : mesh.edges()) sum += mesh.calc_edge_length(edge);
  const double mean_edge = sum / static_cast<double>(mesh.n_edges());
  const double reach = contact.thickness + contact.reach;
  if (mean_edge >= reach) return {};
  return QStringLiteral("%1: cloth-cloth contact (selfContact) on edges of %2 mm on average, shorter than its reach "
                        "(%3 mm, thickness and gathering reach): on garments this fine it has cost 7-8 times the "
                        "body's collision, and torn the shared skirt refined twice on capsules (README, Known limits); "
                        "it is meant for garments refined at most once for now")
      .arg(slot).arg(1000.0 * mean_edge, 0, 'f', 1).arg(1000.0 * reach, 0, 'f', 1);
}

QString cachePrecisionWarning(const QString& slot, const QuadMesh& mesh, const SimulationOptions& settings) {
  if (settings.cache_path.empty()) return {};
  double farthest = 0.0;
  for (const auto v : mesh.vertices())
    for (int k = 0; k < 3; ++k) farthest = std::max(farthest, std::abs(mesh.point(v)[k]));
  const double step = farthest * std::numeric_limits<float>::epsilon();
  if (step <= kLargestCacheStep) return {};
  return QStringLiteral("%1: the garment lies up to %2 m from the origin along an axis, where its PC2 cache (float32 "
                        "positions) keeps steps of %3 mm: its wrinkles are rounded away in the file; move the garment "
                        "to the origin (within %4 m) for a cache as fine as the simulation")
      .arg(slot).arg(farthest, 0, 'g', 4).arg(1000.0 * step, 0, 'g', 2)
      .arg(kLargestCacheStep / std::numeric_limits<float>::epsilon(), 0, 'f', 0);
}

std::vector<LogLine> clipChangeLines(const QString& slot, const CharacterRequest& wanted, const ClipChanges& changes) {
  std::vector<LogLine> lines;
  const JointRenaming& renamed = changes.renamed;
  if (!changes.turned.identity())
    lines.push_back({LOGINFO, QStringLiteral("%1: %2 stands upright with its axes turned (%3)")
                          .arg(slot, QFileInfo(wanted.motionPath).fileName(),
                               QString::fromStdString(changes.turned.describe()))});
  if (!changes.axes_undecided.empty())
    lines.push_back({LOGWARN, QStringLiteral("%1: cannot tell which way %2 stands (%3), so it is read as it is, Y up; "
                                             "rename its joints onto CMU names with motion.joints, or give motion.axes "
                                             "\"asIs\" if it stands Y up")
                                  .arg(slot, QFileInfo(wanted.motionPath).fileName(),
                                       QString::fromStdString(changes.axes_undecided))});
  if (!renamed.empty())
    lines.push_back({LOGINFO, QStringLiteral("%1: %2 joints of %3 renamed onto CMU names (%4 -> %5, ...)")
                          .arg(slot).arg(renamed.size()).arg(QFileInfo(wanted.motionPath).fileName(),
                                                             QString::fromStdString(renamed.begin()->first),
                                                             QString::fromStdString(renamed.begin()->second))});
  return lines;
}

namespace {

/// Warns when the pinned waist is far from the pelvis joint in the rest pose.
void addWaistPlacementWarning(const QString& slot, const SimulationRequest& request, const Motion& motion,
                              const CharacterRunOptions& run, const DynamicsModel& model, std::vector<LogLine>& lines) {
  const int pelvis = motion.skeleton.find(run.pelvis_joint);
  if (model.pinned_vertices.empty()) return;
  Eigen::Vector3d waist = Eigen::Vector3d::Zero();
  for (const int vertex : model.pinned_vertices) waist += model.rest.row(vertex).transpose();
  waist /= static_cast<double>(model.pinned_vertices.size());
  const double distance = (waist - rest_pose(motion.skeleton).position(pelvis)).norm();
  // Placed as on the MakeHuman body, the garment is where its file puts it
  // relative to the body file's: then the files disagree, not the option.
  const bool as_on_body = request.character && request.character->setup.place == GarmentPlacement::makehuman;
  const QString advice =
      as_on_body ? QStringLiteral("placed as on the MakeHuman body (option 'place': \"makehuman\"), the garment's file "
                                  "and the body's do not share their coordinates: a garment modelled on another "
                                  "body, one of the two files moved, or the garment loaded in other units than the "
                                  "body (core.loadObject's units and option 'body.units'; the pipeline's --units and "
                                  "--makehuman-units)")
                 : QStringLiteral("the garment is probably not placed on the character (option 'place': "
                                  "\"makehuman\" for MakeHuman garments, \"firstFrame\" for garments modelled on the "
                                  "clip's frame 0)");
  if (distance > 0.3)
    lines.push_back({LOGWARN, QStringLiteral("%1: the pinned waist is %2 m from the %3 joint in the rest pose: %4")
                                  .arg(slot)
                                  .arg(distance, 0, 'f', 2)
                                  .arg(QString::fromStdString(run.pelvis_joint), advice)});
}

void addStepRateWarning(const QString& slot, const SimulationRequest& request, const CharacterRunOptions& run,
                        std::vector<LogLine>& lines) {
  // Steps come in whole numbers per output frame: 120 asked at 90 fps ran at
  // 90, silently (the report's stepRate said so, after the run).
  const int substeps = steps_per_frame(run);
  if (std::abs(substeps * run.fps - run.step_rate) > 1e-9 * run.step_rate)
    lines.push_back({LOGWARN, QStringLiteral("%1: %2 %3 is no whole number of steps per output frame at %4 fps: the "
                                             "run takes %5 a frame, %6 steps per second (a step rate that is a "
                                             "multiple of %7 keeps the rate asked for)")
                                  .arg(slot, optionCalled(request, QStringLiteral("stepRate"))).arg(run.step_rate)
                                  .arg(run.fps).arg(substeps).arg(substeps * run.fps)
                                  .arg(optionCalled(request, QStringLiteral("fps")))});
}

void addPrerollWarning(const QString& slot, const SimulationRequest& request, const Motion& motion,
                       const CharacterRunOptions& run, std::vector<LogLine>& lines) {
  // A pre-roll too short for the way from the rest pose to the first frame
  // moves the legs faster than any stride: cloth on them tears.
  if (const double speed = preroll_leg_speed(motion, run); speed > kPrerollLegSpeedWarning) {
    CharacterRunOptions one_second = run;
    one_second.preroll_seconds = 1.0;
    const double enough = preroll_leg_speed(motion, one_second) / kPrerollLegSpeedWarning;  // seconds (speed ~ 1 / pre-roll)
    lines.push_back({LOGWARN, QStringLiteral("%1: the pre-roll of %2 s moves the legs from the rest pose to the motion's "
                                     "first frame %3 (a walk's feet: about 4 m/s): cloth on them may tear; "
                                     "%4 %5 s or more keeps them under %6 m/s")
                          .arg(slot).arg(run.preroll_seconds)
                          .arg(std::isfinite(speed) ? QStringLiteral("at up to %1 m/s").arg(speed, 0, 'f', 1)
                                                    : QStringLiteral("in one step"))
                          .arg(optionCalled(request, QStringLiteral("preroll")))
                          .arg(std::ceil(100.0 * enough) / 100.0, 0, 'f', 2).arg(kPrerollLegSpeedWarning, 0, 'f', 0)});
  }
}

/// A glitch or jitter in the capture, within the frames the run plays.
void addCaptureWarnings(const QString& slot, const SimulationRequest& request, const Motion& motion,
                        const CharacterRunOptions& run, std::vector<LogLine>& lines) {
  const int first = static_cast<int>(std::floor(run.motion_start / motion.frame_time));
  // Past the clip's end (in double first: a long run's count of clip
  // frames need not fit in an int).
  const int last = static_cast<int>(std::min(std::ceil((run.motion_start + run.frames / run.fps) / motion.frame_time),
                                             static_cast<double>(motion.frames.rows())));
  const int in_file = request.character->setup.skip_first ? 1 : 0;  // the run's frame 0 is the file's 1
  // Jitter tears below the speed a glitch is told by: said first, with the smoothing that takes it out.
  if (const double jitter = leg_jitter(motion, first, last); jitter > kLegJitterWarning) {
    const double already = request.character->motionSmoothing;
    lines.push_back({LOGWARN, QStringLiteral("%1: the legs of %2 jitter (their largest acceleration at a frame %3 m/s^2 at "
                                     "the median over the frames the run plays; a clean walk's 10-35, a run's about 65): "
                                     "raw capture noise, which tears cloth on the legs; option 'motion.smoothing' %4 s "
                                     "(a Gaussian in time%5) takes it out")
                          .arg(slot, QFileInfo(request.character->motionPath).fileName())
                          .arg(jitter, 0, 'f', 0)
                          .arg(smoothing_against_jitter(motion, already, first, last, 0.5 * kLegJitterWarning))
                          .arg(already > 0.0 ? QStringLiteral("; now %1 s").arg(already) : QString())});
  }
  if (const LegSpeed fastest = fastest_leg_speed(motion, first, last); fastest.speed > kClipLegSpeedWarning)
    lines.push_back({LOGWARN, QStringLiteral("%1: %2 moves its %3 at %4 m/s between its frames %5 and %6 (from 0; a run's "
                                     "feet: about 8): a glitch or jitter in the capture? Cloth on the legs may tear "
                                     "there; smooth or cut the clip (motionInfo's fastestLegSpeed finds such frames)")
                          .arg(slot, QFileInfo(request.character->motionPath).fileName(),
                               QString::fromStdString(fastest.joint))
                          .arg(fastest.speed, 0, 'f', 1).arg(fastest.frame + in_file).arg(fastest.frame + in_file + 1)});
}

/// The report's 'fit' (empty unless the garment is a tube), with a warning
/// when the body needs more girth than the material stretches to.
QVariantMap checkTubeFit(const QString& slot, const SimulationRequest& request, const Character& character,
                         const CharacterRunOptions& run, const DynamicsModel& model, const QuadMesh& garment,
                         std::vector<LogLine>& lines) {
  // A tube garment (two boundary loops: a skirt or dress) too narrow for
  // the motion cannot stay whole within its material's stretch limit:
  // said now, with where, rather than found as a tear after the run.
  QVariantMap fit;
  if (is_tube_garment(garment)) {
    const std::vector<HoopLevel> levels = run_hoop_demand(*character.motion, *character.body, run, garment);
    fit = hoopDemandMap(levels, request.dynamics.material.stretch_limit);
    const int worst_level = most_demanding_level(levels);
    const HoopLevel* worst = worst_level < 0 ? nullptr : &levels[static_cast<std::size_t>(worst_level)];
    if (worst && worst->demand() > request.dynamics.material.stretch_limit && request.character->fitWarning)
      lines.push_back({LOGWARN, QStringLiteral("%1: the body needs %2 % more girth than the garment has %3 m below its top "
                                       "(level %4 of %5, output frame %6), and material '%7' stretches %8 % at "
                                       "most: expect the garment stretched or torn there (a wider garment or a "
                                       "stretchier material fits; the report's 'fit' has every level)")
                            .arg(slot).arg(100.0 * worst->demand(), 0, 'f', 0)
                            .arg(model.rest.col(HoopDemandOptions{}.up_axis).maxCoeff() - worst->height, 0, 'f', 2)
                            .arg(worst_level + 1).arg(levels.size())
                            .arg(worst->frame)
                            .arg(QString::fromStdString(request.dynamics.material.name))
                            .arg(100.0 * request.dynamics.material.stretch_limit, 0, 'f', 0)});
  }
  return fit;
}

void addMotionEndWarning(const QString& slot, const Motion& motion, const CharacterRunOptions& run,
                         std::vector<LogLine>& lines) {
  const double end_time = run.motion_start + run.frames / run.fps;
  if (end_time > motion.duration() + 0.5 / run.fps)
    lines.push_back({LOGWARN, QStringLiteral("%1: the motion ends at %2 s but %3 frames from %4 s run to %5 s; the last "
                                     "frames hold its final pose")
                          .arg(slot).arg(motion.duration(), 0, 'f', 2).arg(run.frames).arg(run.motion_start)
                          .arg(end_time, 0, 'f', 2)});
}

}  // namespace

QVariantMap checkBeforeCharacterRun(const QString& slot, const SimulationRequest& request, const Character& character,
                                    const CharacterRunOptions& run, const DynamicsModel& model,
                                    const QuadMesh& garment, std::vector<LogLine>& lines) {
  const QString contact_warning = selfContactWarning(slot, garment, request.simulation.self_contact);
  if (!contact_warning.isEmpty()) lines.push_back({LOGWARN, contact_warning});
  if (const QString precision = cachePrecisionWarning(slot, garment, request.simulation); !precision.isEmpty())
    lines.push_back({LOGWARN, precision});
  const Motion& motion = *character.motion;
  addWaistPlacementWarning(slot, request, motion, run, model, lines);
  addStepRateWarning(slot, request, run, lines);
  addPrerollWarning(slot, request, motion, run, lines);
  addCaptureWarnings(slot, request, motion, run, lines);
  if (character.capsules_shrunk > 0)
    lines.push_back({LOGINFO, QStringLiteral("%1: %2 of %3 capsules shrunk so the garment starts outside them (fitted "
                                     "capsules stand out of the body where it is narrower than a taper)")
                          .arg(slot).arg(character.capsules_shrunk).arg(character.body_capsules)});
  const QVariantMap fit = checkTubeFit(slot, request, character, run, model, garment, lines);
  addMotionEndWarning(slot, motion, run, lines);
  return fit;
}

}  // namespace mrcloth
