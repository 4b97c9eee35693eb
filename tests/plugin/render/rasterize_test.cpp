#include "plugin/render/rasterize.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace mrcloth::render {
namespace {

const QColor red(255, 0, 0), green(0, 255, 0), blue(0, 0, 255), yellow(255, 255, 0);
const QColor background(10, 20, 30);
const QColor wire(255, 0, 255);

// A unit square in the z = 0 plane, 2x2 quads, normals along +z. Faces in
// order: bottom-left red, bottom-right green, top-left blue, top-right yellow.
Surface flat_square(const Eigen::Vector3d& offset = Eigen::Vector3d::Zero(), double size = 1.0) {
  Surface s;
  s.positions.resize(9, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) s.positions.row(j * 3 + i) = Eigen::RowVector3d(i * 0.5 * size, j * 0.5 * size, 0) + offset.transpose();
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int v = j * 3 + i;
      s.faces.push_back({v, v + 1, v + 4, v + 3});
    }
  s.face_colors = {red, green, blue, yellow};
  s.wireframe = false;
  return s;
}

RenderOptions exact(int width = 200, int height = 100) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.supersample = 1;
  return options;
}

// Orthographic front view of the unit square fitted with a 10 % margin into
// 200 x 100: 80 pixels per metre, the square covers x 60..140, y 10..90.
QImage render_square(Preset preset, const Surface& surface, const RenderOptions& options = exact()) {
  Scene scene;
  scene.background = background;
  scene.surfaces = {surface};
  return render_preset(scene, preset, options, Projection::orthographic, 0.1);
}

QColor at(const QImage& image, int x, int y) { return QColor(image.pixel(x, y)); }

TEST(RenderRasterize, FlatSquareFrontHasExactColours) {
  const QImage image = render_square(Preset::front, flat_square());
  ASSERT_EQ(image.width(), 200);
  ASSERT_EQ(image.height(), 100);
  // Quad centres; facing the camera straight on, so shading is exactly 1.
  EXPECT_EQ(at(image, 80, 70), red);
  EXPECT_EQ(at(image, 120, 70), green);
  EXPECT_EQ(at(image, 80, 30), blue);
  EXPECT_EQ(at(image, 120, 30), yellow);
  for (auto [x, y] : {std::pair{0, 0}, {199, 0}, {0, 99}, {199, 99}, {59, 50}, {140, 50}, {100, 9}, {100, 90}})
    EXPECT_EQ(at(image, x, y), background) << x << "," << y;
  // The square's own border pixels are inside.
  EXPECT_EQ(at(image, 60, 89), red);
  EXPECT_EQ(at(image, 139, 10), yellow);
}

TEST(RenderRasterize, WireframeOnAKnownEdge) {
  Surface s = flat_square();
  s.wireframe = true;
  s.wire_color = wire;
  s.wire_width = 2.0;
  const QImage image = render_square(Preset::front, s);
  // The vertical middle edge x = 0.5 m is at pixel x = 100.0: a 2-pixel line covers columns 99 and 100.
  EXPECT_EQ(at(image, 99, 70), wire);
  EXPECT_EQ(at(image, 100, 70), wire);
  EXPECT_EQ(at(image, 97, 70), red);
  EXPECT_EQ(at(image, 102, 70), green);
  // The horizontal middle edge y = 0.5 m is at pixel y = 50.0.
  EXPECT_EQ(at(image, 80, 49), wire);
  EXPECT_EQ(at(image, 80, 50), wire);
  EXPECT_EQ(at(image, 80, 70), red);
}

TEST(RenderRasterize, WiresBehindASurfaceAreHidden) {
  Scene scene;
  scene.background = background;
  Surface front = flat_square({0, 0, 0.5});
  Surface back = flat_square();
  back.wireframe = true;
  back.wire_color = wire;
  back.wire_width = 3.0;
  scene.surfaces = {front, back};
  Camera camera = preset_camera(Preset::front, Projection::orthographic);
  fit(camera, scene, 200, 100, 0.1);
  const QImage image = render(scene, camera, exact());
  // The far square's middle edge would cover columns 99..100 (and 101 at 3 pixels).
  EXPECT_EQ(at(image, 99, 70), red);
  EXPECT_EQ(at(image, 100, 70), green);
  EXPECT_EQ(at(image, 80, 50), red);
}

TEST(RenderRasterize, BackViewIsMirrored) {
  const QImage image = render_square(Preset::back, flat_square());
  // Seen from -z, +x is on the left: red (x < 0.5) moves to the right half.
  EXPECT_EQ(at(image, 120, 70), red);
  EXPECT_EQ(at(image, 80, 70), green);
  EXPECT_EQ(at(image, 120, 30), blue);
  EXPECT_EQ(at(image, 80, 30), yellow);
}

TEST(RenderRasterize, BackFacesAreLitLikeFrontFaces) {
  // A square tilted 60 degrees about x: Lambert |cos| = 0.5 from either side.
  Surface s = flat_square();
  s.face_colors.clear();
  s.color = QColor(200, 100, 60);
  for (int v = 0; v < 9; ++v) {
    const double y = s.positions(v, 1);
    s.positions(v, 1) = y * 0.5;
    s.positions(v, 2) = y * std::sqrt(3.0) / 2.0;
  }
  const double k = 0.3 + 0.7 * 0.5;
  for (bool smooth : {false, true}) {
    RenderOptions options = exact();
    options.ambient = 0.3;
    options.smooth_shading = smooth;
    const QImage front = render_square(Preset::front, s, options);
    const QImage back = render_square(Preset::back, s, options);
    // Shading tolerance: one step of rounding.
    for (const QImage* image : {&front, &back}) {
      const QColor c = at(*image, 100, 50);
      EXPECT_NEAR(c.red(), 200 * k, 1.0) << (image == &front ? "front" : "back") << " smooth " << smooth;
      EXPECT_NEAR(c.green(), 100 * k, 1.0);
      EXPECT_NEAR(c.blue(), 60 * k, 1.0);
    }
  }
}

TEST(RenderRasterize, NearerSurfaceWinsWhateverTheOrder) {
  Scene scene;
  scene.background = background;
  Surface far_one = flat_square({0, 0, 0}, 1.0);
  far_one.face_colors.clear();
  far_one.color = blue;
  Surface near_one = flat_square({0.25, 0.25, 0.3}, 0.5);
  near_one.face_colors.clear();
  near_one.color = red;
  for (Projection projection : {Projection::orthographic, Projection::perspective}) {
    Camera camera = preset_camera(Preset::front, projection);
    scene.surfaces = {far_one, near_one};
    fit(camera, scene, 200, 100, 0.1);
    const QImage a = render(scene, camera, exact());
    scene.surfaces = {near_one, far_one};
    const QImage b = render(scene, camera, exact());
    EXPECT_EQ(a, b);
    EXPECT_EQ(at(a, 100, 50), red);
    const Projector projector(camera, 200, 100);
    const auto far_only = projector.project({0.1, 0.1, 0.0});
    ASSERT_TRUE(far_only);
    EXPECT_EQ(at(a, int(far_only->x()), int(far_only->y())), blue);
  }
}

TEST(RenderRasterize, VertexColoursAreInterpolated) {
  Surface s = flat_square();
  s.face_colors.clear();
  s.vertex_colors.assign(9, red);
  for (int j = 0; j < 3; ++j) {
    s.vertex_colors[j * 3 + 1] = QColor(128, 0, 128);
    s.vertex_colors[j * 3 + 2] = blue;
  }
  const QImage image = render_square(Preset::front, s);
  // Quarter of the way: halfway between red and the purple middle.
  const QColor c = at(image, 80, 70);
  EXPECT_NEAR(c.red(), 191, 3);
  EXPECT_EQ(c.green(), 0);
  EXPECT_NEAR(c.blue(), 64, 3);
  // Pixel 60's centre is 0.00625 m from the red edge: 1.25 % of the way to purple.
  const QColor left = at(image, 60, 50);
  EXPECT_NEAR(left.red(), 253, 1);
  EXPECT_NEAR(left.blue(), 2, 1);
}

TEST(RenderRasterize, PolygonWithHangingVertexFillsAndDrawsItsEdges) {
  // A square with a hanging vertex in the middle of its bottom edge.
  Surface s;
  s.positions.resize(5, 3);
  s.positions << 0, 0, 0, 0.5, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  s.faces = {{0, 1, 2, 3, 4}};
  s.color = green;
  s.wire_color = wire;
  s.wire_width = 1.0;
  const QImage image = render_square(Preset::front, s);
  EXPECT_EQ(at(image, 100, 50), green);
  EXPECT_EQ(at(image, 80, 89), wire) << "bottom edge, first half";
  EXPECT_EQ(at(image, 120, 89), wire) << "bottom edge, second half";
  EXPECT_EQ(at(image, 80, 88), green);
}

TEST(RenderRasterize, EmptySceneIsBackground) {
  Scene scene;
  scene.background = background;
  for (const Scene& s : {scene, Scene{{Surface{}}, background}}) {
    const QImage image = render(s, preset_camera(Preset::front), exact(64, 48));
    ASSERT_EQ(image.size(), QSize(64, 48));
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) ASSERT_EQ(at(image, x, y), background);
  }
}

TEST(RenderRasterize, NaNVertexSkipsItsFacesOnly) {
  Surface s = flat_square();
  s.wireframe = true;
  s.positions(0, 0) = std::nan("");
  s.positions(4, 2) = std::nan("");  // the centre: every face uses it
  Scene scene;
  scene.background = background;
  scene.surfaces = {s};
  const QImage all_skipped = render_preset(scene, Preset::front, exact(), Projection::perspective);
  EXPECT_EQ(all_skipped.size(), QSize(200, 100));

  s.positions(4, 2) = 0.0;
  const QImage image = render_square(Preset::front, s);
  EXPECT_EQ(at(image, 80, 70), background) << "the face with the NaN vertex is skipped";
  EXPECT_EQ(at(image, 120, 70), green);
  EXPECT_EQ(at(image, 80, 30), blue);
}

TEST(RenderRasterize, DegenerateFacesDoNotCrash) {
  Surface s;
  s.positions.resize(4, 3);
  s.positions << 0, 0, 0, 1, 0, 0, 2, 0, 0, 1e300, -1e300, 1e300;
  s.faces = {{0, 1, 2}, {0, 0, 0}, {0, 1}, {}, {0, 1, 3}, {1, 1, 2, 2}};
  Scene scene;
  scene.surfaces = {s};
  for (Projection projection : {Projection::orthographic, Projection::perspective})
    EXPECT_EQ(render_preset(scene, Preset::three_quarter, exact(), projection).size(), QSize(200, 100));
}

TEST(RenderRasterize, GeometryBehindTheCameraIsClipped) {
  // A floor from far ahead to far behind the camera.
  Surface floor;
  floor.positions.resize(4, 3);
  floor.positions << -10, -1, -10, 10, -1, -10, 10, -1, 10, -10, -1, 10;
  floor.faces = {{0, 1, 2, 3}};
  floor.color = green;
  floor.wire_color = wire;
  Scene scene;
  scene.background = background;
  scene.surfaces = {floor};
  Camera camera = preset_camera(Preset::front, Projection::perspective, Eigen::Vector3d::Zero(), 5.0);
  const QImage image = render(scene, camera, exact());
  EXPECT_EQ(at(image, 100, 5), background) << "sky";
  // The camera is 1 m above the floor: the bottom of the view is floor.
  const QColor bottom = at(image, 100, 95);
  EXPECT_EQ(bottom.red(), 0);
  EXPECT_GT(bottom.green(), 50);
}

TEST(RenderRasterize, InvalidInputThrows) {
  Scene scene;
  scene.surfaces = {flat_square()};
  const Camera camera = preset_camera(Preset::front);
  EXPECT_THROW(render(scene, camera, exact(0, 10)), std::invalid_argument);
  RenderOptions options = exact();
  options.supersample = 0;
  EXPECT_THROW(render(scene, camera, options), std::invalid_argument);
  scene.surfaces[0].faces.push_back({0, 1, 9});
  EXPECT_THROW(render(scene, camera, exact()), std::invalid_argument);
  scene.surfaces = {flat_square()};
  scene.surfaces[0].face_colors.pop_back();
  EXPECT_THROW(render(scene, camera, exact()), std::invalid_argument);
  scene.surfaces = {flat_square()};
  scene.surfaces[0].vertex_colors.assign(3, red);
  scene.surfaces[0].face_colors.clear();
  EXPECT_THROW(render(scene, camera, exact()), std::invalid_argument);
}

TEST(RenderRasterize, SupersamplingAveragesEdges) {
  Surface s = flat_square();
  s.face_colors.clear();
  s.color = QColor(255, 255, 255);
  Scene scene;
  scene.background = QColor(0, 0, 0);
  scene.surfaces = {s};
  // Fitted so that the square's left edge falls in the middle of a pixel column.
  Camera camera = preset_camera(Preset::front, Projection::orthographic);
  camera.target = {0.5 + 0.5 / 80.0, 0.5, 0};
  camera.eye = camera.target + Eigen::Vector3d(0, 0, 5);
  camera.ortho_height = 1.25;
  RenderOptions options = exact();
  options.supersample = 2;
  const QImage image = render(scene, camera, options);
  EXPECT_EQ(at(image, 100, 50), QColor(255, 255, 255));
  // The left edge is at x = 59.5: pixel 59 is half covered.
  EXPECT_EQ(at(image, 58, 50), QColor(0, 0, 0));
  EXPECT_EQ(at(image, 60, 50), QColor(255, 255, 255));
  const QColor edge = at(image, 59, 50);
  EXPECT_NEAR(edge.red(), 128, 2);
}

// About 20k quads of a wavy sheet at 1024 x 768 with 2x supersampling and
// wires: a garment-sized render completes and covers the frame it was fitted
// to. (Its speed is measured by bench_render, not here.)
TEST(RenderRasterize, TwentyThousandQuadsRender) {
  const int n = 142;  // 141 x 141 = 19881 quads
  Surface s;
  s.positions.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = i / double(n - 1) - 0.5, y = j / double(n - 1);
      s.positions.row(j * n + i) << x, y, 0.05 * std::sin(20 * x) * std::cos(13 * y);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int v = j * n + i;
      s.faces.push_back({v, v + 1, v + n + 1, v + n});
    }
  s.wire_width = 1.0;
  Scene scene;
  scene.surfaces = {s};
  RenderOptions options;  // 1024 x 768, 2x supersampling
  const QImage image = render_preset(scene, Preset::three_quarter, options);
  EXPECT_EQ(image.size(), QSize(1024, 768));
  // The sheet is drawn: the centre pixel is not the background.
  EXPECT_NE(image.pixelColor(512, 384), scene.background);
}

}  // namespace
}  // namespace mrcloth::render
