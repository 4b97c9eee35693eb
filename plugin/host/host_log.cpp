#include "host_log.h"

#include "progress_line.h"

#include <QtGlobal>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>

#include <unistd.h>

namespace mrcloth {
namespace {

const HostLog* g_message_target = nullptr;

/// The errno of the first failed write to stdout (0: none). Atomic because
/// a plugin's worker thread may log.
std::atomic_int g_stdout_error{0};

void noteStdoutError(int error) {
  int none = 0;
  g_stdout_error.compare_exchange_strong(none, error != 0 ? error : EIO);
}

/// Writes all of `bytes` to `stream`; false if the stream refused some.
bool writeAll(const QByteArray& bytes, std::FILE* stream) {
  return std::fwrite(bytes.constData(), 1, static_cast<std::size_t>(bytes.size()), stream) ==
         static_cast<std::size_t>(bytes.size());
}

/// Progress lines of a long job come at most this often (plus its last step).
constexpr qint64 kProgressIntervalNs = 1'000'000'000;
/// A bar on a terminal redraws in place, so it may update more often.
constexpr qint64 kBarIntervalNs = 100'000'000;

/// MRCLOTH_PROGRESS_INTERVAL (seconds, > 0) overrides both intervals: a
/// busy batch log may want fewer lines, and a test a job shorter than a
/// second to print some.
qint64 progressInterval(qint64 fallback_ns) {
  bool ok = false;
  const double seconds = qEnvironmentVariable("MRCLOTH_PROGRESS_INTERVAL").toDouble(&ok);
  return ok && seconds > 0.0 && seconds < 1e6 ? static_cast<qint64>(seconds * 1e9) : fallback_ns;
}

/// A bar when stderr is a terminal, plain lines otherwise (logs, pipes, CI);
/// MRCLOTH_PROGRESS=bar or =lines overrides.
bool progressBarWanted() {
  const QByteArray forced = qgetenv("MRCLOTH_PROGRESS");
  if (forced == "bar") return true;
  if (forced == "lines") return false;
  return isatty(fileno(stderr)) != 0;
}

/// "5.8 s", "2 min 05 s", "1 h 02 min".
QString formatDuration(double seconds) {
  if (seconds < 59.95) return QStringLiteral("%1 s").arg(seconds, 0, 'f', 1);
  const qint64 whole = static_cast<qint64>(seconds + 0.5);
  if (whole < 3600) return QStringLiteral("%1 min %2 s").arg(whole / 60).arg(whole % 60, 2, 10, QLatin1Char('0'));
  return QStringLiteral("%1 h %2 min").arg(whole / 3600).arg((whole % 3600) / 60, 2, 10, QLatin1Char('0'));
}

/// Steps per second with three significant digits ("8.34", "125").
QString formatRate(double rate) {
  return rate >= 100.0 ? QString::number(rate, 'f', 0) : QString::number(rate, 'g', 3);
}

void routeQtMessage(QtMsgType type, const QMessageLogContext& context, const QString& message) {
  if (!g_message_target || isRuntimeFolderWarning(message)) return;
  const bool from_script = context.category && qstrcmp(context.category, "js") == 0;
  switch (type) {
    case QtDebugMsg:
    case QtInfoMsg:
      if (from_script) g_message_target->out(message);
      else g_message_target->info(message);
      break;
    case QtWarningMsg:
      g_message_target->warn(message);
      break;
    case QtCriticalMsg:
    case QtFatalMsg:
      g_message_target->error(message);
      break;
  }
}

}  // namespace

bool isRuntimeFolderWarning(const QString& message) {
  return message.startsWith(QLatin1String("QStandardPaths: ")) &&
         (message.contains(QLatin1String("XDG_RUNTIME_DIR")) || message.contains(QLatin1String("runtime directory")));
}

int finishStdout(int exit_code) {
  if (std::fflush(stdout) != 0) noteStdoutError(errno);
  if (std::ferror(stdout)) noteStdoutError(0);  // failed in a call that did not say why (printf)
  const int error = g_stdout_error.load();
  if (error == 0 || error == EPIPE) return exit_code;
  std::fprintf(stderr, "[error] cannot write to stdout: %s\n", std::strerror(error));
  return exit_code == 0 ? 1 : exit_code;
}

HostLog::HostLog(bool quiet, QObject* parent) : QObject(parent), quiet_(quiet), bar_(progressBarWanted()) {}

HostLog::~HostLog() {
  if (handler_installed_) {
    qInstallMessageHandler(nullptr);
    g_message_target = nullptr;
  }
}

void HostLog::installMessageHandler() {
  g_message_target = this;
  qInstallMessageHandler(routeQtMessage);
  handler_installed_ = true;
}

void HostLog::line(bool to_stdout, const QString& prefix, const QString& text) const {
  // Every line of a message carries its prefix: `grep '^\[warn\]'` missed
  // a warning's second line.
  QString lines = text;
  if (!prefix.isEmpty()) lines.replace(QLatin1Char('\n'), QLatin1Char('\n') + prefix);
  const QByteArray bytes = (prefix + lines + QLatin1Char('\n')).toUtf8();
  clearBar();
  if (to_stdout) {
    // Each line as it is printed: into a file or pipe stdout is block
    // buffered, so a log showed nothing during a long run (with --quiet no
    // stderr line flushed it) and lost everything on SIGKILL.
    if (!writeAll(bytes, stdout) || std::fflush(stdout) != 0) noteStdoutError(errno);
  } else {
    // Flush script output first so a terminal shows both streams in order.
    if (std::fflush(stdout) != 0) noteStdoutError(errno);
    // A failed write to stderr has nowhere to be reported.
    writeAll(bytes, stderr);
    std::fflush(stderr);
  }
}

void HostLog::clearBar() const {
  if (!bar_shown_) return;
  std::fputs("\r\033[K", stderr);  // carriage return, erase to the end of the line
  std::fflush(stderr);
  bar_shown_ = false;
}

void HostLog::drawBar(const QString& text) const {
  const QByteArray bytes = (QStringLiteral("\r\033[K") + text).toUtf8();
  if (std::fflush(stdout) != 0) noteStdoutError(errno);
  std::fwrite(bytes.constData(), 1, static_cast<std::size_t>(bytes.size()), stderr);
  std::fflush(stderr);
  bar_shown_ = true;
}

void HostLog::out(const QString& text) const { line(true, {}, text); }
void HostLog::info(const QString& text) const {
  if (!quiet_) line(false, QStringLiteral("[info] "), text);
}
void HostLog::warn(const QString& text) const { line(false, QStringLiteral("[warn] "), text); }
void HostLog::error(const QString& text) const { line(false, QStringLiteral("[error] "), text); }
void HostLog::raw(const QString& text) const { line(false, {}, text); }

void HostLog::onLog(Logtype type, QString message) {
  switch (type) {
    case LOGINFO: info(message); break;
    case LOGOUT: out(message); break;
    case LOGWARN: warn(message); break;
    case LOGERR: error(message); break;
  }
}

void HostLog::onStartJob(QString jobId, QString description, int min, int max) {
  Job& job = jobs_[jobId];
  job = Job{};
  job.description = description;
  job.min = min;
  job.max = max;
  job.value = min;
  job.timer.start();
  if (!quiet_) line(false, QStringLiteral("[job] "), QStringLiteral("%1: %2 ...").arg(jobId, description));
}

void HostLog::onSetJobState(QString jobId, int value) {
  const auto it = jobs_.find(jobId);
  if (it == jobs_.end()) return;
  Job& job = *it;
  job.value = value;
  const qint64 now = job.timer.nsecsElapsed();
  if (job.first_state_ns < 0) {
    job.first_state_ns = now;
    job.first_state = value;
  }
  // A 0..1 job only says "done"; its finish line says the same with a time.
  const int total = job.max - job.min;
  if (quiet_ || total <= 1) return;
  const bool last = value >= job.max;
  const qint64 interval = progressInterval(bar_ ? kBarIntervalNs : kProgressIntervalNs);
  if (!last && job.printed_ns >= 0 && now - job.printed_ns < interval) return;
  if (!last && job.printed_ns < 0 && now < interval) return;  // short jobs print only their end
  job.printed_ns = now;

  const int done = value - job.min;
  QString figures = QStringLiteral("%1/%2 (%3%)").arg(done).arg(total).arg(100.0 * done / total, 0, 'f', 0);
  // Rate from the first state on, so that set-up before it (a factorisation,
  // a simulation's pre-roll) does not make the estimate pessimistic; until a
  // second state there is none (a 30-frame pre-roll before the first of 200
  // frames made the first line's ETA 4 min for a 13 s job), and the last
  // line of a job with one state measures from the start.
  const bool since_first = value > job.first_state && now > job.first_state_ns;
  const double steps = since_first ? value - job.first_state : done;
  const double seconds = static_cast<double>(since_first ? now - job.first_state_ns : now) / 1e9;
  if ((since_first || last) && steps > 0 && seconds > 0) {
    const double rate = steps / seconds;
    figures += QStringLiteral(", %1/s").arg(formatRate(rate));
    if (!last) figures += QStringLiteral(", ETA %1").arg(formatDuration((job.max - value) / rate));
  }
  const double fraction = static_cast<double>(done) / total;
  if (!bar_)
    line(false, QStringLiteral("[job] "), QStringLiteral("%1: %2").arg(jobId, figures));
  else if (!last)
    drawBar(fitProgressBarLine(jobId, fraction, figures, terminalColumns()));
  else  // a line that stays may wrap: it is written once, whole
    line(false, {}, fitProgressBarLine(jobId, fraction, figures, std::numeric_limits<int>::max()));
}

void HostLog::onFinishJob(QString jobId) {
  const auto it = jobs_.constFind(jobId);
  if (it == jobs_.constEnd()) return;
  if (!quiet_) {
    const double milliseconds = static_cast<double>(it->timer.nsecsElapsed()) / 1e6;
    // A long job that ends before its last step was cancelled or failed.
    if (it->max - it->min > 1 && it->value < it->max)
      line(false, QStringLiteral("[job] "), QStringLiteral("%1: stopped at %2/%3 after %4 ms")
                                                .arg(jobId).arg(it->value - it->min).arg(it->max - it->min)
                                                .arg(milliseconds, 0, 'f', 1));
    else
      line(false, QStringLiteral("[job] "),
           QStringLiteral("%1: finished in %2 ms").arg(jobId).arg(milliseconds, 0, 'f', 1));
  }
  jobs_.erase(it);
}

}  // namespace mrcloth
