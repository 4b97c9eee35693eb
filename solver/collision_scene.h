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

class CollisionScene {
 public:
  virtual ~CollisionScene() = default;
  /// Like resolve_point: pushes `position` out to `thickness` from every
  /// surface, on the side the point was on at `start` (its position when
  /// the step began, while the scene was still in its previous pose), and
  /// when `friction` applies friction to the motion from `start` relative
  /// to the surface. Returns the largest normal correction (metres).
  virtual double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true) const = 0;
  /// Depth of p inside surface + thickness (0 when outside), metres.
  virtual double penetration(const Eigen::Vector3d& p) const = 0;
  /// True when there is nothing to collide with (the integrator skips work).
  virtual bool empty() const = 0;
};

/// A fixed set of analytic colliders.
class AnalyticScene : public CollisionScene {
 public:
  explicit AnalyticScene(std::vector<Collider> colliders = {}) : colliders_(std::move(colliders)) {}
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true) const override {
    return resolve_point(colliders_, colliders_, start, position, friction);
  }
  double penetration(const Eigen::Vector3d& p) const override { return mrcloth::penetration(colliders_, p); }
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
  double resolve(const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true) const override {
    double largest = 0.0;
    int active = 0;
    for (const CollisionScene* s : scenes_) {
      if (s->empty()) continue;
      ++active;
      largest = std::max(largest, s->resolve(start, position, friction));
    }
    // One scene has already had the last word; friction acts once per step.
    if (active < 2 || largest <= 0.0) return largest;
    for (const CollisionScene* s : scenes_)
      if (!s->empty()) largest = std::max(largest, s->resolve(start, position, false));
    return largest;
  }
  double penetration(const Eigen::Vector3d& p) const override {
    double deepest = 0.0;
    for (const CollisionScene* s : scenes_) deepest = std::max(deepest, s->penetration(p));
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
