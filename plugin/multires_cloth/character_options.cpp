#include "character_options.h"
#include "option_limits.h"

#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/units.h"
#include "solver/body_capsules.h"
#include "solver/figure_size.h"
#include "solver/motion_filter.h"

#include <QDir>
#include <QFileInfo>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace mrcloth {
namespace {

using options::Fields;
using options::fail;
using options::kLongestPreroll;
using options::kShortestPreroll;
using options::optionLabel;

/// Metres per unit of the CMU BVH files (their default scale).
constexpr double kCmuMetresPerUnit = 0.056444;

/// Runs `body`; an InputError or ArgumentError escaping it is rethrown as
/// the same type with "<label>: " in front, so the error names the option.
/// A FigureSizeError passes unchanged: loadCharacter words it with the file.
template <class Body>
auto naming(const QString& label, Body&& body) -> decltype(body()) {
  const std::string prefix = label.toStdString() + ": ";
  try {
    return body();
  } catch (const FigureSizeError&) {
    throw;
  } catch (const InputError& error) {
    throw InputError(prefix + error.what());
  } catch (const ArgumentError& error) {
    throw ArgumentError(prefix + error.what());
  }
}

QStringList unitNames() {
  return {QStringLiteral("m"), QStringLiteral("cmu"), QStringLiteral("dm"), QStringLiteral("cm"),
          QStringLiteral("mm"), QStringLiteral("inch")};
}

/// The units a body file may be read in (a clip's "cmu" is for clips).
QStringList bodyUnits() {
  QStringList units = unitNames();
  units.removeAll(QStringLiteral("cmu"));
  return units;
}

double metresPerUnit(const QString& units) {
  if (units == QLatin1String("cmu")) return kCmuMetresPerUnit;
  return metres_per_unit(units.toStdString());
}

/// "auto": the units are chosen from the clip's figure (readClip).
const QString kAutoUnits = QStringLiteral("auto");

/// Of unitNames(), the units in which a figure whose legs measure
/// `legs_in_units` (its file's units) comes nearest (by ratio) to
/// `expected_legs` metres; `legs` receives that length in metres.
QString nearestUnits(double legs_in_units, double expected_legs, double* legs = nullptr) {
  QString best;
  double best_error = std::numeric_limits<double>::infinity();
  for (const QString& units : unitNames()) {
    const double metres = legs_in_units * metresPerUnit(units);
    const double error = std::abs(std::log(metres / expected_legs));
    if (error < best_error) {
      best_error = error;
      best = units;
      if (legs) *legs = metres;
    }
  }
  return best;
}

/// motion.joints: "auto" (a known convention renamed onto CMU names),
/// "asIs", or {name in the file: CMU name, ...}.
void parseJointNames(const Fields& fields, CharacterRequest& request) {
  const QString key = QStringLiteral("joints");
  if (!fields.has(key)) return;
  const QVariant value = fields.required(key);
  const QString label = fields.label(key);
  if (value.typeId() == QMetaType::QString) {
    request.conventions.auto_joint_names = fields.choice(key, QStringLiteral("auto"), {QStringLiteral("auto"), QStringLiteral("asIs")}) ==
                             QLatin1String("auto");
    return;
  }
  if (!options::isObjectLike(value) || value.typeId() == QMetaType::QVariantList)
    fail(QStringLiteral("%1 must be \"auto\", \"asIs\" or an object {name in the file: CMU name}, got %2")
             .arg(label, script::describeValue(value)));
  request.conventions.auto_joint_names = false;
  const QVariantMap map = value.toMap();
  for (auto it = map.cbegin(); it != map.cend(); ++it)
    request.conventions.joint_names[it.key().toStdString()] =
        script::toString(it.value(), QStringLiteral("option '%1.%2'").arg(fields.key(key), it.key())).toStdString();
}

void parseMotion(const Fields& top, CharacterRequest& request) {
  const QString key = QStringLiteral("motion");
  const QVariant value = top.required(key);
  if (value.typeId() == QMetaType::QString) {
    request.motionPath = options::existingInputFile(script::toString(value, optionLabel(key)), optionLabel(key));
    request.motionUnits = QStringLiteral("m");
    request.motionScale = 1.0;
    return;
  }
  if (!options::isObjectLike(value))
    fail(QStringLiteral("%1 must be a BVH file path or an object {path, units or scale, skipFirst, start, joints, axes, "
                        "positions, smoothing}, got %2")
             .arg(optionLabel(key), script::describeValue(value)));
  const Fields fields(value, key,
                      {QStringLiteral("path"), QStringLiteral("units"), QStringLiteral("scale"),
                       QStringLiteral("skipFirst"), QStringLiteral("start"), QStringLiteral("joints"),
                       QStringLiteral("axes"), QStringLiteral("positions"), QStringLiteral("smoothing")});
  parseJointNames(fields, request);
  request.positionChannels = fields.choice(QStringLiteral("positions"), QStringLiteral("absolute"),
                                           {QStringLiteral("absolute"), QStringLiteral("relative")}) ==
                                     QLatin1String("relative")
                                 ? PositionChannels::relative
                                 : PositionChannels::absolute;
  request.conventions.auto_axes = fields.choice(QStringLiteral("axes"), QStringLiteral("auto"),
                                   {QStringLiteral("auto"), QStringLiteral("asIs")}) == QLatin1String("auto");
  const QString path = script::toString(fields.required(QStringLiteral("path")), fields.label(QStringLiteral("path")));
  request.motionPath = options::existingInputFile(path, fields.label(QStringLiteral("path")));
  if (fields.has(QStringLiteral("units")) && fields.has(QStringLiteral("scale")))
    fail(QStringLiteral("%1: give either 'units' or 'scale', not both").arg(optionLabel(key)));
  if (fields.has(QStringLiteral("scale"))) {
    request.motionScale = fields.numberFrom(QStringLiteral("scale"), 1.0, 0.0, true);
    request.motionUnits = QStringLiteral("scale %1").arg(request.motionScale);
  } else {
    request.motionUnits = fields.choice(QStringLiteral("units"), QStringLiteral("m"), unitNames() << kAutoUnits);
    request.motionScale = request.motionUnits == kAutoUnits ? 0.0 : metresPerUnit(request.motionUnits);
  }
  if (fields.has(QStringLiteral("skipFirst"))) {
    if (top.has(QStringLiteral("skipFirst")))
      fail(QStringLiteral("give 'skipFirst' either in %1 or at the top level, not both").arg(optionLabel(key)));
    request.setup.skip_first = fields.boolean(QStringLiteral("skipFirst"), request.setup.skip_first);
  }
  request.setup.motion_start = fields.numberFrom(QStringLiteral("start"), request.setup.motion_start, 0.0, false);
  request.motionSmoothing = fields.numberFrom(QStringLiteral("smoothing"), 0.0, 0.0, false);
  // Beyond a second the filter erases the motion itself (a stride takes one).
  if (request.motionSmoothing > kLongestMotionSmoothing)
    fail(QStringLiteral("%1 must be at most %2 s (the Gaussian's standard deviation; 0.01-0.03 s takes mocap jitter "
                        "out), got %3")
             .arg(fields.label(QStringLiteral("smoothing"))).arg(kLongestMotionSmoothing).arg(request.motionSmoothing));
}

/// The types option 'body' (or its 'type') may name.
QStringList bodyTypes() { return {QStringLiteral("capsules"), QStringLiteral("mesh")}; }

/// The MakeHuman body's files, as keys of option 'body'.
QStringList makeHumanFileKeys() {
  return {QStringLiteral("obj"), QStringLiteral("skeleton"), QStringLiteral("weights")};
}

/// body given by name (`value`, a string): only "capsules", as "mesh" needs
/// the MakeHuman files.
CharacterBodyKind bodyByName(const QVariant& value, const QString& key) {
  const QString type = script::toChoice(value, optionLabel(key), bodyTypes());
  if (type == QLatin1String("mesh"))
    fail(QStringLiteral("%1: \"mesh\" needs the MakeHuman files: give {type: \"mesh\", obj, skeleton, weights} "
                        "(base.obj, a .mhskel rig and a .mhw weights file)")
             .arg(optionLabel(key)));
  return CharacterBodyKind::capsules;
}

/// obj, skeleton, weights: all three (the MakeHuman body, read in body.units)
/// or none; type "mesh" needs them.
void parseMakeHumanFiles(const Fields& fields, const QString& key, const QString& type, CharacterSetup& setup) {
  const QStringList files = makeHumanFileKeys();
  QStringList missing;
  for (const QString& file : files)
    if (!fields.has(file)) missing << file;
  if (type == QLatin1String("mesh") && !missing.isEmpty())
    fail(QStringLiteral("%1: type \"mesh\" needs the MakeHuman files obj (base.obj), skeleton (.mhskel) and weights "
                        "(.mhw); missing: %2")
             .arg(optionLabel(key), missing.join(QStringLiteral(", "))));
  if (missing.size() > 0 && missing.size() < files.size())
    fail(QStringLiteral("%1: give all three MakeHuman files (obj, skeleton, weights) to fit the capsules to the "
                        "body, or none; missing: %2")
             .arg(optionLabel(key), missing.join(QStringLiteral(", "))));
  if (missing.isEmpty()) {
    const auto file = [&](const QString& name) {
      return options::existingInputFile(fields.string(name), fields.label(name)).toStdString();
    };
    MakeHumanOptions makehuman;
    makehuman.base_obj = file(QStringLiteral("obj"));
    makehuman.skeleton_file = file(QStringLiteral("skeleton"));
    makehuman.weights_file = file(QStringLiteral("weights"));
    makehuman.metres_per_unit =
        metresPerUnit(fields.choice(QStringLiteral("units"), QStringLiteral("dm"), bodyUnits()));
    setup.makehuman = makehuman;
  } else if (fields.has(QStringLiteral("units"))) {
    fail(QStringLiteral("%1 are the units of the MakeHuman body file (obj): give obj, skeleton and weights with it")
             .arg(fields.label(QStringLiteral("units"))));
  }
}

/// body.legBridges: "auto" or true (automatic), false or 0 (none), or a reach in bones.
void parseLegBridges(const Fields& fields, CharacterSetup& setup) {
  if (!fields.has(QStringLiteral("legBridges"))) return;
  const QString label = fields.label(QStringLiteral("legBridges"));
  const QVariant bridges = fields.required(QStringLiteral("legBridges"));
  if (bridges.typeId() == QMetaType::QString) {
    script::toChoice(bridges, label, {QStringLiteral("auto")});
    setup.leg_bridges = -1.0;
  } else if (bridges.typeId() == QMetaType::Bool) {
    setup.leg_bridges = bridges.toBool() ? -1.0 : 0.0;
  } else {
    const double reach = script::toNumber(bridges, label);
    if (!(reach == 0.0 || (reach >= 0.5 && reach <= 2.0)))
      fail(QStringLiteral("%1 must be \"auto\", false, 0 or a reach from 0.5 to 2 bones below the hips (1: the "
                          "knees, 2: the ankles), got %2")
               .arg(label, script::describeValue(bridges)));
    setup.leg_bridges = reach;
  }
}

/// body.armClearance: "auto" or true (the default clearance), false (the
/// clip's arms as they are), or metres.
void parseArmClearance(const Fields& fields, CharacterSetup& setup) {
  if (!fields.has(QStringLiteral("armClearance"))) return;
  const QString label = fields.label(QStringLiteral("armClearance"));
  const QVariant clearance = fields.required(QStringLiteral("armClearance"));
  if (clearance.typeId() == QMetaType::QString) {
    script::toChoice(clearance, label, {QStringLiteral("auto")});
  } else if (clearance.typeId() == QMetaType::Bool) {
    if (!clearance.toBool()) setup.arm_clearance = -1.0;
  } else {
    const double metres = script::toNumber(clearance, label);
    if (!(metres >= 0.0 && metres <= 0.1))
      fail(QStringLiteral("%1 must be \"auto\", false or a clearance from 0 to 0.1 m, got %2")
               .arg(label, script::describeValue(clearance)));
    setup.arm_clearance = metres;
  }
}

void parseHandMittens(const Fields& fields, const QString& type, CharacterSetup& setup) {
  setup.hand_mittens = fields.boolean(QStringLiteral("handMittens"), setup.hand_mittens);
  if (fields.has(QStringLiteral("handMittens")) && type != QLatin1String("mesh"))
    fail(QStringLiteral("%1 applies to type \"mesh\" (the capsule body has no hands to replace)")
             .arg(fields.label(QStringLiteral("handMittens"))));
}

/// body.waistFollows and body.waistSmoothing, after the MakeHuman files
/// (skinning the waist needs them).
void parseWaist(const Fields& fields, CharacterSetup& setup) {
  if (fields.has(QStringLiteral("waistFollows"))) {
    const QString follows = fields.choice(QStringLiteral("waistFollows"), QStringLiteral("auto"),
                                          {QStringLiteral("auto"), QStringLiteral("pelvis"), QStringLiteral("skin")});
    setup.waist = follows == QLatin1String("pelvis") ? WaistFollows::pelvis
                  : follows == QLatin1String("skin")   ? WaistFollows::skin
                                                       : WaistFollows::automatic;
    if (setup.waist == WaistFollows::skin && !setup.makehuman)
      fail(QStringLiteral("%1 \"skin\" needs a body to skin by: give the MakeHuman files (obj, skeleton, weights)")
               .arg(fields.label(QStringLiteral("waistFollows"))));
  }
  setup.waist_smoothing =
      fields.numberFrom(QStringLiteral("waistSmoothing"), setup.waist_smoothing, 0.0, false);
  if (fields.has(QStringLiteral("waistSmoothing")) &&
      (!setup.makehuman || setup.waist == WaistFollows::pelvis))
    fail(QStringLiteral("%1 applies where the waist follows the skin: give the MakeHuman files (obj, skeleton, "
                        "weights), and no waistFollows \"pelvis\"")
             .arg(fields.label(QStringLiteral("waistSmoothing"))));
}

/// One entry of body.radii (`path` names it, as body.radii.Hips): a
/// radius, or [head, tail].
std::pair<double, double> capsuleRadius(const QVariant& value, const QString& path) {
  const QString entry = QStringLiteral("option '%1'").arg(path);
  std::pair<double, double> radius;
  if (options::isNumber(value)) {
    radius.first = radius.second = script::toNumber(value, entry);
  } else {
    const QVariantList pair = script::toList(value, entry);
    if (pair.size() != 2)
      fail(QStringLiteral("%1 must be a radius or [head, tail] in metres, got %2")
               .arg(entry, script::describeValue(value)));
    radius = {script::toNumber(pair[0], QStringLiteral("option '%1[0]'").arg(path)),
              script::toNumber(pair[1], QStringLiteral("option '%1[1]'").arg(path))};
  }
  if (!(radius.first >= 0.0 && radius.second >= 0.0))
    fail(QStringLiteral("%1 must be >= 0 (0 removes the capsule), got %2").arg(entry, script::describeValue(value)));
  return radius;
}

/// body.radii: {joint name: radius or [head, tail]}, for the capsules only.
void parseCapsuleRadii(const Fields& fields, CharacterSetup& setup) {
  if (!fields.has(QStringLiteral("radii"))) return;
  const QString label = fields.label(QStringLiteral("radii"));
  if (setup.body != CharacterBodyKind::capsules)
    fail(QStringLiteral("%1 applies to capsules only, not to type \"mesh\"").arg(label));
  const QVariant radii = fields.required(QStringLiteral("radii"));
  if (!options::isObjectLike(radii) || radii.typeId() == QMetaType::QVariantList)
    fail(QStringLiteral("%1 must be an object {joint name: radius or [head, tail]}, got %2")
             .arg(label, script::describeValue(radii)));
  const QVariantMap map = radii.toMap();
  for (auto it = map.cbegin(); it != map.cend(); ++it)
    setup.radii[it.key().toStdString()] =
        capsuleRadius(it.value(), QStringLiteral("body.radii.%1").arg(it.key()));
}

void parseBody(const Fields& top, CharacterRequest& request) {
  const QString key = QStringLiteral("body");
  if (!top.has(key)) return;
  const QVariant value = top.required(key);
  if (value.typeId() == QMetaType::QString) {
    request.setup.body = bodyByName(value, key);
    return;
  }
  if (!options::isObjectLike(value))
    fail(QStringLiteral("%1 must be \"capsules\", \"mesh\" or an object {type, obj, skeleton, weights, units, "
                        "thickness, friction}, got %2")
             .arg(optionLabel(key), script::describeValue(value)));
  const Fields fields(value, key, QStringList{QStringLiteral("type")} + makeHumanFileKeys() +
                                      QStringList{QStringLiteral("units"), QStringLiteral("thickness"),
                                                  QStringLiteral("friction"), QStringLiteral("radii"),
                                                  QStringLiteral("legBridges"),
                                                  QStringLiteral("waistFollows"), QStringLiteral("waistSmoothing"),
                                                  QStringLiteral("armClearance"), QStringLiteral("handMittens")});
  const QString type = fields.choice(QStringLiteral("type"), QStringLiteral("capsules"), bodyTypes());
  request.setup.body = type == QLatin1String("mesh") ? CharacterBodyKind::mesh : CharacterBodyKind::capsules;

  parseMakeHumanFiles(fields, key, type, request.setup);
  parseLegBridges(fields, request.setup);
  parseArmClearance(fields, request.setup);
  parseHandMittens(fields, type, request.setup);
  parseWaist(fields, request.setup);
  request.setup.thickness = fields.numberBetween(QStringLiteral("thickness"), request.setup.thickness, 0.0,
                                                  kMostContactThickness, QStringLiteral("m"));
  request.setup.friction = fields.numberFrom(QStringLiteral("friction"), request.setup.friction, 0.0, false);
  parseCapsuleRadii(fields, request.setup);
}

}  // namespace

QStringList characterOptionKeys() {
  return {QStringLiteral("motion"), QStringLiteral("body"),    QStringLiteral("place"),
          QStringLiteral("waist"),  QStringLiteral("preroll"), QStringLiteral("stepRate"),
          QStringLiteral("skipFirst"), QStringLiteral("bodyOutput"), QStringLiteral("fitWarning")};
}

CharacterRequest parseCharacterOptions(const Fields& fields, double fps) {
  CharacterRequest request;
  request.setup.skip_first = fields.boolean(QStringLiteral("skipFirst"), request.setup.skip_first);
  request.fitWarning = fields.boolean(QStringLiteral("fitWarning"), request.fitWarning);
  parseMotion(fields, request);
  parseBody(fields, request);

  const QString place = fields.choice(QStringLiteral("place"), QStringLiteral("none"),
                                      {QStringLiteral("none"), QStringLiteral("makehuman"), QStringLiteral("firstFrame")});
  if (place == QLatin1String("makehuman")) {
    if (!request.setup.makehuman)
      fail(QStringLiteral("%1: \"makehuman\" moves the garment by the MakeHuman body's offset, so option 'body' must "
                          "give the MakeHuman files {obj, skeleton, weights}")
               .arg(fields.label(QStringLiteral("place"))));
    request.setup.place = GarmentPlacement::makehuman;
  } else if (place == QLatin1String("firstFrame")) {
    request.setup.place = GarmentPlacement::first_frame;
  }

  request.setup.preroll_seconds = fields.numberFrom(QStringLiteral("preroll"), request.setup.preroll_seconds, 0.0, false);
  const double preroll = request.setup.preroll_seconds;
  if (preroll > kLongestPreroll || (preroll > 0.0 && preroll < kShortestPreroll))
    fail(QStringLiteral("%1 must be 0 or a number of seconds from %2 to %3, got %4")
             .arg(fields.label(QStringLiteral("preroll")))
             .arg(kShortestPreroll)
             .arg(kLongestPreroll)
             .arg(preroll));
  request.setup.step_rate = fields.numberFrom(QStringLiteral("stepRate"), request.setup.step_rate, 0.0, true);
  if (request.setup.step_rate < fps)
    fail(QStringLiteral("%1 must be at least option 'fps' (%2 frames per second), got %3%4")
             .arg(fields.label(QStringLiteral("stepRate"))).arg(fps).arg(request.setup.step_rate)
             .arg(fields.has(QStringLiteral("stepRate")) ? QString()
                                                         : QStringLiteral(" (its default: give a step rate of at least %1)").arg(fps)));
  // Progress and Ctrl-C come between frames: a frame's work is bounded.
  if (request.setup.step_rate > kMostStepsPerFrame * fps)
    fail(QStringLiteral("%1 must be at most %2 steps per output frame (%2 x option 'fps' = %3), got %4")
             .arg(fields.label(QStringLiteral("stepRate")))
             .arg(kMostStepsPerFrame)
             .arg(kMostStepsPerFrame * fps)
             .arg(request.setup.step_rate));
  return request;
}

namespace {

/// The request's clip in metres, its joints renamed and its axes turned
/// (standardise_clip; `changes` receives what that did), frame 0 kept. Units
/// "auto" are resolved here (the request then says "auto: cm"): the file is
/// read once in its own units, measured, and scaled.
Motion readClipAsRecorded(CharacterRequest& request, ClipChanges& changes) {
  const QString motion_label = optionLabel(QStringLiteral("motion"));
  const bool automatic = request.motionUnits == kAutoUnits;
  BvhReadOptions read_options;
  read_options.scale = automatic ? 1.0 : request.motionScale;
  read_options.skip_first_frame = false;  // frame 0 is needed for place "firstFrame"; make_character drops it
  read_options.position_channels = request.positionChannels;
  Motion clip = naming(motion_label, [&] { return read_bvh(request.motionPath.toStdString(), read_options); });
  // Every later step reads joints by their CMU names, the body standing Y up.
  // Its errors (a joint map naming no joint, two joints alike) name the clip.
  changes = naming(QStringLiteral("%1: %2").arg(motion_label, QDir::toNativeSeparators(request.motionPath)),
                   [&] { return standardise_clip(clip, request.conventions); });
  if (!automatic) return clip;
  const FigureScale figure = figure_scale(clip.skeleton);
  if (!(figure.legs > 0.0))
    throw InputError(QStringLiteral("%1: %2 has %3 (LeftUpLeg to LeftFoot, RightUpLeg to RightFoot, "
                                    "after renaming), so units \"auto\" cannot choose; give the units")
                         .arg(motion_label, QDir::toNativeSeparators(request.motionPath),
                              figure.measured ? QStringLiteral("legs of length 0 (its rest pose puts hip and ankle at "
                                                               "one point)")
                                              : QStringLiteral("no legs to measure"))
                         .toStdString());
  const QString units = nearestUnits(figure.legs, kReferenceLegs);
  request.motionUnits = QStringLiteral("auto: %1").arg(units);
  request.motionScale = metresPerUnit(units);
  scale_motion(clip, request.motionScale);  // the same numbers as reading it in those units
  return clip;
}

/// The clip as readClipAsRecorded reads it, smoothed as motion.smoothing says.
Motion readClip(CharacterRequest& request, ClipChanges& changes) {
  Motion clip = readClipAsRecorded(request, changes);
  // Frame 0 of a clip whose first frame is skipped (CMU's added T-pose) is
  // no part of the motion: not smoothed into it.
  smooth_motion(clip, request.motionSmoothing, request.setup.skip_first ? 1 : 0);
  return clip;
}

/// The largest side of the garment's bounding box, metres.
double garment_span(const QuadMesh& garment) {
  OpenMesh::Vec3d low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (const auto v : garment.vertices()) {
    low.minimize(garment.point(v));
    high.maximize(garment.point(v));
  }
  return garment.n_vertices() > 0 ? (high - low).max() : 0.0;
}

}  // namespace

Character loadCharacter(CharacterRequest& request, const QuadMesh& garment, ClipChanges* changes) {
  // A garment loaded in the wrong units (centimetres read as metres: a
  // 54 m skirt) would run to the end far from the body or crushed onto it.
  const double span = garment_span(garment);
  if (!(span >= kGarmentSpanLow && span <= kGarmentSpanHigh))
    throw InputError(QStringLiteral("the garment spans %1 m (its bounding box's largest side); expected %2-%3 m for a "
                                    "garment worn by a person: check the units it was loaded in (core.loadObject's "
                                    "units; the pipeline's --units)")
                         .arg(span, 0, 'g', 3).arg(kGarmentSpanLow).arg(kGarmentSpanHigh)
                         .toStdString());
  const CharacterSetup& setup = request.setup;
  const QString motion_label = optionLabel(QStringLiteral("motion"));
  ClipChanges changed;
  Motion full = readClip(request, changed);
  if (changes) *changes = changed;

  // What make_character refuses, said here with the file and the option.
  const QString file = QDir::toNativeSeparators(request.motionPath);
  const CharacterRunOptions defaults;
  if (full.skeleton.joints.empty() || full.frames.rows() < 1)
    throw InputError(QStringLiteral("%1: %2 has no joints or no frames").arg(motion_label, file).toStdString());
  if (full.skeleton.find(defaults.pelvis_joint) < 0) {
    // The joint to suggest: one whose name says pelvis or hips, else the
    // first with position channels (the one that carries the figure).
    const auto& joints = full.skeleton.joints;
    const auto says_pelvis = [](const Joint& j) {
      const QString name = QString::fromStdString(j.name).toLower();
      return !j.end_site && (name.contains(QLatin1String("hip")) || name.contains(QLatin1String("pelvis")));
    };
    const auto moves = [](const Joint& j) { return std::any_of(j.channels.begin(), j.channels.end(), is_position); };
    auto suggested = std::find_if(joints.begin(), joints.end(), says_pelvis);
    if (suggested == joints.end()) suggested = std::find_if(joints.begin(), joints.end(), moves);
    if (suggested == joints.end()) suggested = joints.begin();
    throw InputError(QStringLiteral("%1: %2 has no joint '%3', which the pinned waist follows (rename the joints "
                                    "onto the CMU MotionBuilder names with %4 {name in the file: CMU name, ...}, e.g. "
                                    "{\"%5\": \"%3\"}; \"auto\" knows the DAZ/Poser and Mixamo names)")
                         .arg(motion_label, file, QString::fromStdString(defaults.pelvis_joint),
                              optionLabel(QStringLiteral("motion.joints")), QString::fromStdString(suggested->name))
                         .toStdString());
  }
  if (setup.skip_first && full.frames.rows() < 2)
    throw InputError(QStringLiteral("%1: %2 has a single frame, so skipFirst leaves nothing (set skipFirst: false)")
                         .arg(motion_label, file)
                         .toStdString());
  const double duration = (setup.skip_first ? without_first_frame(full) : full).duration();
  if (setup.motion_start > duration + 1e-9)
    fail(QStringLiteral("option 'motion.start' must be at most the clip's length, %1 s, got %2 s")
             .arg(duration, 0, 'f', 3).arg(setup.motion_start));
  for (const auto& [name, radii] : setup.radii)
    if (full.skeleton.find(name) < 0)
      fail(QStringLiteral("option 'body.radii.%1': the motion's skeleton has no joint of that name")
               .arg(QString::fromStdString(name)));
  try {
    return naming(optionLabel(QStringLiteral("body")), [&] { return make_character(full, setup, garment); });
  } catch (const FigureSizeError& error) {
    throw InputError(figureRefusal(request, error.scale).toStdString());
  }
}

MotionReading readMotion(const QVariant& motion) {
  MotionReading reading;
  parseMotion(Fields(QVariantMap{{QStringLiteral("motion"), motion}}, QString(), {QStringLiteral("motion")},
                     QStringLiteral("motionInfo")),
              reading.request);
  reading.clip = readClip(reading.request, reading.changes);
  reading.figure = figure_scale(reading.clip.skeleton);
  if (!plausible(reading.figure)) throw InputError(figureRefusal(reading.request, reading.figure).toStdString());
  return reading;
}

QString figureRefusal(const CharacterRequest& request, const FigureScale& figure) {
  // Said with the file and its units, and the units that would fit.
  double fitting_legs = 0.0;
  const QString fitting = nearestUnits(figure.legs / request.motionScale, figure.expected, &fitting_legs);
  FigureScale refitted = figure;
  refitted.legs = fitting_legs;
  const QString hint = fitting != request.motionUnits && plausible(refitted)
                           ? QStringLiteral("; in '%1' they are %2 m (units \"auto\" picks that)")
                                 .arg(fitting).arg(fitting_legs, 0, 'f', 2)
                           : QString();
  const QString expected = figure.against_body
                               ? QStringLiteral("%1-%2").arg(1.0 / kBodyFactorLimit, 0, 'f', 2).arg(kBodyFactorLimit)
                               : QStringLiteral("%1-%2").arg(kReferenceFactorLow).arg(kReferenceFactorHigh);
  const QString read_in = request.motionUnits.startsWith(QLatin1String("scale"))
                              ? QStringLiteral("at scale %1 m per unit").arg(request.motionScale)
                              : QStringLiteral("in units '%1' (%2 m per unit)").arg(request.motionUnits).arg(request.motionScale);
  return QStringLiteral("%1: %2 read %3: %4; expected %5 times: check the units%6")
      .arg(optionLabel(QStringLiteral("motion")), QDir::toNativeSeparators(request.motionPath), read_in,
           QString::fromStdString(describe(figure)), expected, hint);
}

QString bodyTypeName(CharacterBodyKind type) {
  return type == CharacterBodyKind::mesh ? QStringLiteral("mesh") : QStringLiteral("capsules");
}

QString placementName(GarmentPlacement place) {
  switch (place) {
    case GarmentPlacement::makehuman: return QStringLiteral("makehuman");
    case GarmentPlacement::first_frame: return QStringLiteral("firstFrame");
    case GarmentPlacement::none: break;
  }
  return QStringLiteral("none");
}

QVariantMap characterReportMap(const CharacterRunReport& report, const CharacterRequest& request,
                               const Character& character, const CharacterRunOptions& run) {
  const SimulationReport& pre = report.preroll;
  const int substeps = steps_per_frame(run);
  const Eigen::Vector3d shift = character.placement.translation();
  QVariantMap map{
      {QStringLiteral("preroll"),
       QVariantMap{{QStringLiteral("seconds"), request.setup.preroll_seconds},
                   {QStringLiteral("frames"), pre.frames},
                   {QStringLiteral("steps"), pre.steps},
                   {QStringLiteral("msPerFrame"), QVariantMap{{QStringLiteral("dynamics"), pre.mean_frame.dynamics_ms},
                                                              {QStringLiteral("collision"), pre.mean_frame.collision_ms},
                                                              {QStringLiteral("total"), pre.mean_frame.total_ms()}}},
                   {QStringLiteral("maxStretch"), pre.max_stretch},
                   {QStringLiteral("maxPenetration"), pre.max_penetration},
                   {QStringLiteral("maxDepth"), pre.max_depth},
                   {QStringLiteral("initialPenetration"), pre.initial_penetration},
                   {QStringLiteral("nonFinite"), pre.non_finite}}},
      {QStringLiteral("maxWaistError"), report.max_waist_error},
      {QStringLiteral("armsOpened"), QVariantMap{{QStringLiteral("maxDegrees"), report.max_arm_angle * 180.0 / M_PI},
                                                 {QStringLiteral("steps"), report.arm_steps},
                                                 {QStringLiteral("clearance"), request.setup.arm_clearance >= 0.0
                                                                                   ? QVariant(request.setup.arm_clearance)
                                                                                   : QVariant(false)}}},
      {QStringLiteral("body"), bodyTypeName(request.setup.body)},
      {QStringLiteral("motion"), request.motionPath},
      {QStringLiteral("motionUnits"), request.motionUnits},
      {QStringLiteral("motionStart"), request.setup.motion_start},
      {QStringLiteral("motionDuration"), character.motion->duration()},
      {QStringLiteral("skipFirst"), request.setup.skip_first},
      {QStringLiteral("place"), placementName(request.setup.place)},
      {QStringLiteral("placement"), QVariantList{shift.x(), shift.y(), shift.z()}},
      {QStringLiteral("stepRate"), substeps * run.fps},
      {QStringLiteral("legBridges"), character.leg_bridges},
      {QStringLiteral("capsulesShrunk"), character.capsules_shrunk},
      {QStringLiteral("waistFollows"), character.waist_skin ? QStringLiteral("skin") : QStringLiteral("pelvis")},
      {QStringLiteral("waistSmoothing"), character.waist_skin ? request.setup.waist_smoothing : 0.0},
  };
  if (request.setup.body == CharacterBodyKind::mesh) {
    map.insert(QStringLiteral("bodyVertices"), character.body_vertices);
    map.insert(QStringLiteral("handMittens"), character.hand_mittens);
  } else {
    map.insert(QStringLiteral("capsules"), character.body_capsules);
  }
  return map;
}

QVariantMap hoopDemandMap(const std::vector<HoopLevel>& levels, double stretch_limit) {
  QVariantList list;
  for (const HoopLevel& level : levels) {
    const double demand = level.demand();
    list << QVariantMap{{QStringLiteral("height"), level.height},
                        {QStringLiteral("garmentGirth"), level.garment_girth},
                        {QStringLiteral("bodyGirth"), level.body_girth},
                        {QStringLiteral("demand"), std::isfinite(demand) ? QVariant(demand) : QVariant()},
                        {QStringLiteral("frame"), level.frame}};
  }
  const int worst = most_demanding_level(levels);
  return {{QStringLiteral("levels"), list},
          {QStringLiteral("largestDemand"), worst < 0 ? QVariant() : QVariant(levels[static_cast<std::size_t>(worst)].demand())},
          {QStringLiteral("stretchLimit"), stretch_limit}};
}

}  // namespace mrcloth
