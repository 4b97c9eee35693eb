#pragma once
// Several previews side by side in one image, each with a caption.
//
// Captions and the title need a QGuiApplication (see legend.h); without one
// contact_sheet() throws std::logic_error when there is any text to draw.
//
// Layout, all in pixels, with n images, s = spacing, cw/ch = the largest
// image width/height, c = caption_height, T = title_height if the title is
// not empty else 0:
//   columns = options.columns if > 0 (at most n), else ceil(sqrt(n))
//   rows    = ceil(n / columns)
//   width   = s + columns * (cw + s)
//   height  = T + s + rows * (ch + c + s)
// Image k sits in column k % columns, row k / columns, horizontally centred
// in its cell at x = s + column * (cw + s) + (cw - width_k) / 2 and at the
// top of it, y = T + s + row * (ch + c + s); its caption is in the c pixels
// below the cell's ch. With no images the sheet is s by T + s (at least 1x1).
#include <QColor>
#include <QImage>
#include <QRect>
#include <QSize>
#include <QString>

#include <vector>

namespace mrcloth::render {

struct ContactSheetOptions {
  int columns = 0;                            ///< images per row; 0 = ceil(sqrt(n))
  int spacing = 10;                           ///< pixels around and between cells
  int caption_height = 22;                    ///< pixels below each image for its caption
  QString title;                              ///< drawn centred above the grid; empty = no title band
  int title_height = 34;                      ///< pixels for the title band (only with a title)
  int font_pixel_size = 13;                   ///< caption text size; the title is bold and 4 pixels larger
  QColor background = QColor(255, 255, 255);  ///< sheet colour
  QColor text_color = QColor(20, 20, 20);     ///< captions and title
};

/// Where everything goes, per the formulas above.
struct ContactSheetLayout {
  QSize size;                       ///< whole sheet
  int columns = 0;                  ///< used column count
  int rows = 0;                     ///< used row count
  std::vector<QRect> image_rects;   ///< one per image, its own size
  std::vector<QRect> caption_rects; ///< one per image: cell width by caption_height
};

/// The layout for images of `sizes` (one per image).
ContactSheetLayout contact_sheet_layout(const std::vector<QSize>& sizes, const ContactSheetOptions& options = {});

/// Composes `images` (any sizes; null images leave their cell empty) with
/// `captions` (missing or extra captions are ignored; long ones are elided)
/// into a Format_ARGB32 sheet.
QImage contact_sheet(const std::vector<QImage>& images, const std::vector<QString>& captions,
                     const ContactSheetOptions& options = {});

}  // namespace mrcloth::render
