#pragma once
// OpenFlipper vocabulary: long operations announce themselves as jobs so the
// host can show progress (on stderr, hidden by --quiet). Algorithms stay
// silent; the plugin slot that runs them emits these signals.
//
// Cancelling: the host hands every ProcessInterface a flag that turns true
// when the user asks to stop (Ctrl-C in the mrcloth host). A long job polls
// cancelRequested() between its steps and ends early, leaving no partial
// output. (OpenFlipper's core calls a canceledJob slot instead; scripts run
// synchronously here, so the plugin has to ask.)
#include <QString>
#include <QtPlugin>

#include <atomic>

namespace mrcloth {

class ProcessInterface {
 public:
  virtual ~ProcessInterface() = default;

  // signals: (re-declare each in the plugin's `signals:` section, spelled as here;
  // the host connects them by signature string)
  /// A job starts; its state will go from `min` to `max`.
  virtual void startJob(QString jobId, QString description, int min, int max) = 0;
  /// The job reached `value` (min <= value <= max).
  virtual void setJobState(QString jobId, int value) = 0;
  /// The job ended (successfully or not).
  virtual void finishJob(QString jobId) = 0;

  /// Called by the host before initializePlugin(). `requested` turns true when
  /// the user asks to stop and stays true; it outlives the plugin. Null: never.
  void setCancelFlag(const std::atomic_bool* requested) { cancel_requested_ = requested; }
  /// Whether the user asked the running job to stop.
  bool cancelRequested() const { return cancel_requested_ && cancel_requested_->load(std::memory_order_relaxed); }

 private:
  const std::atomic_bool* cancel_requested_ = nullptr;
};

}  // namespace mrcloth

Q_DECLARE_INTERFACE(mrcloth::ProcessInterface, "mrcloth.ProcessInterface/1.1")
