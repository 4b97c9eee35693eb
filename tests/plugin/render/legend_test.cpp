#include "plugin/render/legend.h"
#include "plugin/render/palette.h"
#include "plugin/render/text_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mrcloth::render {
namespace {

int count_color(const QImage& image, const QRect& rect, const QColor& color) {
  int n = 0;
  for (int y = std::max(0, rect.top()); y <= std::min(image.height() - 1, rect.bottom()); ++y)
    for (int x = std::max(0, rect.left()); x <= std::min(image.width() - 1, rect.right()); ++x)
      n += QColor(image.pixel(x, y)) == color;
  return n;
}

QImage blank(int width = 400, int height = 300) {
  QImage image(width, height, QImage::Format_ARGB32);
  image.fill(QColor(0, 0, 0));
  return image;
}

TEST(RenderLegend, CategoricalLegendInEachCorner) {
  const std::vector<LegendEntry> entries{{QColor(255, 0, 0), "mode 1"}, {QColor(0, 0, 255), "mode 2 (refined)"}};
  LegendStyle style;
  const QSize size = legend_size(entries, style);
  EXPECT_GT(size.width(), style.swatch_size + 40);
  EXPECT_GE(size.height(), 2 * style.swatch_size);
  for (Corner corner : {Corner::top_left, Corner::top_right, Corner::bottom_left, Corner::bottom_right}) {
    QImage image = blank();
    const QRect box = draw_legend(image, entries, corner, style);
    EXPECT_EQ(box.size(), size);
    EXPECT_TRUE(image.rect().contains(box));
    const bool left = corner == Corner::top_left || corner == Corner::bottom_left;
    const bool top = corner == Corner::top_left || corner == Corner::top_right;
    EXPECT_EQ(left ? box.left() : image.width() - 1 - box.right(), style.margin);
    EXPECT_EQ(top ? box.top() : image.height() - 1 - box.bottom(), style.margin);
    // Both swatches, whole.
    EXPECT_EQ(count_color(image, box, QColor(255, 0, 0)), style.swatch_size * style.swatch_size);
    EXPECT_EQ(count_color(image, box, QColor(0, 0, 255)), style.swatch_size * style.swatch_size);
    // Nothing outside the box changed.
    EXPECT_EQ(count_color(image, image.rect(), QColor(0, 0, 0)),
              image.width() * image.height() - box.width() * box.height() + count_color(image, box, QColor(0, 0, 0)));
  }
  QImage image = blank();
  EXPECT_TRUE(draw_legend(image, {}, Corner::top_left).isEmpty());
}

// 1001 modes drew a legend past the image's bottom: now the rows that fit,
// the last one saying how many more there are.
TEST(RenderLegend, ALegendTallerThanTheImageIsCutWithACount) {
  std::vector<LegendEntry> entries;
  for (int k = 0; k < 60; ++k) entries.push_back({QColor(k, 200, 50), QStringLiteral("mode %1").arg(k + 1)});
  const LegendStyle style;
  QImage image = blank();
  const int room = image.height() - 2 * style.margin;
  // Brute force: the most rows whose legend fits.
  std::size_t rows = 0;
  while (rows < entries.size() &&
         legend_size(std::vector<LegendEntry>(entries.begin(), entries.begin() + static_cast<std::ptrdiff_t>(rows + 1)),
                     style).height() <= room)
    ++rows;
  ASSERT_GT(rows, 2u);
  ASSERT_LT(rows, entries.size());
  const std::vector<LegendEntry> fitted = legend_entries_that_fit(entries, room, style);
  ASSERT_EQ(fitted.size(), rows);
  EXPECT_FALSE(fitted.back().color.isValid());
  EXPECT_EQ(fitted.back().label, QStringLiteral("\u2026 and %1 more").arg(entries.size() - rows + 1));
  const QRect box = draw_legend(image, entries, Corner::top_right, style);
  EXPECT_TRUE(image.rect().contains(box));
  for (std::size_t k = 0; k < entries.size(); ++k)
    EXPECT_EQ(count_color(image, box, entries[k].color), k + 1 < rows ? style.swatch_size * style.swatch_size : 0)
        << "entry " << k;
  // Legends that fit are drawn whole.
  EXPECT_EQ(legend_entries_that_fit(entries, legend_size(entries, style).height(), style).size(), entries.size());
}

TEST(RenderLegend, ColorBarShowsTheMapEnds) {
  QImage image = blank();
  ColorBar bar;
  bar.color_map = viridis;
  bar.min_value = 0;
  bar.max_value = 30;
  bar.label = "stretch (%)";
  const QRect box = draw_color_bar(image, bar, Corner::bottom_right);
  ASSERT_FALSE(box.isEmpty());
  EXPECT_TRUE(image.rect().contains(box));
  EXPECT_GE(box.height(), bar.length);
  // Top of the bar is the map at 1, bottom at 0, sampled at row centres;
  // the outermost rows are under the bar's outline, so check the next ones.
  EXPECT_EQ(count_color(image, box, viridis(1.0 - 1.5 / bar.length)), bar.thickness - 2);
  EXPECT_EQ(count_color(image, box, viridis(1.5 / bar.length)), bar.thickness - 2);
}

TEST(RenderLegend, TitleIsCentredAtTheTop) {
  QImage image = blank();
  const QRect box = draw_title(image, "skirt, walk 07_06, frame 120");
  ASSERT_FALSE(box.isEmpty());
  EXPECT_LE(std::abs(box.center().x() - image.width() / 2), 1);
  EXPECT_LT(box.bottom(), image.height() / 3);
  EXPECT_TRUE(draw_title(image, "").isEmpty());
  // The band a picture leaves for it ends where the box does.
  EXPECT_EQ(title_band("skirt, walk 07_06, frame 120"), box.bottom() + 1);
  EXPECT_EQ(title_band(""), 0);
}

TEST(RenderLegend, NiceTicks) {
  EXPECT_EQ(nice_ticks(0, 1, 5), (std::vector<double>{0, 0.2, 0.4, 0.6000000000000001, 0.8, 1}));
  EXPECT_EQ(nice_ticks(0, 3, 5), (std::vector<double>{0, 0.5, 1, 1.5, 2, 2.5, 3}));
  EXPECT_EQ(nice_ticks(3, 0, 3), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(nice_ticks(0, 0.3, 3), (std::vector<double>{0, 0.1, 0.2, 0.30000000000000004}));
  EXPECT_EQ(nice_ticks(13, 97, 4), (std::vector<double>{0, 20, 40, 60, 80, 100}));
  // Empty and non-finite ranges still give at least two ticks around the value.
  for (auto [lo, hi] : {std::pair{5.0, 5.0}, {0.0, 0.0}, {std::nan(""), 1.0}, {-1e-300, -1e-300}}) {
    const auto ticks = nice_ticks(lo, hi, 5);
    ASSERT_GE(ticks.size(), 2u) << lo;
    EXPECT_LT(ticks.front(), ticks.back());
    if (std::isfinite(lo)) {
      EXPECT_LE(ticks.front(), lo);
      EXPECT_GE(ticks.back(), hi);
    }
  }
  // At the ends of a double's range: finite ticks covering the values (a
  // last round tick past 1.8e308 was infinite; denormals' step was 0).
  const double most = std::numeric_limits<double>::max();
  for (auto [lo, hi] : {std::pair{0.0, most}, {-most, 0.0}, {1e308, 1.7e308}, {5e-324, 2e-323}, {0.0, 1e-323},
                        {1e-320, 1e-320}}) {
    const auto ticks = nice_ticks(lo, hi, 5);
    ASSERT_GE(ticks.size(), 2u) << lo << " " << hi;
    for (std::size_t k = 0; k < ticks.size(); ++k) {
      EXPECT_TRUE(std::isfinite(ticks[k])) << lo << " " << hi << " tick " << k;
      if (k > 0) {
        EXPECT_LT(ticks[k - 1], ticks[k]) << lo << " " << hi << " tick " << k;
      }
    }
    EXPECT_LE(ticks.front(), lo) << lo << " " << hi;
    EXPECT_GE(ticks.back(), hi) << lo << " " << hi;
    EXPECT_TRUE(std::isfinite(ticks.back() - ticks.front())) << lo << " " << hi;
  }
  EXPECT_EQ(format_tick(0.6000000000000001, 0.2), "0.6");
  EXPECT_EQ(format_tick(1500, 500), "1500");
  EXPECT_EQ(format_tick(1e-17, 0.1), "0");
  EXPECT_EQ(format_tick(2.5, 0.5), "2.5");
}

TEST(RenderLegend, Palette) {
  EXPECT_EQ(categorical_color(0), categorical_color(10));
  EXPECT_EQ(categorical_color(-1), categorical_color(9));
  EXPECT_NE(categorical_color(0), categorical_color(1));
  EXPECT_EQ(viridis(0.0), QColor(68, 1, 84));
  EXPECT_EQ(viridis(1.0), QColor(253, 231, 37));
  EXPECT_EQ(viridis(2.0), viridis(1.0));
}

}  // namespace
}  // namespace mrcloth::render
