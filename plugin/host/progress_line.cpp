#include "progress_line.h"

#include <QtGlobal>

#include <algorithm>
#include <cstdio>

#include <sys/ioctl.h>
#include <unistd.h>

namespace mrcloth {
namespace {

QString bar(double fraction, int width) {
  const int filled = std::clamp(static_cast<int>(fraction * width), 0, width);
  return QLatin1Char('[') + QString(filled, QLatin1Char('#')) + QString(width - filled, QLatin1Char('.')) +
         QLatin1Char(']');
}

}  // namespace

QString fitProgressBarLine(const QString& job_id, double fraction, const QString& figures, int columns) {
  const int room = std::max(columns - 1, 1);
  const QString head = QStringLiteral("[job] %1: ").arg(job_id);
  // Everything but the bar's inner width: its brackets and the space after.
  const qsizetype fixed = head.size() + 3 + figures.size();
  const qsizetype width = std::min<qsizetype>(kProgressBarWidth, room - fixed);
  if (width >= kLeastProgressBarWidth)
    return head + bar(fraction, static_cast<int>(width)) + QLatin1Char(' ') + figures;
  return (head + figures).left(room);
}

int terminalColumns() {
  winsize size{};
  if (ioctl(fileno(stderr), TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  bool ok = false;
  const int columns = qEnvironmentVariable("COLUMNS").toInt(&ok);
  return ok && columns > 0 ? columns : 80;
}

}  // namespace mrcloth
