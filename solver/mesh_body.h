#pragma once
// Collision with a moving closed triangle mesh (the skinned body): a
// bounding-volume hierarchy refit every pose, closest point, inside/outside
// and the response of a cloth point.
#include "collision_scene.h"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <vector>

namespace mrcloth {

/// Collision with a moving triangle mesh: a bounding-volume hierarchy built
/// once over the triangles and refit when the vertices move; closest point
/// and inside/outside (angle-weighted pseudo-normals, the mesh must be
/// closed) for points within `thickness` plus a margin of the surface, and
/// for points deeper inside. resolve() is resolve_point's response, with
/// friction acting on the motion relative to the surface (the surface's
/// displacement between the last two update() calls); a point inside goes
/// back out, thickness off the triangle, where its way relative to the
/// surface (`start` carried by the surface's motion, to `position`) first
/// entered, unless that way enters nowhere or that place is inside the body
/// too (then, as at the surface, to the nearest surface).
class MeshBody : public CollisionScene {
 public:
  /// thickness: metres, 0 to kMostContactThickness; friction: Coulomb coefficient >= 0.
  MeshBody(const Eigen::MatrixX3d& vertices, std::vector<Eigen::Vector3i> triangles, double thickness = 0.004,
           double friction = 0.3);
  ~MeshBody() override;
  /// New vertex positions (same count), then refit; call once per step.
  /// `ignored` (per triangle in construction order, or empty: none): the
  /// triangles no query sees in this pose (turned_triangles); pseudo-normals
  /// are formed from the others.
  void update(const Eigen::MatrixX3d& vertices, const std::vector<char>& ignored = {});
  /// With a memo (the point's from its last resolve, in this pose or an
  /// earlier one), the search starts from the triangle that was nearest,
  /// and a point with nothing near that was left outside by the last pose
  /// or this one, whose way since crossed no surface, is outside without a
  /// search of the whole tree: the same answers, sooner (up to which of two
  /// triangles meeting at the closest point is named). `nearby` also says
  /// how far the point may move before another part of the body, which
  /// skinning drives into this one, could become its nearest surface
  /// (SurfaceNearby::flip; at least 2.5 mm where none lies within 5 mm
  /// beyond the nearest).
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                 ContactMemo* memo = nullptr, SurfaceNearby* nearby = nullptr) const override;
  double penetration(const Eigen::Vector3d& p) const override;
  double depth(const Eigen::Vector3d& p) const override;
  /// Both from one search, starting from the hint's triangle when it holds one.
  PointDepths depths(const Eigen::Vector3d& p, int* hint = nullptr) const override;
  bool empty() const override { return false; }
  /// Signed distance to the surface (negative inside) and outward normal, ignoring thickness.
  SurfaceQuery query(const Eigen::Vector3d& p) const;
  /// The point of the surface nearest to p (metres), among the triangles
  /// this pose sees (all of them unless update() left some out).
  struct SurfacePoint {
    std::array<int, 3> vertices{-1, -1, -1};  ///< its triangle's corners, rows of the constructor's `vertices`
    std::array<double, 3> weights{0, 0, 0};    ///< its barycentric coordinates on them (>= 0, summing to 1)
    double distance = 0.0;                     ///< from p, metres (unsigned)
  };
  SurfacePoint nearest_point(const Eigen::Vector3d& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrcloth
