#include "multires_cloth_plugin.h"

#include "mesh_ops/texture_coords.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/atomic_file.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/mode_mapping.h"
#include "mesh_ops/mode_painting.h"
#include "mesh_ops/quad_mesh.h"
#include "mesh_ops/quad_refiner.h"
#include "mesh_ops/uniform_refine.h"
#include "plugin/core/job_scope.h"
#include "plugin/core/object_store.h"
#include "plugin/core/script_errors.h"
#include "plugin/core/script_values.h"
#include "analysis_options.h"
#include "comparison_report.h"
#include "mode_report.h"
#include "option_limits.h"
#include "run_checks.h"
#include "run_report.h"
#include "simulation_options.h"
#include "plugin/core/option_fields.h"
#include "solver/character_fit.h"
#include "solver/deformation_modes.h"
#include "solver/result_comparison.h"
#include "solver/dynamics_model.h"
#include "solver/instance_curvature.h"
#include "solver/implicit_integrator.h"
#include "solver/point_cache.h"
#include "solver/simulate.h"

#include <QDir>
#include <QFileInfo>

#include <QElapsedTimer>

#include <algorithm>
#include <array>
#include <cassert>
#include <iterator>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

namespace mrcloth {
namespace {

double millisecondsSince(const QElapsedTimer& timer) { return static_cast<double>(timer.nsecsElapsed()) / 1e6; }

QString describeObject(const StoredObject& object) {
  return QStringLiteral("object %1 '%2'").arg(object.id).arg(object.name);
}

ColorBy toColorBy(const QString& name) {
  if (name == QLatin1String("level")) return ColorBy::level;
  if (name == QLatin1String("mode")) return ColorBy::mode;
  if (name == QLatin1String("curvature")) return ColorBy::curvature;
  return ColorBy::none;
}

/// The mesh a cache animates, as OBJ beside it (Blender's Mesh Cache
/// modifier goes on this mesh); empty when there is no cache.
QString restMeshPath(const std::string& cache_path) { return mrcloth::restMeshPath(QString::fromStdString(cache_path)); }

/// The active faces' corner texture coordinates for an OBJ sequence (none
/// for a mesh without them).
FaceUVs faceUVs(const QuadMesh& mesh) {
  FaceUVs uvs;
  for (const auto& face : active_face_uvs(mesh)) {
    std::vector<Eigen::Vector2d> corners;
    for (const OpenMesh::Vec2d& uv : face) corners.emplace_back(uv[0], uv[1]);
    uvs.push_back(std::move(corners));
  }
  return uvs;
}

/// The OBJ sequence `request` asks for (objSequence), one file per frame of
/// `frames` with `mesh`'s active faces and texture coordinates; none when
/// it asks for none.
QStringList writeObjSequence(const SimulationRequest& request, const std::vector<Positions>& frames,
                             const QuadMesh& mesh) {
  QStringList files;
  if (request.objSequence.isEmpty()) return files;
  for (const std::string& file :
       write_obj_sequence(request.objSequence.toStdString(), frames, active_face_polygons(mesh), faceUVs(mesh)))
    files << QString::fromStdString(file);
  return files;
}

/// The rest mesh written beside its path before the run, put in place
/// right after the cache (StagedFile: a full disk then cannot leave the new
/// cache beside an earlier run's rest mesh); none without a cache.
std::unique_ptr<StagedFile> stageRestMesh(const QuadMesh& mesh, const std::string& cache_path) {
  if (cache_path.empty()) return nullptr;
  return std::make_unique<StagedFile>(restMeshPath(cache_path).toStdString(), ".obj",
                                      [&](const std::string& file) { export_surface(mesh, file); });
}

/// Puts a staged rest mesh in place after a complete run; its path, or empty.
QString commitRestMesh(const std::unique_ptr<StagedFile>& rest_mesh, bool complete) {
  if (!complete || !rest_mesh) return {};
  rest_mesh->commit();
  return QString::fromStdString(rest_mesh->path());
}

/// The run's last frame as a mesh of its own (updateObject): `mesh` (the
/// object simulated) at the full positions of `model`'s `state`.
std::shared_ptr<QuadMesh> lastFrameMesh(const QuadMesh& mesh, const DynamicsModel& model, const ClothState& state) {
  return std::make_shared<QuadMesh>(mesh_at_positions(mesh, full_positions(model, state.positions, state.pinned)));
}

/// The counts every refinement report shares, read from the refined mesh.
QVariantMap meshCounts(const QuadMesh& mesh) {
  return {{QStringLiteral("vertices"), static_cast<qlonglong>(mesh.n_vertices())},
          {QStringLiteral("faces"), static_cast<qlonglong>(mesh.n_faces())},
          {QStringLiteral("hangingNodes"), static_cast<qlonglong>(count_hanging(mesh))},
          {QStringLiteral("verticesPerLevel"), script::toVariantList(vertices_per_level(mesh))},
          {QStringLiteral("facesPerLevel"), script::toVariantList(faces_per_level(mesh))}};
}

}  // namespace

void MultiresClothPlugin::stopCancelled(const QString& text) {
  // Said as a warning too: an interrupted script's error is not shown.
  emit log(LOGWARN, text);
  throw Error(text.toStdString());
}

void MultiresClothPlugin::stopInSetUp(const QString& slot, int frames) {
  const QString text = QStringLiteral("%1: cancelled while setting up, before the first of %2 frames; nothing was written")
                           .arg(slot).arg(frames);
  run_warnings_ << text;  // kept with the run's warnings, as warn() keeps them
  stopCancelled(text);
}

template <class Body>
auto MultiresClothPlugin::guarded(const char* slot, Body&& body) -> decltype(body()) {
  return runScriptSlot(this, scriptObjectName(name()) + QLatin1Char('.') + QLatin1String(slot),
                       std::forward<Body>(body));
}

ObjectStore& MultiresClothPlugin::store() const {
  if (!store_) throw Error("the plugin has no object store (it must be loaded by the mrcloth host)");
  return *store_;
}

QString MultiresClothPlugin::description() const {
  return QStringLiteral("Multi-resolution quad refinement of garments driven by deformation modes");
}

int MultiresClothPlugin::refineUniform(QVariant id, QVariant levels) {
  return guarded("refineUniform", [&] {
    const StoredObject& input = store().get(script::toInt(id, QStringLiteral("id")));
    const int level_count = script::toIntAtLeast(levels, QStringLiteral("levels"), 0);

    // The job counts face splits (every level's; the last is three
    // quarters of them), then the refined faces built, so a huge
    // refinement shows its rate and can stop (2.4 million faces: 4.6 s).
    const double total = uniform_refine_steps(*input.mesh, level_count);
    const int steps = total < 2e9 ? std::max(1, static_cast<int>(total)) : 1;  // more are refused below
    JobScope job(*this, QStringLiteral("refineUniform"),
                 QStringLiteral("uniform refinement of %1, %2 level(s): %3 steps (face splits, then faces built)")
                     .arg(describeObject(input)).arg(level_count).arg(static_cast<qlonglong>(total)),
                 steps);
    QElapsedTimer timer;
    timer.start();
    auto refined = std::make_shared<QuadMesh>(copy_mesh(*input.mesh));
    int steps_done = 0;
    const bool complete = uniform_refine(*refined, level_count, [&](int done, int) {
      steps_done = done;
      job.progress(done);
      return !cancelRequested();
    });
    if (!complete)
      stopCancelled(QStringLiteral("refineUniform: cancelled after %1 of %2 steps; %3 is unchanged and no object was added")
                        .arg(steps_done).arg(steps).arg(describeObject(input)));
    const double milliseconds = millisecondsSince(timer);
    if (steps_done < steps) job.done();  // (levels 0: no step; the callback reported the last otherwise)

    const int result = store().add(refined, QStringLiteral("%1 uniform x%2").arg(input.name).arg(level_count));
    last_report_ = meshCounts(*refined);
    last_report_.insert({{QStringLiteral("operation"), QStringLiteral("refineUniform")},
                         {QStringLiteral("source"), input.id},
                         {QStringLiteral("result"), result},
                         {QStringLiteral("levels"), level_count},
                         {QStringLiteral("milliseconds"), milliseconds}});
    emit log(LOGINFO, QStringLiteral("refineUniform: object %1 -> object %2: %3 vertices, %4 faces (%5 ms)")
                          .arg(input.id).arg(result).arg(refined->n_vertices()).arg(refined->n_faces())
                          .arg(milliseconds, 0, 'f', 1));
    return result;
  });
}

int MultiresClothPlugin::setModes(QVariant id, QVariant vertexIds, QVariant mode) {
  return guarded("setModes", [&] {
    QuadMesh& mesh = store().mesh(script::toInt(id, QStringLiteral("id")));
    const std::vector<int> vertices = script::toIntList(vertexIds, QStringLiteral("vertexIds"));
    set_modes(mesh, vertices, script::toIntBetween(mode, QStringLiteral("mode"), 0, kLargestMode));
    return static_cast<int>(vertices.size());
  });
}

namespace {

/// A brush's radius, metres: a number >= 0, named in the refusal.
double radiusOption(const script::Options& options) {
  const double radius = script::toNumber(options.required(QStringLiteral("radius")), QStringLiteral("option 'radius'"));
  if (radius < 0.0)
    options::fail(QStringLiteral("option 'radius' must be a number >= 0 (metres), got %1").arg(radius));
  return radius;
}

}  // namespace

int MultiresClothPlugin::paintModes(QVariant id, QVariant brush) {
  return guarded("paintModes", [&] {
    const StoredObject& object = store().get(script::toInt(id, QStringLiteral("id")));
    const script::Options options(brush, QStringLiteral("brush"),
                                  {QStringLiteral("type"), QStringLiteral("center"), QStringLiteral("radius"),
                                   QStringLiteral("mode"), QStringLiteral("seeds"), QStringLiteral("layer"),
                                   QStringLiteral("threshold"), QStringLiteral("below")});
    const QString type = options.choice(QStringLiteral("type"), QStringLiteral("sphere"),
                                        {QStringLiteral("sphere"), QStringLiteral("geodesic"), QStringLiteral("threshold")});
    const int mode = script::toInt(options.required(QStringLiteral("mode")), QStringLiteral("option 'mode'"));
    const auto only_for = [&](const QString& key, const QString& brush_type) {
      if (options.has(key) && type != brush_type)
        throw ArgumentError(QStringLiteral("option '%1' belongs to the %2 brush, not the %3 brush")
                                .arg(key, brush_type, type).toStdString());
    };
    only_for(QStringLiteral("center"), QStringLiteral("sphere"));
    only_for(QStringLiteral("seeds"), QStringLiteral("geodesic"));
    only_for(QStringLiteral("layer"), QStringLiteral("threshold"));
    only_for(QStringLiteral("threshold"), QStringLiteral("threshold"));
    only_for(QStringLiteral("below"), QStringLiteral("threshold"));
    if (type == QLatin1String("threshold") && options.has(QStringLiteral("radius")))
      throw ArgumentError("option 'radius' belongs to the sphere and geodesic brushes, not the threshold brush");

    std::size_t painted = 0;
    if (type == QLatin1String("sphere")) {
      const auto center = options.vec3(QStringLiteral("center"));
      const double radius = radiusOption(options);
      painted = paint_modes_sphere(*object.mesh, OpenMesh::Vec3d(center[0], center[1], center[2]), radius, mode);
    } else if (type == QLatin1String("geodesic")) {
      const std::vector<int> seeds = script::toIntList(options.required(QStringLiteral("seeds")), QStringLiteral("option 'seeds'"));
      const double radius = radiusOption(options);
      painted = paint_modes_geodesic(*object.mesh, seeds, radius, mode);
    } else {
      const QString layer_name = script::toString(options.required(QStringLiteral("layer")), QStringLiteral("option 'layer'"));
      const double threshold =
          script::toNumber(options.required(QStringLiteral("threshold")), QStringLiteral("option 'threshold'"));
      painted = fill_modes_threshold(*object.mesh, layer_name.toStdString(), threshold, mode,
                                     !options.boolean(QStringLiteral("below"), false));
    }
    emit log(LOGINFO, QStringLiteral("paintModes: %1 brush, %2 vertices of object %3 set to mode %4")
                          .arg(type).arg(painted).arg(object.id).arg(mode));
    return static_cast<int>(painted);
  });
}

int MultiresClothPlugin::eraseModes(QVariant id, QVariant vertexIds) {
  return guarded("eraseModes", [&] {
    QuadMesh& mesh = store().mesh(script::toInt(id, QStringLiteral("id")));
    const std::vector<int> vertices =
        vertexIds.isValid() ? script::toIntList(vertexIds, QStringLiteral("vertexIds")) : std::vector<int>{};
    return static_cast<int>(erase_modes(mesh, vertices));
  });
}

QVariantList MultiresClothPlugin::getLayer(QVariant id, QVariant name) {
  return guarded("getLayer", [&] {
    const QuadMesh& mesh = store().mesh(script::toInt(id, QStringLiteral("id")));
    const std::vector<double> values = vertex_layer(mesh, script::toString(name, QStringLiteral("name")).toStdString());
    QVariantList list;
    list.reserve(static_cast<qsizetype>(values.size()));
    for (const double value : values) list.append(value);
    return list;
  });
}

void MultiresClothPlugin::saveLayers(QVariant id, QVariant path) {
  guarded("saveLayers", [&] {
    const QuadMesh& mesh = store().mesh(script::toInt(id, QStringLiteral("id")));
    const QString file = script::toString(path, QStringLiteral("path"));
    // Any other name replaced what was there (a cache, a mesh) with a table.
    if (QFileInfo(file).suffix().compare(QLatin1String("csv"), Qt::CaseInsensitive) != 0)
      throw ArgumentError(QStringLiteral("path must end in .csv (the layers are a CSV table), got \"%1\"").arg(file)
                              .toStdString());
    write_vertex_layers_csv(mesh, file.toStdString());
    return 0;
  });
}

int MultiresClothPlugin::loadModes(QVariant id, QVariant path) {
  return guarded("loadModes", [&] {
    QuadMesh& mesh = store().mesh(script::toInt(id, QStringLiteral("id")));
    const QString file = script::toString(path, QStringLiteral("path"));
    const ModesCsvRead read = read_modes_csv(mesh, file.toStdString());
    // A subset is legitimate (a tool's selection), but a CSV of another mesh
    // (the coarse garment's loaded into its refinement) looks just like one.
    if (read.set != mesh.n_vertices())
      emit log(LOGWARN, QStringLiteral("loadModes: %1 sets the modes of %2 of the mesh's %3 vertices; the others keep "
                                       "theirs (a CSV of another mesh?)").arg(file).arg(read.set).arg(mesh.n_vertices()));
    // So does a file of a mesh with as many vertices, or of this one with
    // its vertices in another order (a re-export): its positions tell.
    if (read.misplaced > 0)
      emit log(LOGWARN, QStringLiteral("loadModes: in %1, %2 of the %3 rows' x, y, z lie more than %4 mm from their "
                                       "vertex (at most %5 m: vertex %6, line %7): modes saved from another mesh, or "
                                       "from this one with its vertices in another order or moved? The modes are set "
                                       "by vertex number as given")
                            .arg(file).arg(read.misplaced).arg(read.set).arg(1000.0 * kCsvPositionTolerance)
                            .arg(read.farthest, 0, 'g', 3).arg(read.farthest_vertex).arg(read.farthest_line));
    return static_cast<int>(read.set);
  });
}

QVariantList MultiresClothPlugin::getModes(QVariant id) {
  return guarded("getModes", [&] {
    const std::vector<int> modes = get_modes(store().mesh(script::toInt(id, QStringLiteral("id"))));
    QVariantList list;
    list.reserve(static_cast<qsizetype>(modes.size()));
    for (const int mode : modes) list.append(mode);
    return list;
  });
}

int MultiresClothPlugin::refineAdaptive(QVariant id, QVariant options) {
  return guarded("refineAdaptive", [&] {
    const StoredObject& input = store().get(script::toInt(id, QStringLiteral("id")));
    const script::Options given(options, QStringLiteral("refineAdaptive options"),
                                {QStringLiteral("delta"), QStringLiteral("maxLevel"), QStringLiteral("balance")});
    AdaptiveRefineOptions settings;
    settings.delta = given.number(QStringLiteral("delta"), settings.delta);
    settings.max_level = given.integerAtLeast(QStringLiteral("maxLevel"), settings.max_level, 1);
    settings.balance = given.boolean(QStringLiteral("balance"), settings.balance);

    JobScope job(*this, QStringLiteral("refineAdaptive"),
                 QStringLiteral("adaptive refinement of %1 (delta %2, maxLevel %3, balance %4)")
                     .arg(describeObject(input)).arg(settings.delta).arg(settings.max_level)
                     .arg(settings.balance ? QStringLiteral("on") : QStringLiteral("off")));
    auto refined = std::make_shared<QuadMesh>(copy_mesh(*input.mesh));
    const AdaptiveRefineReport report = adaptive_refine(*refined, settings);
    job.done();

    const int result = store().add(refined, QStringLiteral("%1 adaptive").arg(input.name));
    last_report_ = {
        {QStringLiteral("operation"), QStringLiteral("refineAdaptive")},
        {QStringLiteral("source"), input.id},
        {QStringLiteral("result"), result},
        {QStringLiteral("delta"), settings.delta},
        {QStringLiteral("maxLevel"), settings.max_level},
        {QStringLiteral("balance"), settings.balance},
        {QStringLiteral("passes"), static_cast<qlonglong>(report.faces_refined_per_pass.size())},
        {QStringLiteral("facesRefinedPerPass"), script::toVariantList(report.faces_refined_per_pass)},
        {QStringLiteral("facesRefinedForBalance"), static_cast<qlonglong>(report.faces_refined_for_balance)},
        {QStringLiteral("hangingNodes"), static_cast<qlonglong>(report.hanging_nodes)},
        {QStringLiteral("vertices"), static_cast<qlonglong>(report.vertices)},
        {QStringLiteral("faces"), static_cast<qlonglong>(report.faces)},
        {QStringLiteral("verticesPerLevel"), script::toVariantList(report.vertices_per_level)},
        {QStringLiteral("facesPerLevel"), script::toVariantList(report.faces_per_level)},
        {QStringLiteral("milliseconds"), report.milliseconds}};
    emit log(LOGINFO, QStringLiteral("refineAdaptive: object %1 -> object %2: %3 vertices, %4 faces, %5 hanging "
                                     "nodes, %6 pass(es), %7 face(s) split for balance (%8 ms)")
                          .arg(input.id).arg(result).arg(report.vertices).arg(report.faces)
                          .arg(report.hanging_nodes).arg(report.faces_refined_per_pass.size())
                          .arg(report.faces_refined_for_balance).arg(report.milliseconds, 0, 'f', 1));
    return result;
  });
}

QVariantMap MultiresClothPlugin::lastReport() { return last_report_; }

void MultiresClothPlugin::warn(const QString& text) {
  emit log(LOGWARN, text);
  run_warnings_ << text;
}

void MultiresClothPlugin::logLines(const std::vector<LogLine>& lines) {
  for (const LogLine& line : lines) {
    if (line.type == LOGWARN) warn(line.text);
    else emit log(line.type, line.text);
  }
}

void MultiresClothPlugin::exportSurface(QVariant id, QVariant path, QVariant options) {
  guarded("exportSurface", [&] {
    const StoredObject& object = store().get(script::toInt(id, QStringLiteral("id")));
    const QString file = script::toString(path, QStringLiteral("path"));
    const script::Options given(options, QStringLiteral("exportSurface options"),
                                {QStringLiteral("colorBy"), QStringLiteral("triangulate"), QStringLiteral("cache"),
                                 QStringLiteral("frame")});
    ExportOptions settings;
    settings.color_by = toColorBy(given.choice(QStringLiteral("colorBy"), QStringLiteral("none"),
                                               {QStringLiteral("level"), QStringLiteral("mode"), QStringLiteral("curvature"),
                                                QStringLiteral("none")}));
    settings.triangulate = given.boolean(QStringLiteral("triangulate"), settings.triangulate);
    if (given.has(QStringLiteral("frame")) && !given.has(QStringLiteral("cache")))
      options::fail(QStringLiteral("option 'frame' needs option 'cache' (the PC2 the frame is read from)"));

    if (!given.has(QStringLiteral("cache"))) {
      export_surface(*object.mesh, file.toStdString(), settings);
      emit log(LOGINFO, QStringLiteral("exportSurface: wrote %1 (%2)").arg(file, describeObject(object)));
      return;
    }
    // A frame of a simulation: the object's surface (its faces, layers and
    // texture coordinates) at the cache's positions.
    const QString cache = options::existingInputFile(
        script::toString(given.required(QStringLiteral("cache")), options::optionLabel(QStringLiteral("cache"))),
        options::optionLabel(QStringLiteral("cache")));
    const int frame = given.has(QStringLiteral("frame"))
                          ? script::toInt(given.required(QStringLiteral("frame")), options::optionLabel(QStringLiteral("frame")))
                          : 0;
    Pc2Reader reader(cache.toStdString());
    if (reader.num_points() != static_cast<int>(object.mesh->n_vertices()))
      options::fail(QStringLiteral("option 'cache': %1 has %2 points per frame; %3 has %4 vertices (a cache of "
                                   "another mesh?)")
                        .arg(cache).arg(reader.num_points()).arg(describeObject(object))
                        .arg(object.mesh->n_vertices()));
    const FramePositions positions = reader.finite_frame(frame);
    // Its triangles chosen on the object's own positions: every frame's the same (a DCC tool's
    // sequence of frames needs one topology; the diagonals flipped from frame to frame).
    settings.triangles_of = object.mesh.get();
    export_surface(mesh_at_positions(*object.mesh, positions), file.toStdString(), settings);
    emit log(LOGINFO, QStringLiteral("exportSurface: wrote %1 (%2 at frame %3 of %4)")
                          .arg(file, describeObject(object)).arg(frame).arg(QFileInfo(cache).fileName()));
  });
}

QVariantMap MultiresClothPlugin::simulate(QVariant id, QVariant options) {
  return guarded("simulate", [&] {
    run_warnings_.clear();
    const StoredObject& input = store().get(script::toInt(id, QStringLiteral("id")));
    const SimulationRequest request = parseSimulationOptions(options, *input.mesh);
    requireOutputsSpareInputs(request, input.path);
    if (request.character) return simulateOnCharacter(QStringLiteral("simulate"), input, request);
    const QString contact_warning =
        selfContactWarning(QStringLiteral("simulate"), *input.mesh, request.simulation.self_contact);
    if (!contact_warning.isEmpty()) warn(contact_warning);
    const SimulationOptions& settings = request.simulation;
    if (const QString precision = cachePrecisionWarning(QStringLiteral("simulate"), *input.mesh, settings);
        !precision.isEmpty())
      warn(precision);
    // The job starts with the set-up (the model, then the factorisation),
    // which shows as it and can be cancelled between its phases.
    std::optional<JobScope> job;
    job.emplace(*this, QStringLiteral("simulate"),
                QStringLiteral("simulation of %1: %2 vertices, %3 frames at %4 fps x %5 substeps, %6, pins %7, "
                               "%8 collider(s); setting up first (the model, then factorising its system)")
                    .arg(describeObject(input)).arg(input.mesh->n_vertices()).arg(settings.frames).arg(settings.fps)
                    .arg(settings.substeps).arg(QString::fromStdString(request.dynamics.material.name))
                    .arg(request.pinsText).arg(settings.colliders.size()),
                settings.frames);
    std::optional<DynamicsModel> built = build_dynamics(*input.mesh, request.dynamics, [&] { return !cancelRequested(); });
    if (!built || cancelRequested()) stopInSetUp(QStringLiteral("simulate"), settings.frames);
    const DynamicsModel model = std::move(*built);
    emit log(LOGINFO, QStringLiteral("simulate: setting up: factorising the system of %1 unknowns (free vertices)")
                          .arg(model.free_mass.size()));
    ClothState state = rest_state(model);

    const std::unique_ptr<StagedFile> staged_rest_mesh = stageRestMesh(*input.mesh, settings.cache_path);
    std::vector<Positions> frames;  // kept only for an OBJ sequence
    // Called with 0 frames done between the set-up's phases: no progress yet.
    const SimulationProgress progress = [&](int frames_done, int) {
      if (frames_done > 0) job->progress(frames_done);
      return !cancelRequested();
    };
    const SimulationReport report = mrcloth::simulate(model, state, settings, {}, progress,
                                                      request.objSequence.isEmpty() ? nullptr : &frames);
    job.reset();
    if (report.cancelled && report.frames == 0) stopInSetUp(QStringLiteral("simulate"), settings.frames);
    const bool complete = !report.cancelled && !report.non_finite;

    // Like the PC2 cache, the other outputs exist only for a complete run.
    RunOutputs outputs;
    if (complete) outputs.obj_files = writeObjSequence(request, frames, *input.mesh);
    outputs.rest_mesh = commitRestMesh(staged_rest_mesh, complete);
    if (complete && request.updateObject)
      outputs.result = store().add(lastFrameMesh(*input.mesh, model, state), QStringLiteral("%1 simulated").arg(input.name));

    last_report_ = simulationReportMap(report, model);
    last_report_.insert(runOutputsReportMap(QStringLiteral("simulate"), input.id, request, outputs));
    logLines(simulationOutcomeLines(input.id, request, report));
    last_report_.insert(QStringLiteral("warnings"), run_warnings_);
    return last_report_;
  });
}

QVariantMap MultiresClothPlugin::extractModes(QVariant id, QVariant cachePath, QVariant options) {
  return guarded("extractModes", [&] {
    const StoredObject& input = store().get(script::toInt(id, QStringLiteral("id")));
    const QString path = script::toString(cachePath, QStringLiteral("cachePath"));
    const ModeRequest request = parseModeOptions(options);
    const ModeOptions& modes = request.modes;
    const CurvatureAnalysisOptions& analysis = request.analysis;

    QElapsedTimer timer;
    timer.start();
    const CurvaturePairs pairs = curvature_pairs(*input.mesh);
    CurvatureFeatures features;
    {
      const Pc2Reader header(path.toStdString());  // for the job's length; checked again by the analysis
      const int available = std::max(0, header.num_frames() - analysis.skip_frames);
      const int total = analysis.max_frames > 0 ? std::min(available, analysis.max_frames) : available;
      JobScope job(*this, QStringLiteral("extractModes"),
                   QStringLiteral("curvature of %1 over %2 frames of %3").arg(describeObject(input)).arg(total).arg(path),
                   std::max(1, total));
      features = analyse_curvature(path.toStdString(), pairs, analysis, [&](int done, int) {
        job.progress(done);
        return !cancelRequested();
      });
    }
    if (features.cancelled)
      throw Error("extractModes: cancelled after " + std::to_string(features.frames) + " frames; the modes are unchanged");
    // What the modes would be made of, said before they are: a cache that
    // does not fit the mesh's rest lengths, or one with no bending in it.
    for (const LogLine& line : curvatureCacheWarnings(path, features)) emit log(line.type, line.text);
    ModeReport report;
    try {
      // Each restart is a whole k-means run (2,000 of 50 clusters on 175k
      // vertices: 38 s), so the restarts are the job's steps and a Ctrl-C
      // stops between two of them.
      JobScope job(*this, QStringLiteral("extractModes"),
                   QStringLiteral("k-means of %1 clusters, %2 restarts over %3 vertices")
                       .arg(modes.modes).arg(modes.restarts).arg(features.mean.size()),
                   modes.restarts);
      report = deformation_modes(features.mean, features.deviation, modes, [&](int done, int) {
        job.progress(done);
        return !cancelRequested();
      });
    } catch (const ArgumentError& error) {
      // k-means' own wording names neither the cache nor the cause.
      if (std::string(error.what()).find("requested but only") == std::string::npos) throw;
      throw ArgumentError(path.toStdString() + ": the curvature takes fewer distinct values over the mesh's vertices "
                          "than the " + std::to_string(modes.modes) + " clusters asked for (a cache with no bending, "
                          "or of a still garment?); expected clusters at most that many (" + error.what() + ")");
    }
    if (report.cancelled)
      stopCancelled(QStringLiteral("extractModes: cancelled during clustering, after %1 of %2 restarts; the modes are "
                                   "unchanged")
                        .arg(report.restarts_done).arg(modes.restarts));
    // The computed modes become the mesh's mode layer (what refineAdaptive
    // reads) and its computed layer (what eraseModes goes back to); the
    // features stay as layers for threshold brushes and exports.
    set_computed_modes(*input.mesh, report.modes);
    set_vertex_layer(*input.mesh, layer::mean_curvature,
                     std::vector<double>(features.mean.data(), features.mean.data() + features.mean.size()));
    set_vertex_layer(*input.mesh, layer::curvature_deviation,
                     std::vector<double>(features.deviation.data(), features.deviation.data() + features.deviation.size()));

    last_report_ = modeReportMap(input.id, path, features, pairs.num_vertices, modes, report, millisecondsSince(timer));
    emit log(LOGINFO, modesFoundLine(describeObject(input), features, modes, pairs.num_vertices, report));
    return last_report_;
  });
}

QVariantMap MultiresClothPlugin::mapModes(QVariant refinedId, QVariant coarseId, QVariant options) {
  return guarded("mapModes", [&] {
    const StoredObject& refined = store().get(script::toInt(refinedId, QStringLiteral("refinedId")));
    const StoredObject& coarse = store().get(script::toInt(coarseId, QStringLiteral("coarseId")));
    const script::Options given(options, QStringLiteral("mapModes options"), {QStringLiteral("method")});
    const QString method = given.choice(QStringLiteral("method"), QStringLiteral("index"),
                                        {QStringLiteral("index"), QStringLiteral("highest"), QStringLiteral("frequent")});
    const ModeMapReport report = map_modes(*refined.mesh, *coarse.mesh, mode_mapping_from_name(method.toStdString()));
    const int vertices = static_cast<int>(report.modes.size());
    last_report_ = {{QStringLiteral("operation"), QStringLiteral("mapModes")},
                    {QStringLiteral("source"), refined.id},
                    {QStringLiteral("result"), coarse.id},
                    {QStringLiteral("method"), method},
                    {QStringLiteral("vertices"), vertices},
                    {QStringLiteral("changed"), report.changed},
                    {QStringLiteral("agreeHighest"), report.agree_highest},
                    {QStringLiteral("agreeFrequent"), report.agree_frequent}};
    emit log(LOGINFO, QStringLiteral("mapModes: %1 -> %2 by %3: %4 of %5 coarse vertices changed; the stable-index "
                                     "mode is the cell's highest at %6, its most frequent at %7")
                          .arg(describeObject(refined), describeObject(coarse), method).arg(report.changed)
                          .arg(vertices).arg(report.agree_highest).arg(report.agree_frequent));
    return last_report_;
  });
}

QVariantMap MultiresClothPlugin::compareResults(QVariant id, QVariant cachePath, QVariant referenceId,
                                                QVariant referenceCachePath, QVariant options) {
  return guarded("compareResults", [&] {
    const StoredObject& model = store().get(script::toInt(id, QStringLiteral("id")));
    const StoredObject& reference = store().get(script::toInt(referenceId, QStringLiteral("referenceId")));
    const QString model_cache = options::existingInputFile(script::toString(cachePath, QStringLiteral("cachePath")),
                                                           QStringLiteral("cachePath"));
    const QString reference_cache = options::existingInputFile(
        script::toString(referenceCachePath, QStringLiteral("referenceCachePath")), QStringLiteral("referenceCachePath"));
    const ComparisonOptions settings = parseComparisonOptions(options);
    QElapsedTimer timer;
    timer.start();
    const int frames = Pc2Reader(reference_cache.toStdString()).num_frames();
    ComparisonReport report;
    {
      JobScope job(*this, QStringLiteral("compareResults"),
                   QStringLiteral("%1 against %2 at its %3 material points")
                       .arg(describeObject(model), describeObject(reference)).arg(reference.mesh->n_vertices()),
                   settings.max_frames > 0 ? std::min(frames, settings.max_frames) : frames);
      report = compare_results(*model.mesh, model_cache.toStdString(), *reference.mesh, reference_cache.toStdString(),
                               settings, [&](int done, int) {
                                 job.progress(done);
                                 return !cancelRequested();
                               });
    }
    last_report_ = comparisonReportMap(model.id, reference.id, report, millisecondsSince(timer));
    emit log(LOGINFO, comparisonOutcomeLine(describeObject(model), describeObject(reference), report));
    return last_report_;
  });
}

QVariantMap MultiresClothPlugin::recordInstance(QVariant id, QVariant options) {
  return guarded("recordInstance", [&] {
    run_warnings_.clear();
    const StoredObject& input = store().get(script::toInt(id, QStringLiteral("id")));
    const SimulationRequest request = parseSimulationOptions(options, *input.mesh, SimulationCall::recordInstance);
    requireOutputsSpareInputs(request, input.path);
    return simulateOnCharacter(QStringLiteral("recordInstance"), input, request);
  });
}

QVariantMap MultiresClothPlugin::limits() { return options::limitsMap(); }

QVariantMap MultiresClothPlugin::motionInfo(QVariant motion) {
  return guarded("motionInfo", [&] {
    const MotionReading reading = readMotion(motion);
    const Motion& clip = reading.clip;
    QVariantList joints;
    for (const Joint& joint : clip.skeleton.joints)
      if (!joint.end_site) joints.append(QString::fromStdString(joint.name));
    QVariantMap renamed;
    for (const auto& [from, to] : reading.changes.renamed) renamed.insert(QString::fromStdString(from), QString::fromStdString(to));
    // From where a run starts (skipFirst drops the added T-pose, whose jump
    // to the first real frame is no glitch).
    const int first = (reading.request.setup.skip_first ? 1 : 0) +
                      static_cast<int>(std::floor(reading.request.setup.motion_start / clip.frame_time));
    const LegSpeed fastest = fastest_leg_speed(clip, first);
    return QVariantMap{{QStringLiteral("path"), reading.request.motionPath},
                       {QStringLiteral("units"), reading.request.motionUnits},
                       {QStringLiteral("metresPerUnit"), reading.request.motionScale},
                       {QStringLiteral("joints"), joints},
                       {QStringLiteral("frames"), static_cast<int>(clip.frames.rows())},
                       {QStringLiteral("frameTime"), clip.frame_time},
                       {QStringLiteral("duration"), clip.duration()},
                       {QStringLiteral("legs"), reading.figure.legs},
                       {QStringLiteral("legsFactor"), reading.figure.factor()},
                       {QStringLiteral("jointsRenamed"), renamed},
                       {QStringLiteral("axesTurned"), QString::fromStdString(reading.changes.turned.describe())},
                       {QStringLiteral("axesUndecided"), QString::fromStdString(reading.changes.axes_undecided)},
                       {QStringLiteral("fastestLegSpeed"),
                        QVariantMap{{QStringLiteral("speed"), fastest.speed}, {QStringLiteral("frame"), fastest.frame},
                                    {QStringLiteral("joint"), QString::fromStdString(fastest.joint)}}},
                       {QStringLiteral("legJitter"), leg_jitter(clip, first)}};
  });
}


QVariantMap MultiresClothPlugin::simulateOnCharacter(const QString& slot, const StoredObject& input,
                                                     const SimulationRequest& request) {
  CharacterRequest wanted = *request.character;  // its units resolved by loadCharacter
  ClipChanges changes;
  Character character = loadCharacter(wanted, *input.mesh, &changes);
  const Motion& motion = *character.motion;
  logLines(clipChangeLines(slot, wanted, changes));

  // One job over the set-up (placing the garment, the model, the checks,
  // the factorisation), the pre-roll's frames and the motion's, so that a
  // long set-up or pre-roll shows and can be cancelled like the rest. Its
  // length from what character_run_options takes it from.
  CharacterRunOptions timing;
  timing.fps = request.simulation.fps;
  timing.step_rate = wanted.setup.step_rate;
  timing.preroll_seconds = wanted.setup.preroll_seconds;
  const int preroll_frames = preroll_frame_count(timing);
  const int run_frames = request.simulation.frames;
  std::optional<JobScope> job;
  job.emplace(*this, slot,
              QStringLiteral("simulation of %1 on %2 (%3, %4 body): %5 vertices, pre-roll %6 s (%7 frames), then %8 frames "
                             "at %9 fps x %10 substeps, %11, waist %12; setting up first (placing the garment, the model, "
                             "then factorising its system)")
                  .arg(describeObject(input), QFileInfo(wanted.motionPath).fileName(), wanted.motionUnits,
                       bodyTypeName(wanted.setup.body))
                  .arg(input.mesh->n_vertices()).arg(wanted.setup.preroll_seconds).arg(preroll_frames).arg(run_frames)
                  .arg(request.simulation.fps).arg(steps_per_frame(timing))
                  .arg(QString::fromStdString(request.dynamics.material.name), request.pinsText),
              preroll_frames + run_frames);
  const auto stop_if_cancelled = [&] {
    if (cancelRequested()) stopInSetUp(slot, preroll_frames + run_frames);
  };

  // The garment in the skeleton's rest space (on the skinned body, moved
  // clear of it); the object itself is untouched.
  const PlacedGarment placed = place_garment(character, wanted.setup, *input.mesh);
  stop_if_cancelled();
  const QuadMesh* garment = &placed.mesh;
  if (placed.clearance.moved > 0)
    emit log(LOGINFO, QStringLiteral("%1: %2 garment vertices started inside the body or within its thickness; moved "
                                     "out (at most %3 mm) before the run")
                          .arg(slot).arg(placed.clearance.moved).arg(1000.0 * placed.clearance.largest_move, 0, 'f', 1));
  std::optional<DynamicsModel> built = build_dynamics(*garment, request.dynamics, [&] { return !cancelRequested(); });
  if (!built || cancelRequested()) stopInSetUp(slot, preroll_frames + run_frames);
  const DynamicsModel model = std::move(*built);
  ClothState state = rest_state(model);
  const CharacterRunOptions run = character_run_options(character, wanted.setup, model, request.simulation);
  assert(preroll_frame_count(run) == preroll_frames && run.frames == run_frames && "the job's length is the run's");

  std::vector<LogLine> checks;
  const QVariantMap fit = checkBeforeCharacterRun(slot, request, character, run, model, *garment, checks);
  logLines(checks);

  stop_if_cancelled();
  emit log(LOGINFO, QStringLiteral("%1: setting up: factorising the system of %2 unknowns (free vertices)")
                        .arg(slot).arg(model.free_mass.size()));
  const std::unique_ptr<StagedFile> staged_rest_mesh = stageRestMesh(*garment, run.simulation.cache_path);
  std::vector<Positions> frames;  // kept only for an OBJ sequence
  // Called with 0 frames done between the set-up's phases: no progress yet.
  const SimulationProgress progress = [&](int frames_done, int) {
    if (frames_done > 0) job->progress(frames_done);
    return !cancelRequested();
  };
  const CharacterRunReport report = simulate_on_character(model, state, motion, *character.body, run, progress,
                                                          request.objSequence.isEmpty() ? nullptr : &frames);
  job.reset();
  if (report.motion.cancelled && report.preroll.frames == 0 && report.motion.frames == 0)
    stopInSetUp(slot, preroll_frames + run_frames);
  const SimulationReport& motion_report = report.motion;
  const bool complete = !motion_report.cancelled && !motion_report.non_finite;

  // Like the PC2 cache, the other outputs exist only for a complete run.
  RunOutputs outputs;
  if (complete) outputs.obj_files = writeObjSequence(request, frames, *garment);
  outputs.rest_mesh = commitRestMesh(staged_rest_mesh, complete);
  if (complete && !wanted.bodyOutput.isEmpty()) {
    outputs.body_mesh = restMeshPath(wanted.bodyOutput.toStdString());
    write_body_cache(motion, *character.body, run, wanted.bodyOutput.toStdString(), outputs.body_mesh.toStdString());
  }
  if (complete && request.updateObject)
    outputs.result = store().add(lastFrameMesh(*input.mesh, model, state),
                                 QStringLiteral("%1 on %2").arg(input.name, QFileInfo(wanted.motionPath).completeBaseName()));

  last_report_ = simulationReportMap(motion_report, model);
  last_report_.insert(characterReportMap(report, wanted, character, run));
  last_report_.insert(characterRunReportMap(wanted, changes, fit, placed.clearance, outputs));
  last_report_.insert(runOutputsReportMap(slot, input.id, request, outputs));
  logLines(characterOutcomeLines(slot, input.id, request, wanted, report, run, outputs.rest_mesh));
  last_report_.insert(QStringLiteral("warnings"), run_warnings_);
  return last_report_;
}


}  // namespace mrcloth
