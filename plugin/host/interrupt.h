#pragma once
// Ctrl-C in batch mode. The first SIGINT raises the host's interrupt flag:
// running jobs see it through ProcessInterface::cancelRequested() and stop
// early (a simulation leaves no cache), and the script engine is interrupted
// so the script stops at its next statement; the host then exits with 130
// (128 + SIGINT, as shells report it). SIGTERM (a batch system) and SIGHUP
// (an ssh connection dropped) do the same, exit 143 and 129. A signal the
// parent set to be ignored (nohup, a background job of a script) stays
// ignored. A second signal ends the process at once.
#include <QObject>

#include <array>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

#include <signal.h>

class QJSEngine;

namespace mrcloth {

/// Exit code of a script stopped by SIGINT.
inline constexpr int kInterruptedExitCode = 130;

/// The host's interrupt flag: false until SIGINT, SIGTERM or SIGHUP arrives while
/// an InterruptHandler is installed. Lives for the whole process.
const std::atomic_bool& interruptFlag();

/// The signal that raised the flag (SIGINT, SIGTERM or SIGHUP; 0: none
/// yet). The host exits with 128 plus it, as shells report a signal.
int interruptSignal();

/// "SIGINT", "SIGTERM" or "SIGHUP" for the signals above; "signal" for any other.
const char* interruptSignalName(int signal);

/// While alive: SIGINT, SIGTERM and SIGHUP raise interruptFlag() and
/// interrupt `engine`, each unless it was ignored when the handler was made. A
/// signal handler may only touch lock-free atomics, so a small thread waits
/// for the flag and calls QJSEngine::setInterrupted (which is thread-safe);
/// that catches a script busy in JavaScript. A job cancelled by the flag
/// returns to the script sooner than the thread may look, so the handler also
/// listens to the plugins' job signals and interrupts the engine there, before
/// the script can run another statement.
class InterruptHandler : public QObject {
  Q_OBJECT

 public:
  explicit InterruptHandler(QJSEngine& engine);
  ~InterruptHandler() override;  ///< restores the previous dispositions
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

  /// Connects a ProcessInterface plugin's job signals to checkNow().
  void watchJobs(QObject* plugin);

 public slots:
  /// Interrupts the engine if the flag is up (called on the engine's thread).
  void checkNow();

 private:
  void watch();

  QJSEngine& engine_;

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  /// SIGINT's, SIGTERM's and SIGHUP's dispositions before; only those replaced are restored.
  std::array<struct sigaction, 3> previous_{};
  std::array<bool, 3> replaced_{};
  std::thread watcher_;
};

}  // namespace mrcloth
