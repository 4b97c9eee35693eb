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

namespace mrcloth {

class HostLog;
class ObjectStore;

class ScriptCore : public QObject, public ScriptInterface {
  Q_OBJECT
  Q_INTERFACES(mrcloth::ScriptInterface)

 public:
  ScriptCore(ObjectStore& store, HostLog& log, QStringList scriptArguments, QObject* parent = nullptr);

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
  int loadObject(QVariant path, QVariant options = QVariant());
  void saveObject(QVariant id, QVariant path);
  QVariantMap objectInfo(QVariant id);
  QVariantList objectList();
  void deleteObject(QVariant id);
  void exitApplication(QVariant code = QVariant());
  void print(QJSValue value);
  void log(QJSValue value);
  void warn(QJSValue value);
  QString resourcePath();
  QStringList scriptArguments();
  void makePath(QVariant path);
  bool fileExists(QVariant path);
  double fileSize(QVariant path);
  bool filesEqual(QVariant pathA, QVariant pathB);
  void writeTextFile(QVariant path, QVariant text);
  QString readTextFile(QVariant path);
  bool fileReadable(QVariant path);
  bool include(QVariant path);

 private:
  template <class Body>
  auto guarded(const char* slot, Body&& body) -> decltype(body());

  ObjectStore& store_;
  HostLog& log_;
  QStringList script_arguments_;
  QString script_folder_;
  QSet<QString> included_;  ///< canonical paths of the main script and every file include evaluated
  bool exit_requested_ = false;
  int exit_code_ = 0;
};

}  // namespace mrcloth
