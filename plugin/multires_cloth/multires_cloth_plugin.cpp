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

#include <QElapsedTimer>

#include <memory>

namespace mrcloth {
namespace {

/// Announces a job to the host for as long as it is alive, so that a job
/// that throws is still reported finished.
class JobScope {
 public:
  JobScope(ProcessInterface& process, QString id, const QString& description)
      : process_(process), id_(std::move(id)) {
    process_.startJob(id_, description, 0, 1);
  }
  ~JobScope() { process_.finishJob(id_); }
  void done() { process_.setJobState(id_, 1); }
  JobScope(const JobScope&) = delete;
  JobScope& operator=(const JobScope&) = delete;

 private:
  ProcessInterface& process_;
  QString id_;
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
       QStringLiteral("Report of the last refineUniform/refineAdaptive: operation, source, result, vertices, "
                      "faces, hangingNodes, verticesPerLevel, facesPerLevel (element L = level L), milliseconds; "
                      "adaptive also facesRefinedPerPass, passes, facesRefinedForBalance, delta, maxLevel, "
                      "balance. {} before any refinement."),
       {},
       {}},
      {QStringLiteral("exportSurface(int id, string path, object options = {})"),
       QStringLiteral("Writes the active surface to .obj or .ply (atomically), optionally with vertex colours."),
       {QStringLiteral("id"), QStringLiteral("path"), QStringLiteral("options")},
       {id_text, QStringLiteral("output file; the extension picks the format"),
        QStringLiteral("{colorBy: \"level\" | \"mode\" | \"none\" = \"none\", triangulate: bool = false}")}},
  };
}

}  // namespace mrcloth
