#pragma once
// The scripting object `core`: objects (load, save, inspect, delete), files
// and folders, script arguments and exit. OpenFlipper's core object in
// miniature; plugins add the operations on objects.
#include "plugin/interfaces/script_interface.h"

#include <QJSValue>
#include <QObject>
#include <QSet>
#include <QStringList>
#include <QVariant>
#include <QVariantList>
#include <QVariantMap>

#include <map>
#include <memory>

class QLockFile;

namespace mrcloth {

class HostLog;
class ObjectStore;

class ScriptCore : public QObject, public ScriptInterface {
  Q_OBJECT
  Q_INTERFACES(mrcloth::ScriptInterface)

 public:
  ScriptCore(ObjectStore& store, HostLog& log, QStringList scriptArguments, QObject* parent = nullptr);
  ~ScriptCore() override;  // releases the locks lockFile took

  QList<SlotDescription> slotDescriptions() const override;

  /// Whether the script called exitApplication, and with which code.
  bool exitRequested() const { return exit_requested_; }
  int exitCode() const { return exit_code_; }

  /// The resources folder: $MRCLOTH_RESOURCES if set, else the source tree's
  /// resources folder compiled in by CMake.
  static QString resourceFolder();

  /// The script `mrcloth -b` runs: core.include resolves relative paths
  /// against its folder (else against the working folder), and counts the
  /// script itself as already included.
  void setScriptPath(const QString& path);

  // The scripting API; see slotDescriptions() for the types a script passes.
 public slots:
  // Every argument defaults to undefined, so a call missing one reaches the
  // slot's own check ("levels must be an integer, got undefined"), not Qt's
  // "Unable to determine callable overload".
  int loadObject(QVariant path = QVariant(), QVariant options = QVariant());
  void saveObject(QVariant id = QVariant(), QVariant path = QVariant());
  QVariantMap objectInfo(QVariant id = QVariant());
  QVariantList objectList();
  void deleteObject(QVariant id = QVariant());
  void exitApplication(QVariant code = QVariant());
  void print(QJSValue value);
  void log(QJSValue value);
  void warn(QJSValue value);
  QString resourcePath();
  QStringList scriptArguments();
  void makePath(QVariant path = QVariant());
  bool fileExists(QVariant path = QVariant());
  double fileSize(QVariant path = QVariant());
  bool filesEqual(QVariant pathA = QVariant(), QVariant pathB = QVariant());
  QString fileHash(QVariant path = QVariant());
  bool removeFile(QVariant path = QVariant());
  QStringList removeTemporaries(QVariant folder = QVariant());
  QVariantMap lockFile(QVariant path = QVariant());
  bool unlockFile(QVariant path = QVariant());
  void writeTextFile(QVariant path = QVariant(), QVariant text = QVariant());
  QString readTextFile(QVariant path = QVariant());
  QVariant parseJson(QVariant text = QVariant(), QVariant source = QVariant());
  bool fileReadable(QVariant path = QVariant());
  bool include(QVariant path = QVariant());

 private:
  template <class Body>
  auto guarded(const char* slot, Body&& body) -> decltype(body());

  ObjectStore& store_;
  HostLog& log_;
  QStringList script_arguments_;
  QString script_folder_;
  std::map<QString, std::unique_ptr<QLockFile>> locks_;  ///< by absolute path, held until the host exits
  QSet<QString> included_;  ///< canonical paths of the main script and every file include evaluated
  bool exit_requested_ = false;
  int exit_code_ = 0;
};

}  // namespace mrcloth
