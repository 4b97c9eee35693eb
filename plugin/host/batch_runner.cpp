#include "batch_runner.h"

#include "host_log.h"
#include "interrupt.h"
#include "script_core.h"

#include <QFile>
#include <QJSEngine>
#include <QJSValue>
#include <QStringList>

#include <csignal>

namespace mrcloth {
namespace {

/// A stack frame as QJSEngine reports it: "function:line:column:file"
/// (the file may itself contain ':').
struct StackFrame {
  QString function;
  QString line;
  QString file;  ///< the script or an included file; falls back to the main script
};

StackFrame parseFrame(const QString& frame, const QString& fallback_file) {
  StackFrame parsed{frame.section(QLatin1Char(':'), 0, 0), frame.section(QLatin1Char(':'), 1, 1),
                    frame.section(QLatin1Char(':'), 3)};
  if (parsed.function.isEmpty() || parsed.function == QLatin1String("%entry")) parsed.function = QStringLiteral("<script>");
  // QJSEngine reports files as URLs when it was given a path.
  if (parsed.file.startsWith(QLatin1String("file://"))) parsed.file = parsed.file.mid(7);
  if (parsed.file.isEmpty()) parsed.file = fallback_file;
  return parsed;
}

}  // namespace

int runBatchScript(const QString& path, QJSEngine& engine, const ScriptCore& core, const HostLog& log,
                   const std::atomic_bool& interrupted) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly)) {
    log.error(QStringLiteral("cannot read script %1: %2").arg(path, file.errorString()));
    return 1;
  }
  QString program = QString::fromUtf8(file.readAll());
  // Allow "#!/usr/bin/env -S mrcloth -b" scripts; commenting the line out keeps line numbers.
  if (program.startsWith(QLatin1String("#!"))) program.prepend(QLatin1String("//"));

  QStringList stack;
  const QJSValue result = engine.evaluate(program, path, 1, &stack);
  // Ctrl-C wins over everything the interrupted script did afterwards.
  if (interrupted.load()) {
    const bool terminated = interruptSignal() == SIGTERM;
    log.error(QStringLiteral("%1: interrupted (%2)")
                  .arg(path, terminated ? QStringLiteral("SIGTERM") : QStringLiteral("SIGINT")));
    return terminated ? 128 + SIGTERM : kInterruptedExitCode;
  }
  if (core.exitRequested()) return core.exitCode();
  // An uncaught `throw 42` is not an Error object, but it leaves a stack.
  if (!result.isError() && stack.isEmpty()) return 0;

  // The innermost frame names the file the error was thrown in, which is an
  // included helper when a shared assertion fails.
  QString line = result.property(QStringLiteral("lineNumber")).toString();
  QString where = path;
  if (!stack.isEmpty()) {
    const StackFrame innermost = parseFrame(stack.first(), path);
    where = innermost.file;
    if (!result.isError() || line.isEmpty() || line == QLatin1String("undefined")) line = innermost.line;
  } else if (!result.isError() || line.isEmpty() || line == QLatin1String("undefined")) {
    line = QStringLiteral("?");
  }
  const QString message =
      result.isError() ? result.toString() : QStringLiteral("uncaught exception: %1").arg(result.toString());
  log.raw(QStringLiteral("%1:%2: %3").arg(where, line, message));
  if (stack.size() > 1) {
    for (const QString& frame : stack) {
      const StackFrame parsed = parseFrame(frame, path);
      log.raw(QStringLiteral("    at %1 (%2:%3)").arg(parsed.function, parsed.file, parsed.line));
    }
  }
  return 1;
}

}  // namespace mrcloth
