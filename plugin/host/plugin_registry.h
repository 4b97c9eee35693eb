#pragma once
// Finding, loading and wiring the plugins (OpenFlipper's PluginManager in
// miniature): every library in the plugin folder whose metadata names
// mrcloth's BaseInterface is instantiated, its optional interfaces are
// connected to the host, and initializePlugin()/pluginsInitialized() are
// called in that order.
#include <QObject>
#include <QPluginLoader>
#include <QString>

#include <memory>
#include <vector>

namespace mrcloth {

class BaseInterface;
class HostLog;
class ObjectStore;
class ScriptInterface;

struct LoadedPlugin {
  QString file;                        ///< the library it came from
  QObject* object = nullptr;           ///< owned by its QPluginLoader, alive until the process exits
  BaseInterface* base = nullptr;
  ScriptInterface* script = nullptr;   ///< null if the plugin describes no scripting API
  QString scriptName;                  ///< global name in the script engine, e.g. "multirescloth"
};

class PluginRegistry {
 public:
  PluginRegistry(HostLog& log, ObjectStore& store);

  /// Loads every plugin in `folder` (sorted by file name). A library that
  /// fails to load, is not an mrcloth plugin, or whose script name is taken
  /// is reported as [warn] and skipped; so is a missing folder.
  void loadFolder(const QString& folder);

  const std::vector<LoadedPlugin>& plugins() const { return plugins_; }

  /// The folder the build (or an installation) puts plugins in, relative to the executable.
  static QString defaultFolder();

 private:
  void wire(LoadedPlugin& plugin);

  HostLog& log_;
  ObjectStore& store_;
  std::vector<std::unique_ptr<QPluginLoader>> loaders_;
  std::vector<LoadedPlugin> plugins_;
};

}  // namespace mrcloth
