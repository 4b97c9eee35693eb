#include "plugin/host/progress_line.h"

#include <gtest/gtest.h>

namespace mrcloth {
namespace {

const QString kFigures = QStringLiteral("70/230 (30%), 2.41/s, ETA 1 min 06 s");

TEST(ProgressBarLine, WholeBarWhenThereIsRoom) {
  const QString line = fitProgressBarLine(QStringLiteral("simulate"), 0.5, kFigures, 200);
  EXPECT_EQ(line, QStringLiteral("[job] simulate: [############............] ") + kFigures);
}

TEST(ProgressBarLine, BarNarrowedFirstToFitTheTerminal) {
  // The sweep's line: 85 characters with the whole bar, on 80 columns.
  const QString id = QStringLiteral("recordInstance");
  const QString line = fitProgressBarLine(id, 70.0 / 230.0, kFigures, 80);
  EXPECT_EQ(line.size(), 79);  // the last column is left free
  EXPECT_TRUE(line.startsWith(QStringLiteral("[job] recordInstance: [#####")));
  EXPECT_TRUE(line.endsWith(QStringLiteral("] ") + kFigures));
  const qsizetype open = line.indexOf(QLatin1Char('['), 6);
  const qsizetype close = line.indexOf(QLatin1Char(']'), open);
  const qsizetype width = close - open - 1;
  EXPECT_GE(width, kLeastProgressBarWidth);
  EXPECT_LT(width, kProgressBarWidth);
  EXPECT_EQ(line.mid(open + 1, width).count(QLatin1Char('#')), static_cast<qsizetype>(70.0 / 230.0 * width));
}

TEST(ProgressBarLine, BarLeftOutThenTextCut) {
  const QString id = QStringLiteral("simulate");
  // Room for the text but not for a bar of the least width.
  const QString text = QStringLiteral("[job] simulate: ") + kFigures;
  QString line = fitProgressBarLine(id, 0.3, kFigures, static_cast<int>(text.size()) + 5);
  EXPECT_EQ(line, text);
  // Narrower still: the text is cut at its end, the start (which job) kept.
  line = fitProgressBarLine(id, 0.3, kFigures, 30);
  EXPECT_EQ(line, text.left(29));
}

TEST(ProgressBarLine, NeverLongerThanTheTerminal) {
  for (int columns = 1; columns <= 120; ++columns) {
    const QString line = fitProgressBarLine(QStringLiteral("refineAdaptive"), 1.0, kFigures, columns);
    EXPECT_LE(line.size(), std::max(columns - 1, 1)) << columns << " columns: " << line.toStdString();
  }
}

TEST(ProgressBarLine, FullAndEmptyBars) {
  EXPECT_TRUE(fitProgressBarLine(QStringLiteral("j"), 1.0, QStringLiteral("3/3"), 200)
                  .contains(QStringLiteral("[########################] 3/3")));
  EXPECT_TRUE(fitProgressBarLine(QStringLiteral("j"), 0.0, QStringLiteral("0/3"), 200)
                  .contains(QStringLiteral("[........................] 0/3")));
}

}  // namespace
}  // namespace mrcloth
