#include "plugin/render/charts.h"

#include "plugin/render/legend.h"
#include "plugin/render/palette.h"
#include "plugin/render/text_support.h"

#include <QFontMetrics>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace mrcloth::render {
namespace {

constexpr int tick_length = 5;
constexpr int text_gap = 6;

struct Axis {
  std::vector<double> ticks;
  double lo = 0, hi = 1, step = 1;
};

Axis make_axis(double lo, double hi, int target) {
  Axis axis;
  axis.ticks = nice_ticks(lo, hi, target);
  axis.lo = axis.ticks.front();
  axis.hi = axis.ticks.back();
  axis.step = axis.ticks[1] - axis.ticks[0];
  return axis;
}

// Data value -> pixel between a (at axis.lo) and b (at axis.hi).
double map(const Axis& axis, double v, double a, double b) {
  return a + (v - axis.lo) / (axis.hi - axis.lo) * (b - a);
}

/// Values whose range a double cannot hold (-1.7e308 to 1.7e308) would put
/// every point at NaN pixels.
void check_span(double lo, double hi, const char* who, const char* axis) {
  if (lo <= hi && !std::isfinite(hi - lo)) {
    char range[64];
    std::snprintf(range, sizeof range, "%g to %g", lo, hi);
    throw std::invalid_argument(std::string(who) + ": the " + axis + " values span more than a number holds (" +
                                range + "); expected values a chart can scale");
  }
}

void check_size(const ChartOptions& options, const char* who) {
  if (options.width <= 0 || options.height <= 0)
    throw std::invalid_argument(std::string(who) + ": image size must be positive, got " +
                                std::to_string(options.width) + " x " + std::to_string(options.height));
  require_gui_application(who);
}

LegendStyle legend_style(const ChartOptions& options) {
  LegendStyle style;
  style.font_pixel_size = options.font_pixel_size;
  style.text_color = options.text_color;
  style.margin = 0;
  return style;
}

/// A legend's labels cut (in the middle, so both ends of a file path show)
/// to a quarter of the chart's width: a long series name took the plot's
/// room, down to nothing.
void elide_legend(std::vector<LegendEntry>& legend, const ChartOptions& options) {
  const QFontMetrics metrics(make_font(options.font_pixel_size));
  const int widest = std::max(40, options.width / 4);
  for (LegendEntry& entry : legend) entry.label = metrics.elidedText(entry.label, Qt::ElideMiddle, widest);
}

// Everything around the plot: title, axis labels, value ticks, legend. The
// plot rectangle is what is left; it never collapses below one pixel, so
// tiny images still draw (badly) instead of dividing by zero.
struct Layout {
  QRect plot;
  QRect legend_area;
};

Layout layout_chart(const ChartOptions& options, const QString& title, const QString& x_label,
                    const QString& y_label, const Axis& y_axis, const std::vector<LegendEntry>& legend,
                    bool x_tick_labels) {
  const QFontMetrics metrics(make_font(options.font_pixel_size));
  const QFontMetrics title_metrics(make_font(options.font_pixel_size + 3, true));
  int y_tick_width = 0;
  for (double v : y_axis.ticks)
    y_tick_width = std::max(y_tick_width, metrics.horizontalAdvance(format_tick(v, y_axis.step)));
  const QSize legend_box = legend_size(legend, legend_style(options));

  const int top = options.margin + (title.isEmpty() ? metrics.height() / 2 : title_metrics.height() + text_gap);
  const int left = options.margin + (y_label.isEmpty() ? 0 : metrics.height() + text_gap) + y_tick_width +
                   tick_length + 2;
  const int right = options.width - 1 - options.margin - (legend_box.isEmpty() ? 0 : legend_box.width() + 2 * text_gap);
  const int bottom = options.height - 1 - options.margin - (x_label.isEmpty() ? 0 : metrics.height() + 2) -
                     (x_tick_labels ? metrics.height() + tick_length + 2 : tick_length);
  Layout layout;
  layout.plot = QRect(QPoint(left, top), QPoint(std::max(left, right), std::max(top, bottom)));
  // Down to the image's margin: a longer legend shows the entries that fit (draw_legend).
  layout.legend_area = QRect(layout.plot.right() + 2 * text_gap, top, legend_box.width(),
                             std::max(1, options.height - options.margin - top));
  return layout;
}

void draw_frame(QPainter& painter, const ChartOptions& options, const Layout& layout, const QString& title,
                const QString& x_label, const QString& y_label, const Axis& y_axis,
                const std::vector<LegendEntry>& legend) {
  const QRect& plot = layout.plot;
  const QFont font = make_font(options.font_pixel_size);
  const QFontMetrics metrics(font);
  painter.setFont(font);
  // Horizontal grid and value ticks.
  for (double v : y_axis.ticks) {
    const int y = static_cast<int>(std::lround(map(y_axis, v, plot.bottom(), plot.top())));
    if (options.grid_color.isValid()) {
      painter.setPen(options.grid_color);
      painter.drawLine(plot.left() + 1, y, plot.right(), y);
    }
    painter.setPen(options.axis_color);
    painter.drawLine(plot.left() - tick_length, y, plot.left(), y);
    painter.setPen(options.text_color);
    const QRect text(0, y - metrics.height() / 2, plot.left() - tick_length - 2, metrics.height());
    painter.drawText(text, Qt::AlignRight | Qt::AlignVCenter, format_tick(v, y_axis.step));
  }
  painter.setPen(options.text_color);
  if (!y_label.isEmpty()) {
    painter.save();
    painter.translate(options.margin, plot.center().y());
    painter.rotate(-90);
    const QString text = metrics.elidedText(y_label, Qt::ElideRight, plot.height() + 2 * options.margin);
    painter.drawText(QRect(-plot.height() / 2 - options.margin, 0, plot.height() + 2 * options.margin,
                           metrics.height()),
                     Qt::AlignCenter, text);
    painter.restore();
  }
  if (!x_label.isEmpty()) {
    const QRect text(plot.left(), options.height - options.margin - metrics.height(), plot.width(), metrics.height());
    painter.drawText(text, Qt::AlignCenter, metrics.elidedText(x_label, Qt::ElideRight, options.width));
  }
  if (!title.isEmpty()) {
    const QFont title_font = make_font(options.font_pixel_size + 3, true);
    const QFontMetrics title_metrics(title_font);
    painter.setFont(title_font);
    const QRect text(options.margin, options.margin, options.width - 2 * options.margin, title_metrics.height());
    painter.drawText(text, Qt::AlignCenter, title_metrics.elidedText(title, Qt::ElideRight, text.width()));
    painter.setFont(font);
  }
  if (!legend.empty()) draw_legend(painter, layout.legend_area, legend, Corner::top_left, legend_style(options));
}

void draw_axes(QPainter& painter, const ChartOptions& options, const QRect& plot) {
  painter.setPen(options.axis_color);
  painter.drawLine(plot.bottomLeft(), plot.bottomRight());
  painter.drawLine(plot.bottomLeft(), plot.topLeft());
}

void draw_no_data(QPainter& painter, const ChartOptions& options, const QRect& plot) {
  painter.setPen(options.text_color);
  painter.drawText(plot, Qt::AlignCenter, QStringLiteral("no data"));
}

QColor series_color(const QColor& given, std::size_t index) {
  return given.isValid() ? given : categorical_color(static_cast<int>(index));
}

bool finite(const QPointF& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

}  // namespace

namespace {

/// The finite points' extent of every series (x_lo > x_hi: none).
struct PointRange {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -std::numeric_limits<double>::infinity();
  double y_lo = std::numeric_limits<double>::infinity(), y_hi = -std::numeric_limits<double>::infinity();
  bool empty() const { return !(x_lo <= x_hi); }
};

PointRange point_range(const LineChart& chart) {
  PointRange range;
  for (const LineSeries& series : chart.series)
    for (const QPointF& p : series.points) {
      if (!finite(p)) continue;
      range.x_lo = std::min(range.x_lo, p.x());
      range.x_hi = std::max(range.x_hi, p.x());
      range.y_lo = std::min(range.y_lo, p.y());
      range.y_hi = std::max(range.y_hi, p.y());
    }
  return range;
}

/// A legend entry per named series, in the series' colours.
template <class Series>
std::vector<LegendEntry> series_legend(const std::vector<Series>& series) {
  std::vector<LegendEntry> legend;
  for (std::size_t s = 0; s < series.size(); ++s)
    if (!series[s].name.isEmpty()) legend.push_back({series_color(series[s].color, s), series[s].name});
  return legend;
}

/// The vertical grid lines and the x axis' ticks and their labels.
void draw_x_ticks(QPainter& painter, const ChartOptions& options, const Axis& x_axis, const QRect& plot) {
  const QFontMetrics metrics(make_font(options.font_pixel_size));
  for (double v : x_axis.ticks) {
    const int x = static_cast<int>(std::lround(map(x_axis, v, plot.left(), plot.right())));
    if (options.grid_color.isValid()) {
      painter.setPen(options.grid_color);
      painter.drawLine(x, plot.top(), x, plot.bottom() - 1);
    }
    painter.setPen(options.axis_color);
    painter.drawLine(x, plot.bottom(), x, plot.bottom() + tick_length);
    painter.setPen(options.text_color);
    const QString text = format_tick(v, x_axis.step);
    const int w = metrics.horizontalAdvance(text) + 2;
    painter.drawText(QRect(x - w / 2, plot.bottom() + tick_length + 2, w, metrics.height()), Qt::AlignCenter, text);
  }
}

/// One series as a line through its finite points (a non-finite point is a
/// gap), with a dot on each point when it has few enough.
void draw_line_series(QPainter& painter, const LineChart& chart, std::size_t s, const Axis& x_axis, const Axis& y_axis,
                      const QRect& plot) {
  const LineSeries& series = chart.series[s];
  const QColor color = series_color(series.color, s);
  QPainterPath path;
  bool pen_down = false;
  std::vector<QPointF> dots;
  for (const QPointF& p : series.points) {
    if (!finite(p)) {
      pen_down = false;  // a gap in the data is a gap in the line
      continue;
    }
    const QPointF q(map(x_axis, p.x(), plot.left(), plot.right()), map(y_axis, p.y(), plot.bottom(), plot.top()));
    if (pen_down)
      path.lineTo(q);
    else
      path.moveTo(q);
    pen_down = true;
    dots.push_back(q);
  }
  painter.setPen(QPen(color, std::max(0.5, chart.line_width), Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  painter.setBrush(Qt::NoBrush);
  painter.drawPath(path);
  // A single point has no line, so it always gets its dot.
  if (dots.size() <= static_cast<std::size_t>(std::max(1, chart.max_points_with_markers))) {
    painter.setPen(Qt::NoPen);
    painter.setBrush(color);
    const double r = std::max(2.5, chart.line_width + 1.0);
    for (const QPointF& q : dots) painter.drawEllipse(q, r, r);
  }
}

/// The number of categories (the chart's, or the longest series') and the
/// finite values' range, zero always in it.
struct BarRange {
  std::size_t categories = 0;
  double lo = 0.0, hi = 0.0;
};

BarRange bar_range(const BarChart& chart) {
  BarRange range;
  range.categories = chart.categories.size();
  for (const BarSeries& series : chart.series) {
    range.categories = std::max(range.categories, series.values.size());
    for (double v : series.values) {
      if (!std::isfinite(v)) continue;
      range.lo = std::min(range.lo, v);
      range.hi = std::max(range.hi, v);
    }
  }
  return range;
}

/// Every series' bars, side by side in each category's `group` pixels,
/// from the value axis' zero at `baseline`.
void draw_bars(QPainter& painter, const BarChart& chart, const Axis& y_axis, const QRect& plot, double group,
               int baseline) {
  const double bar = 0.8 * group / chart.series.size();
  for (std::size_t s = 0; s < chart.series.size(); ++s) {
    const BarSeries& series = chart.series[s];
    const QColor color = series_color(series.color, s);
    for (std::size_t c = 0; c < series.values.size(); ++c) {
      const double v = series.values[c];
      if (!std::isfinite(v)) continue;
      const double x0 = plot.left() + c * group + 0.1 * group + s * bar;
      const int left = static_cast<int>(std::lround(x0));
      // One pixel between neighbouring bars when they are wide enough to spare it.
      const int width = std::max(1, static_cast<int>(std::lround(x0 + bar)) - left - (bar >= 4 ? 1 : 0));
      const int top = static_cast<int>(std::lround(map(y_axis, v, plot.bottom(), plot.top())));
      painter.fillRect(QRect(QPoint(left, std::min(top, baseline)), QPoint(left + width - 1, std::max(top, baseline))),
                       color);
    }
  }
}

/// The categories' labels and ticks, thinned out when they would overlap
/// (e.g. a histogram of many modes).
void draw_category_labels(QPainter& painter, const BarChart& chart, const ChartOptions& options, std::size_t categories,
                          const QRect& plot, double group) {
  const QFontMetrics metrics(make_font(options.font_pixel_size));
  std::vector<QString> labels(categories);
  int widest = 0;
  for (std::size_t c = 0; c < categories; ++c) {
    labels[c] = c < chart.categories.size() ? chart.categories[c] : QString::number(c + 1);
    widest = std::max(widest, metrics.horizontalAdvance(labels[c]));
  }
  const std::size_t every =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil((widest + text_gap) / std::max(group, 1e-9))));
  painter.setPen(options.text_color);
  for (std::size_t c = 0; c < categories; c += every) {
    const double center = plot.left() + (c + 0.5) * group;
    const int w = static_cast<int>(std::max(group * every, 1.0));
    const QRect text(static_cast<int>(std::lround(center - w / 2.0)), plot.bottom() + tick_length + 2, w,
                     metrics.height());
    painter.drawText(text, Qt::AlignCenter, metrics.elidedText(labels[c], Qt::ElideRight, w));
    painter.setPen(options.axis_color);
    painter.drawLine(static_cast<int>(std::lround(center)), plot.bottom(), static_cast<int>(std::lround(center)),
                     plot.bottom() + tick_length);
    painter.setPen(options.text_color);
  }
}

}  // namespace

QImage draw_line_chart(const LineChart& chart, const ChartOptions& options) {
  check_size(options, "draw_line_chart");
  const PointRange range = point_range(chart);
  std::vector<LegendEntry> legend = series_legend(chart.series);
  const bool has_data = !range.empty();
  check_span(range.x_lo, range.x_hi, "draw_line_chart", "x");
  check_span(range.y_lo, range.y_hi, "draw_line_chart", "y");
  const Axis x_axis = has_data ? make_axis(range.x_lo, range.x_hi, options.target_ticks) : make_axis(0, 1, options.target_ticks);
  const Axis y_axis = has_data ? make_axis(range.y_lo, range.y_hi, options.target_ticks) : make_axis(0, 1, options.target_ticks);

  QImage image(options.width, options.height, QImage::Format_ARGB32);
  image.fill(options.background);
  QPainter painter(&image);
  painter.setRenderHint(QPainter::TextAntialiasing, true);
  elide_legend(legend, options);
  const Layout layout = layout_chart(options, chart.title, chart.x_label, chart.y_label, y_axis, legend, true);
  const QRect& plot = layout.plot;
  draw_frame(painter, options, layout, chart.title, chart.x_label, chart.y_label, y_axis, legend);
  draw_x_ticks(painter, options, x_axis, plot);
  draw_axes(painter, options, plot);
  if (!has_data) {
    draw_no_data(painter, options, plot);
    return image;
  }
  painter.setRenderHint(QPainter::Antialiasing, true);
  painter.setClipRect(plot.adjusted(-4, -4, 4, 4));
  for (std::size_t s = 0; s < chart.series.size(); ++s) draw_line_series(painter, chart, s, x_axis, y_axis, plot);
  return image;
}

QImage draw_bar_chart(const BarChart& chart, const ChartOptions& options) {
  check_size(options, "draw_bar_chart");
  BarRange range = bar_range(chart);
  std::vector<LegendEntry> legend = series_legend(chart.series);
  check_span(range.lo, range.hi, "draw_bar_chart", "bar");
  if (range.lo == range.hi) range.hi = 1.0;  // all zero (or nothing): show 0..1 rather than a range around zero
  const Axis y_axis = make_axis(range.lo, range.hi, options.target_ticks);

  QImage image(options.width, options.height, QImage::Format_ARGB32);
  image.fill(options.background);
  QPainter painter(&image);
  painter.setRenderHint(QPainter::TextAntialiasing, true);
  elide_legend(legend, options);
  const Layout layout =
      layout_chart(options, chart.title, chart.category_label, chart.value_label, y_axis, legend, true);
  const QRect& plot = layout.plot;
  draw_frame(painter, options, layout, chart.title, chart.category_label, chart.value_label, y_axis, legend);
  if (range.categories == 0 || chart.series.empty()) {
    draw_axes(painter, options, plot);
    draw_no_data(painter, options, plot);
    return image;
  }
  const double group = static_cast<double>(plot.width()) / range.categories;
  const int baseline = static_cast<int>(std::lround(map(y_axis, 0.0, plot.bottom(), plot.top())));
  painter.setRenderHint(QPainter::Antialiasing, false);  // exact series colours, crisp edges
  draw_bars(painter, chart, y_axis, plot, group, baseline);
  draw_axes(painter, options, plot);
  painter.setPen(options.axis_color);
  painter.drawLine(plot.left(), baseline, plot.right(), baseline);
  draw_category_labels(painter, chart, options, range.categories, plot, group);
  return image;
}

}  // namespace mrcloth::render
