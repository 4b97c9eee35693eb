#pragma once
// Where everything the host, the plugins and the scripts say goes:
//  - script output (print, console.log/info, core.print, LOGOUT) -> stdout, unprefixed;
//  - "[info] ..." and "[job] ..." -> stderr, hidden by --quiet; a job with
//    more than one step prints "<id>: 12/60 (20%), 8.3/s, ETA 5.8 s" at most
//    once a second and at its last step; when stderr is a terminal, as a bar
//    redrawn in place instead (MRCLOTH_PROGRESS=bar|lines overrides;
//    MRCLOTH_PROGRESS_INTERVAL=<seconds> sets how often);
//  - "[warn] ..." and "[error] ..." -> stderr, always.
// Keeping stdout for script output only lets a script's printed results be
// piped and compared (the script tests do).
#include "plugin/interfaces/logging_interface.h"

#include <QElapsedTimer>
#include <QHash>
#include <QObject>
#include <QString>

namespace mrcloth {

/// Flushes stdout and says on stderr if any write to it failed (a full disk,
/// /dev/full, EIO): output lost must not pass for a successful run. Returns
/// `exit_code`, or 1 in place of 0 after such a failure. A closed pipe
/// (EPIPE, with SIGPIPE ignored) is left silent, as `... | head` expects.
/// Called once, as the host exits.
int finishStdout(int exit_code);

/// Qt's warnings about the runtime folder (XDG_RUNTIME_DIR unset, of the
/// wrong permissions or owner, or not creatable). The offscreen platform
/// never uses that folder, and batch jobs and CI often have none: the host
/// drops them to keep stderr for what matters.
bool isRuntimeFolderWarning(const QString& message);

class HostLog : public QObject {
  Q_OBJECT

 public:
  explicit HostLog(bool quiet, QObject* parent = nullptr);
  ~HostLog() override;

  void out(const QString& text) const;    ///< stdout
  void info(const QString& text) const;   ///< [info], unless quiet
  void warn(const QString& text) const;   ///< [warn]
  void error(const QString& text) const;  ///< [error]
  /// A line on stderr exactly as given (e.g. "file:line: message").
  void raw(const QString& text) const;

  /// Routes Qt's messages here: the script engine's console (category "js")
  /// to stdout or [warn]/[error], Qt's own warnings to [warn]. Undone by the destructor.
  void installMessageHandler();

  // Slots connected by signature string to the plugins' LoggingInterface and
  // ProcessInterface signals; the parameter types must be spelled as there.
 public slots:
  void onLog(Logtype type, QString message);
  void onStartJob(QString jobId, QString description, int min, int max);
  void onSetJobState(QString jobId, int value);
  void onFinishJob(QString jobId);

 private:
  struct Job {
    QString description;
    int min = 0;
    int max = 0;
    int value = 0;                ///< last state reported
    QElapsedTimer timer;          ///< since startJob
    qint64 first_state_ns = -1;   ///< timer reading at the first state (rates leave set-up time out)
    int first_state = 0;
    qint64 printed_ns = -1;       ///< timer reading of the last progress line
  };
  void line(bool to_stdout, const QString& prefix, const QString& text) const;
  void drawBar(const QString& text) const;  ///< the progress line (fitted to the terminal), redrawn in place
  void clearBar() const;                    ///< erases a drawn bar before another line

  bool quiet_;
  bool bar_;                       ///< progress as a bar on a terminal
  mutable bool bar_shown_ = false; ///< a bar is on the terminal's last line
  bool handler_installed_ = false;
  QHash<QString, Job> jobs_;
};

}  // namespace mrcloth
