#pragma once
// Where a preview is seen from. Characters face +z with y up, so "front"
// looks at them from the +z side; presets give the direction, fit() the
// distance and framing.
#include "plugin/render/scene.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace mrcloth::render {

enum class Preset {
  front,          ///< camera on +z looking along -z: +x appears on the right
  back,           ///< camera on -z looking along +z: mirrored front
  side,           ///< camera on +x looking along -x: +z (the character's front) appears on the left
  three_quarter,  ///< between front and side (45 deg), 15 deg from above
};

enum class Projection { perspective, orthographic };

/// A look-at camera. Units are metres; image y is up along `up`.
struct Camera {
  Eigen::Vector3d eye = Eigen::Vector3d(0, 0, 5);     ///< camera position
  Eigen::Vector3d target = Eigen::Vector3d::Zero();   ///< point seen at the image centre
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();      ///< world direction shown upwards (need not be orthogonal to the view)
  Projection projection = Projection::perspective;    ///< perspective by default: it reads as 3D
  double fov_y_degrees = 30.0;   ///< vertical field of view, perspective only
  double ortho_height = 2.0;     ///< metres visible vertically, orthographic only
  double near_plane = 1e-3;      ///< metres ahead of the eye; closer geometry is clipped
};

/// Names accepted by parse_preset, in enum order.
const std::vector<std::string>& preset_names();
/// The name of `preset` ("front", "back", "side", "three_quarter").
std::string preset_name(Preset preset);
/// Parses a preset name (exact, lower case). Throws std::invalid_argument
/// naming the bad value and listing the valid names.
Preset parse_preset(const std::string& name);

/// Unit vector from the target towards the eye for a preset.
Eigen::Vector3d preset_direction(Preset preset);

/// A camera looking at `target` from `preset`'s direction at `distance` metres.
Camera preset_camera(Preset preset, Projection projection = Projection::perspective,
                     const Eigen::Vector3d& target = Eigen::Vector3d::Zero(), double distance = 5.0);

/// Moves `camera` along its current view direction (eye - target, kept) and
/// adjusts target (orthographic: also ortho_height) so that `box` fills a
/// `width` x `height` image leaving `margin` (fraction of the width on the
/// left and right, of the height on top and bottom, 0 <= margin < 0.5) free:
/// the box's projected corners lie inside that frame and touch it on at
/// least one side. Orthographic views are centred; perspective views keep
/// the box centre at the image centre. An empty box leaves the camera as is.
void fit(Camera& camera, const BoundingBox& box, int width, int height, double margin = 0.05);
/// fit() to bounds(scene).
void fit(Camera& camera, const Scene& scene, int width, int height, double margin = 0.05);

/// Maps world points to image pixels for one camera and image size.
/// Pixel coordinates are continuous: x from the left edge, y from the top
/// edge; pixel (i, j) covers [i, i+1) x [j, j+1), its centre is (i+0.5, j+0.5).
class Projector {
 public:
  /// width, height: image size in pixels (> 0).
  Projector(const Camera& camera, int width, int height);

  /// World point -> view space: x right, y up, z = depth ahead of the eye (metres).
  Eigen::Vector3d to_view(const Eigen::Vector3d& world) const;
  /// View-space point (z >= near plane for perspective) -> pixel x, y.
  Eigen::Vector2d view_to_pixel(const Eigen::Vector3d& view) const;
  /// World point -> (pixel x, pixel y, view depth), or nothing when the point
  /// is behind the near plane or not finite.
  std::optional<Eigen::Vector3d> project(const Eigen::Vector3d& world) const;

  /// Unit vector along the view direction (from the eye into the scene).
  const Eigen::Vector3d& forward() const { return forward_; }
  bool perspective() const { return perspective_; }
  double near_plane() const { return near_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  Eigen::Vector3d eye_, right_, up_, forward_;
  bool perspective_;
  double scale_;  // pixels per unit of x/z (perspective) or per metre (orthographic)
  double near_;
  int width_, height_;
};

}  // namespace mrcloth::render
