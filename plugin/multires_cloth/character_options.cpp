#include "character_options.h"

#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/units.h"
#include "solver/body_capsules.h"

#include <QDir>
#include <QFileInfo>

#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace mrcloth {
namespace {

using options::Fields;
using options::fail;
using options::optionLabel;

/// Metres per unit of the CMU BVH files (their default scale).
constexpr double kCmuMetresPerUnit = 0.056444;

/// Runs `body`; an InputError or ArgumentError escaping it is rethrown as
/// the same type with "<label>: " in front, so the error names the option.
template <class Body>
auto naming(const QString& label, Body&& body) -> decltype(body()) {
  const std::string prefix = label.toStdString() + ": ";
  try {
    return body();
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

double metresPerUnit(const QString& units) {
  if (units == QLatin1String("cmu")) return kCmuMetresPerUnit;
  return metres_per_unit(units.toStdString());
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
    fail(QStringLiteral("%1 must be a BVH file path or an object {path, units or scale, skipFirst, start}, got %2")
             .arg(optionLabel(key), script::describeValue(value)));
  const Fields fields(value, key,
                      {QStringLiteral("path"), QStringLiteral("units"), QStringLiteral("scale"),
                       QStringLiteral("skipFirst"), QStringLiteral("start")});
  const QString path = script::toString(fields.required(QStringLiteral("path")), fields.label(QStringLiteral("path")));
  request.motionPath = options::existingInputFile(path, fields.label(QStringLiteral("path")));
  if (fields.has(QStringLiteral("units")) && fields.has(QStringLiteral("scale")))
    fail(QStringLiteral("%1: give either 'units' or 'scale', not both").arg(optionLabel(key)));
  if (fields.has(QStringLiteral("scale"))) {
    request.motionScale = fields.numberFrom(QStringLiteral("scale"), 1.0, 0.0, true);
    request.motionUnits = QStringLiteral("scale %1").arg(request.motionScale);
  } else {
    request.motionUnits = fields.choice(QStringLiteral("units"), QStringLiteral("m"), unitNames());
    request.motionScale = metresPerUnit(request.motionUnits);
  }
  if (fields.has(QStringLiteral("skipFirst"))) {
    if (top.has(QStringLiteral("skipFirst")))
      fail(QStringLiteral("give 'skipFirst' either in %1 or at the top level, not both").arg(optionLabel(key)));
    request.skipFirst = fields.boolean(QStringLiteral("skipFirst"), request.skipFirst);
  }
  request.motionStart = fields.numberFrom(QStringLiteral("start"), request.motionStart, 0.0, false);
}

void parseBody(const Fields& top, CharacterRequest& request) {
  const QString key = QStringLiteral("body");
  const QStringList types = {QStringLiteral("capsules"), QStringLiteral("mesh")};
  if (!top.has(key)) return;
  const QVariant value = top.required(key);
  if (value.typeId() == QMetaType::QString) {
    const QString type = script::toChoice(value, optionLabel(key), types);
    if (type == QLatin1String("mesh"))
      fail(QStringLiteral("%1: \"mesh\" needs the MakeHuman files: give {type: \"mesh\", obj, skeleton, weights} "
                          "(base.obj, a .mhskel rig and a .mhw weights file)")
               .arg(optionLabel(key)));
    request.body = CharacterBodyType::capsules;
    return;
  }
  if (!options::isObjectLike(value))
    fail(QStringLiteral("%1 must be \"capsules\", \"mesh\" or an object {type, obj, skeleton, weights, thickness, "
                        "friction}, got %2")
             .arg(optionLabel(key), script::describeValue(value)));
  const QStringList files = {QStringLiteral("obj"), QStringLiteral("skeleton"), QStringLiteral("weights")};
  const Fields fields(value, key, QStringList{QStringLiteral("type")} + files +
                                      QStringList{QStringLiteral("thickness"), QStringLiteral("friction"),
                                                  QStringLiteral("radii"), QStringLiteral("legBridges"),
                                                  QStringLiteral("waistFollows"), QStringLiteral("armClearance")});
  const QString type = fields.choice(QStringLiteral("type"), QStringLiteral("capsules"), types);
  request.body = type == QLatin1String("mesh") ? CharacterBodyType::mesh : CharacterBodyType::capsules;

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
    request.hasMakeHuman = true;
    const auto file = [&](const QString& name) {
      return options::existingInputFile(fields.string(name), fields.label(name)).toStdString();
    };
    request.makehuman.base_obj = file(QStringLiteral("obj"));
    request.makehuman.skeleton_file = file(QStringLiteral("skeleton"));
    request.makehuman.weights_file = file(QStringLiteral("weights"));
  }
  if (fields.has(QStringLiteral("legBridges"))) {
    const QString label = fields.label(QStringLiteral("legBridges"));
    const QVariant bridges = fields.required(QStringLiteral("legBridges"));
    if (bridges.typeId() == QMetaType::QString) {
      script::toChoice(bridges, label, {QStringLiteral("auto")});
      request.legBridges = -1.0;
    } else if (bridges.typeId() == QMetaType::Bool) {
      request.legBridges = bridges.toBool() ? -1.0 : 0.0;
    } else {
      const double reach = script::toNumber(bridges, label);
      if (!(reach == 0.0 || (reach >= 0.5 && reach <= 2.0)))
        fail(QStringLiteral("%1 must be \"auto\", false, 0 or a reach from 0.5 to 2 bones below the hips (1: the "
                            "knees, 2: the ankles), got %2")
                 .arg(label, script::describeValue(bridges)));
      request.legBridges = reach;
    }
  }
  if (fields.has(QStringLiteral("armClearance"))) {
    const QString label = fields.label(QStringLiteral("armClearance"));
    const QVariant clearance = fields.required(QStringLiteral("armClearance"));
    if (clearance.typeId() == QMetaType::QString) {
      script::toChoice(clearance, label, {QStringLiteral("auto")});
    } else if (clearance.typeId() == QMetaType::Bool) {
      if (!clearance.toBool()) request.armClearance = -1.0;
    } else {
      const double metres = script::toNumber(clearance, label);
      if (!(metres >= 0.0 && metres <= 0.1))
        fail(QStringLiteral("%1 must be \"auto\", false or a clearance from 0 to 0.1 m, got %2")
                 .arg(label, script::describeValue(clearance)));
      request.armClearance = metres;
    }
  }
  if (fields.has(QStringLiteral("waistFollows"))) {
    const QString follows = fields.choice(QStringLiteral("waistFollows"), QStringLiteral("auto"),
                                          {QStringLiteral("auto"), QStringLiteral("pelvis"), QStringLiteral("skin")});
    request.waistFollows = follows == QLatin1String("pelvis") ? WaistFollows::pelvis
                           : follows == QLatin1String("skin") ? WaistFollows::skin
                                                              : WaistFollows::automatic;
    if (request.waistFollows == WaistFollows::skin && !request.hasMakeHuman)
      fail(QStringLiteral("%1 \"skin\" needs a body to skin by: give the MakeHuman files (obj, skeleton, weights)")
               .arg(fields.label(QStringLiteral("waistFollows"))));
  }
  request.thickness = fields.numberFrom(QStringLiteral("thickness"), request.thickness, 0.0, false);
  request.friction = fields.numberFrom(QStringLiteral("friction"), request.friction, 0.0, false);
  if (fields.has(QStringLiteral("radii"))) {
    const QString label = fields.label(QStringLiteral("radii"));
    if (request.body != CharacterBodyType::capsules)
      fail(QStringLiteral("%1 applies to capsules only, not to type \"mesh\"").arg(label));
    const QVariant radii = fields.required(QStringLiteral("radii"));
    if (!options::isObjectLike(radii) || radii.typeId() == QMetaType::QVariantList)
      fail(QStringLiteral("%1 must be an object {joint name: radius or [head, tail]}, got %2")
               .arg(label, script::describeValue(radii)));
    const QVariantMap map = radii.toMap();
    for (auto it = map.cbegin(); it != map.cend(); ++it) {
      const QString entry = QStringLiteral("option 'body.radii.%1'").arg(it.key());
      std::pair<double, double> radius;
      if (options::isNumber(it.value())) {
        radius.first = radius.second = script::toNumber(it.value(), entry);
      } else {
        const QVariantList pair = script::toList(it.value(), entry);
        if (pair.size() != 2)
          fail(QStringLiteral("%1 must be a radius or [head, tail] in metres, got %2")
                   .arg(entry, script::describeValue(it.value())));
        radius = {script::toNumber(pair[0], entry + QStringLiteral("[0]")),
                  script::toNumber(pair[1], entry + QStringLiteral("[1]"))};
      }
      if (!(radius.first >= 0.0 && radius.second >= 0.0))
        fail(QStringLiteral("%1 must be >= 0 (0 removes the capsule), got %2").arg(entry, script::describeValue(it.value())));
      request.radii[it.key().toStdString()] = radius;
    }
  }
}

/// Moves the root's rest position to where the clip is at `time`: the root
/// OFFSET takes the root's position then, every frame's position channels
/// lose it, so every frame's pose is unchanged but the rest pose (where
/// simulate_on_character's pre-roll starts, and where the garment is
/// modelled) stands where the recording starts instead of at the origin.
void recentreRoot(Motion& motion, const Eigen::Vector3d& root_at_start) {
  Joint& root = motion.skeleton.joints.front();
  for (std::size_t k = 0; k < root.channels.size(); ++k) {
    int axis = -1;
    switch (root.channels[k]) {
      case Channel::x_position: axis = 0; break;
      case Channel::y_position: axis = 1; break;
      case Channel::z_position: axis = 2; break;
      default: break;
    }
    if (axis < 0) continue;
    const double shift = root_at_start[axis] - root.offset[axis];
    motion.frames.col(root.first_channel + static_cast<Eigen::Index>(k)).array() -= shift;
    root.offset[axis] += shift;
  }
}

/// The garment's points moved by `placement` (#V x 3, metres).
Eigen::MatrixX3d placedPoints(const QuadMesh& garment, const Eigen::Isometry3d& placement) {
  Eigen::MatrixX3d placed(static_cast<Eigen::Index>(garment.n_vertices()), 3);
  for (const auto vertex : garment.vertices()) {
    const auto& p = garment.point(vertex);
    placed.row(vertex.idx()) = (placement * Eigen::Vector3d(p[0], p[1], p[2])).transpose();
  }
  return placed;
}

Motion withoutFirstFrame(const Motion& motion) {
  Motion clip;
  clip.skeleton = motion.skeleton;
  clip.frame_time = motion.frame_time;
  clip.frames = motion.frames.bottomRows(motion.frames.rows() - 1);
  return clip;
}

}  // namespace

QStringList characterOptionKeys() {
  return {QStringLiteral("motion"), QStringLiteral("body"),    QStringLiteral("place"),
          QStringLiteral("waist"),  QStringLiteral("preroll"), QStringLiteral("stepRate"),
          QStringLiteral("skipFirst"), QStringLiteral("bodyOutput")};
}

CharacterRequest parseCharacterOptions(const Fields& fields, double fps) {
  CharacterRequest request;
  request.skipFirst = fields.boolean(QStringLiteral("skipFirst"), request.skipFirst);
  parseMotion(fields, request);
  parseBody(fields, request);

  const QString place = fields.choice(QStringLiteral("place"), QStringLiteral("none"),
                                      {QStringLiteral("none"), QStringLiteral("makehuman"), QStringLiteral("firstFrame")});
  if (place == QLatin1String("makehuman")) {
    if (!request.hasMakeHuman)
      fail(QStringLiteral("%1: \"makehuman\" moves the garment by the MakeHuman body's offset, so option 'body' must "
                          "give the MakeHuman files {obj, skeleton, weights}")
               .arg(fields.label(QStringLiteral("place"))));
    request.place = GarmentPlacement::makehuman;
  } else if (place == QLatin1String("firstFrame")) {
    request.place = GarmentPlacement::firstFrame;
  }

  request.prerollSeconds = fields.numberFrom(QStringLiteral("preroll"), request.prerollSeconds, 0.0, false);
  request.stepRate = fields.numberFrom(QStringLiteral("stepRate"), request.stepRate, 0.0, true);
  if (request.stepRate < fps)
    fail(QStringLiteral("%1 must be at least option 'fps' (%2 frames per second), got %3")
             .arg(fields.label(QStringLiteral("stepRate"))).arg(fps).arg(request.stepRate));
  return request;
}

LoadedCharacter loadCharacter(const CharacterRequest& request, const QuadMesh& garment) {
  LoadedCharacter character;
  const QString motion_label = optionLabel(QStringLiteral("motion"));
  BvhReadOptions read_options;
  read_options.scale = request.motionScale;
  read_options.skip_first_frame = false;  // frame 0 is needed for place "firstFrame"; dropped below
  Motion full = naming(motion_label, [&] { return read_bvh(request.motionPath.toStdString(), read_options); });

  const QString file = QDir::toNativeSeparators(request.motionPath);
  const CharacterRunOptions defaults;
  if (full.skeleton.joints.empty() || full.frames.rows() < 1)
    throw InputError(QStringLiteral("%1: %2 has no joints or no frames").arg(motion_label, file).toStdString());
  if (full.skeleton.find(defaults.pelvis_joint) < 0)
    throw InputError(QStringLiteral("%1: %2 has no joint '%3', which the pinned waist follows")
                         .arg(motion_label, file, QString::fromStdString(defaults.pelvis_joint))
                         .toStdString());
  if (request.skipFirst && full.frames.rows() < 2)
    throw InputError(QStringLiteral("%1: %2 has a single frame, so skipFirst leaves nothing (set skipFirst: false)")
                         .arg(motion_label, file)
                         .toStdString());
  Motion clip = request.skipFirst ? withoutFirstFrame(full) : full;
  if (request.motionStart > clip.duration() + 1e-9)
    fail(QStringLiteral("option 'motion.start' must be at most the clip's length, %1 s, got %2 s")
             .arg(clip.duration(), 0, 'f', 3).arg(request.motionStart));

  recentreRoot(full, pose_at(clip, request.motionStart).position(0));
  clip = request.skipFirst ? withoutFirstFrame(full) : full;
  const int pelvis = full.skeleton.find(defaults.pelvis_joint);
  if (request.place == GarmentPlacement::firstFrame)
    character.placement = rest_pose(full.skeleton).global[pelvis] * frame_pose(full, 0).global[pelvis].inverse();
  character.motion = std::make_unique<Motion>(std::move(clip));
  const Skeleton& skeleton = character.motion->skeleton;

  std::optional<SkinnedBody> skinned;
  if (request.hasMakeHuman)
    skinned = naming(optionLabel(QStringLiteral("body")), [&] { return load_makehuman_body(request.makehuman, skeleton); });
  if (request.place == GarmentPlacement::makehuman) {
    // Modelled on base.obj: in the body's A-pose, where the pre-roll starts.
    character.placement = Eigen::Translation3d(skinned->obj_offset);
    character.garmentPose = mesh_pose(*skinned, skeleton);
  }

  for (const auto& [name, radii] : request.radii)
    if (skeleton.find(name) < 0)
      fail(QStringLiteral("option 'body.radii.%1': the motion's skeleton has no joint of that name")
               .arg(QString::fromStdString(name)));
  character.legBridges = request.legBridges >= 0.0
                             ? request.legBridges
                             : automatic_leg_bridges(static_cast<int>(boundary_loops(garment).size()),
                                                     placedPoints(garment, character.placement), skeleton);
  if (request.armClearance >= 0.0) {
    ArmClearanceOptions arms;
    arms.clearance = request.armClearance;
    character.armClearance = std::make_shared<const ArmClearance>(
        skinned ? make_arm_clearance(skeleton, arms, skinned->rest_vertices, skinned->weights, skinned->joint_rest)
                : make_arm_clearance(skeleton, arms));
  }
  const bool waist_on_skin = request.waistFollows == WaistFollows::skin ||
                             (request.waistFollows == WaistFollows::automatic && request.hasMakeHuman);
  if (waist_on_skin) character.waistSkin = std::make_shared<const SkinnedBody>(*skinned);
  naming(optionLabel(QStringLiteral("body")), [&] {
    if (request.body == CharacterBodyType::mesh) {
      character.bodyVertices = static_cast<int>(skinned->rest_vertices.rows());
      CapsuleRig bridges;
      if (character.legBridges > 0.0) {
        // Sized like default leg capsules; the rig's bones are dropped, the mesh is the body.
        bridges = make_capsule_rig(skeleton);
        add_leg_bridges(bridges, skeleton, character.legBridges);
        bridges.bones.clear();
      }
      character.body = std::make_unique<SkinnedPosedBody>(std::move(*skinned), skeleton, request.thickness,
                                                          request.friction, std::move(bridges));
      return;
    }
    CapsuleRigOptions rig_options;
    rig_options.thickness = request.thickness;
    rig_options.friction = request.friction;
    rig_options.radii = request.radii;
    CapsuleRig rig = make_capsule_rig(skeleton, rig_options);
    if (skinned) {
      fit_capsules_to_body(rig, skeleton, *skinned, request.radii);
      character.fittedCapsules = true;
    }
    // The garment must start outside every capsule: shrink those it starts
    // inside (fitted capsules stand out of a body wherever it is narrower
    // than a linear taper).
    const std::vector<Eigen::Vector3d> joints = skinned ? skinned->joint_rest : std::vector<Eigen::Vector3d>{};
    CharacterRunOptions start;
    start.garment_pose = character.garmentPose;
    start.motion_start = request.motionStart;
    character.capsulesShrunk = clear_capsules_for_garment(rig, *character.motion, start, joints,
                                                          placedPoints(garment, character.placement));
    character.bodyCapsules = static_cast<int>(rig.bones.size());
    if (character.legBridges > 0.0) add_leg_bridges(rig, skeleton, character.legBridges);
    character.body = std::make_unique<CapsulePosedBody>(std::move(rig), skeleton, joints);
  });
  return character;
}

CharacterRunOptions characterRunOptions(const CharacterRequest& request, const LoadedCharacter& character,
                                        const DynamicsModel& model, const SimulationOptions& simulation) {
  CharacterRunOptions run;
  run.garment_pose = character.garmentPose;
  run.frames = simulation.frames;
  run.fps = simulation.fps;
  run.step_rate = request.stepRate;
  run.preroll_seconds = request.prerollSeconds;
  run.motion_start = request.motionStart;
  run.simulation = simulation;
  run.arm_clearance = character.armClearance;
  if (character.waistSkin) waist_follows_skin(run, *character.waistSkin, *character.motion, model);
  return run;
}

QString bodyTypeName(CharacterBodyType type) {
  return type == CharacterBodyType::mesh ? QStringLiteral("mesh") : QStringLiteral("capsules");
}

QString placementName(GarmentPlacement place) {
  switch (place) {
    case GarmentPlacement::makehuman: return QStringLiteral("makehuman");
    case GarmentPlacement::firstFrame: return QStringLiteral("firstFrame");
    case GarmentPlacement::none: break;
  }
  return QStringLiteral("none");
}

QVariantMap characterReportMap(const CharacterRunReport& report, const CharacterRequest& request,
                               const LoadedCharacter& character, const CharacterRunOptions& run) {
  const SimulationReport& pre = report.preroll;
  const int substeps = std::max(1, static_cast<int>(std::lround(run.step_rate / run.fps)));
  const Eigen::Vector3d shift = character.placement.translation();
  QVariantMap map{
      {QStringLiteral("preroll"),
       QVariantMap{{QStringLiteral("seconds"), request.prerollSeconds},
                   {QStringLiteral("frames"), pre.frames},
                   {QStringLiteral("steps"), pre.steps},
                   {QStringLiteral("msPerFrame"), QVariantMap{{QStringLiteral("dynamics"), pre.mean_frame.dynamics_ms},
                                                              {QStringLiteral("collision"), pre.mean_frame.collision_ms},
                                                              {QStringLiteral("total"), pre.ms_per_frame_total}}},
                   {QStringLiteral("maxStretch"), pre.max_stretch},
                   {QStringLiteral("maxPenetration"), pre.max_penetration},
                   {QStringLiteral("maxDepth"), pre.max_depth},
                   {QStringLiteral("initialPenetration"), pre.initial_penetration},
                   {QStringLiteral("nonFinite"), pre.non_finite}}},
      {QStringLiteral("maxWaistError"), report.max_waist_error},
      {QStringLiteral("armsOpened"), QVariantMap{{QStringLiteral("maxDegrees"), report.max_arm_angle * 180.0 / M_PI},
                                                 {QStringLiteral("steps"), report.arm_steps},
                                                 {QStringLiteral("clearance"), request.armClearance >= 0.0
                                                                                   ? QVariant(request.armClearance)
                                                                                   : QVariant(false)}}},
      {QStringLiteral("body"), bodyTypeName(request.body)},
      {QStringLiteral("motion"), request.motionPath},
      {QStringLiteral("motionUnits"), request.motionUnits},
      {QStringLiteral("motionStart"), request.motionStart},
      {QStringLiteral("motionDuration"), character.motion->duration()},
      {QStringLiteral("skipFirst"), request.skipFirst},
      {QStringLiteral("place"), placementName(request.place)},
      {QStringLiteral("placement"), QVariantList{shift.x(), shift.y(), shift.z()}},
      {QStringLiteral("stepRate"), substeps * run.fps},
      {QStringLiteral("legBridges"), character.legBridges},
      {QStringLiteral("capsulesShrunk"), character.capsulesShrunk},
      {QStringLiteral("waistFollows"), character.waistSkin ? QStringLiteral("skin") : QStringLiteral("pelvis")},
  };
  if (request.body == CharacterBodyType::mesh) map.insert(QStringLiteral("bodyVertices"), character.bodyVertices);
  else map.insert(QStringLiteral("capsules"), character.bodyCapsules);
  return map;
}

}  // namespace mrcloth
