#include "preview_plugin.h"

#include "mesh_ops/atomic_file.h"
#include "mesh_ops/errors.h"
#include "plugin/core/job_scope.h"
#include "plugin/core/object_store.h"
#include "plugin/core/option_fields.h"
#include "plugin/core/script_errors.h"
#include "plugin/core/script_values.h"
#include "plugin/render/camera.h"
#include "plugin/render/charts.h"
#include "plugin/render/contact_sheet.h"
#include "plugin/render/image_io.h"
#include "plugin/render/legend.h"
#include "plugin/render/rasterize.h"
#include "preview_scene.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QImageReader>
#include <QPainter>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

using options::Fields;

// The bounds of the numeric options, as limits() hands them to scripts.
constexpr int kLeastImageSide = 16;   ///< pixels: a render's width and height
constexpr int kMostImageSide = 8192;
constexpr int kLeastChartSide = 100;  ///< pixels: a chart's (room for its axes and labels)
constexpr int kMostSupersample = 4;   ///< samples per pixel along each side
constexpr int kMostSheetSide = 16384; ///< pixels: a contact sheet's width and height (1 GiB of ARGB32)
constexpr double kMarginBelow = 0.45; ///< a render's margin, a fraction of the image (exclusive)

/// What one render call asks for.
struct RenderRequest {
  preview::PictureOptions picture;  ///< size, camera, margin, title, legend
  ColorBy color_by = ColorBy::none;
  bool wireframe = true;
  QString cache;            ///< garment cache; empty: the mesh's own points
  QString body_cache;       ///< body cache; empty: no body
  QString body_mesh;        ///< its rest OBJ (default: beside the cache)
  bool fit_all = false;     ///< fit the body too (default: the garment only)
};

const QStringList kRenderKeys = {QStringLiteral("width"),  QStringLiteral("height"),  QStringLiteral("camera"),
                                 QStringLiteral("projection"), QStringLiteral("colorBy"), QStringLiteral("wireframe"),
                                 QStringLiteral("legend"), QStringLiteral("title"),   QStringLiteral("cache"),
                                 QStringLiteral("frame"),  QStringLiteral("body"),    QStringLiteral("supersample"),
                                 QStringLiteral("margin"), QStringLiteral("fit")};

QStringList presetNames() {
  QStringList names;
  for (const std::string& name : render::preset_names()) names << QString::fromStdString(name);
  return names;
}

RenderRequest parseRenderOptions(const Fields& fields) {
  RenderRequest request;
  preview::PictureOptions& picture = request.picture;
  picture.width = fields.integerBetween(QStringLiteral("width"), picture.width, kLeastImageSide, kMostImageSide);
  picture.height = fields.integerBetween(QStringLiteral("height"), picture.height, kLeastImageSide, kMostImageSide);
  picture.camera = render::parse_preset(
      fields.choice(QStringLiteral("camera"), QStringLiteral("front"), presetNames()).toStdString());
  picture.projection = fields.choice(QStringLiteral("projection"), QStringLiteral("perspective"),
                                     {QStringLiteral("perspective"), QStringLiteral("orthographic")}) ==
                               QLatin1String("orthographic")
                           ? render::Projection::orthographic
                           : render::Projection::perspective;
  const QString color_by = fields.choice(QStringLiteral("colorBy"), QStringLiteral("none"),
                                         {QStringLiteral("none"), QStringLiteral("mode"), QStringLiteral("level"),
                                          QStringLiteral("curvature")});
  request.color_by = color_by == QLatin1String("mode")        ? ColorBy::mode
                     : color_by == QLatin1String("level")     ? ColorBy::level
                     : color_by == QLatin1String("curvature") ? ColorBy::curvature
                                                              : ColorBy::none;
  request.wireframe = fields.boolean(QStringLiteral("wireframe"), request.wireframe);
  picture.legend = fields.boolean(QStringLiteral("legend"), picture.legend);
  picture.title = fields.string(QStringLiteral("title"));
  picture.supersample = fields.integerBetween(QStringLiteral("supersample"), picture.supersample, 1, kMostSupersample);
  const long long samples =
      static_cast<long long>(picture.width) * picture.height * picture.supersample * picture.supersample;
  if (samples > render::kMaxRenderSamples)
    options::fail(QStringLiteral("options 'width' x 'height' (%1 x %2) at 'supersample' %3 take %4 samples; expected at "
                                 "most %5 (for instance 5792 x 5792 at 2, 8192 x 4096 at 2, or 8192 x 8192 at 1)")
                      .arg(picture.width).arg(picture.height).arg(picture.supersample).arg(samples)
                      .arg(render::kMaxRenderSamples));
  picture.margin = fields.numberFrom(QStringLiteral("margin"), picture.margin, 0.0, false);
  if (picture.margin >= kMarginBelow)
    options::fail(QStringLiteral("option 'margin' must be below %1 (a fraction of the image), got %2")
                      .arg(kMarginBelow).arg(picture.margin));
  request.fit_all = fields.choice(QStringLiteral("fit"), QStringLiteral("garment"),
                                  {QStringLiteral("garment"), QStringLiteral("all")}) == QLatin1String("all");
  if (fields.has(QStringLiteral("cache")))
    request.cache = options::existingInputFile(fields.string(QStringLiteral("cache")), fields.label(QStringLiteral("cache")));
  if (fields.has(QStringLiteral("body"))) {
    const Fields body(fields.required(QStringLiteral("body")), QStringLiteral("body"),
                      {QStringLiteral("cache"), QStringLiteral("mesh")});
    request.body_cache = options::existingInputFile(
        script::toString(body.required(QStringLiteral("cache")), body.label(QStringLiteral("cache"))),
        body.label(QStringLiteral("cache")));
    const QFileInfo cache(request.body_cache);
    request.body_mesh = body.has(QStringLiteral("mesh"))
                            ? body.string(QStringLiteral("mesh"))
                            : cache.dir().filePath(cache.completeBaseName() + QStringLiteral(".obj"));
    options::existingInputFile(request.body_mesh, body.label(QStringLiteral("mesh")));
  }
  return request;
}

/// The request's body, its rest mesh read once; none when no body is drawn.
std::optional<preview::BodyFrames> bodyFramesOf(const RenderRequest& request) {
  if (request.body_cache.isEmpty()) return std::nullopt;
  return preview::BodyFrames(request.body_mesh.toStdString(), request.body_cache.toStdString());
}

/// The frames renderSequence draws: option 'frames', else every frame of
/// the cache (`count` frames), each checked against the cache and the
/// body's cache before any image is written.
std::vector<int> framesToDraw(const Fields& fields, const RenderRequest& request, int count) {
  std::vector<int> frames;
  if (fields.has(QStringLiteral("frames"))) {
    frames = script::toIntList(fields.required(QStringLiteral("frames")), fields.label(QStringLiteral("frames")));
    for (const int f : frames)
      if (f < 0 || f >= count)
        options::fail(QStringLiteral("option 'frames': frame %1 is out of range (the cache has %2 frames)").arg(f).arg(count));
  } else {
    for (int f = 0; f < count; ++f) frames.push_back(f);
  }
  if (frames.empty())
    options::fail(count == 0 ? QStringLiteral("option 'cache': %1 holds no frames; nothing to draw").arg(request.cache)
                             : QStringLiteral("option 'frames' is empty; expected the frames to draw"));
  if (!request.body_cache.isEmpty()) {
    const int body_frames = preview::cache_frames(request.body_cache.toStdString());
    const int last = *std::max_element(frames.begin(), frames.end());
    if (last >= body_frames)
      options::fail(QStringLiteral("option 'body': the body cache %1 has %2 frames, but frame %3 of the garment's is "
                                   "to be drawn; expected a body cache of the same run")
                        .arg(request.body_cache).arg(body_frames).arg(last));
  }
  return frames;
}

/// One camera for a whole sequence: framed on the garment (with fit "all",
/// and `body`, when given) over every frame drawn.
render::BoundingBox sequenceFraming(const QuadMesh& mesh, const RenderRequest& request, const std::vector<int>& frames,
                                    const preview::BodyFrames* body) {
  render::BoundingBox framing;
  for (const int f : frames) {
    const Eigen::MatrixX3d p = preview::cache_frame(request.cache.toStdString(), f, static_cast<int>(mesh.n_vertices()));
    for (Eigen::Index v = 0; v < p.rows(); ++v) framing.add(p.row(v).transpose());
    if (request.fit_all && body) {
      const render::BoundingBox box = render::bounds(body->at(f));
      if (!box.empty()) {
        framing.add(box.min);
        framing.add(box.max);
      }
    }
  }
  return framing;
}

/// Refuses option 'animation' (empty: none) unless it names a .gif or .mp4
/// file in a folder that exists: before any frame is drawn, as the images'
/// own folder is.
void requireAnimationTarget(const QString& animation) {
  if (animation.isEmpty()) return;
  if (!animation.endsWith(QLatin1String(".gif"), Qt::CaseInsensitive) &&
      !animation.endsWith(QLatin1String(".mp4"), Qt::CaseInsensitive))
    options::fail(QStringLiteral("option 'animation' must name a .gif or .mp4 file, got \"%1\"").arg(animation));
  if (!QFileInfo(animation).absoluteDir().exists())
    throw OutputError(QStringLiteral("option 'animation': %1: folder '%2' does not exist")
                          .arg(animation, QFileInfo(animation).absolutePath()).toStdString());
}

/// One picture: the garment (and `body`, when given) at `frame`, framed by
/// `framing` when given (a steady camera across a sequence), else by the
/// garment (with fit "all", and the body).
QImage renderFrame(const QuadMesh& mesh, const RenderRequest& request, int frame, const preview::BodyFrames* body,
                   const std::optional<render::BoundingBox>& framing = std::nullopt) {
  const Eigen::MatrixX3d positions =
      request.cache.isEmpty()
          ? Eigen::MatrixX3d()
          : preview::cache_frame(request.cache.toStdString(), frame, static_cast<int>(mesh.n_vertices()));
  preview::GarmentLayer garment = preview::garment_layer(mesh, positions, request.color_by);
  garment.surface.wireframe = request.wireframe;
  render::Scene scene;
  scene.surfaces.push_back(garment.surface);
  if (body) scene.surfaces.push_back(body->at(frame));

  return preview::draw_picture(
      scene, framing ? *framing : request.fit_all ? render::bounds(scene) : render::bounds(garment.surface), garment,
      request.picture);
}

/// std::runtime_error / invalid_argument from the render library are the
/// script's output or argument errors.
template <class Body>
auto translateRenderErrors(Body&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const std::invalid_argument& error) {
    throw ArgumentError(error.what());
  } catch (const std::logic_error& error) {
    throw Error(error.what());
  } catch (const Error&) {
    throw;
  } catch (const std::runtime_error& error) {
    throw OutputError(error.what());
  }
}

void saveImage(const QImage& image, const QString& path) {
  translateRenderErrors([&] { render::save_image(image, path.toStdString()); });
}

std::vector<double> numberList(const QVariant& value, const QString& what) {
  std::vector<double> numbers;
  const QVariantList list = script::toList(value, what);
  for (qsizetype k = 0; k < list.size(); ++k)
    numbers.push_back(script::toNumber(list[k], QStringLiteral("%1[%2]").arg(what).arg(k)));
  return numbers;
}

render::ChartOptions chartSize(const Fields& fields) {
  render::ChartOptions options;
  // As render's: 1e9 pixels failed only at saving, after a flood of Qt warnings.
  options.width = fields.integerBetween(QStringLiteral("width"), options.width, kLeastChartSide, kMostImageSide);
  options.height = fields.integerBetween(QStringLiteral("height"), options.height, kLeastChartSide, kMostImageSide);
  return options;
}

}  // namespace

/// A GIF (ImageMagick's convert) or MP4 (ffmpeg) of the frames, only when the
/// tool is installed: a warning otherwise, never a failure. Written beside
/// and renamed, so an interrupted encoder leaves nothing.
void PreviewPlugin::writeAnimation(const QVariantList& frames, const QString& path, double fps) {
  const bool gif = path.endsWith(QLatin1String(".gif"), Qt::CaseInsensitive);
  const QString tool = QStandardPaths::findExecutable(gif ? QStringLiteral("convert") : QStringLiteral("ffmpeg"));
  if (tool.isEmpty()) {
    emit log(LOGWARN, QStringLiteral("renderSequence: %1 not written: %2 is not installed (the PNG frames are)")
                          .arg(path, gif ? QStringLiteral("ImageMagick's convert") : QStringLiteral("ffmpeg")));
    return;
  }
  // A temporary the start-of-run sweep knows, replacing `path` only once whole.
  const QString temporary = QString::fromStdString(
      temporary_path_beside(path.toStdString(), "." + QFileInfo(path).suffix().toStdString()));
  QStringList arguments;
  std::optional<QTemporaryDir> ordered;  // ffmpeg's numbered frames; removed on return
  if (gif) {
    arguments << QStringLiteral("-delay") << QString::number(std::max(1L, std::lround(100.0 / fps)))
              << QStringLiteral("-loop") << QStringLiteral("0");
    for (const QVariant& frame : frames) arguments << frame.toString();
    arguments << temporary;
  } else {
    // ffmpeg reads numbered images, consecutive from a start: the frames as
    // drawn (any list: [10, 5, 11]) linked in their order into a folder of
    // its own. (A pattern on the images' names took whatever the prefix's
    // folder held, from an earlier run too, and failed on gaps.)
    ordered.emplace();
    if (!ordered->isValid()) {
      emit log(LOGWARN, QStringLiteral("renderSequence: %1 not written: no temporary folder for ffmpeg's frames (%2)")
                            .arg(path, ordered->errorString()));
      return;
    }
    for (qsizetype k = 0; k < frames.size(); ++k)
      if (!QFile::link(QFileInfo(frames[k].toString()).absoluteFilePath(),
                       ordered->filePath(QStringLiteral("%1.png").arg(k, 6, 10, QLatin1Char('0'))))) {
        emit log(LOGWARN, QStringLiteral("renderSequence: %1 not written: cannot link its frames in %2")
                              .arg(path, ordered->path()));
        return;
      }
    arguments << QStringLiteral("-y") << QStringLiteral("-loglevel") << QStringLiteral("error") << QStringLiteral("-framerate")
              << QString::number(fps) << QStringLiteral("-start_number") << QStringLiteral("0") << QStringLiteral("-i")
              << ordered->filePath(QStringLiteral("%06d.png")) << QStringLiteral("-pix_fmt")
              << QStringLiteral("yuv420p") << QStringLiteral("-vf") << QStringLiteral("scale=trunc(iw/2)*2:trunc(ih/2)*2")
              << temporary;
  }
  QProcess process;
  process.start(tool, arguments);
  const bool ok = process.waitForFinished(-1) && process.exitStatus() == QProcess::NormalExit && process.exitCode() == 0;
  if (!ok || !QFile::exists(temporary)) {
    QFile::remove(temporary);
    emit log(LOGWARN, QStringLiteral("renderSequence: %1 not written: %2 failed: %3")
                          .arg(path, tool, QString::fromLocal8Bit(process.readAllStandardError()).trimmed()));
    return;
  }
  replace_with_temporary(temporary.toStdString(), path.toStdString());
}

template <class Body>
auto PreviewPlugin::guarded(const char* slot, Body&& body) -> decltype(body()) {
  return runScriptSlot(this, scriptObjectName(name()) + QLatin1Char('.') + QLatin1String(slot),
                       [&] { return translateRenderErrors(std::forward<Body>(body)); });
}

void PreviewPlugin::stopCancelled(const char* slot, const std::string& what) {
  const std::string text = std::string(slot) + ": cancelled; " + what;
  emit log(LOGWARN, QString::fromStdString(text));
  throw Error(text);
}

QString PreviewPlugin::description() const {
  return QStringLiteral("Off-screen previews (PNG, JPEG, BMP or PPM by the file's suffix): renders of meshes and caches, contact sheets, charts");
}

QVariantMap PreviewPlugin::render(QVariant id, QVariant path, QVariant options) {
  return guarded("render", [&] {
    if (!store_) throw Error("the plugin has no object store (it must be loaded by the mrcloth host)");
    const StoredObject& object = store_->get(script::toInt(id, QStringLiteral("id")));
    const QString file = script::toString(path, QStringLiteral("path"));
    const Fields fields(options, QString(), kRenderKeys, QStringLiteral("render options"));
    const RenderRequest request = parseRenderOptions(fields);
    const int frame = fields.integerAtLeast(QStringLiteral("frame"), 0, 0);
    if (fields.has(QStringLiteral("frame")) && request.cache.isEmpty())
      options::fail(QStringLiteral("option 'frame' needs option 'cache' (the PC2 the frame is read from)"));
    const std::optional<preview::BodyFrames> body = bodyFramesOf(request);
    const QImage image = renderFrame(*object.mesh, request, frame, body ? &*body : nullptr);
    // A large image takes seconds to draw (no check inside): Ctrl-C then
    // still stops before anything is written.
    if (cancelRequested()) stopCancelled("render", file.toStdString() + " was not written");
    saveImage(image, file);
    if (request.color_by == ColorBy::curvature && preview::largest_curvature(*object.mesh) <= 0.0)
      // The layer exists (largest_curvature refuses a mesh without one): extractModes ran on an unbent cache.
      emit log(LOGWARN, QStringLiteral("render: %1: the mean_curvature layer is zero everywhere (the cache "
                                       "extractModes analysed shows no bending): the picture is one colour")
                            .arg(file));
    return QVariantMap{{QStringLiteral("file"), file}, {QStringLiteral("width"), image.width()},
                       {QStringLiteral("height"), image.height()}, {QStringLiteral("frame"), frame}};
  });
}

QVariantList PreviewPlugin::renderSequence(QVariant id, QVariant prefix, QVariant options) {
  return guarded("renderSequence", [&] {
    if (!store_) throw Error("the plugin has no object store (it must be loaded by the mrcloth host)");
    const StoredObject& object = store_->get(script::toInt(id, QStringLiteral("id")));
    const QString stem = script::toString(prefix, QStringLiteral("prefix"));
    QStringList keys = kRenderKeys;
    keys.removeAll(QStringLiteral("frame"));
    keys << QStringLiteral("frames") << QStringLiteral("animation") << QStringLiteral("fps");
    const Fields fields(options, QString(), keys, QStringLiteral("renderSequence options"));
    const RenderRequest request = parseRenderOptions(fields);
    if (request.cache.isEmpty()) options::fail(QStringLiteral("missing option 'cache': the PC2 whose frames are drawn"));
    const int count = preview::cache_frames(request.cache.toStdString());
    const std::vector<int> frames = framesToDraw(fields, request, count);
    if (!QFileInfo(stem).absoluteDir().exists())
      throw OutputError(QStringLiteral("%1: folder '%2' does not exist").arg(stem, QFileInfo(stem).absolutePath()).toStdString());
    const std::optional<preview::BodyFrames> body = bodyFramesOf(request);
    const render::BoundingBox framing = sequenceFraming(*object.mesh, request, frames, body ? &*body : nullptr);
    const QString animation = fields.string(QStringLiteral("animation"));
    // simulate's range; a GIF's delay (100 / fps hundredths of a second) then fits its counter.
    const double fps = fields.numberBetween(QStringLiteral("fps"), 30.0, options::kLeastFps, options::kMostFps,
                                            QStringLiteral("frames per second"));
    requireAnimationTarget(animation);
    QVariantList files;
    JobScope job(*this, QStringLiteral("renderSequence"),
                 QStringLiteral("%1 frames of %2").arg(frames.size()).arg(QFileInfo(request.cache).fileName()),
                 static_cast<int>(frames.size()));
    const int digits = std::max(4, static_cast<int>(std::to_string(count).size()));
    for (std::size_t k = 0; k < frames.size(); ++k) {
      if (cancelRequested())
        stopCancelled("renderSequence", "stopped after " + std::to_string(k) + " of " + std::to_string(frames.size()) + " frames" +
                    (k > 0 ? "; the " + std::to_string(k) + " images written (" + files.front().toString().toStdString() +
                                 " on) are kept, and no animation was made"
                           : "; nothing was written"));
      const QString file = QStringLiteral("%1_%2.png").arg(stem).arg(frames[k], digits, 10, QLatin1Char('0'));
      try {
        saveImage(renderFrame(*object.mesh, request, frames[k], body ? &*body : nullptr, framing), file);
      } catch (const OutputError& error) {
        if (k == 0) throw;
        throw OutputError(std::string(error.what()) + "; the " + std::to_string(k) + " images written before it (" +
                          files.front().toString().toStdString() + " on) are kept, and no animation was made");
      }
      files << file;
      job.progress(static_cast<int>(k + 1));
    }
    if (!animation.isEmpty()) writeAnimation(files, animation, fps);
    return files;
  });
}

namespace {

/// An image for a contact sheet. Qt's readers refuse images over 128 MB by
/// default, which renders and charts above about 5800 pixels square are:
/// any image that fits in a sheet is read.
QImage readSheetImage(const QString& path) {
  QImageReader reader(path);
  reader.setAllocationLimit(static_cast<int>(4LL * kMostSheetSide * kMostSheetSide / (1024 * 1024)));  // MB
  // Said by its size, before reading (beyond the limit Qt says only "Unable to read image data").
  if (const QSize size = reader.size(); size.isValid() && std::max(size.width(), size.height()) > kMostSheetSide)
    throw ArgumentError(QStringLiteral("%1 is %2x%3 pixels; expected images a sheet can hold, at most %4 along each "
                                       "side")
                            .arg(path).arg(size.width()).arg(size.height()).arg(kMostSheetSide)
                            .toStdString());
  const QImage image = reader.read();
  if (image.isNull())
    throw InputError(path.toStdString() + ": not an image Qt can read (" + reader.errorString().toStdString() + ")");
  return image;
}

}  // namespace

QVariantMap PreviewPlugin::contactSheet(QVariant images, QVariant path, QVariant options) {
  return guarded("contactSheet", [&] {
    const QVariantList list = script::toList(images, QStringLiteral("images"));
    if (list.isEmpty()) options::fail(QStringLiteral("images is empty; expected at least one image"));
    const QString file = script::toString(path, QStringLiteral("path"));
    const Fields fields(options, QString(), {QStringLiteral("columns"), QStringLiteral("captions"), QStringLiteral("title")},
                        QStringLiteral("contactSheet options"));
    std::vector<QImage> pictures;
    for (qsizetype k = 0; k < list.size(); ++k) {
      const QString image_path = options::existingInputFile(script::toString(list[k], QStringLiteral("images[%1]").arg(k)),
                                                           QStringLiteral("images[%1]").arg(k));
      if (cancelRequested()) stopCancelled("contactSheet", file.toStdString() + " was not written");
      pictures.push_back(readSheetImage(image_path));
    }
    std::vector<QString> captions;
    if (fields.has(QStringLiteral("captions"))) {
      const QVariantList texts = script::toList(fields.required(QStringLiteral("captions")), fields.label(QStringLiteral("captions")));
      if (texts.size() != list.size())
        options::fail(QStringLiteral("%1 has %2 entries for %3 images; expected one per image")
                          .arg(fields.label(QStringLiteral("captions"))).arg(texts.size()).arg(list.size()));
      for (qsizetype k = 0; k < texts.size(); ++k)
        captions.push_back(script::toString(texts[k], QStringLiteral("captions[%1]").arg(k)));
    }
    render::ContactSheetOptions sheet;
    sheet.columns = fields.integerAtLeast(QStringLiteral("columns"), 0, 0);
    sheet.title = fields.string(QStringLiteral("title"));
    std::vector<QSize> sizes;
    for (const QImage& picture : pictures) sizes.push_back(picture.size());
    const QSize sheet_size = render::contact_sheet_layout(sizes, sheet).size;
    if (std::max(sheet_size.width(), sheet_size.height()) > kMostSheetSide)
      options::fail(QStringLiteral("the sheet of these %1 images would be %2x%3 pixels; expected at most %4 along each "
                                   "side (fewer columns or rows, or smaller images)")
                        .arg(pictures.size()).arg(sheet_size.width()).arg(sheet_size.height()).arg(kMostSheetSide));
    const QImage result = render::contact_sheet(pictures, captions, sheet);
    if (cancelRequested()) stopCancelled("contactSheet", file.toStdString() + " was not written");
    saveImage(result, file);
    return QVariantMap{{QStringLiteral("file"), file}, {QStringLiteral("width"), result.width()},
                       {QStringLiteral("height"), result.height()}};
  });
}

void PreviewPlugin::lineChart(QVariant path, QVariant chart) {
  guarded("lineChart", [&] {
    const QString file = script::toString(path, QStringLiteral("path"));
    const Fields fields(chart, QString(),
                        {QStringLiteral("title"), QStringLiteral("xLabel"), QStringLiteral("yLabel"),
                         QStringLiteral("series"), QStringLiteral("width"), QStringLiteral("height")},
                        QStringLiteral("lineChart chart"));
    render::LineChart line;
    line.title = fields.string(QStringLiteral("title"));
    line.x_label = fields.string(QStringLiteral("xLabel"));
    line.y_label = fields.string(QStringLiteral("yLabel"));
    const QVariantList series = script::toList(fields.required(QStringLiteral("series")), fields.label(QStringLiteral("series")));
    for (qsizetype k = 0; k < series.size(); ++k) {
      const QString key = QStringLiteral("series[%1]").arg(k);
      const Fields one(series[k], key, {QStringLiteral("name"), QStringLiteral("x"), QStringLiteral("y")});
      const std::vector<double> y = numberList(one.required(QStringLiteral("y")), one.key(QStringLiteral("y")));
      std::vector<double> x;
      if (one.has(QStringLiteral("x"))) {
        x = numberList(one.required(QStringLiteral("x")), one.key(QStringLiteral("x")));
        if (x.size() != y.size())
          options::fail(QStringLiteral("%1: x has %2 values, y has %3").arg(key).arg(x.size()).arg(y.size()));
      } else {
        for (std::size_t i = 0; i < y.size(); ++i) x.push_back(static_cast<double>(i));
      }
      render::LineSeries s;
      s.name = one.string(QStringLiteral("name"));
      for (std::size_t i = 0; i < y.size(); ++i) s.points.emplace_back(x[i], y[i]);
      line.series.push_back(s);
    }
    saveImage(render::draw_line_chart(line, chartSize(fields)), file);
  });
}

void PreviewPlugin::barChart(QVariant path, QVariant chart) {
  guarded("barChart", [&] {
    const QString file = script::toString(path, QStringLiteral("path"));
    const Fields fields(chart, QString(),
                        {QStringLiteral("title"), QStringLiteral("xLabel"), QStringLiteral("yLabel"),
                         QStringLiteral("categories"), QStringLiteral("series"), QStringLiteral("width"),
                         QStringLiteral("height")},
                        QStringLiteral("barChart chart"));
    render::BarChart bars;
    bars.title = fields.string(QStringLiteral("title"));
    bars.category_label = fields.string(QStringLiteral("xLabel"));
    bars.value_label = fields.string(QStringLiteral("yLabel"));
    if (fields.has(QStringLiteral("categories"))) {
      const QVariantList names = script::toList(fields.required(QStringLiteral("categories")), fields.label(QStringLiteral("categories")));
      for (qsizetype k = 0; k < names.size(); ++k)
        bars.categories.push_back(script::toString(names[k], QStringLiteral("categories[%1]").arg(k)));
    }
    const QVariantList series = script::toList(fields.required(QStringLiteral("series")), fields.label(QStringLiteral("series")));
    for (qsizetype k = 0; k < series.size(); ++k) {
      const QString key = QStringLiteral("series[%1]").arg(k);
      const Fields one(series[k], key, {QStringLiteral("name"), QStringLiteral("values")});
      render::BarSeries s;
      s.name = one.string(QStringLiteral("name"));
      s.values = numberList(one.required(QStringLiteral("values")), one.key(QStringLiteral("values")));
      // A missing bar would be drawn as 0.
      if (!bars.categories.empty() && s.values.size() != bars.categories.size())
        options::fail(QStringLiteral("%1 has %2 values for %3 categories; expected one per category")
                          .arg(one.label(QStringLiteral("values"))).arg(s.values.size()).arg(bars.categories.size()));
      bars.series.push_back(s);
    }
    saveImage(render::draw_bar_chart(bars, chartSize(fields)), file);
  });
}

namespace {

QVariantMap previewLimits() {
  const auto range = [](double least, double most) { return QVariantList{least, most}; };
  return QVariantMap{{QStringLiteral("imageSide"), range(kLeastImageSide, kMostImageSide)},
                     {QStringLiteral("chartSide"), range(kLeastChartSide, kMostImageSide)},
                     {QStringLiteral("supersample"), range(1, kMostSupersample)},
                     {QStringLiteral("sheetSide"), range(1, kMostSheetSide)},
                     {QStringLiteral("samples"), range(1, static_cast<double>(render::kMaxRenderSamples))}};
}

}  // namespace

QVariantMap PreviewPlugin::limits() { return previewLimits(); }

QList<SlotDescription> PreviewPlugin::slotDescriptions() const {
  const QString render_options = QStringLiteral(
      "{width, height: pixels @imageSide@ = 800, camera: \"front\" | \"back\" | \"side\" | \"three_quarter\" = \"front\", "
      "projection: \"perspective\" | \"orthographic\" = \"perspective\", colorBy: \"none\" | \"mode\" | \"level\" | "
      "\"curvature\" = \"none\" (with a legend or colour bar), wireframe: bool = true (the active faces' edges, "
      "T-nodes included), legend: bool = true (drawn on images at least 240 pixels wide and high, in a column of "
      "its own on the right where it fits in 45 % of the width), title: string = none, cache: PC2 of this mesh = "
      "none (its frame is drawn), frame: int >= 0 = 0, body: {cache: body PC2 (simulate's bodyOutput), mesh: its OBJ = beside "
      "the cache}, fit: \"garment\" | \"all\" = \"garment\" (what the camera frames), margin: fraction from 0 to below ") +
      QString::number(kMarginBelow) + QStringLiteral(" = 0.08, supersample: @supersample@ = 2 (samples per pixel along each side; "
      "width x height x supersample^2 within @samples@)}");
  const QString chart_size = QStringLiteral("width, height: pixels @chartSide@ = 800 x 500");
  QList<SlotDescription> descriptions{
      {QStringLiteral("render(int id, string path, object options = {}) -> object"),
       QStringLiteral("Renders the object (at rest, or at a frame of its cache) off-screen, shaded, to an image "
                      "(written atomically). Returns {file, width, height, frame}."),
       {QStringLiteral("id"), QStringLiteral("path"), QStringLiteral("options")},
       {QStringLiteral("object id"), QStringLiteral("image file to write, its format by suffix: .png, .jpg/.jpeg, .bmp, .ppm (its folder must exist)"), render_options}},
      {QStringLiteral("renderSequence(int id, string prefix, object options) -> string[]"),
       QStringLiteral("Renders frames of the object's cache to <prefix>_0000.png ... with one camera fitted to "
                      "the garment over all of them; returns the files. Cancellable (Ctrl-C)."),
       {QStringLiteral("id"), QStringLiteral("prefix"), QStringLiteral("options")},
       {QStringLiteral("object id"), QStringLiteral("path prefix of the PNG files"),
        QStringLiteral("as render's, with cache required and frames: int[] = every frame instead of frame; "
                       "animation: .gif (needs ImageMagick's convert) or .mp4 (needs ffmpeg) file = none, skipped "
                       "with a warning when the tool is missing; fps: number > 0 = 30 (the animation's rate)")}},
      {QStringLiteral("contactSheet(string[] images, string path, object options = {}) -> object"),
       QStringLiteral("Composes images in a grid with captions and a title into one image of @sheetSide@ pixels "
                      "along each side; returns {file, width, height}."),
       {QStringLiteral("images"), QStringLiteral("path"), QStringLiteral("options")},
       {QStringLiteral("image files (PNG, ...)"), QStringLiteral("image file to write (.png, .jpg/.jpeg, .bmp, .ppm)"),
        QStringLiteral("{columns: int >= 0 = 0 (0: about square), captions: string[] = none, title: string = none}")}},
      {QStringLiteral("lineChart(string path, object chart)"),
       QStringLiteral("Draws a line chart to an image file."),
       {QStringLiteral("path"), QStringLiteral("chart")},
       {QStringLiteral("image file to write (.png, .jpg/.jpeg, .bmp, .ppm)"),
        QStringLiteral("{title, xLabel, yLabel: strings, series: [{name, y: number[], x: number[] = 0, 1, ...}], ") +
            chart_size + QLatin1Char('}')}},
      {QStringLiteral("barChart(string path, object chart)"),
       QStringLiteral("Draws a grouped bar chart to an image file."),
       {QStringLiteral("path"), QStringLiteral("chart")},
       {QStringLiteral("image file to write (.png, .jpg/.jpeg, .bmp, .ppm)"),
        QStringLiteral("{title, xLabel, yLabel: strings, categories: string[], series: [{name, values: number[] (one "
                       "per category)}], ") +
            chart_size + QLatin1Char('}')}},
      {QStringLiteral("limits() -> object"),
       QStringLiteral("The bounds of the numeric options, each [least, most], as the calls check them: imageSide "
                      "(render's width and height, pixels), chartSide (the charts'), supersample, samples (render's "
                      "width x height x supersample^2). For checking a tool's own inputs before a run (the "
                      "pipeline does)."),
       {},
       {}},
  };
  return withLimits(std::move(descriptions), previewLimits());
}

}  // namespace mrcloth
