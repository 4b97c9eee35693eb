#include "plugin_registry.h"

#include "host_log.h"
#include "interrupt.h"
#include "plugin/interfaces/base_interface.h"
#include "plugin/interfaces/load_save_interface.h"
#include "plugin/interfaces/logging_interface.h"
#include "plugin/interfaces/process_interface.h"
#include "plugin/interfaces/script_interface.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <QJsonObject>
#include <QLibrary>

namespace mrcloth {

PluginRegistry::PluginRegistry(HostLog& log, ObjectStore& store) : log_(log), store_(store) {}

QString PluginRegistry::defaultFolder() {
  // MRCLOTH_PLUGIN_DIR_FROM_HOST is relative (CMake computes it from the
  // output folders), so a moved build or installation keeps working.
  return QDir::cleanPath(QDir(QCoreApplication::applicationDirPath())
                             .filePath(QStringLiteral(MRCLOTH_PLUGIN_DIR_FROM_HOST)));
}

void PluginRegistry::loadFolder(const QString& folder) {
  const QDir directory(folder);
  if (!directory.exists()) {
    log_.warn(QStringLiteral("plugin folder %1 does not exist: no plugins loaded").arg(folder));
    return;
  }
  const std::size_t before = plugins_.size();
  for (const QFileInfo& entry : directory.entryInfoList(QDir::Files, QDir::Name)) {
    if (!QLibrary::isLibrary(entry.fileName())) continue;
    auto loader = std::make_unique<QPluginLoader>(entry.absoluteFilePath());
    // Check the metadata first so that foreign libraries are never instantiated.
    const QString iid = loader->metaData().value(QStringLiteral("IID")).toString();
    if (iid != QLatin1String(MRCLOTH_BASE_INTERFACE_IID)) {
      if (!iid.isEmpty())
        log_.info(QStringLiteral("skipping %1: not an mrcloth plugin").arg(entry.fileName()));
      continue;
    }
    QObject* object = loader->instance();
    if (!object) {
      log_.warn(QStringLiteral("cannot load plugin %1: %2").arg(entry.fileName(), loader->errorString()));
      continue;
    }
    LoadedPlugin plugin;
    plugin.file = entry.absoluteFilePath();
    plugin.object = object;
    plugin.base = qobject_cast<BaseInterface*>(object);
    if (!plugin.base) {
      log_.warn(QStringLiteral("skipping %1: it does not implement BaseInterface").arg(entry.fileName()));
      continue;
    }
    plugin.script = qobject_cast<ScriptInterface*>(object);
    plugin.scriptName = scriptObjectName(plugin.base->name());
    bool taken = plugin.scriptName == QLatin1String("core");
    for (const LoadedPlugin& other : plugins_) taken = taken || other.scriptName == plugin.scriptName;
    if (taken || plugin.scriptName.isEmpty()) {
      log_.warn(QStringLiteral("skipping %1: its script name '%2' is empty or already taken")
                    .arg(entry.fileName(), plugin.scriptName));
      continue;
    }
    wire(plugin);
    plugin.base->initializePlugin();
    log_.info(QStringLiteral("loaded plugin '%1' %2 as `%3`")
                  .arg(plugin.base->name(), plugin.base->version(), plugin.scriptName));
    plugins_.push_back(plugin);
    loaders_.push_back(std::move(loader));
  }
  if (plugins_.size() == before) log_.warn(QStringLiteral("no mrcloth plugins found in %1").arg(folder));
  for (std::size_t i = before; i < plugins_.size(); ++i) plugins_[i].base->pluginsInitialized();
}

void PluginRegistry::wire(LoadedPlugin& plugin) {
  QObject* object = plugin.object;
  auto connectOrWarn = [&](const char* signal, const char* slot, const char* what) {
    if (!QObject::connect(object, signal, &log_, slot))
      log_.warn(QStringLiteral("plugin '%1' declares %2 but its signal %3 could not be connected "
                               "(declare it in `signals:` spelled as in the interface)")
                    .arg(plugin.base->name(), QLatin1String(what), QLatin1String(signal + 1)));
  };
  if (qobject_cast<LoggingInterface*>(object))
    connectOrWarn(SIGNAL(log(Logtype, QString)), SLOT(onLog(Logtype, QString)), "LoggingInterface");
  if (auto* process = qobject_cast<ProcessInterface*>(object)) {
    process->setCancelFlag(&interruptFlag());
    connectOrWarn(SIGNAL(startJob(QString, QString, int, int)), SLOT(onStartJob(QString, QString, int, int)),
                  "ProcessInterface");
    connectOrWarn(SIGNAL(setJobState(QString, int)), SLOT(onSetJobState(QString, int)), "ProcessInterface");
    connectOrWarn(SIGNAL(finishJob(QString)), SLOT(onFinishJob(QString)), "ProcessInterface");
  }
  if (auto* load_save = qobject_cast<LoadSaveInterface*>(object)) load_save->setObjectStore(&store_);
}

}  // namespace mrcloth
