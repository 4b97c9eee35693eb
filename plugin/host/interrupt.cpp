#include "interrupt.h"

#include <QJSEngine>

#include <chrono>
#include <csignal>

namespace mrcloth {
namespace {

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

InterruptHandler::InterruptHandler(QJSEngine& engine) : engine_(engine) {
  previous_ = std::signal(SIGINT, onInterrupt);
  if (previous_ == SIG_ERR) previous_ = SIG_DFL;
  // A batch system's SIGTERM stops as Ctrl-C does: between frames, no
  // half-written file left (its default would leave the temporary cache).
  previous_term_ = std::signal(SIGTERM, onInterrupt);
  if (previous_term_ == SIG_ERR) previous_term_ = SIG_DFL;
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
  std::signal(SIGINT, previous_);
  std::signal(SIGTERM, previous_term_);
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
