#pragma once
// Legends, colour bars and titles drawn onto a rendered preview.
//
// Text needs a QGuiApplication to exist (Qt's fonts live in it); headless,
// set QT_QPA_PLATFORM=offscreen before constructing it. Without one these
// functions throw std::logic_error rather than letting Qt abort.
#include <QColor>
#include <QImage>
#include <QPainter>
#include <QRect>
#include <QString>

#include <functional>
#include <vector>

namespace mrcloth::render {

enum class Corner { top_left, top_right, bottom_left, bottom_right };

/// Look of legends, colour bars and titles.
struct LegendStyle {
  int font_pixel_size = 13;                       ///< text height in pixels (DejaVu Sans)
  QColor text_color = QColor(20, 20, 20);         ///< labels and title
  QColor box_color = QColor(255, 255, 255, 230);  ///< box behind the entries, slightly see-through
  QColor border_color = QColor(150, 150, 150);    ///< box outline; invalid QColor = none
  int padding = 6;                                ///< pixels between the box's edge and its contents
  int margin = 10;                                ///< pixels between the box and the image (or area) edge
  int swatch_size = 12;                           ///< side of a legend entry's colour square in pixels
};

/// One categorical legend entry.
struct LegendEntry {
  QColor color;   ///< swatch colour; invalid = no swatch
  QString label;  ///< text beside it
};

/// A continuous colour scale: a vertical bar with the minimum at the bottom.
struct ColorBar {
  std::function<QColor(double)> color_map;  ///< t in [0, 1] -> colour; empty = grey ramp
  double min_value = 0.0;                   ///< value shown at t = 0
  double max_value = 1.0;                   ///< value shown at t = 1
  QString label;                            ///< drawn above the bar, with units, e.g. "stretch (%)"
  int length = 160;                         ///< bar length in pixels
  int thickness = 14;                       ///< bar width in pixels
};

/// Size the legend box for `entries` takes with `style` (empty for no entries).
QSize legend_size(const std::vector<LegendEntry>& entries, const LegendStyle& style = {});

/// `entries` if their legend is at most `height` pixels tall, else as many
/// as fit with the last row saying how many more there are ("… and 12
/// more", without a swatch: an invalid colour).
std::vector<LegendEntry> legend_entries_that_fit(const std::vector<LegendEntry>& entries, int height,
                                                const LegendStyle& style = {});

/// Draws the legend in `corner` of `area` with painter, its entries cut to
/// those that fit in the area's height (legend_entries_that_fit). Returns
/// the box drawn (empty for no entries).
QRect draw_legend(QPainter& painter, const QRect& area, const std::vector<LegendEntry>& entries,
                  Corner corner = Corner::top_right, const LegendStyle& style = {});
/// Same, in a corner of the whole image.
QRect draw_legend(QImage& image, const std::vector<LegendEntry>& entries, Corner corner = Corner::top_right,
                  const LegendStyle& style = {});

/// Size the box of `bar` (label, bar and values) takes with `style`.
QSize color_bar_size(const ColorBar& bar, const LegendStyle& style = {});

/// Draws `bar` with its label and min/mid/max values in `corner` of `area`
/// (of the whole image). Returns the box drawn.
QRect draw_color_bar(QPainter& painter, const QRect& area, const ColorBar& bar, Corner corner = Corner::bottom_right,
                     const LegendStyle& style = {});
QRect draw_color_bar(QImage& image, const ColorBar& bar, Corner corner = Corner::bottom_right,
                     const LegendStyle& style = {});

/// Draws `title` in bold (font 3 pixels larger than the style's) centred at
/// the top of the image, on the box colour. Returns the box drawn (empty
/// for an empty title).
QRect draw_title(QImage& image, const QString& title, const LegendStyle& style = {});

/// Pixels from the image's top to the bottom of the box draw_title draws
/// for `title` (0 for no title).
int title_band(const QString& title, const LegendStyle& style = {});

}  // namespace mrcloth::render
