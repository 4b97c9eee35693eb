#include "plugin/render/charts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrcloth::render {
namespace {

ChartOptions size(int width, int height) {
  ChartOptions options;
  options.width = width;
  options.height = height;
  return options;
}

// Per column, how many pixels have exactly `color`.
std::vector<int> column_counts(const QImage& image, const QColor& color) {
  std::vector<int> counts(image.width(), 0);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) counts[x] += QColor(image.pixel(x, y)) == color;
  return counts;
}

TEST(RenderCharts, BarHeightsFollowTheValues) {
  const QColor color(200, 30, 30);
  BarChart chart;
  chart.title = "vertices per refinement level";
  chart.categories = {"0", "1", "2"};
  chart.value_label = "vertices";
  chart.category_label = "level";
  chart.series = {{"", {1, 2, 3}, color}};
  const QImage image = draw_bar_chart(chart, size(600, 400));
  ASSERT_EQ(image.size(), QSize(600, 400));
  // The bars are the runs of columns that contain the colour.
  std::vector<int> heights;
  const std::vector<int> counts = column_counts(image, color);
  for (int x = 0; x < image.width(); ++x)
    if (counts[x] > 0 && (x == 0 || counts[x - 1] == 0)) heights.push_back(counts[x]);
  ASSERT_EQ(heights.size(), 3u);
  EXPECT_LT(heights[0], heights[1]);
  EXPECT_LT(heights[1], heights[2]);
  EXPECT_NEAR(heights[1], 2 * heights[0], 2);
  EXPECT_NEAR(heights[2], 3 * heights[0], 3);
  // Overall in thirds of the width too.
  int thirds[3] = {0, 0, 0};
  for (int x = 0; x < image.width(); ++x) thirds[x * 3 / image.width()] += counts[x];
  EXPECT_GT(thirds[2], thirds[0]);
}

TEST(RenderCharts, GroupedBarsWithLegend) {
  BarChart chart;
  chart.title = "time per frame per model";
  chart.categories = {"skirt", "trousers", "dress"};
  chart.series = {{"coarse", {1.5, 2.0, 2.5}, QColor(10, 100, 200)},
                  {"multi-resolution", {3.0, 4.0, std::nan("")}, QColor(250, 150, 0)}};
  chart.value_label = "ms";
  const QImage image = draw_bar_chart(chart, size(700, 400));
  EXPECT_EQ(image.size(), QSize(700, 400));
  // Three coarse bars, two multi-resolution ones; each series also has a legend swatch.
  int runs[2] = {0, 0};
  for (int s = 0; s < 2; ++s) {
    const std::vector<int> counts = column_counts(image, chart.series[s].color);
    for (int x = 0; x < image.width(); ++x) runs[s] += counts[x] > 0 && (x == 0 || counts[x - 1] == 0);
  }
  EXPECT_EQ(runs[0], 3 + 1);
  EXPECT_EQ(runs[1], 2 + 1);
}

TEST(RenderCharts, BarChartEdgeCases) {
  EXPECT_EQ(draw_bar_chart({}, size(300, 200)).size(), QSize(300, 200));
  BarChart zeros;
  zeros.series = {{"none", {0, 0, 0}, {}}};
  EXPECT_EQ(draw_bar_chart(zeros, size(300, 200)).size(), QSize(300, 200));
  BarChart negative;
  negative.series = {{"", {-2, 5, std::numeric_limits<double>::infinity()}, {}}};
  EXPECT_EQ(draw_bar_chart(negative, size(300, 200)).size(), QSize(300, 200));
  BarChart histogram;  // many categories: labels are thinned, nothing breaks
  histogram.series.push_back({"vertices per mode", {}, {}});
  for (int i = 0; i < 200; ++i) histogram.series[0].values.push_back(i % 17);
  EXPECT_EQ(draw_bar_chart(histogram, size(400, 300)).size(), QSize(400, 300));
  EXPECT_EQ(draw_bar_chart(histogram, size(5, 5)).size(), QSize(5, 5));
  EXPECT_THROW(draw_bar_chart(histogram, size(0, 300)), std::invalid_argument);
}

// Values at the ends of a double's range draw their bars and lines (no
// bars, or no line and Qt's NaN warnings, before).
TEST(RenderCharts, ValuesAtTheEndsOfADoublesRangeAreDrawn) {
  const QColor color(200, 30, 30);
  for (const std::vector<double>& values : {std::vector<double>{1e308, 1.7e308}, {5e-324, 1e-323}}) {
    BarChart bars;
    bars.series = {{"", values, color}};
    int painted = 0;
    for (int c : column_counts(draw_bar_chart(bars, size(300, 200)), color)) painted += c;
    EXPECT_GT(painted, 100) << values[0];
    LineChart line;
    line.series = {{"", {{0, 0}, {1, values[0]}, {2, values[1]}}, color}};
    painted = 0;
    for (int c : column_counts(draw_line_chart(line, size(300, 200)), color)) painted += c;
    EXPECT_GT(painted, 50) << values[0];
  }
}

// A long series name (two cache paths) took the plot's room down to
// nothing: legend labels are cut to a quarter of the width, so the plot
// keeps the rest. The plot is the rectangle of the horizontal grid lines.
TEST(RenderCharts, LongSeriesNamesLeaveThePlotItsRoom) {
  const auto plot_width = [](const QString& name) {
    LineChart chart;
    chart.series = {{name, {{0, 1}, {1, 2}}, QColor(0, 90, 200)}};
    ChartOptions options = size(600, 300);
    const QImage image = draw_line_chart(chart, options);
    // The widest run of grid colour on a row.
    int widest = 0;
    for (int y = 0; y < image.height(); ++y) {
      int run = 0;
      for (int x = 0; x < image.width(); ++x) {
        run = QColor(image.pixel(x, y)) == options.grid_color ? run + 1 : 0;
        widest = std::max(widest, run);
      }
    }
    return widest;
  };
  const int short_name = plot_width("skirt");
  const int long_name = plot_width(QString(120, QLatin1Char('x')));
  EXPECT_GT(short_name, 400);
  EXPECT_GE(long_name, short_name - 600 / 4) << "the plot keeps at least three quarters less the axis";
}

TEST(RenderCharts, LineChartDrawsEachSeries) {
  LineChart chart;
  chart.title = "time per frame";
  chart.x_label = "frame";
  chart.y_label = "ms";
  chart.series = {{"skirt", {{0, 10}, {1, 12}, {2, 11}, {3, 15}}, QColor(0, 90, 200)},
                  {"trousers", {{0, 20}, {1, 18}, {2, 25}, {3, 21}}, QColor(230, 60, 0)}};
  const QImage image = draw_line_chart(chart, size(640, 360));
  ASSERT_EQ(image.size(), QSize(640, 360));
  for (const auto& series : chart.series) {
    int n = 0;
    for (int c : column_counts(image, series.color)) n += c;
    EXPECT_GT(n, 200) << series.name.toStdString();
  }
}

TEST(RenderCharts, LineChartEdgeCases) {
  EXPECT_EQ(draw_line_chart({}, size(300, 200)).size(), QSize(300, 200));
  LineChart empty_series;
  empty_series.series = {{"nothing", {}, {}}};
  EXPECT_EQ(draw_line_chart(empty_series, size(300, 200)).size(), QSize(300, 200));
  LineChart single;
  single.series = {{"one", {{5, 5}}, QColor(0, 0, 0)}};
  const QImage one = draw_line_chart(single, size(300, 200));
  int dark = 0;
  for (int c : column_counts(one, QColor(0, 0, 0))) dark += c;
  EXPECT_GT(dark, 4) << "a single point still shows";
  LineChart flat;
  flat.series = {{"flat", {{0, 2}, {1, 2}, {2, 2}}, {}}, {"gap", {{0, 1}, {std::nan(""), 3}, {2, 1}}, {}}};
  EXPECT_EQ(draw_line_chart(flat, size(300, 200)).size(), QSize(300, 200));
  EXPECT_EQ(draw_line_chart(flat, size(1, 1)).size(), QSize(1, 1));
  EXPECT_THROW(draw_line_chart(flat, size(300, -1)), std::invalid_argument);
}

}  // namespace
}  // namespace mrcloth::render
