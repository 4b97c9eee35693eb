#include "batch_runner.h"

#include "host_log.h"
#include "interrupt.h"
#include "promise_jobs.h"
#include "script_exposure.h"
#include "script_core.h"

#include <QFile>
#include <QJSEngine>
#include <QJSValue>
#include <QStringList>

#include <algorithm>

namespace mrcloth {
namespace {

/// A stack frame as QJSEngine reports it: "function:line:column:file"
/// (the file may itself contain ':').
struct StackFrame {
  QString function;
  QString line;
  QString file;  ///< the script or an included file; falls back to the main script
};

/// QJSEngine reports files as URLs when it was given a path: "file:///abs"
/// or, for a relative one, "file:rel".
QString withoutFileScheme(const QString& file) {
  if (file.startsWith(QLatin1String("file://"))) return file.mid(7);
  return file.startsWith(QLatin1String("file:")) ? file.mid(5) : file;
}

/// A frame's function as reports name it: the script's own code is
/// "%entry"; a function without a name (an arrow passed to map) is
/// anonymous, not the script (it printed as <script> too).
QString shownFunction(const QString& function) {
  if (function == QLatin1String("%entry")) return QStringLiteral("<script>");
  return function.isEmpty() ? QStringLiteral("<anonymous>") : function;
}

StackFrame parseFrame(const QString& frame, const QString& fallback_file) {
  StackFrame parsed{shownFunction(frame.section(QLatin1Char(':'), 0, 0)), frame.section(QLatin1Char(':'), 1, 1),
                    frame.section(QLatin1Char(':'), 3)};
  parsed.file = withoutFileScheme(parsed.file);
  if (parsed.file.isEmpty()) parsed.file = fallback_file;
  return parsed;
}

/// Reports a promise rejected with no handler as an uncaught exception is
/// reported: where its Error was made, and the frames of its stack
/// ("function@url:line" each; the promise tracking's own left out).
void reportUnhandled(const QJSValue& reason, const QString& path, const HostLog& log) {
  if (!reason.isError()) {
    log.raw(QStringLiteral("%1:?: uncaught (in promise): rejected with %2").arg(path, thrownValueText(reason)));
    return;
  }
  log.raw(QStringLiteral("%1:%2: uncaught (in promise) %3")
              .arg(withoutFileScheme(reason.property(QStringLiteral("fileName")).toString()),
                   reason.property(QStringLiteral("lineNumber")).toString(), reason.toString()));
  QStringList frames = withoutSlotGuardFrames(
      reason.property(QStringLiteral("stack")).toString().split(QLatin1Char('\n'), Qt::SkipEmptyParts));
  frames.erase(std::remove_if(frames.begin(), frames.end(),
                              [](const QString& frame) { return frame.contains(PromiseJobs::kTrackingFile); }),
               frames.end());
  if (frames.size() < 2) return;
  for (const QString& frame : frames) {
    const qsizetype at = frame.indexOf(QLatin1Char('@'));
    log.raw(QStringLiteral("    at %1 (%2)").arg(shownFunction(frame.left(at)), withoutFileScheme(frame.mid(at + 1))));
  }
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

  const PromiseJobs promises(engine);
  QStringList stack;
  const QJSValue result = engine.evaluate(program, path, 1, &stack);
  // The engine fills the stack exactly when the script threw (anything:
  // `throw 42`, a syntax error too). The result being an Error is no sign:
  // a script whose last statement's value is an error it caught ran to its
  // end (it exited 1, and its promises' callbacks never ran).
  const bool threw = !stack.isEmpty();
  stack = withoutSlotGuardFrames(stack);
  if (!threw) promises.drain([&] { return interrupted.load() || core.exitRequested(); });
  // Ctrl-C wins over everything the interrupted script did afterwards.
  if (interrupted.load()) {
    const int signal = interruptSignal();
    log.error(QStringLiteral("%1: interrupted (%2)").arg(path, QLatin1String(interruptSignalName(signal))));
    // 128 + the signal, as shells report it: 130, 143, 129.
    return signal > 0 ? 128 + signal : kInterruptedExitCode;
  }
  if (core.exitRequested()) return core.exitCode();
  if (!threw) {
    const QList<QJSValue> unhandled = promises.unhandled();
    for (const QJSValue& reason : unhandled) reportUnhandled(reason, path, log);
    return unhandled.isEmpty() ? 0 : 1;
  }

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
      result.isError() ? result.toString() : QStringLiteral("uncaught exception: %1").arg(thrownValueText(result));
  log.raw(QStringLiteral("%1:%2: %3").arg(where, line, message));
  if (stack.size() > 1) {
    // A runaway recursion's stack (a RangeError) ran to 1,238 lines: its
    // innermost and outermost frames say where, the middle repeats.
    constexpr qsizetype kInnermost = 12, kOutermost = 4;
    for (qsizetype k = 0; k < stack.size(); ++k) {
      if (k == kInnermost && stack.size() > kInnermost + kOutermost + 1) {
        log.raw(QStringLiteral("    ... %1 more frames").arg(stack.size() - kInnermost - kOutermost));
        k = stack.size() - kOutermost;
      }
      const StackFrame parsed = parseFrame(stack[k], path);
      log.raw(QStringLiteral("    at %1 (%2:%3)").arg(parsed.function, parsed.file, parsed.line));
    }
  }
  return 1;
}

}  // namespace mrcloth
