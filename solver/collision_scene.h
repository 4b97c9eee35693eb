#pragma once
// What the cloth collides with during one time step: analytic colliders
// and/or moving bodies. The integrator only asks a scene to resolve and
// measure points; bodies are posed before each step by the driver.
#include "colliders.h"

#include <Eigen/Core>

#include <algorithm>
#include <memory>
#include <vector>

namespace mrcloth {

/// What a scene may remember about one cloth point between the collision
/// rounds of a step to answer its later queries faster; it never changes an
/// answer. The caller owns one per point and passes it to every resolve of
/// that point; a scene that does not use it leaves it alone, and the first
/// scene of a composite that uses it owns it.
struct ContactMemo {
  std::vector<int> items;               ///< scene-defined (MeshBody: every triangle within `radius` of `centre`)
  Eigen::Vector3d centre{0, 0, 0};      ///< where they were gathered
  double radius = -1.0;                 ///< < 0: nothing remembered
  bool outside = true;                  ///< whether centre was outside the surface
  double clear = 0.0;                   ///< MeshBody: no (seen) triangle is nearer than this to centre
  bool sided = true;                    ///< MeshBody: false near ignored triangles, where `outside` may not carry to points near centre
  const void* owner = nullptr;          ///< the scene that wrote it
  unsigned long long serial = 0;        ///< that scene's pose then
};

class CollisionScene {
 public:
  virtual ~CollisionScene() = default;
  /// Like resolve_point: pushes `position` out to `thickness` from every
  /// surface, on the side the point was on at `start` (its position when
  /// the step began, while the scene was still in its previous pose), and
  /// when `friction` applies friction to the motion from `start` relative
  /// to the surface. Returns the largest normal correction (metres).
  /// `memo`, if given, is this point's (see ContactMemo).
  virtual double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                         ContactMemo* memo = nullptr) const = 0;
  /// Depth of p inside surface + thickness (0 when outside), metres.
  virtual double penetration(const Eigen::Vector3d& p) const = 0;
  /// Depth of p below the surface itself, thickness not counted (0 when
  /// outside), metres: how far cloth is inside the body.
  virtual double depth(const Eigen::Vector3d& p) const = 0;
  /// True when there is nothing to collide with (the integrator skips work).
  virtual bool empty() const = 0;
};

/// A fixed set of analytic colliders.
class AnalyticScene : public CollisionScene {
 public:
  explicit AnalyticScene(std::vector<Collider> colliders = {}) : colliders_(std::move(colliders)) {}
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                 ContactMemo* = nullptr) const override {
    return resolve_point(colliders_, colliders_, start, position, friction);
  }
  double penetration(const Eigen::Vector3d& p) const override { return mrcloth::penetration(colliders_, p); }
  double depth(const Eigen::Vector3d& p) const override { return mrcloth::depth(colliders_, p); }
  bool empty() const override { return colliders_.empty(); }
  std::vector<Collider>& colliders() { return colliders_; }
  const std::vector<Collider>& colliders() const { return colliders_; }

 private:
  std::vector<Collider> colliders_;
};

/// Several scenes as one: resolves against each non-empty one in turn, and
/// when there are several and one pushed, once more without friction (a
/// point pushed from one into another settles); penetration is the deepest.
class CompositeScene : public CollisionScene {
 public:
  void add(const CollisionScene* scene) { scenes_.push_back(scene); }
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true,
                 ContactMemo* memo = nullptr) const override {
    double largest = 0.0;
    int active = 0;
    for (const CollisionScene* s : scenes_) {
      if (s->empty()) continue;
      ++active;
      largest = std::max(largest, s->resolve(start, position, friction, memo));
    }
    // One scene has already had the last word; friction acts once per step.
    if (active < 2 || largest <= 0.0) return largest;
    for (const CollisionScene* s : scenes_)
      if (!s->empty()) largest = std::max(largest, s->resolve(start, position, false, memo));
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
  bool empty() const override {
    for (const CollisionScene* s : scenes_)
      if (!s->empty()) return false;
    return true;
  }

 private:
  std::vector<const CollisionScene*> scenes_;
};

}  // namespace mrcloth
