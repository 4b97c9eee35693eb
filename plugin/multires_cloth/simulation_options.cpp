#include "simulation_options.h"
#include "option_limits.h"

#include "plugin/core/option_fields.h"

#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"
#include "plugin/core/script_values.h"
#include "solver/colliders.h"
#include "solver/material.h"
#include "solver/point_cache.h"
#include "solver/worker_pool.h"

#include <QDir>
#include <QFileInfo>

#include <array>

namespace mrcloth {
namespace {

using options::Fields;
using options::fail;
using options::isNumber;
using options::kLeastFps;
using options::kMostCollisionRounds;
using options::kMostFps;
using options::kMostIterations;
using options::kMostLimiterSweeps;
using options::kMostNewtonCg;
using options::kMostSelfContactThickness;
using options::kMostSubsteps;
using options::kMostThreads;
using options::isObjectLike;
using options::optionLabel;

QStringList presetNames() {
  QStringList names;
  for (const std::string& name : material_preset_names()) names << QString::fromStdString(name);
  return names;
}

Material parseMaterial(const QVariant& value) {
  const QString label = optionLabel(QStringLiteral("material"));
  const QStringList presets = presetNames();
  if (value.typeId() == QMetaType::QString)
    return material_preset(script::toChoice(value, label, presets).toStdString());
  if (!isObjectLike(value))
    fail(QStringLiteral("%1 must be a preset name (\"%2\") or an object {preset, arealDensity, ...}, got %3")
             .arg(label, presets.join(QStringLiteral("\", \"")), script::describeValue(value)));
  const Fields fields(value, QStringLiteral("material"),
                      {QStringLiteral("preset"), QStringLiteral("arealDensity"), QStringLiteral("stretchStiffness"),
                       QStringLiteral("shearStiffness"), QStringLiteral("bendStiffness"), QStringLiteral("damping"),
                       QStringLiteral("stretchLimit")});
  Material m = material_preset(
      fields.has(QStringLiteral("preset"))
          ? script::toChoice(fields.required(QStringLiteral("preset")), fields.label(QStringLiteral("preset")), presets)
                .toStdString()
          : Material{}.name);
  m.areal_density = fields.numberFrom(QStringLiteral("arealDensity"), m.areal_density, 0.0, true);
  m.stretch_stiffness = fields.numberFrom(QStringLiteral("stretchStiffness"), m.stretch_stiffness, 0.0, true);
  m.shear_stiffness = fields.numberFrom(QStringLiteral("shearStiffness"), m.shear_stiffness, 0.0, true);
  m.bend_stiffness = fields.numberFrom(QStringLiteral("bendStiffness"), m.bend_stiffness, 0.0, false);
  m.damping = fields.numberFrom(QStringLiteral("damping"), m.damping, 0.0, false);
  m.stretch_limit = fields.numberFrom(QStringLiteral("stretchLimit"), m.stretch_limit, 0.0, true);
  return m;
}

Collider parseCollider(const QVariant& value, const QString& path) {
  const QStringList types = {QStringLiteral("plane"), QStringLiteral("sphere"), QStringLiteral("capsule")};
  const QStringList plane_keys = {QStringLiteral("point"), QStringLiteral("normal")};
  const QStringList sphere_keys = {QStringLiteral("center"), QStringLiteral("radius")};
  const QStringList capsule_keys = {QStringLiteral("a"), QStringLiteral("b"), QStringLiteral("radius"),
                                    QStringLiteral("radiusA"), QStringLiteral("radiusB")};
  // The accepted keys depend on the type; an unknown or missing type accepts
  // them all so that the type itself is what the error is about.
  const QString type = value.toMap().value(QStringLiteral("type")).toString();
  QStringList accepted = {QStringLiteral("type")};
  if (type == QLatin1String("plane")) accepted += plane_keys;
  else if (type == QLatin1String("sphere")) accepted += sphere_keys;
  else if (type == QLatin1String("capsule")) accepted += capsule_keys;
  else accepted += plane_keys + sphere_keys + capsule_keys;
  accepted.removeDuplicates();
  accepted += {QStringLiteral("thickness"), QStringLiteral("friction")};
  const Fields fields(value, path, accepted);
  script::toChoice(fields.required(QStringLiteral("type")), fields.label(QStringLiteral("type")), types);

  Collider collider;
  if (type == QLatin1String("plane")) {
    PlaneCollider plane;
    plane.point = fields.vec3(QStringLiteral("point"), plane.point);
    plane.normal = fields.vec3(QStringLiteral("normal"), plane.normal);
    collider.shape = plane;
  } else if (type == QLatin1String("sphere")) {
    SphereCollider sphere;
    sphere.center = fields.vec3(QStringLiteral("center"));
    fields.required(QStringLiteral("radius"));
    sphere.radius = fields.numberFrom(QStringLiteral("radius"), sphere.radius, 0.0, true);
    collider.shape = sphere;
  } else {
    CapsuleCollider capsule;
    capsule.a = fields.vec3(QStringLiteral("a"));
    capsule.b = fields.vec3(QStringLiteral("b"));
    const bool both = fields.has(QStringLiteral("radius"));
    const bool each = fields.has(QStringLiteral("radiusA")) || fields.has(QStringLiteral("radiusB"));
    if (both && each)
      fail(QStringLiteral("%1: give either 'radius' or 'radiusA' and 'radiusB', not both").arg(optionLabel(path)));
    if (both) {
      capsule.radius_a = capsule.radius_b = fields.numberFrom(QStringLiteral("radius"), 0.0, 0.0, true);
    } else {
      if (!each) fields.required(QStringLiteral("radius"));  // "missing option '...radius'"
      fields.required(QStringLiteral("radiusA"));
      fields.required(QStringLiteral("radiusB"));
      capsule.radius_a = fields.numberFrom(QStringLiteral("radiusA"), 0.0, 0.0, false);
      capsule.radius_b = fields.numberFrom(QStringLiteral("radiusB"), 0.0, 0.0, false);
    }
    collider.shape = capsule;
  }
  collider.thickness =
      fields.numberBetween(QStringLiteral("thickness"), collider.thickness, 0.0, kMostContactThickness, QStringLiteral("m"));
  collider.friction = fields.numberFrom(QStringLiteral("friction"), collider.friction, 0.0, false);
  return collider;
}

std::vector<Collider> parseColliders(const QVariant& value) {
  const QVariantList list = script::toList(value, optionLabel(QStringLiteral("colliders")));
  std::vector<Collider> colliders;
  for (qsizetype i = 0; i < list.size(); ++i)
    colliders.push_back(parseCollider(list[i], QStringLiteral("colliders[%1]").arg(i)));
  try {
    validate_colliders(colliders);  // what the shapes need beyond types (a zero normal, two zero radii)
  } catch (const ArgumentError& error) {
    fail(QStringLiteral("%1: %2").arg(optionLabel(QStringLiteral("colliders")), QString::fromUtf8(error.what())));
  }
  return colliders;
}

std::vector<int> loopVertices(const QuadMesh& mesh, const QString& name, const QString& label) {
  try {
    return boundary_loop_by_name(mesh, name.toStdString());
  } catch (const ArgumentError& error) {
    fail(QStringLiteral("%1: %2").arg(label, QString::fromUtf8(error.what())));
  }
}

/// Pins (or the waist, `key`): a loop name, or an array whose elements are
/// vertex ids or loop names.
std::vector<int> parsePins(const QVariant& value, const QuadMesh& mesh, const QString& key, QString& text) {
  const QString label = optionLabel(key);
  const QString expected = QStringLiteral("a boundary loop name (\"top\", \"bottom\", \"loop:N\")");
  if (value.typeId() == QMetaType::QString) {
    const QString name = script::toString(value, label);
    std::vector<int> pins = loopVertices(mesh, name, label);
    text = QStringLiteral("\"%1\" (%2 vertices)").arg(name).arg(pins.size());
    return pins;
  }
  if (!isObjectLike(value))
    fail(QStringLiteral("%1 must be %2 or an array of vertex ids and loop names, got %3")
             .arg(label, expected, script::describeValue(value)));
  const QVariantList list = script::toList(value, label);
  std::vector<int> pins;
  QStringList names;
  int ids = 0;
  for (qsizetype i = 0; i < list.size(); ++i) {
    const QString element = QStringLiteral("option '%1[%2]'").arg(key).arg(i);
    if (list[i].typeId() == QMetaType::QString) {
      const QString name = script::toString(list[i], element);
      const std::vector<int> loop = loopVertices(mesh, name, element);
      pins.insert(pins.end(), loop.begin(), loop.end());
      names << QStringLiteral("\"%1\"").arg(name);
    } else if (isNumber(list[i])) {
      pins.push_back(script::toInt(list[i], element));
      ++ids;
    } else {
      fail(QStringLiteral("%1 must be a vertex id or %2, got %3").arg(element, expected, script::describeValue(list[i])));
    }
  }
  if (ids > 0) names << QStringLiteral("%1 vertex id%2").arg(ids).arg(ids == 1 ? QString() : QStringLiteral("s"));
  text = names.isEmpty() ? QStringLiteral("none") : names.join(QStringLiteral(" + "));
  return pins;
}

/// The frame of the OBJ sequence `prefix` (of `frames` frames) that is the
/// file `path` (absolute), or -1.
long long sequenceFrame(const QString& prefix, int frames, const QString& path) {
  if (prefix.isEmpty()) return -1;
  // A frame of the sequence: "<prefix>_<digits>.obj" with a frame's number.
  const QString start = QFileInfo(prefix).absoluteFilePath() + QStringLiteral("_");
  if (!path.startsWith(start) || !path.endsWith(QLatin1String(".obj"))) return -1;
  bool number = false;
  const long long index = path.mid(start.size(), path.size() - start.size() - 4).toLongLong(&number);
  if (!number || index < 0 || index >= frames) return -1;
  const QString frame = QFileInfo(QString::fromStdString(obj_sequence_path(
                                      prefix.toStdString(), static_cast<std::size_t>(index), static_cast<std::size_t>(frames))))
                            .absoluteFilePath();
  return frame == path ? index : -1;
}

/// (what, absolute path) of a run's files beside its OBJ sequence: the
/// caches and the rest meshes written beside them.
std::vector<std::pair<QString, QString>> namedOutputs(const QString& output, const QString& bodyOutput) {
  std::vector<std::pair<QString, QString>> files;
  for (const auto& [option, cache] : {std::pair{QStringLiteral("option 'output'"), output},
                                      std::pair{QStringLiteral("option 'bodyOutput'"), bodyOutput}}) {
    if (cache.isEmpty()) continue;
    files.emplace_back(option, QFileInfo(cache).absoluteFilePath());
    files.emplace_back(QStringLiteral("the rest mesh beside %1").arg(option), QFileInfo(restMeshPath(cache)).absoluteFilePath());
  }
  return files;
}

/// Refuses two outputs of one run that name one file (the later write
/// would replace the earlier: a body cache over the garment's, a rest mesh
/// over an OBJ sequence's frame), naming both options.
void requireDistinctOutputs(const QString& output, const QString& bodyOutput, const QString& objSequence, int frames) {
  const std::vector<std::pair<QString, QString>> files = namedOutputs(output, bodyOutput);
  for (std::size_t a = 0; a < files.size(); ++a) {
    // Written after the run: a folder there failed the call after the run had written its caches.
    if (QFileInfo(files[a].second).isDir())
      throw OutputError(QStringLiteral("%1, %2, is a folder; expected a file's path").arg(files[a].first, files[a].second)
                            .toStdString());
    for (std::size_t b = a + 1; b < files.size(); ++b)
      if (files[a].second == files[b].second)
        fail(QStringLiteral("%1 and %2 are one file, %3; expected outputs that do not overwrite each other")
                 .arg(files[a].first, files[b].first, files[a].second));
    if (const long long index = sequenceFrame(objSequence, frames, files[a].second); index >= 0)
      fail(QStringLiteral("%1 is frame %2 of option 'objSequence', %3; expected outputs that do not overwrite each other")
               .arg(files[a].first).arg(index).arg(files[a].second));
  }
  for (int frame = 0; !objSequence.isEmpty() && frame < frames; ++frame) {
    const QString path = QString::fromStdString(
        obj_sequence_path(objSequence.toStdString(), static_cast<std::size_t>(frame), static_cast<std::size_t>(frames)));
    if (QFileInfo(path).isDir())
      throw OutputError(QStringLiteral("frame %1 of option 'objSequence', %2, is a folder; expected a file's path")
                            .arg(frame).arg(QFileInfo(path).absoluteFilePath()).toStdString());
  }
}

}  // namespace

void requireOutputsSpareInputs(const SimulationRequest& request, const QString& garmentFile) {
  std::vector<std::pair<QString, QString>> inputs;  // (what, absolute path)
  const auto add = [&](const QString& what, const QString& path) {
    if (!path.isEmpty()) inputs.emplace_back(what, QFileInfo(path).absoluteFilePath());
  };
  add(QStringLiteral("the garment's file"), garmentFile);
  if (request.character) {
    const CharacterRequest& character = *request.character;
    add(QStringLiteral("option 'motion'"), character.motionPath);
    if (character.setup.makehuman) {
      add(QStringLiteral("option 'body.obj'"), QString::fromStdString(character.setup.makehuman->base_obj));
      add(QStringLiteral("option 'body.skeleton'"), QString::fromStdString(character.setup.makehuman->skeleton_file));
      add(QStringLiteral("option 'body.weights'"), QString::fromStdString(character.setup.makehuman->weights_file));
    }
  }
  const std::vector<std::pair<QString, QString>> outputs =
      namedOutputs(QString::fromStdString(request.simulation.cache_path),
                   request.character ? request.character->bodyOutput : QString());
  for (const auto& [what, path] : inputs) {
    for (const auto& [written, out] : outputs)
      if (out == path)
        throw OutputError(QStringLiteral("%1 is %2, %3; expected outputs that leave the run's inputs as they are")
                              .arg(written, what, path).toStdString());
    if (const long long index = sequenceFrame(request.objSequence, request.simulation.frames, path); index >= 0)
      throw OutputError(QStringLiteral("frame %1 of option 'objSequence' is %2, %3; expected outputs that leave the "
                                       "run's inputs as they are")
                            .arg(index).arg(what, path).toStdString());
  }
}

namespace {

/// The folder a file (or an OBJ sequence prefix) goes into must exist.
QString checkedOutputPath(const Fields& fields, const QString& key) {
  const QString path = fields.string(key);
  if (path.isEmpty()) return path;
  const QFileInfo info(path);
  const QFileInfo folder(info.absolutePath());
  if (folder.exists() && !folder.isDir())
    throw OutputError(QStringLiteral("%1: '%2' is a file, not a folder")
                          .arg(fields.label(key), QDir::toNativeSeparators(info.absolutePath()))
                          .toStdString());
  if (!info.absoluteDir().exists())
    throw OutputError(QStringLiteral("%1: folder '%2' does not exist")
                          .arg(fields.label(key), QDir::toNativeSeparators(info.absolutePath()))
                          .toStdString());
  if (info.isDir())
    throw OutputError(QStringLiteral("%1: '%2' is a folder").arg(fields.label(key), path).toStdString());
  return path;
}

}  // namespace

QString restMeshPath(const QString& cache_path) {
  const QFileInfo cache(cache_path);
  return cache.dir().filePath(cache.completeBaseName() + QStringLiteral(".obj"));
}

QStringList simulationOptionKeys() {
  return QStringList{QStringLiteral("frames"),    QStringLiteral("fps"),         QStringLiteral("substeps"),
                     QStringLiteral("iterations"), QStringLiteral("newtonCg"), QStringLiteral("limiterSweeps"), QStringLiteral("limiterAcceleration"),
                     QStringLiteral("limiterMassExponent"), QStringLiteral("tNodeSag"), QStringLiteral("pinsYield"), QStringLiteral("collisionRounds"),
                     QStringLiteral("contactSlack"), QStringLiteral("material"),   QStringLiteral("alpha"),
                     QStringLiteral("alphaBend"), QStringLiteral("bendModel"), QStringLiteral("gravity"),     QStringLiteral("pins"),
                     QStringLiteral("colliders"), QStringLiteral("output"),      QStringLiteral("objSequence"),
                     QStringLiteral("updateObject"), QStringLiteral("selfContact"), QStringLiteral("threads")} +
         characterOptionKeys() + QStringList{QStringLiteral("optionNames")};
}

namespace {

/// Refuses what the call does not take: recordInstance without motion or
/// output, a character's option without motion, substeps with it.
void refuseOptionsOutOfPlace(const Fields& fields, bool record, bool character) {
  if (record && !character)
    fields.required(QStringLiteral("motion"));  // "missing option 'motion' (accepted: ...)"
  if (!character) {
    for (const QString& key : characterOptionKeys())
      if (fields.has(key))
        fail(QStringLiteral("%1 needs option 'motion' (a BVH file to move the garment with)").arg(optionLabel(key)));
  } else if (fields.has(QStringLiteral("substeps"))) {
    fail(QStringLiteral("option 'substeps' does not apply with option 'motion': give the time steps per second as "
                        "option 'stepRate' (default 120)"));
  }
  if (record && !fields.has(QStringLiteral("output")))
    fail(QStringLiteral("missing option 'output': recordInstance writes its PC2 cache there and the rest mesh beside "
                        "it (same name, .obj)"));
}

/// frames, fps, and the counts of the loops in a frame: substeps (without
/// motion), iterations, newtonCg, limiterSweeps.
void parseStepCounts(const Fields& fields, bool record, bool character, SimulationOptions& sim) {
  sim.frames = fields.integerAtLeast(QStringLiteral("frames"), record ? 200 : sim.frames, 1);
  sim.fps = fields.numberBetween(QStringLiteral("fps"), sim.fps, kLeastFps, kMostFps, QStringLiteral("frames per second"));
  // Progress and Ctrl-C come between frames: a frame's work is bounded.
  if (!character) sim.substeps = fields.integerBetween(QStringLiteral("substeps"), sim.substeps, 1, kMostSubsteps);
  sim.iterations = fields.integerBetween(QStringLiteral("iterations"), sim.iterations, 1, kMostIterations);
  // The same for the inner loops (a typo of 60000 sweeps left a frame
  // running for hours with Ctrl-C waiting on it).
  sim.newton_cg = fields.integerBetween(QStringLiteral("newtonCg"), sim.newton_cg, 0, kMostNewtonCg);
  sim.strain_limit_sweeps =
      fields.integerBetween(QStringLiteral("limiterSweeps"), sim.strain_limit_sweeps, 0, kMostLimiterSweeps);
}

/// limiterAcceleration: "auto" or a number >= 0 and < 1.
void parseLimiterAcceleration(const Fields& fields, SimulationOptions& sim) {
  // "auto": the default estimate raised to the garment's chain's
  // (chain_spectral_radius), which the longer chains of refined meshes need.
  const QVariant acceleration =
      fields.has(QStringLiteral("limiterAcceleration")) ? fields.required(QStringLiteral("limiterAcceleration")) : QVariant();
  if (acceleration.typeId() == QMetaType::QString) {
    if (acceleration.toString() != QLatin1String("auto"))
      fail(QStringLiteral("%1 must be \"auto\" or a number >= 0 and < 1 (0: plain limiter sweeps), got %2")
               .arg(fields.label(QStringLiteral("limiterAcceleration")), script::describeValue(acceleration)));
    sim.acceleration_from_chain = true;
  } else if (acceleration.isValid()) {
    sim.acceleration_from_chain = false;
    sim.limiter_acceleration =
        fields.numberFrom(QStringLiteral("limiterAcceleration"), sim.limiter_acceleration, 0.0, false);
    if (!(sim.limiter_acceleration < 1.0))
      fail(QStringLiteral("%1 must be \"auto\" or a number >= 0 and < 1 (0: plain limiter sweeps), got %2")
               .arg(fields.label(QStringLiteral("limiterAcceleration")))
               .arg(sim.limiter_acceleration));
  }
}

void parseLimiterMassExponent(const Fields& fields, SimulationOptions& sim) {
  sim.limiter_mass_exponent =
      fields.numberFrom(QStringLiteral("limiterMassExponent"), sim.limiter_mass_exponent, 0.0, false);
  if (!(sim.limiter_mass_exponent <= 1.0))
    fail(QStringLiteral("%1 must be a number >= 0 and <= 1 (1: mass-weighted limiter projections), got %2")
             .arg(fields.label(QStringLiteral("limiterMassExponent")))
             .arg(sim.limiter_mass_exponent));
}

/// The settings that take their value as given, checked for type and range:
/// tNodeSag, pinsYield, collisionRounds, contactSlack, threads, gravity.
void parsePlainSettings(const Fields& fields, SimulationOptions& sim) {
  sim.t_node_sag = fields.boolean(QStringLiteral("tNodeSag"), sim.t_node_sag);
  sim.pins_yield = fields.boolean(QStringLiteral("pinsYield"), sim.pins_yield);
  sim.collision_rounds =
      fields.integerBetween(QStringLiteral("collisionRounds"), sim.collision_rounds, 1, kMostCollisionRounds);
  sim.contact_slack = fields.numberFrom(QStringLiteral("contactSlack"), sim.contact_slack, 0.0, false);
  sim.threads = resolve_thread_count(
      fields.integerBetween(QStringLiteral("threads"), sim.threads, 0, kMostThreads));
  sim.gravity = fields.vec3(QStringLiteral("gravity"), sim.gravity);
}

/// selfContact's thickness: false (none) or metres from 0 to
/// kMostSelfContactThickness; `label` names it.
double selfContactThickness(const QVariant& thickness, const QString& label) {
  double metres = 0.0;
  if (thickness.typeId() == QMetaType::Bool) {
    if (thickness.toBool())
      fail(QStringLiteral("%1 must be false or a thickness from 0 to %2 m, got true")
               .arg(label).arg(kMostSelfContactThickness));
  } else {
    metres = script::toNumber(thickness, label);
    if (!(metres >= 0.0 && metres <= kMostSelfContactThickness))
      fail(QStringLiteral("%1 must be false or a thickness from 0 to %2 m, got %3")
               .arg(label)
               .arg(kMostSelfContactThickness)
               .arg(script::describeValue(thickness)));
  }
  return metres;
}

/// selfContact (given): a thickness, or {thickness, neighbourhood}.
void parseSelfContact(const Fields& fields, SelfContactOptions& self_contact) {
  const QString label = fields.label(QStringLiteral("selfContact"));
  const QVariant contact = fields.required(QStringLiteral("selfContact"));
  QVariant thickness = contact;
  QString thickness_label = label;
  if (isObjectLike(contact) && contact.typeId() != QMetaType::QVariantList) {
    // {thickness, neighbourhood}: the sheet's neighbourhood given too.
    const Fields parts(contact, QStringLiteral("selfContact"),
                       {QStringLiteral("thickness"), QStringLiteral("neighbourhood")});
    thickness = parts.required(QStringLiteral("thickness"));
    thickness_label = parts.label(QStringLiteral("thickness"));
    // Up to 10 cm: beyond, a garment's own folds are no longer held, and
    // each vertex's neighbourhood (kept for the run) grows with its square.
    self_contact.neighbourhood = parts.numberFrom(QStringLiteral("neighbourhood"), -1.0, 0.0, false);
    if (self_contact.neighbourhood > 0.1)
      fail(QStringLiteral("%1 must be at most 0.1 m, got %2")
               .arg(parts.label(QStringLiteral("neighbourhood")))
               .arg(self_contact.neighbourhood));
  }
  self_contact.thickness = selfContactThickness(thickness, thickness_label);
}

/// output: the PC2 cache's path (empty: none), whose folder exists.
QString parseCacheOutput(const Fields& fields) {
  const QString output = checkedOutputPath(fields, QStringLiteral("output"));
  if (QFileInfo(output).suffix().compare(QLatin1String("obj"), Qt::CaseInsensitive) == 0)
    fail(QStringLiteral("option 'output' must be the PC2 cache (e.g. walk.pc2), not an .obj: the rest mesh is written "
                        "beside it as <name>.obj, got \"%1\"").arg(output));
  return output;
}

/// material, alpha, alphaBend, bendModel.
void parseDynamics(const Fields& fields, DynamicsOptions& dynamics) {
  if (fields.has(QStringLiteral("material"))) dynamics.material = parseMaterial(fields.required(QStringLiteral("material")));
  dynamics.alpha = fields.number(QStringLiteral("alpha"), dynamics.alpha);
  dynamics.alpha_bend = fields.number(QStringLiteral("alphaBend"), dynamics.alpha_bend);
  dynamics.bend_model = fields.choice(QStringLiteral("bendModel"), QStringLiteral("distance"),
                                     {QStringLiteral("distance"), QStringLiteral("secondDifference")}) ==
                               QStringLiteral("secondDifference")
                           ? BendModel::second_difference
                           : BendModel::distance;
}

/// The pinned vertices (request.dynamics.pinned) and how they were given
/// (request.pinsText).
void parseWaistOrPins(const Fields& fields, const QuadMesh& mesh, bool character, SimulationRequest& request) {
  DynamicsOptions& dynamics = request.dynamics;
  // The pins; on a character they are its waist, "top" unless given.
  request.pinsText = QStringLiteral("none");
  QString pins_key = QStringLiteral("pins");
  if (character) {
    if (fields.has(QStringLiteral("waist")) && fields.has(QStringLiteral("pins")))
      fail(QStringLiteral("give the pinned waist as option 'waist' or option 'pins', not both"));
    if (!fields.has(QStringLiteral("pins"))) pins_key = QStringLiteral("waist");
  }
  if (fields.has(pins_key))
    dynamics.pinned = parsePins(fields.required(pins_key), mesh, pins_key, request.pinsText);
  else if (character)
    dynamics.pinned = parsePins(QStringLiteral("top"), mesh, pins_key, request.pinsText);
}

/// The character's options (parseCharacterOptions) and bodyOutput, the
/// body's PC2 cache.
CharacterRequest parseCharacter(const Fields& fields, double fps) {
  CharacterRequest character = parseCharacterOptions(fields, fps);
  character.bodyOutput = checkedOutputPath(fields, QStringLiteral("bodyOutput"));
  if (QFileInfo(character.bodyOutput).suffix().compare(QLatin1String("obj"), Qt::CaseInsensitive) == 0)
    fail(QStringLiteral("option 'bodyOutput' must be the body's PC2 cache (e.g. body.pc2), not an .obj: its rest "
                        "mesh is written beside it as <name>.obj, got \"%1\"").arg(character.bodyOutput));
  return character;
}

/// optionNames (given): {option key: the caller's name for it}.
QHash<QString, QString> parseOptionNames(const Fields& fields) {
  QHash<QString, QString> option_names;
  const QStringList known = simulationOptionKeys();
  const Fields names(fields.required(QStringLiteral("optionNames")), QStringLiteral("optionNames"), known);
  for (const QString& key : known)
    if (names.has(key)) {
      const QVariant name = names.required(key);
      if (name.typeId() != QMetaType::QString) script::toString(name, names.label(key));  // refused with its type
      option_names.insert(key, name.toString());
    }
  return option_names;
}

}  // namespace

SimulationRequest parseSimulationOptions(const QVariant& options, const QuadMesh& mesh, SimulationCall call) {
  const bool record = call == SimulationCall::recordInstance;
  const Fields fields(options, QString(), simulationOptionKeys(),
                      record ? QStringLiteral("recordInstance options") : QStringLiteral("simulate options"));
  const bool character = fields.has(QStringLiteral("motion"));
  refuseOptionsOutOfPlace(fields, record, character);

  SimulationRequest request;
  SimulationOptions& sim = request.simulation;
  parseStepCounts(fields, record, character, sim);
  parseLimiterAcceleration(fields, sim);
  parseLimiterMassExponent(fields, sim);
  parsePlainSettings(fields, sim);
  if (fields.has(QStringLiteral("colliders"))) sim.colliders = parseColliders(fields.required(QStringLiteral("colliders")));
  if (fields.has(QStringLiteral("selfContact"))) parseSelfContact(fields, sim.self_contact);
  const QString output = parseCacheOutput(fields);
  sim.cache_path = output.toStdString();

  parseDynamics(fields, request.dynamics);
  parseWaistOrPins(fields, mesh, character, request);
  request.objSequence = checkedOutputPath(fields, QStringLiteral("objSequence"));
  request.updateObject = fields.boolean(QStringLiteral("updateObject"), request.updateObject);
  if (character) request.character = parseCharacter(fields, sim.fps);
  requireDistinctOutputs(output, request.character ? request.character->bodyOutput : QString(), request.objSequence,
                         sim.frames);
  if (fields.has(QStringLiteral("optionNames"))) request.optionNames = parseOptionNames(fields);
  return request;
}

QString optionCalled(const SimulationRequest& request, const QString& key) {
  return request.optionNames.contains(key) ? request.optionNames.value(key) : QStringLiteral("option '%1'").arg(key);
}

QString stretchSummary(const SimulationReport& report) {
  QString text = QStringLiteral("max stretch %1 %").arg(100.0 * report.max_stretch, 0, 'f', 2);
  // Said when the peak is a spring the pins set: the cloth's own is then smaller.
  if (report.stretch_pinned())
    text += QStringLiteral(" (between pinned vertices, set by what drives them; the cloth's %1 %)")
                .arg(100.0 * report.max_cloth_stretch, 0, 'f', 2);
  return text;
}

QString penetrationSummary(const SimulationReport& report) {
  QString text = QStringLiteral("max penetration %1 mm").arg(1000.0 * report.max_penetration, 0, 'f', 3);
  if (report.penetration_pinned())
    text += QStringLiteral(" (a pinned vertex, set by what drives the pins; the cloth's %1 mm)")
                .arg(1000.0 * report.max_cloth_penetration, 0, 'f', 3);
  return text;
}

QString pinnedDepthWarning(const QString& slot, const SimulationReport& report, const SimulationRequest& request) {
  const QString pins_yield = optionCalled(request, QStringLiteral("pinsYield"));
  if (report.max_pinned_depth > 1e-3)
    return QStringLiteral("%1: pinned vertices went %2 mm below the body's surface (deepest at output frame %3): with "
                          "%4 false pins stay on their targets, so the body overlaps the pinned rim there (the "
                          "cloth's own deepest: %5 mm below)")
        .arg(slot).arg(1000.0 * report.max_pinned_depth, 0, 'f', 1).arg(report.pinned_depth_frame)
        .arg(pins_yield.isEmpty() ? QStringLiteral("pins that do not yield") : pins_yield)
        .arg(1000.0 * report.max_cloth_depth, 0, 'f', 1);
  if (report.max_pin_yield > 1e-3)
    return QStringLiteral("%1: the body overlapped the pins' targets by up to %2 mm (output frame %3): those pins were "
                          "moved out onto its surface, off the targets what drives them gave%4")
        .arg(slot).arg(1000.0 * report.max_pin_yield, 0, 'f', 1).arg(report.pin_yield_frame)
        .arg(pins_yield.isEmpty() ? QString()
             : request.optionNames.contains(QStringLiteral("pinsYield"))
                 ? QStringLiteral(" (%1 false keeps them there, inside the body)").arg(pins_yield)
                 : QStringLiteral(" (pinsYield: false keeps them there, inside the body)"));
  return {};
}

QVariantMap simulationReportMap(const SimulationReport& report, const DynamicsModel& model) {
  qlonglong stretch = 0, shear = 0, bend = 0;
  for (const Spring& spring : model.springs) {
    switch (spring.kind) {
      case SpringKind::stretch: ++stretch; break;
      case SpringKind::shear: ++shear; break;
      case SpringKind::bend: ++bend; break;
    }
  }
  QVariantList per_frame;
  per_frame.reserve(static_cast<qsizetype>(report.per_frame.size()));
  for (const FrameTiming& timing : report.per_frame)
    per_frame.append(QVariantMap{{QStringLiteral("dynamics"), timing.dynamics_ms},
                                 {QStringLiteral("collision"), timing.collision_ms}});
  return {
      {QStringLiteral("frames"), report.frames},
      {QStringLiteral("steps"), report.steps},
      {QStringLiteral("timeStep"), report.time_step},
      {QStringLiteral("precomputeMs"), report.precompute_ms},
      // limiter is part of dynamics; posing and firstRound are parts of collision; measure (the
      // report's own measuring of each output frame) is outside total.
      {QStringLiteral("msPerFrame"), QVariantMap{{QStringLiteral("dynamics"), report.mean_frame.dynamics_ms},
                                                 {QStringLiteral("collision"), report.mean_frame.collision_ms},
                                                 {QStringLiteral("total"), report.mean_frame.total_ms()},
                                                 {QStringLiteral("limiter"), report.mean_frame.limiter_ms},
                                                 {QStringLiteral("posing"), report.mean_frame.posing_ms},
                                                 {QStringLiteral("firstRound"), report.mean_frame.first_round_ms},
                                                 {QStringLiteral("measure"), report.mean_frame.measure_ms}}},
      {QStringLiteral("maxStretch"), report.max_stretch},
      {QStringLiteral("maxClothStretch"), report.max_cloth_stretch},
      {QStringLiteral("maxPinnedStretch"), report.max_pinned_stretch},
      {QStringLiteral("maxTearOpening"), report.max_tear_opening},
      {QStringLiteral("meanRounds"), report.mean_rounds},
      {QStringLiteral("limiterAcceleration"), report.limiter_acceleration},
      {QStringLiteral("maxPenetration"), report.max_penetration},
      {QStringLiteral("maxDepth"), report.max_depth},
      {QStringLiteral("maxClothPenetration"), report.max_cloth_penetration},
      {QStringLiteral("maxClothDepth"), report.max_cloth_depth},
      {QStringLiteral("maxPinnedDepth"), report.max_pinned_depth},
      {QStringLiteral("maxPinYield"), report.max_pin_yield},
      {QStringLiteral("maxFaceDepth"), report.max_face_depth},
      {QStringLiteral("maxSelfCrossings"), report.max_self_crossings},
      {QStringLiteral("deepest"), QVariantMap{{QStringLiteral("vertex"), report.deepest_vertex},
                                              {QStringLiteral("frame"), report.deepest_frame},
                                              {QStringLiteral("pinned"), report.penetration_pinned()}}},
      {QStringLiteral("mostStretched"),
       QVariantMap{{QStringLiteral("vertices"), QVariantList{report.stretch_vertices[0], report.stretch_vertices[1]}},
                   {QStringLiteral("frame"), report.stretch_frame},
                   {QStringLiteral("pinned"), report.stretch_pinned()}}},
      {QStringLiteral("initialPenetration"), report.initial_penetration},
      {QStringLiteral("nonFinite"), report.non_finite},
      {QStringLiteral("cancelled"), report.cancelled},
      {QStringLiteral("output"), QString::fromStdString(report.cache_path)},
      {QStringLiteral("vertices"), model.num_vertices},
      {QStringLiteral("freeVertices"), static_cast<qlonglong>(model.free_vertices.size())},
      {QStringLiteral("pinnedVertices"), static_cast<qlonglong>(model.pinned_vertices.size())},
      {QStringLiteral("hangingVertices"), static_cast<qlonglong>(model.hanging_vertices.size())},
      {QStringLiteral("springs"), QVariantMap{{QStringLiteral("stretch"), stretch},
                                              {QStringLiteral("shear"), shear},
                                              {QStringLiteral("bend"), bend}}},
      {QStringLiteral("perFrameMs"), per_frame},
  };
}

}  // namespace mrcloth
