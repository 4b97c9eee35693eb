#pragma once
// Analytic colliders: plane, sphere, tapered capsule (a cone-sphere: two
// spheres of different radii and the cone tangent to both). Each has a
// thickness (the cloth keeps this distance from the surface) and a Coulomb
// friction coefficient. Positions in metres.
#include <Eigen/Core>

#include <limits>
#include <variant>
#include <vector>

namespace mrcloth {

struct PlaneCollider {
  Eigen::Vector3d point{0, 0, 0};   ///< a point on the plane
  Eigen::Vector3d normal{0, 1, 0};  ///< outward normal (normalised on use)
};
struct SphereCollider {
  Eigen::Vector3d center{0, 0, 0};
  double radius = 0.1;  ///< metres, > 0
};
struct CapsuleCollider {
  Eigen::Vector3d a{0, 0, 0}, b{0, 1, 0};  ///< segment end points
  double radius_a = 0.1, radius_b = 0.1;     ///< radii at a and b, metres, >= 0, not both 0
};

/// The largest gap (metres) a collider or body may keep between cloth and
/// its surface: cloth rests millimetres off the skin, and a thickness of
/// centimetres already stretches a garment pushed out to it at the first
/// step; larger values are units mistakes (4 meaning 4 mm), and a larger
/// shape is a larger radius.
inline constexpr double kMostContactThickness = 0.05;

struct Collider {
  std::variant<PlaneCollider, SphereCollider, CapsuleCollider> shape;
  double thickness = 0.002;  ///< metres kept between cloth and surface, 0 to kMostContactThickness
  double friction = 0.3;     ///< Coulomb coefficient mu >= 0
};

/// Signed distance from p to the collider's surface (negative inside),
/// ignoring thickness, with the outward unit normal of the closest surface
/// point. Exact for all three shapes (the tapered capsule uses the exact
/// cone-sphere distance).
struct SurfaceQuery {
  double distance = 0.0;
  Eigen::Vector3d normal{0, 1, 0};
};
SurfaceQuery query_surface(const Collider& collider, const Eigen::Vector3d& p);

/// What lies near a point after its collision response, for the rest of a
/// time step (the scene does not move within a step): how far the point is
/// from every thickened surface, and the nearest one linearised there.
struct SurfaceNearby {
  double clearance = 0.0;             ///< metres, >= 0: the point is at least this far outside every surface + thickness (0: on one)
  bool has_plane = false;             ///< whether the nearest thickened surface was found, within the scene's reach
  Eigen::Vector3d point{0, 0, 0};     ///< the point's projection onto that thickened surface, metres
  Eigen::Vector3d normal{0, 1, 0};    ///< its outward unit normal there
  /// Metres the point may move from here and its nearest surface stay that
  /// plane's (infinite: anywhere within the clearance); less where another
  /// part of a body that passes into itself lies just behind.
  double flip = std::numeric_limits<double>::infinity();
};

/// The nearest of `colliders`' thickened surfaces to p (p outside all of
/// them, as resolve_point leaves it): exact within `reach` (metres) of
/// them, a lower bound beyond.
SurfaceNearby nearest_surface(const std::vector<Collider>& colliders, const Eigen::Vector3d& p, double reach);

/// True when p is certainly farther than thickness from a capsule (farther
/// from its axis segment than its larger radius plus the thickness): a few
/// dot products, for skipping the exact query. Always false for planes and
/// spheres.
bool surely_clear(const Collider& collider, const Eigen::Vector3d& p);

/// Throws ArgumentError for a non-positive radius, a zero normal, negative
/// friction, a thickness outside 0 to kMostContactThickness, or non-finite
/// values; names the collider index.
void validate_colliders(const std::vector<Collider>& colliders);

/// The collision response of one point, for a step that moved it from
/// `previous` to `position`: if it is closer than thickness to (or inside) a
/// collider, it is projected to distance `thickness` along the normal, and
/// its tangential displacement over the step is reduced by mu times the
/// normal correction (static friction removes it entirely when within the
/// cone). Colliders are applied in order, in sweeps repeated until one
/// changes nothing (at most 8), so points between overlapping colliders
/// resolve. Returns the largest normal correction applied (metres).
double resolve_point(const std::vector<Collider>& colliders, const Eigen::Vector3d& previous,
                     Eigen::Vector3d& position);

/// Where a point that moved rigidly with a collider from `before` to
/// `after` (the same shape, moved) is now: a sphere translates; a capsule
/// moves with its axis (translation of `a`, the smallest rotation taking the
/// old axis to the new, its length scaled along the axis); a plane is a
/// half-space with no wrong side, so points stay where they were.
Eigen::Vector3d carry_with(const Collider& before, const Collider& after, const Eigen::Vector3d& p);

/// The response of one point to colliders that moved over the step from
/// `before` to `after` (the same colliders in the same order; pass the same
/// vector twice for static ones). As resolve_point, except for a point whose
/// start, carried with a collider, was outside it and whose nearest surface
/// now faces more than 60 degrees away from the surface it entered by (the
/// collider moved past it within the step): that point is pushed to the
/// tangent plane of the thickened collider at its entry point, so a limb
/// faster than the cloth's step cannot push cloth out on its far side.
/// Friction (when `friction`) acts on the motion relative to the collider.
double resolve_point(const std::vector<Collider>& before, const std::vector<Collider>& after,
                     const Eigen::Vector3d& start, Eigen::Vector3d& position, bool friction = true);

/// As resolve_point(before, after, ...), against the colliders listed in
/// `among` only (indices into both vectors).
double resolve_point_among(const std::vector<Collider>& before, const std::vector<Collider>& after,
                           const std::vector<int>& among, const Eigen::Vector3d& start, Eigen::Vector3d& position,
                           bool friction = true);

/// Appends to `out` the index of every collider whose thickened surface
/// may come within `margin` (metres) of p: a superset, from bounds cheaper
/// than the exact distance (a capsule: its axis' distance less its larger
/// radius); planes always.
void colliders_near(const std::vector<Collider>& colliders, const Eigen::Vector3d& p, double margin,
                    std::vector<int>& out);

/// Deepest penetration of p below any collider surface less thickness
/// (metres, 0 when p is at least `thickness` outside all of them).
double penetration(const std::vector<Collider>& colliders, const Eigen::Vector3d& p);

/// Deepest depth of p below any collider's surface itself, thickness not
/// counted (metres, 0 when p is outside all of them).
double depth(const std::vector<Collider>& colliders, const Eigen::Vector3d& p);

}  // namespace mrcloth
