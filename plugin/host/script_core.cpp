#include "script_core.h"

#include "host_log.h"
#include "script_exposure.h"
#include "mesh_ops/atomic_file.h"
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/lumped_mass.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/quad_mesh.h"
#include "mesh_ops/texture_coords.h"
#include "plugin/core/object_store.h"
#include "plugin/core/script_errors.h"
#include "plugin/core/script_values.h"
#include "solver/json_lite.h"
#include "solver/material.h"

#include <QCoreApplication>
#include <QCryptographicHash>
#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJSEngine>
#include <QLockFile>
#include <QUrl>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>

namespace mrcloth {
namespace {

QVariantList toVariantList(const OpenMesh::Vec3d& point) { return {point[0], point[1], point[2]}; }

/// Axis-aligned bounding box of all vertices, as {min: [x, y, z], max: [x, y, z]} in metres.
QVariantMap boundingBox(const QuadMesh& mesh) {
  const double infinity = std::numeric_limits<double>::infinity();
  OpenMesh::Vec3d low(infinity, infinity, infinity), high(-infinity, -infinity, -infinity);
  for (const auto vertex : mesh.vertices()) {
    low.minimize(mesh.point(vertex));
    high.maximize(mesh.point(vertex));
  }
  if (mesh.n_vertices() == 0) low = high = OpenMesh::Vec3d(0, 0, 0);
  return {{QStringLiteral("min"), toVariantList(low)}, {QStringLiteral("max"), toVariantList(high)}};
}

/// Vertices per mode: element m counts the vertices of mode m.
std::vector<std::size_t> verticesPerMode(const QuadMesh& mesh) {
  const std::vector<int> modes = get_modes(mesh);
  std::vector<std::size_t> counts;
  for (const int mode : modes) {
    if (mode < 0) continue;
    if (static_cast<std::size_t>(mode) >= counts.size()) counts.resize(static_cast<std::size_t>(mode) + 1, 0);
    ++counts[static_cast<std::size_t>(mode)];
  }
  return counts;
}

/// How long (ms) lockFile tries before it says who holds the lock.
constexpr int kLockPatienceMs = 500;

/// How long (ms) a lock file naming no owner may stand before it is taken
/// for one a killed process left (QLockFile writes its owner at once).
constexpr qint64 kOwnerlessLockMs = 3000;

/// An existing regular file, else InputError naming it.
QFileInfo existingFile(const QString& path) {
  const QFileInfo info(path);
  if (!info.exists()) throw InputError(path.toStdString() + ": no such file");
  if (!info.isFile()) throw InputError(path.toStdString() + ": not a file");
  return info;
}

/// Why `folder` could not be made: the nearest existing part of the path is
/// a file, a link to nothing, or the system's reason (`error`).
std::string whyNoFolder(const std::string& folder, const std::error_code& error) {
  namespace fs = std::filesystem;
  std::error_code ignored;
  for (fs::path part = fs::absolute(folder, ignored).lexically_normal(); !part.empty(); part = part.parent_path()) {
    if (fs::is_symlink(part, ignored) && !fs::exists(part, ignored)) return part.string() + " is a link to nothing";
    if (fs::exists(part, ignored)) {
      if (!fs::is_directory(part, ignored)) return part.string() + " is a file, not a folder";
      break;
    }
    if (part == part.parent_path()) break;
  }
  return error ? error.message() : std::string("it is not a folder after creating it");
}

/// Whether the lock at `path` names its owner as QLockFile writes it: a
/// process id, an application and a host name on lines of their own (a
/// file whose first line was a number, "42", passed for a lock).
bool namesOwner(const QLockFile& lock) {
  qint64 pid = 0;
  QString host, application;
  return lock.getLockInfo(&pid, &host, &application) && pid > 0 && !host.isEmpty();
}

/// Whether the file holds nothing but white space (what a process killed
/// while creating a lock leaves), read up to a lock's size.
bool blankFile(const QString& path) {
  QFile file(path);
  return file.open(QIODevice::ReadOnly) && file.read(4096).trimmed().isEmpty();
}

/// A lock file naming no owner (empty) that has not changed for a few
/// seconds: left by a process killed while creating it.
bool ownerless(const QLockFile& lock, const QString& path) {
  if (namesOwner(lock) || !blankFile(path)) return false;
  const QFileInfo file(path);
  return file.isFile() && file.lastModified().msecsTo(QDateTime::currentDateTime()) > kOwnerlessLockMs;
}

int highestLevel(const std::vector<std::size_t>& faces_per_level) {
  for (std::size_t level = faces_per_level.size(); level-- > 0;)
    if (faces_per_level[level] > 0) return static_cast<int>(level);
  return 0;
}

}  // namespace

ScriptCore::ScriptCore(ObjectStore& store, HostLog& log, QStringList scriptArguments, QObject* parent)
    : QObject(parent), store_(store), log_(log), script_arguments_(std::move(scriptArguments)) {}

ScriptCore::~ScriptCore() = default;

template <class Body>
auto ScriptCore::guarded(const char* slot, Body&& body) -> decltype(body()) {
  return runScriptSlot(this, QStringLiteral("core.") + QLatin1String(slot), std::forward<Body>(body));
}

QString ScriptCore::resourceFolder() {
  const QString overridden = qEnvironmentVariable("MRCLOTH_RESOURCES");
  if (!overridden.isEmpty()) return QDir::cleanPath(overridden);
  // An installed host has its resources beside it (relocatable: found from
  // the host's own folder); in the build tree that folder does not exist and
  // the source tree's resources are read, so edited scripts need no rebuild.
  // (Without an application object the host's folder is unknown: a
  // relative path would then be read from the working folder.)
  if (QCoreApplication::instance()) {
    const QString installed = QDir::cleanPath(
        QDir(QCoreApplication::applicationDirPath()).filePath(QStringLiteral(MRCLOTH_INSTALLED_RESOURCES_FROM_HOST)));
    if (QFileInfo(installed + QStringLiteral("/scripts/pipeline.js")).isFile()) return installed;
  }
  return QDir::cleanPath(QStringLiteral(MRCLOTH_RESOURCES_DIR));
}

int ScriptCore::loadObject(QVariant path, QVariant options) {
  return guarded("loadObject", [&] {
    const QString file = script::toString(path, QStringLiteral("path"));
    const script::Options given(options, QStringLiteral("loadObject options"), {QStringLiteral("units")});
    LoadOptions settings;
    settings.units = given.string(QStringLiteral("units"), QString::fromStdString(settings.units)).toStdString();

    LoadResult loaded = load_garment(file.toStdString(), settings);
    for (const std::string& text : loaded.warnings) {
      const QString warning = QString::fromStdString(text);
      // mesh_ops usually names the file itself; name it only when it does not.
      log_.warn(QStringLiteral("loadObject: ") + (warning.contains(file) ? warning : file + QStringLiteral(": ") + warning));
    }
    auto mesh = std::make_shared<QuadMesh>(std::move(loaded.mesh));
    const int id = store_.add(mesh, QFileInfo(file).completeBaseName(), file);
    log_.info(QStringLiteral("loadObject: %1 -> object %2: %3 vertices, %4 faces")
                  .arg(file).arg(id).arg(mesh->n_vertices()).arg(mesh->n_faces()));
    return id;
  });
}

void ScriptCore::saveObject(QVariant id, QVariant path) {
  guarded("saveObject", [&] {
    const int object_id = script::toInt(id, QStringLiteral("id"));
    const QString file = script::toString(path, QStringLiteral("path"));
    save_mesh(store_.mesh(object_id), file.toStdString());
    store_.setPath(object_id, file);
    log_.info(QStringLiteral("saveObject: object %1 -> %2").arg(object_id).arg(file));
  });
}

QVariantMap ScriptCore::objectInfo(QVariant id) {
  return guarded("objectInfo", [&] {
    const StoredObject& object = store_.get(script::toInt(id, QStringLiteral("id")));
    const QuadMesh& mesh = *object.mesh;
    const std::vector<double> masses = lumped_mass(mesh, kDefaultArealDensity);
    const std::vector<std::size_t> faces_by_level = faces_per_level(mesh);
    return QVariantMap{
        {QStringLiteral("id"), object.id},
        {QStringLiteral("name"), object.name},
        {QStringLiteral("path"), object.path},
        {QStringLiteral("vertices"), static_cast<qlonglong>(mesh.n_vertices())},
        {QStringLiteral("faces"), static_cast<qlonglong>(mesh.n_faces())},
        {QStringLiteral("hangingNodes"), static_cast<qlonglong>(count_hanging(mesh))},
        {QStringLiteral("area"), garment_area(mesh)},
        {QStringLiteral("arealDensity"), kDefaultArealDensity},
        {QStringLiteral("totalMass"), std::accumulate(masses.begin(), masses.end(), 0.0)},
        {QStringLiteral("facesPerLevel"), script::toVariantList(faces_by_level)},
        {QStringLiteral("verticesPerLevel"), script::toVariantList(vertices_per_level(mesh))},
        {QStringLiteral("verticesPerMode"), script::toVariantList(verticesPerMode(mesh))},
        {QStringLiteral("maxLevel"), highestLevel(faces_by_level)},
        {QStringLiteral("textureCoordinates"), has_texture_coords(mesh)},
        {QStringLiteral("boundaryLoops"), static_cast<qlonglong>(boundary_loops(mesh).size())},
        {QStringLiteral("bbox"), boundingBox(mesh)}};
  });
}

QVariantList ScriptCore::objectList() {
  return guarded("objectList", [&] {
    QVariantList list;
    for (const StoredObject& object : store_.list())
      list.append(QVariantMap{{QStringLiteral("id"), object.id},
                              {QStringLiteral("name"), object.name},
                              {QStringLiteral("path"), object.path}});
    return list;
  });
}

void ScriptCore::deleteObject(QVariant id) {
  guarded("deleteObject", [&] { store_.remove(script::toInt(id, QStringLiteral("id"))); });
}

void ScriptCore::exitApplication(QVariant code) {
  guarded("exitApplication", [&] {
    // One range for every value (1e12 was refused as beyond an int's).
    const int exit_code = code.isValid() ? script::toIntBetween(code, QStringLiteral("code"), 0, 255) : 0;
    exit_requested_ = true;
    exit_code_ = exit_code;
    // An interrupt, unlike a thrown error, cannot be caught by the script's
    // try/catch: evaluation stops here and the host returns exit_code_.
    if (QJSEngine* engine = qjsEngine(this)) engine->setInterrupted(true);
  });
}

namespace {

/// The text of a value a script prints, as String(value) gives it; none if
/// its toString threw, which is thrown on to the script. QJSValue::toString
/// would print the error's text instead, and the script went on. String()
/// returns a string or throws, so anything else is what it threw (a thrown
/// string alone passes for the text).
std::optional<QString> printedText(const QObject* core, const QJSValue& value) {
  QJSEngine* engine = qjsEngine(core);
  if (!engine || !value.isObject()) return value.toString();
  const QJSValue text = engine->globalObject().property(QStringLiteral("String")).call({value});
  if (text.isString()) return text.toString();
  engine->throwError(text);
  return std::nullopt;
}

}  // namespace

void ScriptCore::print(QJSValue value) {
  if (const auto text = printedText(this, value)) log_.out(*text);
}
void ScriptCore::log(QJSValue value) {
  if (const auto text = printedText(this, value)) log_.info(*text);
}
void ScriptCore::warn(QJSValue value) {
  if (const auto text = printedText(this, value)) log_.warn(*text);
}

QString ScriptCore::resourcePath() { return resourceFolder(); }

QStringList ScriptCore::scriptArguments() { return script_arguments_; }

void ScriptCore::makePath(QVariant path) {
  guarded("makePath", [&] {
    const std::string folder = script::toString(path, QStringLiteral("path")).toStdString();
    // std::filesystem gives the system's reason (QDir::mkpath says only that it failed).
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error || !std::filesystem::is_directory(folder))
      throw OutputError("cannot create folder " + folder + " (" + whyNoFolder(folder, error) + ")");
  });
}

void ScriptCore::writeTextFile(QVariant path, QVariant text) {
  guarded("writeTextFile", [&] {
    const std::string file = script::toString(path, QStringLiteral("path")).toStdString();
    const QByteArray bytes = script::toText(text, QStringLiteral("text")).toUtf8();  // empty: an empty file
    require_writable_target(file);
    write_file_atomically(file, "", [&](const std::string& temporary) {
      QFile out(QString::fromStdString(temporary));
      return out.open(QIODevice::WriteOnly) && out.write(bytes) == bytes.size() && out.flush();
    });
  });
}

QString ScriptCore::readTextFile(QVariant path) {
  return guarded("readTextFile", [&] {
    const QString name = script::toString(path, QStringLiteral("path"));
    QFile in(existingFile(name).filePath());
    if (!in.open(QIODevice::ReadOnly)) throw InputError(name.toStdString() + ": cannot read (" + in.errorString().toStdString() + ")");
    return QString::fromUtf8(in.readAll());
  });
}

namespace {

/// A JSON value as scripts get it (objects keep their members' order).
QVariant toVariant(const JsonValue& value) {
  switch (value.kind()) {
    case JsonValue::Kind::null: return QVariant::fromValue(nullptr);
    case JsonValue::Kind::boolean: return value.as_bool();
    case JsonValue::Kind::number: return value.as_number();
    case JsonValue::Kind::string: return QString::fromStdString(value.as_string());
    case JsonValue::Kind::array: {
      QVariantList list;
      for (const JsonValue& item : value.as_array()) list << toVariant(item);
      return list;
    }
    case JsonValue::Kind::object: {
      QVariantMap map;
      for (const auto& [key, member] : value.as_object()) map.insert(QString::fromStdString(key), toVariant(member));
      return map;
    }
  }
  return {};
}

}  // namespace

QVariant ScriptCore::parseJson(QVariant text, QVariant source) {
  return guarded("parseJson", [&] {
    const QString name = script::toString(source, QStringLiteral("source"));
    // An empty text is JSON's error (an empty file), not a missing argument.
    const QString json = text.typeId() == QMetaType::QString ? text.toString() : script::toString(text, QStringLiteral("text"));
    // The project's strict reader: JSON.parse says only "Parse error", and a
    // hand-edited file wants the line.
    return toVariant(parse_json(json.toStdString(), name.toStdString()));
  });
}

bool ScriptCore::fileReadable(QVariant path) {
  return guarded("fileReadable", [&] {
    const QFileInfo info(script::toString(path, QStringLiteral("path")));
    if (!info.isFile()) return false;
    // isReadable() trusts permission bits; opening is what counts.
    QFile file(info.filePath());
    return file.open(QIODevice::ReadOnly);
  });
}

bool ScriptCore::fileExists(QVariant path) {
  return guarded("fileExists", [&] { return QFileInfo::exists(script::toString(path, QStringLiteral("path"))); });
}

double ScriptCore::fileSize(QVariant path) {
  return guarded("fileSize", [&] {
    return static_cast<double>(existingFile(script::toString(path, QStringLiteral("path"))).size());
  });
}

bool ScriptCore::filesEqual(QVariant pathA, QVariant pathB) {
  return guarded("filesEqual", [&] {
    const QString name_a = script::toString(pathA, QStringLiteral("pathA"));
    const QString name_b = script::toString(pathB, QStringLiteral("pathB"));
    QFile file_a(existingFile(name_a).absoluteFilePath()), file_b(existingFile(name_b).absoluteFilePath());
    for (QFile* file : {&file_a, &file_b})
      if (!file->open(QIODevice::ReadOnly))
        throw InputError(file->fileName().toStdString() + ": cannot open file (" + file->errorString().toStdString() + ")");
    if (file_a.size() != file_b.size()) return false;
    constexpr qint64 kChunk = qint64{1} << 20;
    while (!file_a.atEnd())
      if (file_a.read(kChunk) != file_b.read(kChunk)) return false;
    return true;
  });
}

QString ScriptCore::fileHash(QVariant path) {
  return guarded("fileHash", [&] {
    const QString name = script::toString(path, QStringLiteral("path"));
    QFile in(existingFile(name).filePath());
    if (!in.open(QIODevice::ReadOnly)) throw InputError(name.toStdString() + ": cannot read (" + in.errorString().toStdString() + ")");
    QCryptographicHash hash(QCryptographicHash::Sha256);
    if (!hash.addData(&in)) throw InputError(name.toStdString() + ": cannot read (" + in.errorString().toStdString() + ")");
    return QString::fromLatin1(hash.result().toHex());
  });
}

bool ScriptCore::removeFile(QVariant path) {
  return guarded("removeFile", [&] {
    const QString name = script::toString(path, QStringLiteral("path"));
    const QFileInfo info(name);
    if (!info.exists() && !info.isSymLink()) return false;
    if (info.isDir()) throw OutputError(name.toStdString() + ": cannot remove (it is a folder; expected a file)");
    QFile file(name);
    if (!file.remove()) throw OutputError(name.toStdString() + ": cannot remove (" + file.errorString().toStdString() + ")");
    return true;
  });
}

QStringList ScriptCore::removeTemporaries(QVariant folder) {
  return guarded("removeTemporaries", [&] {
    QStringList removed;
    for (const std::string& file : remove_temporaries_in(script::toString(folder, QStringLiteral("folder")).toStdString()))
      removed.push_back(QString::fromStdString(file));
    return removed;
  });
}

QVariantMap ScriptCore::lockFile(QVariant path) {
  return guarded("lockFile", [&] {
    const QFileInfo given(script::toString(path, QStringLiteral("path")));
    const QFileInfo folder(given.absolutePath());
    if (!folder.isDir())
      throw OutputError(given.absoluteFilePath().toStdString() + ": cannot create the lock file (its folder " +
                        folder.absoluteFilePath().toStdString() + " does not exist)");
    if (given.isDir())
      throw OutputError(given.absoluteFilePath().toStdString() + ": cannot create the lock file (it is a folder)");
    // One key per file however it is named (a link to its folder).
    const QString name = QDir(folder.canonicalFilePath()).filePath(given.fileName());
    if (locks_.count(name)) return QVariantMap{{QStringLiteral("locked"), true}};
    auto lock = std::make_unique<QLockFile>(name);
    // Never stale by age (a run may take hours): only when its process is gone.
    lock->setStaleLockTime(0);
    // Half a second of retries: two runs taking over one stale lock at once
    // settle on a winner, whose name the other then reads (it read the dead one's).
    // Any other file there (a report, a mistyped path) is not a lock, and is
    // refused before trying: Qt takes a file naming no running process of
    // its application for a stale lock and writes over it (then unlockFile
    // removed it); one naming no process was taken over once 3 s old.
    if (QFileInfo(name).isFile() && !namesOwner(*lock) && !blankFile(name))
      throw ArgumentError(name.toStdString() + " exists and is not a lock file (it names no process); expected a "
                          "path kept for the lock alone");
    const bool free = lock->tryLock(kLockPatienceMs);
    if (!free && lock->error() == QLockFile::LockFailedError && ownerless(*lock, name)) {
      // A process killed between creating the file and writing its owner
      // leaves it empty: no owner to ask, so it is taken over once it is
      // older than a writer needs.
      lock->removeStaleLockFile();
      lock->tryLock(0);
    }
    if (lock->isLocked()) {
      locks_.emplace(name, std::move(lock));
      return QVariantMap{{QStringLiteral("locked"), true}};
    }
    if (lock->error() != QLockFile::LockFailedError)
      throw OutputError(name.toStdString() + ": cannot create the lock file (" +
                        (lock->error() == QLockFile::PermissionError ? "permission denied" : "unknown error") + ")");
    qint64 pid = 0;
    QString host, application;
    lock->getLockInfo(&pid, &host, &application);
    return QVariantMap{{QStringLiteral("locked"), false}, {QStringLiteral("pid"), pid},
                       {QStringLiteral("host"), host}, {QStringLiteral("application"), application}};
  });
}

bool ScriptCore::unlockFile(QVariant path) {
  return guarded("unlockFile", [&] {
    const QFileInfo given(script::toString(path, QStringLiteral("path")));
    const QString folder = QFileInfo(given.absolutePath()).canonicalFilePath();
    if (folder.isEmpty()) return false;
    // Erasing the QLockFile unlocks it, removes the file and closes its descriptor.
    return locks_.erase(QDir(folder).filePath(given.fileName())) > 0;
  });
}

void ScriptCore::setScriptPath(const QString& path) {
  const QFileInfo info(path);
  script_folder_ = info.absolutePath();
  if (info.isFile()) included_.insert(info.canonicalFilePath());
}

bool ScriptCore::include(QVariant path) {
  // An error inside the included file is rethrown after guarded(), with its
  // own name and "core.include: <file>:<line>: " before its message.
  QString failure_name, failure_message;
  const bool evaluated = guarded("include", [&] {
    const QString given = script::toString(path, QStringLiteral("path"));
    const QDir base(script_folder_.isEmpty() ? QDir::currentPath() : script_folder_);
    const QString file = QDir::cleanPath(base.absoluteFilePath(given));
    const QString key = existingFile(file).canonicalFilePath();
    // Include once: a file already included (or being included: a cycle) is skipped.
    if (included_.contains(key)) return false;
    QJSEngine* engine = qjsEngine(this);
    if (!engine) throw std::logic_error("include needs a script engine");
    QFile source(file);
    if (!source.open(QIODevice::ReadOnly))
      throw InputError(file.toStdString() + ": cannot open file (" + source.errorString().toStdString() + ")");
    QString program = QString::fromUtf8(source.readAll());
    if (program.startsWith(QLatin1String("#!"))) program.prepend(QLatin1String("//"));

    included_.insert(key);
    QStringList stack;
    const QJSValue result = engine->evaluate(program, file, 1, &stack);
    // Filled exactly when the file threw (see batch_runner.cpp): a file whose
    // last value is an Error it caught was taken for a failed include.
    const bool threw = !stack.isEmpty();
    stack = withoutSlotGuardFrames(stack);
    // exitApplication or Ctrl-C inside the file: the engine stays interrupted
    // and stops the including script too.
    if (engine->isInterrupted()) return true;
    if (!threw) return true;

    included_.remove(key);  // a failed include may be retried, and fails again
    // Stack frames read "function:line:column:file" (the file may contain ':').
    const QString top = stack.isEmpty() ? QString() : stack.first();
    QString where = result.isError() ? result.property(QStringLiteral("fileName")).toString() : QString();
    QString line = result.isError() ? result.property(QStringLiteral("lineNumber")).toString() : QString();
    if (where.isEmpty() || where == QLatin1String("undefined")) where = top.isEmpty() ? file : top.section(QLatin1Char(':'), 3);
    if (const QUrl url(where); url.isLocalFile()) where = url.toLocalFile();  // errors carry file:// URLs
    if (line.isEmpty() || line == QLatin1String("undefined"))
      line = top.isEmpty() ? QStringLiteral("?") : top.section(QLatin1Char(':'), 1, 1);
    failure_name = result.isError() ? result.property(QStringLiteral("name")).toString() : QStringLiteral("Error");
    failure_message = QStringLiteral("core.include: %1:%2: %3")
                          .arg(where, line,
                               result.isError() ? result.toString()
                                                : QStringLiteral("uncaught exception: %1").arg(thrownValueText(result)));
    return false;
  });
  if (!failure_message.isEmpty()) throwScriptError(this, failure_name, failure_message);
  return evaluated;
}

QList<SlotDescription> ScriptCore::slotDescriptions() const {
  const QString id_text = QStringLiteral("object id");
  return {
      {QStringLiteral("loadObject(string path, object options = {}) -> int"),
       QStringLiteral("Loads an OBJ/OFF/PLY/OM garment as a refinable quad mesh in metres; returns its id. Load "
                      "warnings (e.g. polygons split into quads) are logged."),
       {QStringLiteral("path"), QStringLiteral("options")},
       {QStringLiteral("garment file"),
        QStringLiteral("{units: \"m\" | \"dm\" | \"cm\" | \"mm\" | \"inch\" = \"m\"}: unit of the file's coordinates")}},
      {QStringLiteral("saveObject(int id, string path)"),
       QStringLiteral("Saves the object (atomically); .om keeps the hierarchy and every layer, .obj/.off/.ply the "
                      "active surface only."),
       {QStringLiteral("id"), QStringLiteral("path")},
       {id_text, QStringLiteral("output file; the extension picks the format")}},
      {QStringLiteral("objectInfo(int id) -> object"),
       QStringLiteral("Returns {id, name, path, vertices, faces, hangingNodes, area (m^2), arealDensity (kg/m^2), "
                      "totalMass (kg), facesPerLevel, verticesPerLevel, verticesPerMode, maxLevel, "
                      "textureCoordinates (bool: UVs from the file, carried through refinement into OBJs written), "
                      "boundaryLoops (openings: a skirt's waist and hem), bbox: {min: [x, y, z], max: [x, y, z]} "
                      "(m)}. Per-level lists: element L = level L "
                      "(coarse = 1, element 0 unused); verticesPerMode: element m = mode m."),
       {QStringLiteral("id")},
       {id_text}},
      {QStringLiteral("objectList() -> object[]"),
       QStringLiteral("Returns [{id, name, path}] of every object, by id."),
       {},
       {}},
      {QStringLiteral("deleteObject(int id)"),
       QStringLiteral("Forgets the object; its id is never reused."),
       {QStringLiteral("id")},
       {id_text}},
      {QStringLiteral("exitApplication(int code = 0)"),
       QStringLiteral("Stops the script at once (catch blocks cannot intercept it; finally blocks still run); mrcloth exits with `code`."),
       {QStringLiteral("code")},
       {QStringLiteral("exit code in [0, 255]")}},
      {QStringLiteral("print(any value)"),
       QStringLiteral("Prints the value as a line on stdout (like print() and console.log())."),
       {QStringLiteral("value")},
       {QStringLiteral("anything; converted with String(value)")}},
      {QStringLiteral("log(any value)"),
       QStringLiteral("Logs an [info] line on stderr (hidden by --quiet)."),
       {QStringLiteral("value")},
       {QStringLiteral("anything; converted with String(value)")}},
      {QStringLiteral("warn(any value)"),
       QStringLiteral("Logs a [warn] line on stderr."),
       {QStringLiteral("value")},
       {QStringLiteral("anything; converted with String(value)")}},
      {QStringLiteral("resourcePath() -> string"),
       QStringLiteral("Returns the resources folder (garments/, scripts/): $MRCLOTH_RESOURCES, else the installed "
                      "share/mrcloth beside an installed host, else the source tree's resources/."),
       {},
       {}},
      {QStringLiteral("scriptArguments() -> string[]"),
       QStringLiteral("Returns the command-line arguments after `--`."),
       {},
       {}},
      {QStringLiteral("makePath(string path)"),
       QStringLiteral("Creates the folder and any missing parents (no error if it exists)."),
       {QStringLiteral("path")},
       {QStringLiteral("folder to create")}},
      {QStringLiteral("writeTextFile(string path, string text)"),
       QStringLiteral("Writes text (UTF-8) to a file atomically: it appears complete or not at all, replacing "
                      "any file there (OutputError naming the path if its folder is missing)."),
       {QStringLiteral("path"), QStringLiteral("text")},
       {QStringLiteral("file to write"), QStringLiteral("its contents, e.g. JSON.stringify(report)")}},
      {QStringLiteral("readTextFile(string path) -> string"),
       QStringLiteral("Returns a text file's contents (UTF-8), e.g. for JSON.parse (InputError if it is missing or "
                      "unreadable)."),
       {QStringLiteral("path")},
       {QStringLiteral("file to read")}},
      {QStringLiteral("parseJson(string text, string source) -> value"),
       QStringLiteral("Parses JSON text (RFC 8259, strictly: no comments, trailing commas or repeated keys); unlike "
                      "JSON.parse, an error names the source and line (InputError \"source:line: what; expected ...\")."),
       {QStringLiteral("text"), QStringLiteral("source")},
       {QStringLiteral("the JSON, e.g. core.readTextFile(path)"), QStringLiteral("what to call it in an error, e.g. the path")}},
      {QStringLiteral("fileReadable(string path) -> bool"),
       QStringLiteral("Returns whether the path is a file this process can open for reading."),
       {QStringLiteral("path")},
       {QStringLiteral("file")}},
      {QStringLiteral("fileExists(string path) -> bool"),
       QStringLiteral("Returns whether the file or folder exists."),
       {QStringLiteral("path")},
       {QStringLiteral("file or folder")}},
      {QStringLiteral("fileSize(string path) -> number"),
       QStringLiteral("Returns the size of a file in bytes (InputError if it is missing or a folder)."),
       {QStringLiteral("path")},
       {QStringLiteral("file")}},
      {QStringLiteral("filesEqual(string pathA, string pathB) -> bool"),
       QStringLiteral("Returns whether two files have exactly the same bytes (InputError if either is missing)."),
       {QStringLiteral("pathA"), QStringLiteral("pathB")},
       {QStringLiteral("first file"), QStringLiteral("second file")}},
      {QStringLiteral("fileHash(string path) -> string"),
       QStringLiteral("Returns the SHA-256 of a file's bytes as 64 hex digits, as sha256sum prints it (InputError if "
                      "it is missing or unreadable)."),
       {QStringLiteral("path")},
       {QStringLiteral("file")}},
      {QStringLiteral("removeFile(string path) -> bool"),
       QStringLiteral("Removes a file; returns false if there was none (OutputError if it is a folder or cannot be "
                      "removed)."),
       {QStringLiteral("path")},
       {QStringLiteral("file to remove")}},
      {QStringLiteral("removeTemporaries(string folder) -> string[]"),
       QStringLiteral("Removes the temporary files a writer killed mid-write left in the folder (hidden "
                      "\".NAME.tmp-HEX-N[.EXT]\" files; not in its subfolders, which may be other runs' outputs) "
                      "and returns their paths; nothing if the folder does not exist. Only for a folder no other "
                      "process is writing into (see lockFile)."),
       {QStringLiteral("folder")},
       {QStringLiteral("folder to sweep")}},
      {QStringLiteral("lockFile(string path) -> object"),
       QStringLiteral("Takes a lock file (Qt's QLockFile) held until mrcloth exits, so that two runs do not "
                      "write into one folder. Returns {locked: true}, also when this run holds it already (by "
                      "any path to its folder), or {locked: false, pid, host, application} naming the live "
                      "process that holds it (pid 0: the file names no process yet). A lock whose process is "
                      "gone (killed), or that has named no process for 3 s (killed while taking it), is taken "
                      "over; a held one never expires. OutputError if the path is a folder or its folder is "
                      "missing, or the lock file cannot be created; ArgumentError if another file is there (not "
                      "blank, naming no process as a lock does)."),
       {QStringLiteral("path")},
       {QStringLiteral("lock file, e.g. \"out/stages/.lock\" (its folder must exist)")}},
      {QStringLiteral("unlockFile(string path) -> bool"),
       QStringLiteral("Releases a lock lockFile took (its file is removed; each lock holds a file descriptor, so a "
                      "batch locking folder after folder releases them); returns false if this run holds none there."),
       {QStringLiteral("path")},
       {QStringLiteral("lock file given to lockFile")}},
      {QStringLiteral("include(string path) -> bool"),
       QStringLiteral("Evaluates a JavaScript file in the global scope, so its functions and `var`s become globals "
                      "(top-level let/const stay private to the file). A relative path is relative to the "
                      "folder of the script run by -b. Each file is included at most once: including a file "
                      "already included, the running script itself or a file still being included (a cycle) does "
                      "nothing and returns false; otherwise returns true. A missing file is an InputError; an "
                      "error thrown while evaluating the file is rethrown with its name and the message "
                      "\"core.include: <file>:<line>: <error>\"."),
       {QStringLiteral("path")},
       {QStringLiteral("JavaScript file, absolute or relative to the running script's folder")}},
  };
}

}  // namespace mrcloth
