#pragma once
// Batch mode: evaluate one script file and turn its outcome into an exit code.
#include <QString>

#include <atomic>

class QJSEngine;

namespace mrcloth {

class HostLog;
class ScriptCore;

/// Evaluates the script at `path` in `engine` (file name passed along so that
/// errors carry the right line numbers; a leading #! line is ignored).
/// Once the script has run, its promises' pending reactions run (then /
/// catch callbacks; promise_jobs.h). Returns 130 after "[error]
/// interrupted" if `interrupted` became true (Ctrl-C; see interrupt.h; 143
/// for SIGTERM); else core.exitApplication's code if the script called it;
/// else 1 after printing "<path>:<line>: <error>" (and the JS stack) for an
/// uncaught exception, a promise rejected with no handler ("uncaught (in
/// promise)") or an unreadable file; else 0.
int runBatchScript(const QString& path, QJSEngine& engine, const ScriptCore& core, const HostLog& log,
                   const std::atomic_bool& interrupted);

}  // namespace mrcloth
