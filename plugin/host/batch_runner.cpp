#include "batch_runner.h"

#include "host_log.h"
#include "interrupt.h"
#include "script_core.h"

#include <QFile>
#include <QJSEngine>
#include <QJSValue>
#include <QStringList>

namespace mrcloth {
namespace {

/// A stack frame as QJSEngine reports it: "function:line:column:file"
/// (the file may itself contain ':').
struct StackFrame {
  QString function;
  QString line;
};

StackFrame parseFrame(const QString& frame) {
  StackFrame parsed{frame.section(QLatin1Char(':'), 0, 0), frame.section(QLatin1Char(':'), 1, 1)};
  if (parsed.function.isEmpty() || parsed.function == QLatin1String("%entry")) parsed.function = QStringLiteral("<script>");
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
    log.error(QStringLiteral("%1: interrupted (SIGINT)").arg(path));
    return kInterruptedExitCode;
  }
  if (core.exitRequested()) return core.exitCode();
  // An uncaught `throw 42` is not an Error object, but it leaves a stack.
  if (!result.isError() && stack.isEmpty()) return 0;

  QString line = result.property(QStringLiteral("lineNumber")).toString();
  if (!result.isError() || line.isEmpty() || line == QLatin1String("undefined"))
    line = stack.isEmpty() ? QStringLiteral("?") : parseFrame(stack.first()).line;
  const QString message =
      result.isError() ? result.toString() : QStringLiteral("uncaught exception: %1").arg(result.toString());
  log.raw(QStringLiteral("%1:%2: %3").arg(path, line, message));
  if (stack.size() > 1) {
    for (const QString& frame : stack) {
      const StackFrame parsed = parseFrame(frame);
      log.raw(QStringLiteral("    at %1 (%2:%3)").arg(parsed.function, path, parsed.line));
    }
  }
  return 1;
}

}  // namespace mrcloth
