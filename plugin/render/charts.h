#pragma once
// Line and bar charts as images, for reports: time per frame per model,
// vertices per refinement level, histogram of modes.
//
// Text needs a QGuiApplication (see legend.h); without one these throw
// std::logic_error.
#include <QColor>
#include <QImage>
#include <QPointF>
#include <QString>

#include <vector>

namespace mrcloth::render {

/// Look shared by both chart kinds.
struct ChartOptions {
  int width = 800;                                ///< image width in pixels (> 0)
  int height = 500;                               ///< image height in pixels (> 0)
  int font_pixel_size = 13;                       ///< labels and ticks; the title is bold and 3 pixels larger
  QColor background = QColor(255, 255, 255);      ///< image colour
  QColor text_color = QColor(20, 20, 20);         ///< title, labels, tick values
  QColor axis_color = QColor(80, 80, 80);         ///< axes and tick marks
  QColor grid_color = QColor(225, 225, 225);      ///< lines at the value ticks; invalid QColor = no grid
  int margin = 12;                                ///< pixels kept free at the image edges
  int target_ticks = 5;                           ///< about how many tick intervals per axis
};

/// One line of a line chart.
struct LineSeries {
  QString name;                 ///< legend text; empty = not in the legend
  std::vector<QPointF> points;  ///< (x, y) in data units, drawn in this order; non-finite points break the line
  QColor color;                 ///< invalid = categorical_color(series index)
};

struct LineChart {
  QString title;                    ///< above the plot; empty = none
  QString x_label;                  ///< under the x axis, with units
  QString y_label;                  ///< beside the y axis, with units
  std::vector<LineSeries> series;   ///< may be empty (an empty plot saying "no data")
  double line_width = 2.0;          ///< pixels
  int max_points_with_markers = 60; ///< series with at most this many points get a dot at each point
};

/// One value per category, drawn as one bar of each group.
struct BarSeries {
  QString name;                ///< legend text; empty = not in the legend
  std::vector<double> values;  ///< value per category (missing or NaN = no bar)
  QColor color;                ///< invalid = categorical_color(series index)
};

struct BarChart {
  QString title;                    ///< above the plot; empty = none
  QString category_label;           ///< under the category axis
  QString value_label;              ///< beside the value axis, with units
  std::vector<QString> categories;  ///< group labels left to right; missing ones are numbered from 1
  std::vector<BarSeries> series;    ///< bars of one group side by side, in this order
};

/// Draws `chart` with nice ticks on both axes (see nice_ticks in
/// text_support.h) into a Format_ARGB32 image of options' size. Empty
/// series, one point and all-equal values are fine. Throws
/// std::invalid_argument for a non-positive size.
QImage draw_line_chart(const LineChart& chart, const ChartOptions& options = {});

/// Draws `chart` (bars grow from 0; negative values go down) into a
/// Format_ARGB32 image of options' size; bars are unantialiased rectangles
/// of exactly their series colour. Throws std::invalid_argument for a
/// non-positive size.
QImage draw_bar_chart(const BarChart& chart, const ChartOptions& options = {});

}  // namespace mrcloth::render
