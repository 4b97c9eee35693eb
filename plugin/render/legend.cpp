#include "plugin/render/legend.h"

#include "plugin/render/text_support.h"

#include <QFontMetrics>

#include <algorithm>
#include <cmath>

namespace mrcloth::render {
namespace {

constexpr int swatch_gap = 6;  // pixels between a swatch (or bar) and its text
constexpr int row_gap = 4;     // pixels between legend rows

QRect place(const QSize& size, const QRect& area, Corner corner, int margin) {
  const bool left = corner == Corner::top_left || corner == Corner::bottom_left;
  const bool top = corner == Corner::top_left || corner == Corner::top_right;
  const int x = left ? area.left() + margin : area.right() + 1 - margin - size.width();
  const int y = top ? area.top() + margin : area.bottom() + 1 - margin - size.height();
  return QRect(QPoint(x, y), size);
}

void draw_box(QPainter& painter, const QRect& box, const LegendStyle& style) {
  painter.fillRect(box, style.box_color);
  if (style.border_color.isValid()) {
    painter.setPen(style.border_color);
    painter.setBrush(Qt::NoBrush);
    painter.drawRect(box.adjusted(0, 0, -1, -1));
  }
}

int row_height(const QFontMetrics& metrics, const LegendStyle& style) {
  return std::max(style.swatch_size, metrics.height());
}

QColor bar_color(const ColorBar& bar, double t) {
  if (bar.color_map) return bar.color_map(t);
  const int v = static_cast<int>(std::lround(40 + 200 * std::clamp(t, 0.0, 1.0)));
  return QColor(v, v, v);
}

struct BarLayout {
  QSize size;
  int label_height = 0;
  int value_width = 0;
  std::vector<double> values;  // max, middle, min: top to bottom
  double step = 1.0;
};

BarLayout bar_layout(const ColorBar& bar, const QFontMetrics& metrics, const LegendStyle& style) {
  BarLayout layout;
  layout.values = {bar.max_value, 0.5 * (bar.min_value + bar.max_value), bar.min_value};
  layout.step = std::abs(bar.max_value - bar.min_value) / 2.0;
  if (!(layout.step > 0)) layout.step = std::max(std::abs(bar.max_value), 1.0);
  for (double v : layout.values)
    layout.value_width = std::max(layout.value_width, metrics.horizontalAdvance(format_tick(v, layout.step / 10)));
  layout.label_height = bar.label.isEmpty() ? 0 : metrics.height() + row_gap;
  const int length = std::max(bar.length, 2 * metrics.height());
  const int width = std::max(metrics.horizontalAdvance(bar.label),
                             std::max(bar.thickness, 1) + swatch_gap + layout.value_width);
  // Half a text line above and below the bar, for the end values centred on its ends.
  layout.size = QSize(width + 2 * style.padding, layout.label_height + length + metrics.height() + 2 * style.padding);
  return layout;
}

}  // namespace

QSize legend_size(const std::vector<LegendEntry>& entries, const LegendStyle& style) {
  if (entries.empty()) return {};
  require_gui_application("legend_size");
  const QFontMetrics metrics(make_font(style.font_pixel_size));
  int text_width = 0;
  for (const auto& e : entries) text_width = std::max(text_width, metrics.horizontalAdvance(e.label));
  const int n = static_cast<int>(entries.size());
  return QSize(2 * style.padding + style.swatch_size + swatch_gap + text_width,
               2 * style.padding + n * row_height(metrics, style) + (n - 1) * row_gap);
}

std::vector<LegendEntry> legend_entries_that_fit(const std::vector<LegendEntry>& entries, int height,
                                                const LegendStyle& style) {
  if (entries.empty() || legend_size(entries, style).height() <= height) return entries;
  require_gui_application("legend_entries_that_fit");
  const QFontMetrics metrics(make_font(style.font_pixel_size));
  const int row = row_height(metrics, style);
  // Rows that fit, the last of them saying how many did not (at least that one).
  const int rows = std::max(1, (height - 2 * style.padding + row_gap) / (row + row_gap));
  const auto kept = static_cast<std::size_t>(std::min<int>(rows - 1, static_cast<int>(entries.size()) - 1));
  std::vector<LegendEntry> fitted(entries.begin(), entries.begin() + static_cast<std::ptrdiff_t>(kept));
  fitted.push_back({QColor(), QStringLiteral("\u2026 and %1 more").arg(entries.size() - kept)});
  return fitted;
}

QRect draw_legend(QPainter& painter, const QRect& area, const std::vector<LegendEntry>& all_entries, Corner corner,
                  const LegendStyle& style) {
  if (all_entries.empty()) return {};
  require_gui_application("draw_legend");
  const QFont font = make_font(style.font_pixel_size);
  const QFontMetrics metrics(font);
  const std::vector<LegendEntry> entries = legend_entries_that_fit(all_entries, area.height() - 2 * style.margin, style);
  const QRect box = place(legend_size(entries, style), area, corner, style.margin);
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, false);
  painter.setRenderHint(QPainter::TextAntialiasing, true);
  painter.setFont(font);
  draw_box(painter, box, style);
  const int row = row_height(metrics, style);
  int y = box.top() + style.padding;
  for (const auto& e : entries) {
    const QRect swatch(box.left() + style.padding, y + (row - style.swatch_size) / 2, style.swatch_size,
                       style.swatch_size);
    if (e.color.isValid()) painter.fillRect(swatch, e.color);
    painter.setPen(style.text_color);
    const QRect text(swatch.right() + 1 + swatch_gap, y, box.right() - swatch.right() - swatch_gap, row);
    painter.drawText(text, Qt::AlignLeft | Qt::AlignVCenter, e.label);
    y += row + row_gap;
  }
  painter.restore();
  return box;
}

QRect draw_legend(QImage& image, const std::vector<LegendEntry>& entries, Corner corner, const LegendStyle& style) {
  if (entries.empty() || image.isNull()) return {};
  require_gui_application("draw_legend");
  QPainter painter(&image);
  return draw_legend(painter, image.rect(), entries, corner, style);
}

QSize color_bar_size(const ColorBar& bar, const LegendStyle& style) {
  require_gui_application("color_bar_size");
  return bar_layout(bar, QFontMetrics(make_font(style.font_pixel_size)), style).size;
}

QRect draw_color_bar(QPainter& painter, const QRect& area, const ColorBar& bar, Corner corner,
                     const LegendStyle& style) {
  require_gui_application("draw_color_bar");
  const QFont font = make_font(style.font_pixel_size);
  const QFontMetrics metrics(font);
  const BarLayout layout = bar_layout(bar, metrics, style);
  const QRect box = place(layout.size, area, corner, style.margin);
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, false);
  painter.setRenderHint(QPainter::TextAntialiasing, true);
  painter.setFont(font);
  draw_box(painter, box, style);
  painter.setPen(style.text_color);
  if (!bar.label.isEmpty())
    painter.drawText(QRect(box.left() + style.padding, box.top() + style.padding, box.width() - 2 * style.padding,
                           metrics.height()),
                     Qt::AlignLeft | Qt::AlignVCenter, bar.label);
  const int length = std::max(bar.length, 2 * metrics.height());
  const int thickness = std::max(bar.thickness, 1);
  const int left = box.left() + style.padding;
  const int top = box.top() + style.padding + layout.label_height + metrics.height() / 2;
  for (int k = 0; k < length; ++k)
    painter.fillRect(left, top + k, thickness, 1, bar_color(bar, 1.0 - (k + 0.5) / length));
  painter.setPen(style.border_color.isValid() ? style.border_color : style.text_color);
  painter.drawRect(left, top, thickness - 1, length - 1);
  painter.setPen(style.text_color);
  for (std::size_t i = 0; i < layout.values.size(); ++i) {
    const int y = top + static_cast<int>(std::lround(i * (length - 1) / 2.0));
    const QRect text(left + thickness + swatch_gap, y - metrics.height() / 2, layout.value_width + 1,
                     metrics.height());
    painter.drawText(text, Qt::AlignLeft | Qt::AlignVCenter, format_tick(layout.values[i], layout.step / 10));
  }
  painter.restore();
  return box;
}

QRect draw_color_bar(QImage& image, const ColorBar& bar, Corner corner, const LegendStyle& style) {
  if (image.isNull()) return {};
  require_gui_application("draw_color_bar");
  QPainter painter(&image);
  return draw_color_bar(painter, image.rect(), bar, corner, style);
}

namespace {

QFont title_font(const LegendStyle& style) { return make_font(style.font_pixel_size + 3, true); }

/// The title's box, centred at the top of an image `image_width` wide.
QRect title_box(const QString& title, int image_width, const LegendStyle& style) {
  const QFontMetrics metrics(title_font(style));
  const int width = std::min(metrics.horizontalAdvance(title) + 2 * style.padding, image_width);
  return QRect((image_width - width) / 2, style.margin, width, metrics.height() + 2 * style.padding);
}

}  // namespace

int title_band(const QString& title, const LegendStyle& style) {
  if (title.isEmpty()) return 0;
  require_gui_application("title_band");
  return title_box(title, 1, style).bottom() + 1;
}

QRect draw_title(QImage& image, const QString& title, const LegendStyle& style) {
  if (title.isEmpty() || image.isNull()) return {};
  require_gui_application("draw_title");
  const QFont font = title_font(style);
  const QFontMetrics metrics(font);
  const QRect box = title_box(title, image.width(), style);
  QPainter painter(&image);
  painter.setRenderHint(QPainter::TextAntialiasing, true);
  painter.setFont(font);
  painter.fillRect(box, style.box_color);
  painter.setPen(style.text_color);
  // Elide against the image, not the box: the box is sized from the same
  // (rounded) advance, and eliding against it can cut a title that fits.
  painter.drawText(box, Qt::AlignCenter,
                   metrics.elidedText(title, Qt::ElideRight, std::max(0, image.width() - 2 * style.padding)));
  return box;
}

}  // namespace mrcloth::render
