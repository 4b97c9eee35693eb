#include "plugin/render/contact_sheet.h"

#include "plugin/render/text_support.h"

#include <QFontMetrics>
#include <QPainter>

#include <algorithm>
#include <cmath>

namespace mrcloth::render {

ContactSheetLayout contact_sheet_layout(const std::vector<QSize>& sizes, const ContactSheetOptions& options) {
  ContactSheetLayout layout;
  const int n = static_cast<int>(sizes.size());
  const int s = std::max(0, options.spacing);
  const int c = std::max(0, options.caption_height);
  const int title = options.title.isEmpty() ? 0 : std::max(0, options.title_height);
  int cell_w = 0, cell_h = 0;
  for (const QSize& size : sizes) {
    cell_w = std::max(cell_w, size.width());
    cell_h = std::max(cell_h, size.height());
  }
  if (n > 0) {
    layout.columns = options.columns > 0 ? std::min(options.columns, n)
                                         : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)) - 1e-9));
    layout.rows = (n + layout.columns - 1) / layout.columns;
  }
  layout.size = QSize(std::max(1, s + layout.columns * (cell_w + s)),
                      std::max(1, title + s + layout.rows * (cell_h + c + s)));
  for (int k = 0; k < n; ++k) {
    const int column = k % layout.columns, row = k / layout.columns;
    const int x = s + column * (cell_w + s);
    const int y = title + s + row * (cell_h + c + s);
    layout.image_rects.emplace_back(x + (cell_w - sizes[k].width()) / 2, y, sizes[k].width(), sizes[k].height());
    layout.caption_rects.emplace_back(x, y + cell_h, cell_w, c);
  }
  return layout;
}

QImage contact_sheet(const std::vector<QImage>& images, const std::vector<QString>& captions,
                     const ContactSheetOptions& options) {
  std::vector<QSize> sizes;
  for (const QImage& image : images) sizes.push_back(image.isNull() ? QSize(0, 0) : image.size());
  const ContactSheetLayout layout = contact_sheet_layout(sizes, options);

  QImage sheet(layout.size, QImage::Format_ARGB32);
  sheet.fill(options.background);
  QPainter painter(&sheet);
  for (std::size_t k = 0; k < images.size(); ++k)
    if (!images[k].isNull()) painter.drawImage(layout.image_rects[k].topLeft(), images[k]);

  bool any_text = !options.title.isEmpty();
  for (std::size_t k = 0; k < std::min(captions.size(), images.size()); ++k) any_text = any_text || !captions[k].isEmpty();
  if (!any_text) return sheet;
  require_gui_application("contact_sheet");
  painter.setRenderHint(QPainter::TextAntialiasing, true);
  painter.setPen(options.text_color);
  const QFont font = make_font(options.font_pixel_size);
  const QFontMetrics metrics(font);
  painter.setFont(font);
  for (std::size_t k = 0; k < std::min(captions.size(), images.size()); ++k) {
    const QRect& rect = layout.caption_rects[k];
    painter.drawText(rect, Qt::AlignHCenter | Qt::AlignVCenter,
                     metrics.elidedText(captions[k], Qt::ElideRight, rect.width()));
  }
  if (!options.title.isEmpty()) {
    const QFont title_font = make_font(options.font_pixel_size + 4, true);
    painter.setFont(title_font);
    const QRect rect(0, 0, layout.size.width(), std::max(0, options.title_height));
    painter.drawText(rect, Qt::AlignCenter,
                     QFontMetrics(title_font).elidedText(options.title, Qt::ElideRight, rect.width()));
  }
  return sheet;
}

}  // namespace mrcloth::render
