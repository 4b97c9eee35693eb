// preview_scene: garments coloured by level, mode and curvature with their
// legends, checked against the layers they come from and, for levels, in an
// actual render (a face seen straight on shows exactly its colour); caches
// and bodies read back from files written with the solver's writers.
#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/mode_painting.h"
#include "plugin/preview/preview_scene.h"
#include "plugin/render/camera.h"
#include "plugin/render/rasterize.h"
#include "solver/point_cache.h"

#include <QTemporaryDir>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace mrcloth::preview {
namespace {

QColor qcolor(const std::array<unsigned char, 3>& rgb) { return QColor(rgb[0], rgb[1], rgb[2]); }

/// `call` throws an `E` whose message contains every fragment.
template <class E>
void expect_throws(const std::function<void()>& call, const std::vector<std::string>& fragments) {
  try {
    call();
  } catch (const E& error) {
    const std::string message = error.what();
    for (const std::string& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos) << "message '" << message << "' lacks '" << fragment << "'";
    return;
  } catch (const std::exception& other) {
    ADD_FAILURE() << "wrong exception type: " << other.what();
    return;
  }
  ADD_FAILURE() << "nothing thrown";
}

/// 2 x 2 unit quads in z = 0 facing +z (make_grid: vertex (i, j) at j * 3 + i,
/// counter-clockwise faces). Vertex 0 gets mode 8, so with delta 10 only
/// face 0 (corners 0 1 4 3, R sum 8 + 1 + 1 + 1 = 11) splits; max level 2
/// stops there: 3 level-1 faces (two with a hanging midpoint) and 4 level-2
/// faces covering [0, 1] x [0, 1].
QuadMesh two_level_grid() {
  QuadMesh mesh = test::make_grid(2, 2);
  set_modes(mesh, {0}, 8);
  adaptive_refine(mesh, {10.0, 2, true});
  return mesh;
}

std::vector<int> face_levels(const QuadMesh& mesh) {
  const auto level = get_layers(mesh).level;
  std::vector<int> levels;
  for (const auto f : mesh.faces()) levels.push_back(mesh.property(level, f));
  return levels;
}

Eigen::MatrixX3d mesh_points(const QuadMesh& mesh) {
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    points.row(v.idx()) << p[0], p[1], p[2];
  }
  return points;
}

TEST(PreviewGarmentLayer, TwoLevelGridIsAsWorkedByHand) {
  const QuadMesh mesh = two_level_grid();
  EXPECT_EQ(mesh.n_vertices(), 14u);
  std::map<int, int> count;
  for (const int level : face_levels(mesh)) ++count[level];
  EXPECT_EQ(count, (std::map<int, int>{{1, 3}, {2, 4}}));
}

TEST(PreviewGarmentLayer, LevelColoursEveryFaceAndListsTheLevelsPresent) {
  const QuadMesh mesh = two_level_grid();
  const GarmentLayer layer = garment_layer(mesh, {}, ColorBy::level);
  const std::vector<int> levels = face_levels(mesh);
  ASSERT_EQ(layer.surface.faces.size(), levels.size());
  ASSERT_EQ(layer.surface.face_colors.size(), levels.size());
  for (std::size_t f = 0; f < levels.size(); ++f)
    EXPECT_EQ(layer.surface.face_colors[f], qcolor(palette_color(levels[f]))) << "face " << f;
  EXPECT_TRUE(layer.surface.vertex_colors.empty());
  // Exactly the levels present, in increasing order, with their face counts.
  ASSERT_EQ(layer.legend.size(), 2u);
  EXPECT_EQ(layer.legend[0].color, qcolor(palette_color(1)));
  EXPECT_EQ(layer.legend[0].label, QStringLiteral("level 1 (3 faces)"));
  EXPECT_EQ(layer.legend[1].color, qcolor(palette_color(2)));
  EXPECT_EQ(layer.legend[1].label, QStringLiteral("level 2 (4 faces)"));
  EXPECT_FALSE(layer.color_bar.has_value());
  // The two palette colours differ, so the render check below can tell levels apart.
  EXPECT_NE(qcolor(palette_color(1)), qcolor(palette_color(2)));
}

TEST(PreviewGarmentLayer, SurfaceIsTheActiveFacesAtTheMeshPoints) {
  const QuadMesh mesh = two_level_grid();
  const GarmentLayer layer = garment_layer(mesh, {}, ColorBy::none);
  EXPECT_EQ(layer.surface.faces, active_face_polygons(mesh));
  EXPECT_EQ(layer.surface.positions, mesh_points(mesh));
  // The faces next to the refined one carry its hanging midpoint: 5 corners.
  std::multiset<std::size_t> sizes;
  for (const auto& face : layer.surface.faces) sizes.insert(face.size());
  EXPECT_EQ(sizes, (std::multiset<std::size_t>{4, 4, 4, 4, 4, 5, 5}));
  EXPECT_TRUE(layer.surface.face_colors.empty());
  EXPECT_TRUE(layer.surface.vertex_colors.empty());
  EXPECT_TRUE(layer.legend.empty());
  EXPECT_FALSE(layer.color_bar.has_value());
}

TEST(PreviewGarmentLayer, RenderedLevelsShowTheirExactPaletteColours) {
  const QuadMesh mesh = two_level_grid();
  GarmentLayer layer = garment_layer(mesh, {}, ColorBy::level);
  layer.surface.wireframe = false;
  render::Scene scene;
  scene.surfaces.push_back(layer.surface);
  render::Camera camera = render::preset_camera(render::Preset::front, render::Projection::orthographic);
  render::fit(camera, render::bounds(layer.surface), 200, 200, 0.1);
  render::RenderOptions options;
  options.width = 200;
  options.height = 200;
  options.supersample = 1;
  const QImage image = render::render(scene, camera, options);
  ASSERT_EQ(image.size(), QSize(200, 200));

  // The 2 m grid fills 160 of 200 pixels: 80 pixels per metre, a level-2
  // face is 40 pixels wide, so every face centre is far from any edge.
  const render::Projector projector(camera, 200, 200);
  const std::vector<int> levels = face_levels(mesh);
  std::set<int> seen;
  for (std::size_t f = 0; f < layer.surface.faces.size(); ++f) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const int v : layer.surface.faces[f]) centre += layer.surface.positions.row(v).transpose();
    centre /= static_cast<double>(layer.surface.faces[f].size());
    const auto pixel = projector.project(centre);
    ASSERT_TRUE(pixel.has_value());
    const int x = static_cast<int>(std::floor((*pixel)[0])), y = static_cast<int>(std::floor((*pixel)[1]));
    ASSERT_TRUE(x >= 0 && x < 200 && y >= 0 && y < 200) << x << "," << y;
    EXPECT_EQ(QColor(image.pixel(x, y)), qcolor(palette_color(levels[f]))) << "face " << f << " at " << x << "," << y;
    seen.insert(levels[f]);
  }
  EXPECT_EQ(seen, (std::set<int>{1, 2}));
  // The level-2 quarter [0, 0.5]^2 is at the bottom left (front view: +x right, +y up).
  EXPECT_EQ(QColor(image.pixel(40, 159)), qcolor(palette_color(2)));
  EXPECT_EQ(QColor(image.pixel(159, 40)), qcolor(palette_color(1)));
  for (const auto& [x, y] : {std::pair{0, 0}, {199, 0}, {0, 199}, {199, 199}, {10, 100}, {100, 10}})
    EXPECT_EQ(QColor(image.pixel(x, y)), scene.background) << x << "," << y;
}

TEST(PreviewGarmentLayer, ModeColoursEveryVertexAndListsTheModesPresent) {
  QuadMesh mesh = test::make_grid(2, 2);
  set_modes(mesh, {0, 1}, 3);
  set_modes(mesh, {8}, 5);
  const GarmentLayer layer = garment_layer(mesh, {}, ColorBy::mode);
  const std::vector<int> modes = get_modes(mesh);
  ASSERT_EQ(layer.surface.vertex_colors.size(), 9u);
  for (std::size_t v = 0; v < modes.size(); ++v)
    EXPECT_EQ(layer.surface.vertex_colors[v], qcolor(palette_color(modes[v]))) << "vertex " << v;
  EXPECT_TRUE(layer.surface.face_colors.empty());
  ASSERT_EQ(layer.legend.size(), 3u);
  const int expected[] = {1, 3, 5};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(layer.legend[k].color, qcolor(palette_color(expected[k])));
    EXPECT_EQ(layer.legend[k].label, QStringLiteral("mode %1").arg(expected[k]));
  }
  EXPECT_FALSE(layer.color_bar.has_value());
}

// The legend takes a column of its own: no garment pixel at or right of
// the legend box's left edge (the garment, framed on the whole width, lay
// under the legend on pictures of 240-450 pixels). The legend box is where
// its grey outline is.
TEST(PreviewPicture, TheLegendHasAColumnOfItsOwn) {
  QuadMesh mesh = test::make_grid(4, 4);
  set_modes(mesh, {0, 1, 2}, 3);
  set_modes(mesh, {20, 21}, 5);
  const GarmentLayer garment = garment_layer(mesh, {}, ColorBy::mode);
  render::Scene scene;
  scene.surfaces.push_back(garment.surface);
  PictureOptions options;
  options.width = options.height = 300;
  options.supersample = 1;
  const render::LegendStyle style;
  for (const bool legend : {true, false}) {
    options.legend = legend;
    const QImage image = draw_picture(scene, render::bounds(garment.surface), garment, options);
    ASSERT_EQ(image.size(), QSize(300, 300));
    QRect box;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        if (QColor(image.pixel(x, y)) == style.border_color) box |= QRect(x, y, 1, 1);
    EXPECT_EQ(box.isEmpty(), !legend);
    int rightmost = -1;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        if (!box.contains(x, y) && QColor(image.pixel(x, y)) != scene.background) rightmost = std::max(rightmost, x);
    if (legend) {
      EXPECT_EQ(box.right(), 300 - 1 - style.margin);
      EXPECT_LT(rightmost, box.left()) << "a garment pixel at or right of the legend's left edge";
      EXPECT_GT(rightmost, box.left() / 2) << "the garment fills the rest";
    } else {
      EXPECT_GT(rightmost, 250) << "without a legend the garment has the whole width";
    }
  }
}

// The title takes a band at the top: no garment pixel in it beside the
// (narrow) title box (on short pictures the garment's top lay under it).
TEST(PreviewPicture, TheTitleHasABandOfItsOwn) {
  const QuadMesh mesh = test::make_grid(4, 4);
  const GarmentLayer garment = garment_layer(mesh, {}, ColorBy::none);
  render::Scene scene;
  scene.surfaces.push_back(garment.surface);
  PictureOptions options;
  options.width = 600;
  options.height = 300;
  options.supersample = 1;
  options.title = "t";
  const int band = render::title_band(options.title);
  ASSERT_GT(band, 0.08 * options.height) << "the band reaches below the margin: the test can fail";
  const QImage image = draw_picture(scene, render::bounds(garment.surface), garment, options);
  int garment_rows_in_band = 0, lowest = -1;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      if (QColor(image.pixel(x, y)) == scene.background || std::abs(x - image.width() / 2) < 40) continue;
      garment_rows_in_band += y < band;
      lowest = std::max(lowest, y);
    }
  EXPECT_EQ(garment_rows_in_band, 0);
  EXPECT_GT(lowest, image.height() * 3 / 4) << "the garment fills the rest";
}

TEST(PreviewGarmentLayer, ModeOnARefinedMeshCoversTheNewVertices) {
  const QuadMesh mesh = two_level_grid();
  const GarmentLayer layer = garment_layer(mesh, {}, ColorBy::mode);
  const std::vector<int> modes = get_modes(mesh);
  ASSERT_EQ(layer.surface.vertex_colors.size(), mesh.n_vertices());
  std::set<int> present(modes.begin(), modes.end());
  for (std::size_t v = 0; v < modes.size(); ++v)
    EXPECT_EQ(layer.surface.vertex_colors[v], qcolor(palette_color(modes[v]))) << "vertex " << v;
  ASSERT_EQ(layer.legend.size(), present.size());
  std::size_t k = 0;
  for (const int mode : present) EXPECT_EQ(layer.legend[k++].label, QStringLiteral("mode %1").arg(mode));
}

TEST(PreviewGarmentLayer, CurvatureIsSequentialOverTheLargestValue) {
  QuadMesh mesh = test::make_grid(2, 2);
  const std::vector<double> values{0.0, 0.5, 1.0, 1.5, 4.0, 2.0, 0.25, 3.0, 1.0};
  set_vertex_layer(mesh, layer::mean_curvature, values);
  const GarmentLayer layer = garment_layer(mesh, {}, ColorBy::curvature);
  ASSERT_EQ(layer.surface.vertex_colors.size(), values.size());
  for (std::size_t v = 0; v < values.size(); ++v)
    EXPECT_EQ(layer.surface.vertex_colors[v], qcolor(sequential_color(values[v] / 4.0))) << "vertex " << v;
  // The largest value is yellow, zero dark purple (the ends of the scale).
  EXPECT_EQ(layer.surface.vertex_colors[4], qcolor(sequential_color(1.0)));
  EXPECT_EQ(layer.surface.vertex_colors[0], qcolor(sequential_color(0.0)));
  EXPECT_TRUE(layer.surface.face_colors.empty());
  EXPECT_TRUE(layer.legend.empty());
  ASSERT_TRUE(layer.color_bar.has_value());
  EXPECT_EQ(layer.color_bar->min_value, 0.0);
  EXPECT_EQ(layer.color_bar->max_value, 4.0);
  ASSERT_TRUE(static_cast<bool>(layer.color_bar->color_map));
  for (const double t : {0.0, 0.3, 0.5, 1.0}) EXPECT_EQ(layer.color_bar->color_map(t), qcolor(sequential_color(t))) << t;
  EXPECT_FALSE(layer.color_bar->label.isEmpty());
}

TEST(PreviewGarmentLayer, CurvatureAllZeroIsTheLowEndOfTheScale) {
  QuadMesh mesh = test::make_grid(1, 1);
  set_vertex_layer(mesh, layer::mean_curvature, {0.0, 0.0, 0.0, 0.0});
  const GarmentLayer layer = garment_layer(mesh, {}, ColorBy::curvature);
  ASSERT_EQ(layer.surface.vertex_colors.size(), 4u);
  for (const QColor& c : layer.surface.vertex_colors) EXPECT_EQ(c, qcolor(sequential_color(0.0)));
  ASSERT_TRUE(layer.color_bar.has_value());
  EXPECT_EQ(layer.color_bar->max_value, 0.0);
}

TEST(PreviewGarmentLayer, CurvatureWithoutTheLayerThrows) {
  const QuadMesh mesh = test::make_grid(2, 2);
  expect_throws<ArgumentError>([&] { garment_layer(mesh, {}, ColorBy::curvature); }, {"mean_curvature"});
}

TEST(PreviewGarmentLayer, PositionsOfAnotherRowCountThrow) {
  const QuadMesh mesh = test::make_grid(2, 2);
  for (const Eigen::Index rows : {1, 8, 10, 14}) {
    const Eigen::MatrixX3d wrong = Eigen::MatrixX3d::Zero(rows, 3);
    expect_throws<ArgumentError>([&] { garment_layer(mesh, wrong, ColorBy::none); },
                                 {std::to_string(rows) + " points", "9 vertices"});
  }
}

TEST(PreviewGarmentLayer, GivenPositionsAreUsed) {
  const QuadMesh mesh = test::make_grid(2, 2);
  Eigen::MatrixX3d moved = mesh_points(mesh);
  moved.col(2) = Eigen::VectorXd::LinSpaced(9, -0.3, 0.7);
  moved.col(0) *= 1.25;
  for (const ColorBy by : {ColorBy::none, ColorBy::level, ColorBy::mode}) {
    const GarmentLayer layer = garment_layer(mesh, moved, by);
    EXPECT_EQ(layer.surface.positions, moved);
    EXPECT_EQ(layer.surface.faces, active_face_polygons(mesh));
  }
  // The mesh's own points are untouched.
  EXPECT_EQ(mesh.point(mesh.vertex_handle(8)), QuadMesh::Point(2, 2, 0));
}

// --- caches and bodies ---

class PreviewFiles : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(dir.isValid()); }
  std::string path(const char* name) const { return dir.filePath(QString::fromUtf8(name)).toStdString(); }

  /// Frame k of a cache of `points` points: multiples of 1/64 (exact in
  /// float, so the cache keeps them exactly), different in every frame.
  static FramePositions frame_values(int points, int k) {
    FramePositions p(points, 3);
    for (int i = 0; i < points; ++i) p.row(i) << (7 * i + 3 * k) / 64.0, (-5 * k + i) / 16.0, 0.5 + (i * k) / 64.0;
    return p;
  }

  void write_cache(const std::string& file, int points, int frames) const {
    Pc2Writer writer(file, points);
    for (int k = 0; k < frames; ++k) writer.add_frame(frame_values(points, k));
    writer.finish();
  }

  QTemporaryDir dir;
};

TEST_F(PreviewFiles, CacheFrameReadsBackAtFloatPrecision) {
  const std::string pc2 = path("garment.pc2");
  write_cache(pc2, 9, 3);
  EXPECT_EQ(cache_frames(pc2), 3);
  for (int k = 0; k < 3; ++k) {
    const Eigen::MatrixX3d frame = cache_frame(pc2, k, 9);
    ASSERT_EQ(frame.rows(), 9);
    EXPECT_EQ(frame, Eigen::MatrixX3d(frame_values(9, k))) << "frame " << k;
  }
  // Values that float cannot hold come back at float precision.
  const std::string inexact = path("inexact.pc2");
  FramePositions thirds(2, 3);
  thirds << 1.0 / 3.0, 0.1, -2.0 / 7.0, 1e3 / 3.0, 12345.678, -1e-4 / 3.0;
  {
    Pc2Writer writer(inexact, 2);
    writer.add_frame(thirds);
    writer.finish();
  }
  const Eigen::MatrixX3d back = cache_frame(inexact, 0, 2);
  for (int i = 0; i < 2; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back(i, c), thirds(i, c), 6e-8 * std::abs(thirds(i, c))) << i << "," << c;
  // Without an expected count, any count is accepted.
  EXPECT_EQ(cache_frame(pc2, 2), Eigen::MatrixX3d(frame_values(9, 2)));
  EXPECT_NE(cache_frame(pc2, 1), cache_frame(pc2, 2));
}

TEST_F(PreviewFiles, CacheFrameOutOfRangeNamesFileAndFrame) {
  const std::string pc2 = path("garment.pc2");
  write_cache(pc2, 9, 3);
  expect_throws<ArgumentError>([&] { cache_frame(pc2, 3, 9); }, {pc2, "frame 3", "3 frames"});
  expect_throws<ArgumentError>([&] { cache_frame(pc2, -1, 9); }, {pc2, "frame -1", "3 frames"});
  expect_throws<ArgumentError>([&] { cache_frame(pc2, 100); }, {pc2, "frame 100"});
}

TEST_F(PreviewFiles, CacheOfAnotherPointCountNamesFileAndCounts) {
  const std::string pc2 = path("garment.pc2");
  write_cache(pc2, 9, 2);
  expect_throws<ArgumentError>([&] { cache_frame(pc2, 0, 16); }, {pc2, "9 points", "16 vertices"});
  expect_throws<ArgumentError>([&] { cache_frame(pc2, 0, 8); }, {pc2, "9 points", "8 vertices"});
}

TEST_F(PreviewFiles, MissingOrBrokenCacheIsAnInputErrorNamingTheFile) {
  const std::string missing = path("missing.pc2");
  expect_throws<InputError>([&] { cache_frame(missing, 0); }, {missing});
  expect_throws<InputError>([&] { cache_frames(missing); }, {missing});
  const std::string obj = path("not_a_cache.pc2");
  write_obj(obj, frame_values(3, 0), {{0, 1, 2}});
  expect_throws<InputError>([&] { cache_frame(obj, 0); }, {obj});
}

TEST_F(PreviewFiles, BodyFramesAreTheObjFacesAtEachCacheFrameWithTheObjReadOnce) {
  const std::string obj = path("body.obj");
  const std::string pc2 = path("body.pc2");
  const std::vector<std::vector<int>> faces{{0, 1, 2}, {1, 3, 4, 2}, {4, 5, 2}};
  write_obj(obj, frame_values(6, 0), faces);
  write_cache(pc2, 6, 4);
  const BodyFrames body(obj, pc2);
  // A sequence reads the rest OBJ once: gone afterwards, every frame still draws.
  std::filesystem::remove(obj);
  for (const int frame : {3, 0, 2}) {
    const render::Surface surface = body.at(frame);
    EXPECT_EQ(surface.faces, faces);
    EXPECT_EQ(surface.positions, Eigen::MatrixX3d(frame_values(6, frame))) << "frame " << frame;
    EXPECT_FALSE(surface.wireframe);
    EXPECT_TRUE(surface.vertex_colors.empty());
    EXPECT_TRUE(surface.face_colors.empty());
  }
  expect_throws<ArgumentError>([&] { (void)body.at(4); }, {pc2, "frame 4"});
  // The cache is read per frame: a frame rewritten since is drawn as it is now.
  write_cache(pc2, 6, 2);
  expect_throws<ArgumentError>([&] { (void)body.at(3); }, {pc2, "frame 3"});
}

TEST_F(PreviewFiles, BodyFramesRefuseACacheOfAnotherPointCount) {
  const std::string obj = path("body.obj");
  const std::string pc2 = path("other.pc2");
  write_obj(obj, frame_values(6, 0), {{0, 1, 2}, {3, 4, 5}});
  write_cache(pc2, 7, 2);
  expect_throws<ArgumentError>([&] { (void)BodyFrames(obj, pc2).at(0); }, {pc2, "7 points", "6 vertices"});
  expect_throws<InputError>([&] { BodyFrames(path("no_body.obj"), pc2); }, {"no_body.obj"});
}

}  // namespace
}  // namespace mrcloth::preview
