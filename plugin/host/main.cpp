// mrcloth: the headless host. Loads the plugins, exposes `core` and every
// plugin to a JavaScript engine, and runs one script in batch mode
// (OpenFlipper's `-b` without the GUI).
#include "batch_runner.h"
#include "command_line.h"
#include "host_log.h"
#include "interrupt.h"
#include "plugin/core/object_store.h"
#include "plugin/interfaces/base_interface.h"
#include "plugin/interfaces/process_interface.h"
#include "plugin_registry.h"
#include "script_api.h"
#include "script_core.h"
#include "script_exposure.h"
#include "weak_collections.h"

#include <QGuiApplication>
#include <QJSEngine>

#include <cerrno>
#include <clocale>
#include <cstdio>
#include <optional>

#include <fcntl.h>
#include <unistd.h>

namespace {

using namespace mrcloth;

void printUsage(std::FILE* stream) {
  std::fputs(usageText().toUtf8().constData(), stream);
}

/// The --api listing: core first, then every plugin with a scripting API.
/// Descriptions that disagree with the real slots are reported as [warn].
void printApi(const ScriptCore& core, const PluginRegistry& plugins, const HostLog& log) {
  QString text = QStringLiteral("mrcloth %1 scripting API. Run scripts with: mrcloth -b script.js [-- args...]\n"
                                "Errors in any call throw a JavaScript Error (name: ArgumentError, InputError, "
                                "OutputError or Error).\n\n")
                     .arg(QCoreApplication::applicationVersion());
  text += formatScriptApi(QStringLiteral("core"), QStringLiteral("the host: objects, files, script control"),
                          core.slotDescriptions());
  QStringList problems = checkSlotDescriptions(core, QStringLiteral("core"), core.slotDescriptions());
  for (const LoadedPlugin& plugin : plugins.plugins()) {
    const QString heading = QStringLiteral("%1 %2: %3")
                                .arg(plugin.base->name(), plugin.base->version(), plugin.base->description());
    const QList<SlotDescription> slot_list = plugin.script ? plugin.script->slotDescriptions() : QList<SlotDescription>{};
    text += QLatin1Char('\n') + formatScriptApi(plugin.scriptName, heading, slot_list);
    problems += checkSlotDescriptions(*plugin.object, plugin.scriptName, slot_list);
  }
  log.out(text);
  for (const QString& problem : problems) log.warn(problem);
}

/// Started with stdin, stdout or stderr closed (daemons, some schedulers),
/// the next file the host opened would take that descriptor, and log lines
/// meant for stderr would be written into it (a PC2 cache was). /dev/null
/// keeps 0-2 taken. Must run before anything opens a file.
void occupyClosedStandardDescriptors() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    // open takes the lowest free descriptor, this one, as the lower ones
    // are taken by now; dup2 only in case.
    const int opened = open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
    if (opened == -1 || opened == fd) continue;
    dup2(opened, fd);
    close(opened);
  }
}

/// Drops Qt's runtime-folder warnings, which come while the application is
/// made, before the host log exists (its handler drops them too once it
/// takes over); the rest go where they went.
void dropRuntimeFolderWarnings() {
  const QtMessageHandler default_handler = qInstallMessageHandler(nullptr);
  static QtMessageHandler forward = default_handler;
  qInstallMessageHandler([](QtMsgType type, const QMessageLogContext& context, const QString& message) {
    if (isRuntimeFolderWarning(message)) return;
    if (forward) forward(type, context, message);
    else std::fprintf(stderr, "%s\n", message.toLocal8Bit().constData());
  });
}

/// The exit code of a command line that asks for no script (usage errors,
/// --help, --version, nothing to do), once its text is printed; none when
/// there is work to do (a script, --api or the pipeline), read into `command`.
std::optional<int> answerWithoutWork(CommandLine& command) {
  try {
    command = parseCommandLine(QCoreApplication::arguments().mid(1));
  } catch (const UsageError& error) {
    std::fprintf(stderr, "[error] %s\n\n", error.what());
    printUsage(stderr);
    return 2;
  }
  if (command.help) {
    printUsage(stdout);
    return 0;
  }
  if (command.version) {
    std::printf("mrcloth %s\n", MRCLOTH_VERSION);
    return 0;
  }
  if (!command.api && !command.pipeline && command.scriptPath.isEmpty()) {
    std::fputs("[error] nothing to do: give a script with -b <script.js>, or --api, or --help\n\n", stderr);
    printUsage(stderr);
    return 2;
  }
  return std::nullopt;
}

/// After Ctrl-C stopped a pipeline (the pipeline records each stage as it
/// completes, in `pipelineStage`): says how to go on.
void warnHowToResume(const QJSEngine& engine, const CommandLine& command, HostLog& log) {
  const QJSValue stage = engine.globalObject().property(QStringLiteral("pipelineStage"));
  if (!(command.pipeline || stage.isObject()) || !interruptFlag().load()) return;
  const QString where = stage.isObject() ? QStringLiteral(" stopped in %1 with %2 stage(s) complete, which are kept;")
                                               .arg(stage.property(QStringLiteral("label")).toString())
                                               .arg(stage.property(QStringLiteral("complete")).toInt())
                                         : QString();
  log.warn(QStringLiteral("pipeline:%1 the same command with --resume continues from the stages complete").arg(where));
}

/// The host's work; returns the exit code. The application and every
/// object are gone when it returns, so that whatever they write is in.
int runHost(int argc, char* argv[]) {
  // A GUI application for fonts and images (previews), on Qt's offscreen
  // platform: the host never opens a window and needs no display or GPU.
  // Always, not only when unset: a desktop's QT_QPA_PLATFORM (wayland, xcb)
  // inherited by a batch job without a display made Qt abort even --version.
  qputenv("QT_QPA_PLATFORM", "offscreen");
  dropRuntimeFolderWarnings();
  QGuiApplication application(argc, argv);
  // Qt has set the C library's locale from the user's; numbers in messages
  // and files stay "1.5" (in de_DE the libraries' messages said "1,98 m"
  // beside "0.4-2 times"). Text and collation keep the user's locale.
  std::setlocale(LC_NUMERIC, "C");
  QCoreApplication::setApplicationName(QStringLiteral("mrcloth"));
  QCoreApplication::setApplicationVersion(QStringLiteral(MRCLOTH_VERSION));

  CommandLine command;
  if (const std::optional<int> code = answerWithoutWork(command)) return *code;

  HostLog log(command.quiet);
  log.installMessageHandler();
  ObjectStore store;
  PluginRegistry plugins(log, store);
  plugins.loadFolder(command.pluginFolder.isEmpty() ? PluginRegistry::defaultFolder() : command.pluginFolder);
  ScriptCore core(store, log, command.scriptArguments);
  if (command.pipeline) command.scriptPath = core.resourcePath() + QStringLiteral("/scripts/pipeline.js");
  core.setScriptPath(command.scriptPath);

  if (command.api) {
    printApi(core, plugins, log);
    return 0;
  }

  // Declared after core so that it is destroyed first.
  QJSEngine engine;
  engine.installExtensions(QJSEngine::ConsoleExtension);
  replaceWeakCollections(engine);
  exposeToScripts(engine, QStringLiteral("core"), &core);
  for (const LoadedPlugin& plugin : plugins.plugins()) exposeToScripts(engine, plugin.scriptName, plugin.object);

  // Ctrl-C: jobs stop early, the script stops, exit code 130.
  InterruptHandler interrupt_handler(engine);
  for (const LoadedPlugin& plugin : plugins.plugins())
    if (qobject_cast<ProcessInterface*>(plugin.object)) interrupt_handler.watchJobs(plugin.object);
  const int code = runBatchScript(command.scriptPath, engine, core, log, interruptFlag());
  warnHowToResume(engine, command, log);
  return code;
}

}  // namespace

int main(int argc, char* argv[]) {
  occupyClosedStandardDescriptors();
  return finishStdout(runHost(argc, argv));
}
