#include "plugin/render/image_io.h"

#include <QDir>
#include <QFile>
#include <QTemporaryDir>

#include <gtest/gtest.h>

#include <stdexcept>

namespace mrcloth::render {
namespace {

QImage pattern() {
  QImage image(31, 17, QImage::Format_ARGB32);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) image.setPixel(x, y, qRgba(x * 8, y * 15, (x * y) % 256, 255));
  return image;
}

TEST(RenderImageIo, RoundTrip) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const std::string path = dir.filePath("preview.png").toStdString();
  const QImage image = pattern();
  save_png(image, path);
  const QImage loaded(QString::fromStdString(path));
  ASSERT_FALSE(loaded.isNull());
  EXPECT_EQ(loaded.convertToFormat(QImage::Format_ARGB32), image);
  // Overwriting works and leaves only the one file.
  save_png(image.mirrored(), path);
  EXPECT_EQ(QImage(QString::fromStdString(path)).convertToFormat(QImage::Format_ARGB32), image.mirrored());
  EXPECT_EQ(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"preview.png"});
}

TEST(RenderImageIo, MissingFolderThrowsNamingThePath) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const std::string path = dir.filePath("no_such_folder/preview.png").toStdString();
  try {
    save_png(pattern(), path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_FALSE(QFile::exists(QString::fromStdString(path)));
  EXPECT_TRUE(QDir(dir.path()).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot).isEmpty());
}

TEST(RenderImageIo, FailureKeepsTheExistingFile) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const std::string path = dir.filePath("preview.png").toStdString();
  save_png(pattern(), path);
  EXPECT_THROW(save_png(QImage(), path), std::runtime_error);
  EXPECT_EQ(QImage(QString::fromStdString(path)).convertToFormat(QImage::Format_ARGB32), pattern());
  EXPECT_EQ(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"preview.png"});
  // A folder where the file should be.
  EXPECT_THROW(save_png(pattern(), dir.path().toStdString()), std::runtime_error);
}

}  // namespace
}  // namespace mrcloth::render
