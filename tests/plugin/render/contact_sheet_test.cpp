#include "plugin/render/contact_sheet.h"

#include <gtest/gtest.h>

namespace mrcloth::render {
namespace {

QImage filled(int width, int height, const QColor& color) {
  QImage image(width, height, QImage::Format_ARGB32);
  image.fill(color);
  return image;
}

const std::vector<QColor> colors{QColor(255, 0, 0), QColor(0, 160, 0), QColor(0, 0, 255)};

TEST(RenderContactSheet, ThreeImagesInTwoColumns) {
  ContactSheetOptions options;
  options.columns = 2;
  options.spacing = 10;
  options.caption_height = 22;
  std::vector<QImage> images;
  for (const QColor& c : colors) images.push_back(filled(100, 50, c));
  const QImage sheet = contact_sheet(images, {"front", "back", "side"}, options);
  // width = s + columns (cw + s), height = T + s + rows (ch + c + s).
  EXPECT_EQ(sheet.size(), QSize(10 + 2 * (100 + 10), 0 + 10 + 2 * (50 + 22 + 10)));
  const std::vector<QPoint> origins{{10, 10}, {120, 10}, {10, 92}};
  for (std::size_t k = 0; k < 3; ++k) {
    const QPoint o = origins[k];
    for (QPoint p : {o, o + QPoint(99, 0), o + QPoint(0, 49), o + QPoint(99, 49), o + QPoint(50, 25)})
      EXPECT_EQ(QColor(sheet.pixel(p)), colors[k]) << "image " << k << " at " << p.x() << "," << p.y();
    EXPECT_EQ(QColor(sheet.pixel(o - QPoint(1, 1))), QColor(255, 255, 255));
    EXPECT_EQ(QColor(sheet.pixel(o + QPoint(100, 50))), QColor(255, 255, 255));
  }
  // The empty fourth cell is background.
  EXPECT_EQ(QColor(sheet.pixel(170, 117)), QColor(255, 255, 255));
  // The captions put dark pixels under their images.
  int dark = 0;
  for (int y = 60; y < 82; ++y)
    for (int x = 10; x < 110; ++x) dark += qGray(sheet.pixel(x, y)) < 128;
  EXPECT_GT(dark, 10);
}

TEST(RenderContactSheet, LayoutFormulas) {
  ContactSheetOptions options;
  options.spacing = 4;
  options.caption_height = 20;
  options.title = "walk cycle";
  options.title_height = 30;
  // 5 images automatic: ceil(sqrt(5)) = 3 columns, 2 rows; cells 80 x 60.
  const std::vector<QSize> sizes{{80, 60}, {40, 60}, {80, 30}, {80, 60}, {80, 60}};
  const ContactSheetLayout layout = contact_sheet_layout(sizes, options);
  EXPECT_EQ(layout.columns, 3);
  EXPECT_EQ(layout.rows, 2);
  EXPECT_EQ(layout.size, QSize(4 + 3 * 84, 30 + 4 + 2 * (60 + 20 + 4)));
  EXPECT_EQ(layout.image_rects[1], QRect(4 + 84 + 20, 34, 40, 60));  // centred horizontally
  EXPECT_EQ(layout.image_rects[4], QRect(4 + 84, 34 + 84, 80, 60));
  EXPECT_EQ(layout.caption_rects[4], QRect(4 + 84, 34 + 84 + 60, 80, 20));
  options.columns = 10;  // more columns than images: one row
  EXPECT_EQ(contact_sheet_layout(sizes, options).columns, 5);
}

TEST(RenderContactSheet, TitleAndEdgeCases) {
  ContactSheetOptions options;
  options.title = "skirt previews";
  const QImage sheet = contact_sheet({filled(30, 20, QColor(1, 2, 3))}, {}, options);
  EXPECT_EQ(sheet.size(), QSize(10 + 30 + 10, 34 + 10 + 20 + 22 + 10));
  EXPECT_EQ(QColor(sheet.pixel(10, 44)), QColor(1, 2, 3));
  const QImage empty = contact_sheet({}, {});
  EXPECT_FALSE(empty.isNull());
  const QImage with_null = contact_sheet({QImage(), filled(10, 10, QColor(9, 9, 9))}, {"nothing", "ten"});
  EXPECT_FALSE(with_null.isNull());
}

}  // namespace
}  // namespace mrcloth::render
