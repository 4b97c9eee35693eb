#include "plugin/render/camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrcloth::render {
namespace {

TEST(RenderCamera, PresetNamesRoundTrip) {
  for (Preset p : {Preset::front, Preset::back, Preset::side, Preset::three_quarter})
    EXPECT_EQ(parse_preset(preset_name(p)), p);
  EXPECT_EQ(parse_preset("three_quarter"), Preset::three_quarter);
}

TEST(RenderCamera, BadPresetNameListsValidOnes) {
  try {
    parse_preset("frontal");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\"frontal\""), std::string::npos) << what;
    for (const char* name : {"\"front\"", "\"back\"", "\"side\"", "\"three_quarter\""})
      EXPECT_NE(what.find(name), std::string::npos) << what;
  }
  EXPECT_THROW(parse_preset("Front"), std::invalid_argument);
  EXPECT_THROW(parse_preset(""), std::invalid_argument);
}

TEST(RenderCamera, FrontShowsPlusXOnTheRightAndYUp) {
  const Camera camera = preset_camera(Preset::front, Projection::orthographic);
  const Projector projector(camera, 200, 100);
  const auto right = projector.project({0.5, 0, 0});
  const auto up = projector.project({0, 0.5, 0});
  ASSERT_TRUE(right && up);
  EXPECT_GT(right->x(), 100.0);
  EXPECT_LT(up->y(), 50.0);
  EXPECT_DOUBLE_EQ(projector.forward().z(), -1.0);
}

TEST(RenderCamera, SideLooksFromPlusX) {
  const Camera camera = preset_camera(Preset::side, Projection::perspective);
  EXPECT_GT(camera.eye.x(), 1.0);
  const Projector projector(camera, 200, 100);
  // The character's front (+z) appears on the left from this side.
  const auto front = projector.project({0, 0, 0.5});
  ASSERT_TRUE(front);
  EXPECT_LT(front->x(), 100.0);
}

TEST(RenderCamera, ThreeQuarterIsFromAbove) {
  const Eigen::Vector3d d = preset_direction(Preset::three_quarter);
  EXPECT_NEAR(d.norm(), 1.0, 1e-12);
  EXPECT_GT(d.y(), 0.1);
  EXPECT_NEAR(d.x(), d.z(), 1e-12);
  EXPECT_GT(d.x(), 0.5);
}

TEST(RenderCamera, PointsBehindTheCameraDoNotProject) {
  const Camera camera = preset_camera(Preset::front, Projection::perspective, Eigen::Vector3d::Zero(), 2.0);
  const Projector projector(camera, 100, 100);
  EXPECT_FALSE(projector.project({0, 0, 3.0}));
  EXPECT_FALSE(projector.project({std::nan(""), 0, 0}));
  EXPECT_TRUE(projector.project({0, 0, 0}));
}

// The fitted box's projected corners lie inside the frame left by the
// margin and touch it (within a pixel) on at least one side.
void expect_fitted(Preset preset, Projection projection, const BoundingBox& box, int width, int height,
                   double margin) {
  Camera camera = preset_camera(preset, projection);
  fit(camera, box, width, height, margin);
  const Projector projector(camera, width, height);
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d p((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                            (i & 4) ? box.max.z() : box.min.z());
    const auto q = projector.project(p);
    ASSERT_TRUE(q) << preset_name(preset) << ": corner behind the camera";
    min_x = std::min(min_x, q->x());
    max_x = std::max(max_x, q->x());
    min_y = std::min(min_y, q->y());
    max_y = std::max(max_y, q->y());
  }
  const double left = margin * width, right = (1 - margin) * width;
  const double top = margin * height, bottom = (1 - margin) * height;
  const std::string where = preset_name(preset) + (projection == Projection::perspective ? " perspective" : " ortho");
  EXPECT_GE(min_x, left - 1e-6) << where;
  EXPECT_LE(max_x, right + 1e-6) << where;
  EXPECT_GE(min_y, top - 1e-6) << where;
  EXPECT_LE(max_y, bottom + 1e-6) << where;
  const double gap = std::min({min_x - left, right - max_x, min_y - top, bottom - max_y});
  EXPECT_LE(gap, 1.0) << where << ": the model does not fill the frame";
}

TEST(RenderCamera, FitFillsTheFrameWithTheMargin) {
  BoundingBox body;  // roughly a standing person
  body.add({-0.3, 0.0, -0.15});
  body.add({0.35, 1.75, 0.2});
  BoundingBox wide;  // a flat wide garment piece
  wide.add({-1.0, 0.9, 0.0});
  wide.add({1.0, 1.1, 0.0});
  for (Preset preset : {Preset::front, Preset::back, Preset::side, Preset::three_quarter})
    for (Projection projection : {Projection::perspective, Projection::orthographic}) {
      expect_fitted(preset, projection, body, 640, 480, 0.05);
      expect_fitted(preset, projection, wide, 320, 480, 0.1);
    }
}

// A garment far smaller than the near plane's millimetre (loaded in the
// wrong units) fills the frame too: it was drawn as a dot 2 mm away.
TEST(RenderCamera, FitFillsTheFrameWithATinyModel) {
  BoundingBox tiny;
  tiny.add({0.0, 0.0, 0.0});
  tiny.add({3e-6, 2e-6, 1e-6});
  for (Preset preset : {Preset::front, Preset::side, Preset::three_quarter})
    for (Projection projection : {Projection::perspective, Projection::orthographic})
      expect_fitted(preset, projection, tiny, 320, 240, 0.05);
}

TEST(RenderCamera, FitOfAnEmptyBoxLeavesTheCamera) {
  Camera camera = preset_camera(Preset::front);
  const Camera before = camera;
  fit(camera, BoundingBox{}, 100, 100);
  EXPECT_EQ(camera.eye, before.eye);
  EXPECT_EQ(camera.target, before.target);
}

TEST(RenderCamera, BoundsIgnoreNonFiniteAndUnusedVertices) {
  Surface s;
  s.positions.resize(5, 3);
  s.positions << 0, 0, 0, 1, 0, 0, 1, 1, 0, std::nan(""), 0, 0, 100, 100, 100;
  s.faces = {{0, 1, 2, 3}};
  const BoundingBox box = bounds(s);
  ASSERT_FALSE(box.empty());
  EXPECT_EQ(box.min, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(box.max, Eigen::Vector3d(1, 1, 0));
  EXPECT_TRUE(bounds(Scene{}).empty());
}

}  // namespace
}  // namespace mrcloth::render
