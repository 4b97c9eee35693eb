#pragma once
// What the cloth collides with during one time step: analytic colliders
// and/or moving bodies. The integrator only asks a scene to resolve and
// measure points; bodies are posed before each step by the driver.
#include "colliders.h"

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <memory>
#include <vector>

namespace mrcloth {

/// What a scene may remember about one cloth point from its last resolve
/// to answer the next one (a later round of the step, or the next step)
/// sooner; it never changes an answer. The caller owns one per point and
/// passes it to every resolve of that point; a scene that does not use it
/// leaves it alone, and the first scene of a composite that uses it owns it.
struct ContactMemo {
  std::vector<int> items;               ///< scene-defined (CapsuleBody: the capsules within `radius` of `centre`)
  int nearest = -1;                     ///< scene-defined (MeshBody: the seen triangle nearest to `centre`, -1: none within `radius`)
  Eigen::Vector3d centre{0, 0, 0};      ///< where the point was left
  double radius = -1.0;                 ///< < 0: nothing remembered
  bool outside = true;                  ///< whether centre was outside the surface
  bool sided = true;                    ///< MeshBody: whether `outside` may be carried to points whose way from centre crossed no surface
  const void* owner = nullptr;          ///< the scene that wrote it
  unsigned long long serial = 0;        ///< that scene's pose then
};

/// Within this distance (metres) beyond its thickness a scene reports the
/// nearest surface's tangent plane in SurfaceNearby (beyond it, only a
/// lower bound on the clearance).
constexpr double kNearbyReach = 0.01;

/// What measuring a point found: how far it is inside the thickened
/// surfaces and inside the surfaces themselves (metres, 0 outside).
struct PointDepths {
  double penetration = 0.0;  ///< as CollisionScene::penetration
  double depth = 0.0;        ///< as CollisionScene::depth
};

class CollisionScene {
 public:
  virtual ~CollisionScene() = default;
  /// Like resolve_point: pushes `position` out to `thickness` from every
  /// surface, on the side the point was on at `start` (its position when
  /// the step began, while the scene was still in its previous pose), and
  /// when `friction` applies friction to the motion from `start` relative
  /// to the surface. Returns the largest normal correction (metres).
  /// `memo`, if given, is this point's (see ContactMemo). `nearby`, if
  /// given, receives what lies near where the point ends: its clearance
  /// (a lower bound, exact within kNearbyReach) and, within kNearbyReach,
  /// the nearest thickened surface's tangent plane.
  virtual double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                         ContactMemo* memo = nullptr, SurfaceNearby* nearby = nullptr) const = 0;
  /// Depth of p inside surface + thickness (0 when outside), metres.
  virtual double penetration(const Eigen::Vector3d& p) const = 0;
  /// Depth of p below the surface itself, thickness not counted (0 when
  /// outside), metres: how far cloth is inside the body.
  virtual double depth(const Eigen::Vector3d& p) const = 0;
  /// penetration(p) and depth(p) together, from one search where a scene
  /// can. `hint`, if given, is the caller's int for this point, -1 at first:
  /// a scene may keep there what it found (MeshBody: the nearest triangle)
  /// to start the point's next measurement from it, which gives the same
  /// answers sooner (up to which of two triangles meeting at the closest
  /// point is named).
  virtual PointDepths depths(const Eigen::Vector3d& p, int* /*hint*/ = nullptr) const {
    return {penetration(p), depth(p)};
  }
  /// True when there is nothing to collide with (the integrator skips work).
  virtual bool empty() const = 0;
};

/// A fixed set of analytic colliders.
class AnalyticScene : public CollisionScene {
 public:
  explicit AnalyticScene(std::vector<Collider> colliders = {}) : colliders_(std::move(colliders)) {}
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                 ContactMemo* = nullptr, SurfaceNearby* nearby = nullptr) const override {
    const double largest = resolve_point(colliders_, colliders_, start, position, friction);
    if (nearby) *nearby = nearest_surface(colliders_, position, kNearbyReach);
    return largest;
  }
  double penetration(const Eigen::Vector3d& p) const override { return mrcloth::penetration(colliders_, p); }
  double depth(const Eigen::Vector3d& p) const override { return mrcloth::depth(colliders_, p); }
  bool empty() const override { return colliders_.empty(); }
  std::vector<Collider>& colliders() { return colliders_; }
  const std::vector<Collider>& colliders() const { return colliders_; }

 private:
  std::vector<Collider> colliders_;
};

/// What an empty scene finds near any point: nothing, anywhere.
inline SurfaceNearby nothing_near() {
  SurfaceNearby none;
  none.clearance = std::numeric_limits<double>::infinity();
  return none;
}

/// What two scenes found near one point, as one: the smaller clearance and
/// its plane; the point's side may flip within the smaller flip distance.
inline SurfaceNearby nearer(const SurfaceNearby& a, const SurfaceNearby& b) {
  SurfaceNearby out = b.clearance < a.clearance ? b : a;
  out.flip = std::min(a.flip, b.flip);
  return out;
}

/// Several scenes as one: resolves against each non-empty one in turn, and
/// when there are several and one pushed, once more without friction (a
/// point pushed from one into another settles); penetration is the deepest.
class CompositeScene : public CollisionScene {
 public:
  void add(const CollisionScene* scene) { scenes_.push_back(scene); }
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                 ContactMemo* memo = nullptr, SurfaceNearby* nearby = nullptr) const override {
    double largest = 0.0;
    int active = 0;
    SurfaceNearby here;
    if (nearby) *nearby = nothing_near();
    for (const CollisionScene* s : scenes_) {
      if (s->empty()) continue;
      ++active;
      largest = std::max(largest, s->resolve(start, position, friction, memo, nearby ? &here : nullptr));
      if (nearby) *nearby = nearer(*nearby, here);
    }
    // One scene has already had the last word; friction acts once per step.
    // (With one scene, or no push, what each scene found near the point
    // still holds where it ends.)
    if (active < 2 || largest <= 0.0) return largest;
    if (nearby) *nearby = nothing_near();
    for (const CollisionScene* s : scenes_) {
      if (s->empty()) continue;
      largest = std::max(largest, s->resolve(start, position, false, memo, nearby ? &here : nullptr));
      if (nearby) *nearby = nearer(*nearby, here);
    }
    return largest;
  }
  double penetration(const Eigen::Vector3d& p) const override {
    double deepest = 0.0;
    for (const CollisionScene* s : scenes_) deepest = std::max(deepest, s->penetration(p));
    return deepest;
  }
  double depth(const Eigen::Vector3d& p) const override {
    double deepest = 0.0;
    for (const CollisionScene* s : scenes_) deepest = std::max(deepest, s->depth(p));
    return deepest;
  }
  /// The deepest of each; the hint goes to the one scene that is not empty,
  /// and to none when several are (each would read another's).
  PointDepths depths(const Eigen::Vector3d& p, int* hint = nullptr) const override {
    int active = 0;
    for (const CollisionScene* s : scenes_) active += s->empty() ? 0 : 1;
    PointDepths deepest;
    for (const CollisionScene* s : scenes_) {
      if (s->empty()) continue;
      const PointDepths here = s->depths(p, active == 1 ? hint : nullptr);
      deepest.penetration = std::max(deepest.penetration, here.penetration);
      deepest.depth = std::max(deepest.depth, here.depth);
    }
    return deepest;
  }
  bool empty() const override {
    for (const CollisionScene* s : scenes_)
      if (!s->empty()) return false;
    return true;
  }

 private:
  std::vector<const CollisionScene*> scenes_;
};

}  // namespace mrcloth
