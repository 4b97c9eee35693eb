#include "interrupt.h"

#include <QJSEngine>

#include <chrono>
#include <csignal>
#include <cstddef>

namespace mrcloth {
namespace {

/// The signals that stop a script, in the order of InterruptHandler's arrays.
constexpr std::array<int, 3> kSignals{SIGINT, SIGTERM, SIGHUP};

std::atomic_bool g_interrupted{false};
std::atomic_int g_signal{0};
static_assert(std::atomic_bool::is_always_lock_free, "the signal handler needs a lock-free flag");
static_assert(std::atomic_int::is_always_lock_free, "the signal handler needs a lock-free signal number");

extern "C" void onInterrupt(int signal) {
  g_signal.store(signal);
  g_interrupted.store(true);
  // A second signal must work even if the script never gets back to the host.
  std::signal(signal, SIG_DFL);
}

}  // namespace

const std::atomic_bool& interruptFlag() { return g_interrupted; }

int interruptSignal() { return g_signal.load(); }

const char* interruptSignalName(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "signal";
  }
}

InterruptHandler::InterruptHandler(QJSEngine& engine) : engine_(engine) {
  // A batch system's SIGTERM and a dropped connection's SIGHUP stop as
  // Ctrl-C does: between frames, no half-written file left (their default
  // would leave the temporary cache). A signal ignored on entry was meant to
  // be by whoever started the host (nohup; a non-interactive shell's
  // background job ignores SIGINT), so it stays ignored.
  struct sigaction handler {};
  handler.sa_handler = onInterrupt;
  sigemptyset(&handler.sa_mask);
  handler.sa_flags = SA_RESTART;  // as std::signal had it: file I/O is not cut short by EINTR
  for (std::size_t k = 0; k < kSignals.size(); ++k) {
    if (sigaction(kSignals[k], nullptr, &previous_[k]) != 0 || previous_[k].sa_handler == SIG_IGN) continue;
    replaced_[k] = sigaction(kSignals[k], &handler, nullptr) == 0;
  }
  watcher_ = std::thread([this] { watch(); });
}

void InterruptHandler::watchJobs(QObject* plugin) {
  // Signature strings, as the registry connects the host log; the
  // connection is direct, so the check runs inside the plugin's emit.
  QObject::connect(plugin, SIGNAL(setJobState(QString, int)), this, SLOT(checkNow()));
  QObject::connect(plugin, SIGNAL(finishJob(QString)), this, SLOT(checkNow()));
}

void InterruptHandler::checkNow() {
  if (g_interrupted.load()) engine_.setInterrupted(true);
}

InterruptHandler::~InterruptHandler() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  watcher_.join();
  for (std::size_t k = 0; k < kSignals.size(); ++k)
    if (replaced_[k]) sigaction(kSignals[k], &previous_[k], nullptr);
}

void InterruptHandler::watch() {
  // Polls: a signal handler cannot notify a condition variable. 20 ms is
  // far below what a person notices and costs nothing measurable.
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    if (g_interrupted.load()) {
      engine_.setInterrupted(true);
      return;
    }
    wake_.wait_for(lock, std::chrono::milliseconds(20));
  }
}

}  // namespace mrcloth
