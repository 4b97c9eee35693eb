#include "plugin/render/image_io.h"

#include <QSaveFile>

#include <stdexcept>

namespace mrcloth::render {

void save_png(const QImage& image, const std::string& path) {
  auto fail = [&](const std::string& why) { throw std::runtime_error("save_png: cannot write " + path + ": " + why); };
  if (image.isNull()) fail("the image is empty");
  QSaveFile file(QString::fromStdString(path));
  if (!file.open(QIODevice::WriteOnly)) fail(file.errorString().toStdString());
  if (!image.save(&file, "PNG")) {
    file.cancelWriting();
    fail("PNG encoding failed");
  }
  if (!file.commit()) fail(file.errorString().toStdString());
}

}  // namespace mrcloth::render
