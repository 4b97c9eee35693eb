#include "plugin/render/image_io.h"

#include "mesh_ops/atomic_file.h"

#include <QBuffer>
#include <QFileInfo>

#include <fstream>
#include <stdexcept>

namespace mrcloth::render {
namespace {

/// Qt's format name for a path's suffix; empty when we do not write it.
QByteArray format_for(const QString& path) {
  const QString suffix = QFileInfo(path).suffix().toLower();
  if (suffix.isEmpty() || suffix == QLatin1String("png")) return "PNG";
  if (suffix == QLatin1String("jpg") || suffix == QLatin1String("jpeg")) return "JPEG";
  if (suffix == QLatin1String("bmp")) return "BMP";
  if (suffix == QLatin1String("ppm")) return "PPM";
  return {};
}

/// The image laid over opaque white (for formats without alpha, which
/// would otherwise show a transparent background black).
QImage over_white(const QImage& image) {
  const QImage source = image.convertToFormat(QImage::Format_ARGB32);
  QImage out(source.size(), QImage::Format_RGB32);
  for (int y = 0; y < source.height(); ++y) {
    const auto* in = reinterpret_cast<const QRgb*>(source.constScanLine(y));
    auto* to = reinterpret_cast<QRgb*>(out.scanLine(y));
    for (int x = 0; x < source.width(); ++x) {
      const int a = qAlpha(in[x]);
      const auto blend = [a](int c) { return (c * a + 255 * (255 - a) + 127) / 255; };
      to[x] = qRgb(blend(qRed(in[x])), blend(qGreen(in[x])), blend(qBlue(in[x])));
    }
  }
  return out;
}

}  // namespace

void save_image(const QImage& image, const std::string& path) {
  auto fail = [&](const std::string& why) { throw std::runtime_error("cannot write " + path + ": " + why); };
  if (image.isNull()) fail("the image is empty");
  const QString target = QString::fromStdString(path);
  const QByteArray format = format_for(target);
  if (format.isEmpty())
    throw std::invalid_argument("cannot write " + path + ": '." + QFileInfo(target).suffix().toStdString() +
                                "' is not an image format written here; expected .png, .jpg, .jpeg, .bmp or .ppm");
  // Encoded in memory, then written as every other output is: QSaveFile
  // reported success on a full disk and left an empty or cut file.
  QByteArray encoded;
  QBuffer buffer(&encoded);
  buffer.open(QIODevice::WriteOnly);
  const bool alpha = format == "PNG";
  if (!(alpha ? image : over_white(image)).save(&buffer, format.constData(), format == "JPEG" ? 95 : -1))
    fail(format.toStdString() + " encoding failed");
  // No suffix (written as PNG): no extension, so the temporary's name stays
  // one the start-of-run sweep knows (it ended in a lone "." before).
  const QString suffix = QFileInfo(target).suffix();
  const std::string extension = suffix.isEmpty() ? std::string() : "." + suffix.toStdString();
  mrcloth::write_file_atomically(path, extension, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(encoded.constData(), encoded.size());
    out.close();
    return !out.fail();
  });
}

}  // namespace mrcloth::render
