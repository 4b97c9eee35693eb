#pragma once
// A skinned body mesh driven by a BVH skeleton: the MakeHuman base mesh with
// its CMU rig and weights, linear-blend skinned. Collision with it is
// MeshBody's (mesh_body.h); reading MakeHuman's files into one,
// makehuman_body.h (included here).
#include "makehuman_body.h"
#include "skeleton.h"

#include <Eigen/Core>

#include <string>
#include <array>
#include <vector>

namespace mrcloth {

/// A body mesh bound to a skeleton. The mesh may have been modelled in
/// another pose than the skeleton's rest pose (MakeHuman: an A-pose, CMU: a
/// T-pose); the rest correction rotates each bone from the mesh's pose to
/// the rest pose, and skin() poses the input mesh directly, so the mesh's
/// own pose (mesh_pose) reproduces the input exactly.
struct SkinnedBody {
  Eigen::MatrixX3d rest_vertices;                       ///< #V x 3, metres: the body in the skeleton's rest (T-)pose
  std::vector<Eigen::Vector3i> triangles;               ///< the body's quads split into triangles
  /// Per triangle, its corners' texture coordinates (the body file's `vt`);
  /// empty when the file has none, or for a body made for collisions only.
  std::vector<std::array<Eigen::Vector2d, 3>> triangle_uvs;
  std::vector<std::vector<std::pair<int, double>>> weights;  ///< per vertex (skeleton joint, weight), weights sum to 1
  /// Per skeleton joint, the point its bone turns about in rest space
  /// (metres): the body keeps its own proportions, so these are the mesh's
  /// joints after the rest correction, not the skeleton's. Empty: skin()
  /// uses the skeleton's rest joint positions.
  std::vector<Eigen::Vector3d> joint_rest;
  /// The input mesh (#V x 3, metres, skeleton space), its joints (per
  /// skeleton joint) and per joint the global rotation taking the mesh's
  /// pose to the rest pose. Empty: the input is rest_vertices, already in
  /// the rest pose (no correction).
  Eigen::MatrixX3d input_vertices;
  std::vector<Eigen::Vector3d> input_joints;
  std::vector<Eigen::Matrix3d> rest_correction;
  /// base.obj coordinates x metres_per_unit + obj_offset = input_vertices (the A-pose
  /// mesh in the skeleton's space); garments modelled on base.obj map the
  /// same way. Metres.
  Eigen::Vector3d obj_offset{0, 0, 0};
};

/// Linear-blend skinning: vertices of the body in `pose` (#V x 3). Each
/// bone takes the rotation of its skeleton joint relative to the mesh's own
/// pose, about its joint carried along the body's own bone chain from the
/// skeleton's root. In the skeleton's rest pose this gives rest_vertices,
/// in mesh_pose the input mesh, both to round-off.
Eigen::MatrixX3d skin(const SkinnedBody& body, const Skeleton& skeleton, const Pose& pose);

/// Triangles (in body.triangles order) that skinning has turned over in
/// `pose`: linear blend skinning folds the skin where a joint bends far
/// (behind a bent knee), and a folded triangle's normal then points against
/// the normal its own vertices' blended rotations carry its source normal
/// to. Such a triangle is skin buried in the fold, not the body's outside:
/// its normal would push cloth into the leg. `posed` is skin(body,
/// skeleton, pose). 1: turned over.
std::vector<char> turned_triangles(const SkinnedBody& body, const Skeleton& skeleton, const Pose& pose,
                                   const Eigen::MatrixX3d& posed);

/// turned_triangles for one body pose after pose (a posed body's every
/// step): the source normals formed once, the per-vertex blends in a
/// buffer kept between calls. The same flags, to the bit.
class TurnedTriangles {
 public:
  /// The body must outlive this; each call checks it against the skeleton.
  /// Throws ArgumentError for a triangle naming a vertex the body lacks.
  explicit TurnedTriangles(const SkinnedBody& body);
  /// turned_triangles(body, skeleton, pose, posed); valid until the next call.
  const std::vector<char>& operator()(const Skeleton& skeleton, const Pose& pose, const Eigen::MatrixX3d& posed);

 private:
  const SkinnedBody& body_;
  std::vector<Eigen::Vector3d> source_normal_;  ///< per triangle, its (unnormalised) normal in the source mesh
  std::vector<int> may_turn_;                   ///< the triangles not moved by one joint alone, ascending
  std::vector<int> blended_;                    ///< their corners, ascending
  std::vector<Eigen::Matrix3d> blend_;          ///< per vertex, the linear part of its blend in the last pose (corners in blended_)
  std::vector<char> turned_;
};

/// The skeleton posed as the body's input mesh was modelled (MakeHuman's
/// A-pose): every joint's rest rotation undone by its rest correction, the
/// root where the rest pose has it, positions by forward kinematics with the
/// skeleton's own offsets. The skeleton's rest pose for a body without a
/// correction. Garments modelled on the mesh fit the body in this pose.
Pose mesh_pose(const SkinnedBody& body, const Skeleton& skeleton);

/// Per skeleton joint, 1 for the hands: every joint named LeftHand or
/// RightHand (CMU's names) and every joint below it (fingers, thumbs, their
/// End Sites).
std::vector<char> hand_joints(const Skeleton& skeleton);

/// Per body vertex, the hand it belongs to: where more than half its skin
/// weight is on the hands (hand_joints), the joint named LeftHand or
/// RightHand that its heaviest hand joint hangs from; elsewhere -1.
std::vector<int> hand_vertices(const SkinnedBody& body, const Skeleton& skeleton);

/// The body with its hands cut off, for collisions: every triangle with a
/// hand vertex removed, and each wrist's opening closed by a fan of
/// triangles around a new vertex at the opening's centroid (in the rest and
/// the input mesh), skinned by the opening's mean weights, so the mesh stays
/// closed and consistently oriented. Hands are fingers and gaps a few
/// millimetres wide: cloth caught between them is dragged along and torn
/// (see README, Known limits); collide with capsules there instead
/// (hand_mitten_capsules in character_setup.h). Vertices are kept (the
/// hands' are no longer used by any triangle), the new ones appended.
/// ArgumentError when the cut does not leave one simple opening per hand
/// that has vertices (a body without hand vertices comes back unchanged).
SkinnedBody without_hands(const SkinnedBody& body, const Skeleton& skeleton);

/// Gives `to` (a body made from `from`: the same vertices first, perhaps
/// more appended, and other triangles, as without_hands makes) `from`'s
/// texture coordinates: a triangle `from` has keeps its UVs, any other
/// corner takes a UV its vertex has in `from`, and a vertex `from` has in no
/// triangle (a cap's centre) the UV of its triangle's first corner that has
/// one. Leaves `to` untextured when `from` is.
void carry_uvs(const SkinnedBody& from, SkinnedBody& to);

}  // namespace mrcloth
