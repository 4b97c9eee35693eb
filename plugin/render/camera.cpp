#include "plugin/render/camera.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrcloth::render {
namespace {

constexpr double pi = 3.14159265358979323846;

// Right/up/forward for a look-at camera; falls back to another up direction
// when the given one is parallel to the view (e.g. looking straight down).
void camera_basis(const Camera& camera, Eigen::Vector3d& right, Eigen::Vector3d& up, Eigen::Vector3d& forward) {
  forward = camera.target - camera.eye;
  if (!(forward.norm() > 0.0) || !forward.allFinite()) forward = -Eigen::Vector3d::UnitZ();
  forward.normalize();
  right = forward.cross(camera.up);
  if (!(right.norm() > 1e-9 * std::max(1.0, camera.up.norm()))) {
    right = forward.cross(Eigen::Vector3d::UnitZ());
    if (right.norm() < 1e-9) right = forward.cross(Eigen::Vector3d::UnitX());
  }
  right.normalize();
  up = right.cross(forward);
}

double half_fov_tan(const Camera& camera) {
  const double fov = std::clamp(camera.fov_y_degrees, 1e-3, 179.0);
  return std::tan(0.5 * fov * pi / 180.0);
}

}  // namespace

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names{"front", "back", "side", "three_quarter"};
  return names;
}

std::string preset_name(Preset preset) { return preset_names().at(static_cast<std::size_t>(preset)); }

Preset parse_preset(const std::string& name) {
  const auto& names = preset_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<Preset>(i);
  std::string valid;
  for (const auto& n : names) valid += (valid.empty() ? "\"" : ", \"") + n + "\"";
  throw std::invalid_argument("unknown camera preset \"" + name + "\"; valid presets: " + valid);
}

Eigen::Vector3d preset_direction(Preset preset) {
  switch (preset) {
    case Preset::front: return Eigen::Vector3d::UnitZ();
    case Preset::back: return -Eigen::Vector3d::UnitZ();
    case Preset::side: return Eigen::Vector3d::UnitX();
    case Preset::three_quarter: {
      const double elevation = 15.0 * pi / 180.0;
      const double c = std::cos(elevation) * std::sqrt(0.5);
      return Eigen::Vector3d(c, std::sin(elevation), c).normalized();
    }
  }
  return Eigen::Vector3d::UnitZ();
}

Camera preset_camera(Preset preset, Projection projection, const Eigen::Vector3d& target, double distance) {
  Camera camera;
  camera.projection = projection;
  camera.target = target;
  camera.eye = target + distance * preset_direction(preset);
  return camera;
}

void fit(Camera& camera, const BoundingBox& box, int width, int height, double margin) {
  if (box.empty() || width <= 0 || height <= 0) return;
  margin = std::clamp(margin, 0.0, 0.49);
  const double usable = 1.0 - 2.0 * margin;
  Eigen::Vector3d right, up, forward;
  camera_basis(camera, right, up, forward);
  camera.up = up;  // keeps the basis stable once the target moves

  const Eigen::Vector3d center = box.center();
  std::vector<Eigen::Vector3d> corners;  // relative to the centre, in (right, up, forward)
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d p((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                            (i & 4) ? box.max.z() : box.min.z());
    const Eigen::Vector3d q = p - center;
    corners.emplace_back(q.dot(right), q.dot(up), q.dot(forward));
  }
  double min_depth = 0.0;  // most negative forward offset: the corner nearest the eye
  for (const auto& c : corners) min_depth = std::min(min_depth, c.z());
  const double extent = std::max(box.diagonal(), 1e-6);

  if (camera.projection == Projection::orthographic) {
    Eigen::Vector2d lo(corners[0].x(), corners[0].y()), hi = lo;
    for (const auto& c : corners) {
      lo = lo.cwiseMin(c.head<2>());
      hi = hi.cwiseMax(c.head<2>());
    }
    camera.target = center + right * 0.5 * (lo.x() + hi.x()) + up * 0.5 * (lo.y() + hi.y());
    const double needed_x = (hi.x() - lo.x()) * height / (usable * width);
    const double needed_y = (hi.y() - lo.y()) / usable;
    camera.ortho_height = std::max({needed_x, needed_y, 1e-6});
    // Far enough that nothing is clipped by the near plane; distance does not scale an orthographic view.
    const double distance = -min_depth + extent + camera.near_plane;
    camera.eye = camera.target - forward * distance;
    return;
  }

  // Perspective, looking at the centre: corner i projects to
  // focal * x_i / (D + z_i) pixels from the centre, which must be at most
  // usable * width / 2; solving for the distance D gives a bound per corner
  // and axis, and the largest bound is met with equality (the view touches).
  const double focal = 0.5 * height / half_fov_tan(camera);
  // A garment smaller than the near plane (one loaded in the wrong units:
  // 3 micrometres) was kept 2 mm away and drawn as a dot; the plane comes
  // closer for it (never for anything over 10 cm, whose pictures stay as they were).
  camera.near_plane = std::min(camera.near_plane, 0.01 * extent);
  double distance = -min_depth + 2.0 * camera.near_plane;
  for (const auto& c : corners) {
    distance = std::max(distance, 2.0 * focal * std::abs(c.x()) / (usable * width) - c.z());
    distance = std::max(distance, 2.0 * focal * std::abs(c.y()) / (usable * height) - c.z());
  }
  camera.target = center;
  camera.eye = center - forward * distance;
}

void fit(Camera& camera, const Scene& scene, int width, int height, double margin) {
  fit(camera, bounds(scene), width, height, margin);
}

Projector::Projector(const Camera& camera, int width, int height)
    : eye_(camera.eye),
      perspective_(camera.projection == Projection::perspective),
      near_(std::max(camera.near_plane, 1e-9)),
      width_(width),
      height_(height) {
  camera_basis(camera, right_, up_, forward_);
  if (perspective_)
    scale_ = 0.5 * height / half_fov_tan(camera);
  else
    scale_ = height / std::max(camera.ortho_height, 1e-12);
}

Eigen::Vector3d Projector::to_view(const Eigen::Vector3d& world) const {
  const Eigen::Vector3d q = world - eye_;
  return {q.dot(right_), q.dot(up_), q.dot(forward_)};
}

Eigen::Vector2d Projector::view_to_pixel(const Eigen::Vector3d& view) const {
  const double k = perspective_ ? scale_ / view.z() : scale_;
  return {0.5 * width_ + k * view.x(), 0.5 * height_ - k * view.y()};
}

std::optional<Eigen::Vector3d> Projector::project(const Eigen::Vector3d& world) const {
  if (!world.allFinite()) return std::nullopt;
  const Eigen::Vector3d view = to_view(world);
  if (view.z() < near_) return std::nullopt;
  const Eigen::Vector2d pixel = view_to_pixel(view);
  return Eigen::Vector3d(pixel.x(), pixel.y(), view.z());
}

}  // namespace mrcloth::render
