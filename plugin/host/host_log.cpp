#include "host_log.h"

#include <QtGlobal>

#include <cstdio>

namespace mrcloth {
namespace {

const HostLog* g_message_target = nullptr;

void routeQtMessage(QtMsgType type, const QMessageLogContext& context, const QString& message) {
  if (!g_message_target) return;
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

HostLog::HostLog(bool quiet, QObject* parent) : QObject(parent), quiet_(quiet) {}

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
  const QByteArray bytes = (prefix + text + QLatin1Char('\n')).toUtf8();
  if (to_stdout) {
    std::fwrite(bytes.constData(), 1, static_cast<std::size_t>(bytes.size()), stdout);
  } else {
    // Flush script output first so a terminal shows both streams in order.
    std::fflush(stdout);
    std::fwrite(bytes.constData(), 1, static_cast<std::size_t>(bytes.size()), stderr);
    std::fflush(stderr);
  }
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
  job.description = description;
  job.min = min;
  job.max = max;
  job.timer.start();
  if (!quiet_) line(false, QStringLiteral("[job] "), QStringLiteral("%1: %2 ...").arg(jobId, description));
}

void HostLog::onSetJobState(QString jobId, int value) {
  const auto it = jobs_.constFind(jobId);
  // A 0..1 job only says "done"; its finish line says the same with a time.
  if (quiet_ || it == jobs_.constEnd() || it->max - it->min <= 1) return;
  const double percent = 100.0 * (value - it->min) / (it->max - it->min);
  line(false, QStringLiteral("[job] "),
       QStringLiteral("%1: %2/%3 (%4%)").arg(jobId).arg(value - it->min).arg(it->max - it->min).arg(percent, 0, 'f', 0));
}

void HostLog::onFinishJob(QString jobId) {
  const auto it = jobs_.constFind(jobId);
  if (it == jobs_.constEnd()) return;
  if (!quiet_) {
    const double milliseconds = static_cast<double>(it->timer.nsecsElapsed()) / 1e6;
    line(false, QStringLiteral("[job] "), QStringLiteral("%1: finished in %2 ms").arg(jobId).arg(milliseconds, 0, 'f', 1));
  }
  jobs_.erase(it);
}

}  // namespace mrcloth
