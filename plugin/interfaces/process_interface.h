#pragma once
// OpenFlipper vocabulary: long operations announce themselves as jobs so the
// host can show progress (on stderr, hidden by --quiet). Algorithms stay
// silent; the plugin slot that runs them emits these signals.
#include <QString>
#include <QtPlugin>

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
};

}  // namespace mrcloth

Q_DECLARE_INTERFACE(mrcloth::ProcessInterface, "mrcloth.ProcessInterface/1.0")
