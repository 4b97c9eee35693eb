#include "plugin/render/image_io.h"

#include <QDir>
#include <QFile>
#include <QTemporaryDir>

#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/mount.h>
#include <unistd.h>

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
  save_image(image, path);
  const QImage loaded(QString::fromStdString(path));
  ASSERT_FALSE(loaded.isNull());
  EXPECT_EQ(loaded.convertToFormat(QImage::Format_ARGB32), image);
  // Overwriting works and leaves only the one file.
  save_image(image.mirrored(), path);
  EXPECT_EQ(QImage(QString::fromStdString(path)).convertToFormat(QImage::Format_ARGB32), image.mirrored());
  EXPECT_EQ(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"preview.png"});
}

/// A folder on a small file system of its own (tmpfs; needs root, as CI
/// has): where `mounted()`, `fill()` leaves it without a free byte.
class SmallFileSystem {
 public:
  explicit SmallFileSystem(const QString& folder) : folder_(folder.toStdString()) {
    QDir().mkpath(folder);
    mounted_ = geteuid() == 0 && mount("tmpfs", folder_.c_str(), "tmpfs", 0, "size=64k") == 0;
  }
  ~SmallFileSystem() {
    if (mounted_) umount(folder_.c_str());
  }
  bool mounted() const { return mounted_; }
  void fill() const {
    std::FILE* filler = std::fopen((folder_ + "/filler").c_str(), "wb");
    const std::vector<char> block(512, 'x');
    while (filler && std::fwrite(block.data(), 1, block.size(), filler) == block.size() && std::fflush(filler) == 0) {
    }
    if (filler) std::fclose(filler);
  }

 private:
  std::string folder_;
  bool mounted_ = false;
};

// A write that runs out of room fails and keeps the file that was there:
// with QSaveFile an image smaller than Qt's 16 KB buffer was committed
// empty or cut short on a full disk, and the call reported success.
TEST(RenderImageIo, AFullDiskFailsAndKeepsTheExistingFile) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const SmallFileSystem disk(dir.filePath("disk"));
  if (!disk.mounted()) GTEST_SKIP() << "mounting a small tmpfs needs root; a full disk cannot be made here";
  const std::string path = dir.filePath("disk/preview.png").toStdString();
  save_image(pattern(), path);
  disk.fill();
  try {
    save_image(pattern().mirrored(), path);
    ADD_FAILURE() << "a write to a full disk reported success";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_EQ(QImage(QString::fromStdString(path)).convertToFormat(QImage::Format_ARGB32), pattern());
  EXPECT_EQ(QDir(dir.filePath("disk")).entryList(QDir::Files | QDir::Hidden), (QStringList{"filler", "preview.png"}));
}

TEST(RenderImageIo, MissingFolderThrowsNamingThePath) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  const std::string path = dir.filePath("no_such_folder/preview.png").toStdString();
  try {
    save_image(pattern(), path);
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
  save_image(pattern(), path);
  EXPECT_THROW(save_image(QImage(), path), std::runtime_error);
  EXPECT_EQ(QImage(QString::fromStdString(path)).convertToFormat(QImage::Format_ARGB32), pattern());
  EXPECT_EQ(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"preview.png"});
  // A folder where the file should be.
  EXPECT_THROW(save_image(pattern(), dir.path().toStdString()), std::runtime_error);
}

TEST(RenderImageIo, TheSuffixChoosesTheFormat) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  // Half-transparent red: formats without alpha get it laid over white.
  QImage translucent(8, 4, QImage::Format_ARGB32);
  translucent.fill(qRgba(255, 0, 0, 128));
  const auto magic = [&](const QString& name) {
    QFile file(dir.filePath(name));
    EXPECT_TRUE(file.open(QIODevice::ReadOnly)) << name.toStdString();
    return file.read(4);
  };
  save_image(translucent, dir.filePath("a.PNG").toStdString());
  EXPECT_EQ(magic("a.PNG"), QByteArray("\x89PNG"));
  EXPECT_EQ(QImage(dir.filePath("a.PNG")).pixel(0, 0), qRgba(255, 0, 0, 128));
  save_image(translucent, dir.filePath("plain").toStdString());  // no suffix: PNG
  EXPECT_EQ(magic("plain"), QByteArray("\x89PNG"));
  save_image(translucent, dir.filePath("b.jpg").toStdString());
  EXPECT_EQ(magic("b.jpg").left(3), QByteArray("\xff\xd8\xff"));
  save_image(translucent, dir.filePath("c.jpeg").toStdString());
  EXPECT_EQ(magic("c.jpeg").left(3), QByteArray("\xff\xd8\xff"));
  save_image(translucent, dir.filePath("d.bmp").toStdString());
  EXPECT_EQ(magic("d.bmp").left(2), QByteArray("BM"));
  EXPECT_EQ(QImage(dir.filePath("d.bmp")).pixel(0, 0), qRgb(255, 127, 127));  // (255 * 128 + 255 * 127 + 127) / 255 = 255, 0 -> 127
  save_image(translucent, dir.filePath("e.ppm").toStdString());
  EXPECT_EQ(magic("e.ppm").left(2), QByteArray("P6"));
  EXPECT_EQ(QImage(dir.filePath("e.ppm")).pixel(3, 2), qRgb(255, 127, 127));
  // A JPEG of it decodes near that colour (lossy).
  const QRgb jpeg = QImage(dir.filePath("b.jpg")).pixel(4, 2);
  EXPECT_NEAR(qRed(jpeg), 255, 6);
  EXPECT_NEAR(qGreen(jpeg), 127, 6);
  EXPECT_NEAR(qBlue(jpeg), 127, 6);
  // A suffix we do not write is refused by name, and nothing is written.
  const std::string tif = dir.filePath("f.tif").toStdString();
  try {
    save_image(translucent, tif);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(tif), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'.tif'"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(QFile::exists(QString::fromStdString(tif)));
  EXPECT_EQ(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden).size(), 6);
}

}  // namespace
}  // namespace mrcloth::render
