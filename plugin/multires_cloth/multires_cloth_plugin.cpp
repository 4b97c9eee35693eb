#include "multires_cloth_plugin.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/quad_mesh.h"
#include "mesh_ops/uniform_refine.h"
#include "plugin/core/object_store.h"
#include "plugin/core/script_errors.h"
#include "plugin/core/script_values.h"
#include "simulation_options.h"
#include "solver/dynamics_model.h"
#include "solver/implicit_integrator.h"
#include "solver/point_cache.h"
#include "solver/simulate.h"

#include <QElapsedTimer>

#include <memory>

namespace mrcloth {
namespace {

/// Announces a job of `steps` steps to the host for as long as it is alive,
/// so that a job that throws is still reported finished.
class JobScope {
 public:
  JobScope(ProcessInterface& process, QString id, const QString& description, int steps = 1)
      : process_(process), id_(std::move(id)), steps_(steps) {
    process_.startJob(id_, description, 0, steps_);
  }
  ~JobScope() { process_.finishJob(id_); }
  void progress(int steps_done) { process_.setJobState(id_, steps_done); }
  void done() { process_.setJobState(id_, steps_); }
  JobScope(const JobScope&) = delete;
  JobScope& operator=(const JobScope&) = delete;

 private:
  ProcessInterface& process_;
  QString id_;
  int steps_;
};

double millisecondsSince(const QElapsedTimer& timer) { return static_cast<double>(timer.nsecsElapsed()) / 1e6; }

QString describeObject(const StoredObject& object) {
  return QStringLiteral("object %1 '%2'").arg(object.id).arg(object.name);
}

ColorBy toColorBy(const QString& name) {
  if (name == QLatin1String("level")) return ColorBy::level;
  if (name == QLatin1String("mode")) return ColorBy::mode;
  return ColorBy::none;
}

/// The counts every refinement report shares, read from the refined mesh.
QVariantMap meshCounts(const QuadMesh& mesh) {
  return {{QStringLiteral("vertices"), static_cast<qlonglong>(mesh.n_vertices())},
          {QStringLiteral("faces"), static_cast<qlonglong>(mesh.n_faces())},
          {QStringLiteral("hangingNodes"), static_cast<qlonglong>(count_hanging(mesh))},
          {QStringLiteral("verticesPerLevel"), script::toVariantList(vertices_per_level(mesh))},
          {QStringLiteral("facesPerLevel"), script::toVariantList(faces_per_level(mesh))}};
}

/// Every active face as its polygon (hanging vertices included), for OBJ sequences.
std::vector<std::vector<int>> activeFaces(const QuadMesh& mesh) {
  std::vector<std::vector<int>> faces;
  faces.reserve(mesh.n_faces());
  for (const auto face : mesh.faces()) {
    std::vector<int> polygon;
    for (const auto vertex : mesh.fv_range(face)) polygon.push_back(vertex.idx());
    faces.push_back(std::move(polygon));
  }
  return faces;
}

}  // namespace

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

    JobScope job(*this, QStringLiteral("refineUniform"),
                 QStringLiteral("uniform refinement of %1, %2 level(s)").arg(describeObject(input)).arg(level_count));
    QElapsedTimer timer;
    timer.start();
    auto refined = std::make_shared<QuadMesh>(copy_mesh(*input.mesh));
    uniform_refine(*refined, level_count);
    const double milliseconds = millisecondsSince(timer);
    job.done();

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
    set_modes(mesh, vertices, script::toInt(mode, QStringLiteral("mode")));
    return static_cast<int>(vertices.size());
  });
}

int MultiresClothPlugin::paintModes(QVariant id, QVariant brush) {
  return guarded("paintModes", [&] {
    const StoredObject& object = store().get(script::toInt(id, QStringLiteral("id")));
    const script::Options options(brush, QStringLiteral("brush"),
                                  {QStringLiteral("center"), QStringLiteral("radius"), QStringLiteral("mode")});
    const auto center = options.vec3(QStringLiteral("center"));
    const double radius = script::toNumber(options.required(QStringLiteral("radius")), QStringLiteral("option 'radius'"));
    const int mode = script::toInt(options.required(QStringLiteral("mode")), QStringLiteral("option 'mode'"));

    const std::size_t painted =
        paint_modes_sphere(*object.mesh, OpenMesh::Vec3d(center[0], center[1], center[2]), radius, mode);
    emit log(LOGINFO, QStringLiteral("paintModes: %1 vertices of object %2 set to mode %3")
                          .arg(painted).arg(object.id).arg(mode));
    return static_cast<int>(painted);
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

void MultiresClothPlugin::exportSurface(QVariant id, QVariant path, QVariant options) {
  guarded("exportSurface", [&] {
    const StoredObject& object = store().get(script::toInt(id, QStringLiteral("id")));
    const QString file = script::toString(path, QStringLiteral("path"));
    const script::Options given(options, QStringLiteral("exportSurface options"),
                                {QStringLiteral("colorBy"), QStringLiteral("triangulate")});
    ExportOptions settings;
    settings.color_by = toColorBy(given.choice(QStringLiteral("colorBy"), QStringLiteral("none"),
                                               {QStringLiteral("level"), QStringLiteral("mode"), QStringLiteral("none")}));
    settings.triangulate = given.boolean(QStringLiteral("triangulate"), settings.triangulate);

    export_surface(*object.mesh, file.toStdString(), settings);
    emit log(LOGINFO, QStringLiteral("exportSurface: wrote %1 (%2)").arg(file, describeObject(object)));
  });
}

QVariantMap MultiresClothPlugin::simulate(QVariant id, QVariant options) {
  return guarded("simulate", [&] {
    const StoredObject& input = store().get(script::toInt(id, QStringLiteral("id")));
    const SimulationRequest request = parseSimulationOptions(options, *input.mesh);
    const DynamicsModel model = build_dynamics(*input.mesh, request.dynamics);
    ClothState state = rest_state(model);

    const SimulationOptions& settings = request.simulation;
    std::vector<Positions> frames;  // kept only for an OBJ sequence
    SimulationReport report;
    {
      JobScope job(*this, QStringLiteral("simulate"),
                   QStringLiteral("simulation of %1: %2 vertices, %3 frames at %4 fps x %5 substeps, %6, pins %7, "
                                  "%8 collider(s)")
                       .arg(describeObject(input)).arg(model.num_vertices).arg(settings.frames).arg(settings.fps)
                       .arg(settings.substeps).arg(QString::fromStdString(request.dynamics.material.name))
                       .arg(request.pinsText).arg(settings.colliders.size()),
                   settings.frames);
      const SimulationProgress progress = [&](int frames_done, int) {
        job.progress(frames_done);
        return !cancelRequested();
      };
      report = mrcloth::simulate(model, state, settings, {}, progress,
                                 request.objSequence.isEmpty() ? nullptr : &frames);
    }
    const bool complete = !report.cancelled && !report.non_finite;

    // Like the PC2 cache, the other outputs exist only for a complete run.
    QStringList obj_files;
    if (complete && !request.objSequence.isEmpty())
      for (const std::string& file : write_obj_sequence(request.objSequence.toStdString(), frames, activeFaces(*input.mesh)))
        obj_files << QString::fromStdString(file);
    int result = 0;
    if (complete && request.updateObject) {
      auto simulated = std::make_shared<QuadMesh>(copy_mesh(*input.mesh));
      const Positions last = full_positions(model, state.positions, state.pinned);
      for (const auto vertex : simulated->vertices()) {
        const auto row = last.row(vertex.idx());
        simulated->set_point(vertex, OpenMesh::Vec3d(row(0), row(1), row(2)));
      }
      result = store().add(simulated, QStringLiteral("%1 simulated").arg(input.name));
    }

    last_report_ = simulationReportMap(report, model);
    last_report_.insert({{QStringLiteral("operation"), QStringLiteral("simulate")},
                         {QStringLiteral("source"), input.id},
                         {QStringLiteral("material"), QString::fromStdString(request.dynamics.material.name)},
                         {QStringLiteral("objFiles"), obj_files}});
    if (result > 0) last_report_.insert(QStringLiteral("resultId"), result);

    if (report.initial_penetration > 0.0)
      emit log(LOGWARN, QStringLiteral("simulate: the cloth starts %1 mm inside a collider (or its thickness); "
                                       "it is pushed out on the first step, which stretches it: move the "
                                       "colliders or the garment so they start apart")
                            .arg(1000.0 * report.initial_penetration, 0, 'f', 1));
    if (report.cancelled)
      emit log(LOGWARN, QStringLiteral("simulate: cancelled after %1 of %2 frames; nothing was written")
                            .arg(report.frames).arg(settings.frames));
    else if (report.non_finite)
      emit log(LOGWARN, QStringLiteral("simulate: the simulation became non-finite (NaN or infinity) in frame %1 "
                                       "of %2; nothing was written (try more substeps or a softer material)")
                            .arg(report.frames + 1).arg(settings.frames));
    else
      emit log(LOGINFO, QStringLiteral("simulate: object %1: %2 frames, %3 steps, %4 ms/frame (dynamics %5, "
                                       "collision %6), max stretch %7 %, max penetration %8 mm%9")
                            .arg(input.id).arg(report.frames).arg(report.steps)
                            .arg(report.ms_per_frame_total, 0, 'f', 2).arg(report.ms_per_frame_dynamics, 0, 'f', 2)
                            .arg(report.ms_per_frame_collision, 0, 'f', 2).arg(100.0 * report.max_stretch, 0, 'f', 2)
                            .arg(1000.0 * report.max_penetration, 0, 'f', 3)
                            .arg(report.cache_path.empty() ? QString()
                                                           : QStringLiteral(" -> ") +
                                                                 QString::fromStdString(report.cache_path)));
    return last_report_;
  });
}

QList<SlotDescription> MultiresClothPlugin::slotDescriptions() const {
  const QString id_text = QStringLiteral("object id (from core.loadObject or a refinement)");
  return {
      {QStringLiteral("refineUniform(int id, int levels) -> int"),
       QStringLiteral("Copies the object and splits every face `levels` times; returns the new object's id "
                      "(the input is untouched)."),
       {QStringLiteral("id"), QStringLiteral("levels")},
       {id_text, QStringLiteral("number of uniform 1-to-4 splits, >= 0")}},
      {QStringLiteral("setModes(int id, int[] vertexIds, int mode) -> int"),
       QStringLiteral("Sets the deformation mode of the given vertices; returns how many ids were given."),
       {QStringLiteral("id"), QStringLiteral("vertexIds"), QStringLiteral("mode")},
       {id_text, QStringLiteral("vertex indices in [0, vertices)"),
        QStringLiteral("mode to set, >= 0 (1 = least deformation, the default)")}},
      {QStringLiteral("paintModes(int id, object brush) -> int"),
       QStringLiteral("Sets the mode of every vertex inside a sphere; returns the number of vertices painted."),
       {QStringLiteral("id"), QStringLiteral("brush")},
       {id_text, QStringLiteral("{center: [x, y, z] in m, radius: m (inclusive), mode: int >= 0}, all required")}},
      {QStringLiteral("getModes(int id) -> int[]"),
       QStringLiteral("Returns the mode of every vertex, indexed by vertex."),
       {QStringLiteral("id")},
       {id_text}},
      {QStringLiteral("refineAdaptive(int id, object options = {}) -> int"),
       QStringLiteral("Copies the object and refines it where its modes ask for it (Algorithms 2 and 3); returns "
                      "the new object's id (the input is untouched). See lastReport()."),
       {QStringLiteral("id"), QStringLiteral("options")},
       {id_text, QStringLiteral("{delta: number = 8 (split a face when the R of its 4 corners sums to >= delta), "
                                "maxLevel: int >= 1 = 3 (coarse = 1), balance: bool = true (2:1 balance)}")}},
      {QStringLiteral("lastReport() -> object"),
       QStringLiteral("Report of the last refineUniform/refineAdaptive/simulate. Refinements: operation, source, "
                      "result, vertices, faces, hangingNodes, verticesPerLevel, facesPerLevel (element L = level "
                      "L), milliseconds; adaptive also facesRefinedPerPass, passes, facesRefinedForBalance, delta, "
                      "maxLevel, balance. simulate: what simulate returned. {} before any of them."),
       {},
       {}},
      {QStringLiteral("exportSurface(int id, string path, object options = {})"),
       QStringLiteral("Writes the active surface to .obj or .ply (atomically), optionally with vertex colours."),
       {QStringLiteral("id"), QStringLiteral("path"), QStringLiteral("options")},
       {id_text, QStringLiteral("output file; the extension picks the format"),
        QStringLiteral("{colorBy: \"level\" | \"mode\" | \"none\" = \"none\", triangulate: bool = false}")}},
      {QStringLiteral("simulate(int id, object options = {}) -> object"),
       QStringLiteral("Simulates the object's cloth from rest (mass-spring model of paper section 6, implicit "
                      "steps) and returns a report: frames, steps, timeStep (s), precomputeMs, msPerFrame "
                      "{dynamics, collision, total}, maxStretch (strain), maxPenetration (m), initialPenetration (m), nonFinite, cancelled, "
                      "output, vertices, freeVertices, pinnedVertices, hangingVertices, springs {stretch, shear, "
                      "bend}, perFrameMs [{dynamics, collision}], objFiles, resultId (with updateObject). The "
                      "object is untouched. Files appear only when the run completes (not on Ctrl-C or NaN)."),
       {QStringLiteral("id"), QStringLiteral("options")},
       {id_text,
        QStringLiteral(
            "{frames: int >= 1 = 60, fps: number > 0 = 30, substeps: int >= 1 = 4 (steps per frame), "
            "iterations: int >= 1 = 4 (per step), material: \"cotton\" | \"denim\" | \"silk\" = \"cotton\" or "
            "{preset, arealDensity (kg/m^2), stretchStiffness, shearStiffness, bendStiffness (N/m), damping "
            "(1/s), stretchLimit (strain)}, alpha: number = 0 and alphaBend: number = 1 (stiffness x "
            "2^(alpha (level - 1))), gravity: [x, y, z] m/s^2 = [0, -9.81, 0], pins: vertex ids or a boundary "
            "loop \"top\" | \"bottom\" | \"loop:N\" (or an array mixing both) = none, colliders: [{type: "
            "\"plane\", point = [0, 0, 0], normal = [0, 1, 0]} | {type: \"sphere\", center, radius} | {type: "
            "\"capsule\", a, b, radius or radiusA and radiusB}, each with thickness (m) = 0.002 and friction = "
            "0.3], output: PC2 file (its folder must exist) = none, objSequence: OBJ file prefix "
            "(<prefix>_0000.obj ...) = none, updateObject: bool = false (store the last frame as a new "
            "object)}; lengths in m")}},
  };
}

}  // namespace mrcloth
