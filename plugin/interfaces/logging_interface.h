#pragma once
// OpenFlipper vocabulary: a plugin reports to the user only through the log
// signal; the host decides where lines go ([info]/[warn]/[error] on stderr,
// LOGOUT on stdout) and what --quiet hides. Plugins never print.
#include <QString>
#include <QtPlugin>

namespace mrcloth {

/// Severity of a log line. LOGOUT is plain program output (never hidden).
enum Logtype { LOGINFO, LOGOUT, LOGWARN, LOGERR };

class LoggingInterface {
 public:
  virtual ~LoggingInterface() = default;

  // signals:
  /// Implemented by moc: the plugin re-declares it in its `signals:` section
  /// spelled exactly `void log(Logtype type, QString message)`, because the
  /// host connects it by signature string (SIGNAL(log(Logtype,QString))) on
  /// the plugin's QObject, as OpenFlipper's core does.
  virtual void log(Logtype type, QString message) = 0;
};

}  // namespace mrcloth

Q_DECLARE_INTERFACE(mrcloth::LoggingInterface, "mrcloth.LoggingInterface/1.0")
