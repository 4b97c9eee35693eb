#pragma once
// Algorithm 1 of the paper: split one active quad 1 -> 4.
#include "quad_mesh.h"

#include <functional>
#include <initializer_list>
#include <unordered_map>

namespace mrcloth {

/// The most active faces a refinement may make: each takes 350-500 bytes,
/// so this is 7-10 GB (a garment of 800 coarse faces refined 7 times has
/// 13 million). Uniform and adaptive refinement refuse more, before the
/// memory runs out (an adaptive maxLevel of 14 took a 24 GB machine's).
constexpr double kMostFaces = 2e7;

/// What one split created: the centre and the four edge midpoints
/// (midpoint k sits on the edge from corner k to corner k+1).
struct QuadSplit {
  int record = -1;                    ///< the record that was split
  int center = -1;                    ///< new centre vertex
  std::array<int, 4> midpoints{};     ///< edge midpoints, reused or new
  std::array<bool, 4> midpoint_is_new{};
  std::array<int, 4> children{};      ///< the four new records
};

/// Applies Algorithm 1 to records of one mesh. Splits only touch the forest
/// and add vertices; `finish()` then rebuilds the mesh's faces and hanging
/// flags once (cheaper than after every split). Until `finish()` the mesh's
/// faces are stale. The destructor does not finish: call it.
class QuadRefiner {
 public:
  /// Binds to `mesh` (which must have a forest) and indexes its existing midpoints.
  explicit QuadRefiner(QuadMesh& mesh);

  /// Splits active record `record` into four active children of level+1 and
  /// marks it inactive. Edge midpoints already created by a neighbour are
  /// reused, never duplicated. A new vertex takes R = the mean of its fathers'
  /// current R (Algorithm 3's rule; the caller decrements old vertices first)
  /// and mode = that mean of their modes rounded half up; a new midpoint
  /// records its edge's end points as parents. Throws ArgumentError
  /// if the record does not exist or is inactive.
  QuadSplit split(int record);

  /// Midpoint vertex of the edge (a, b) or -1 if that edge was never split.
  int midpoint(int a, int b) const;

  /// Rebuilds faces and hanging flags (see rebuild_active_faces, which
  /// `progress` and the result are).
  bool finish(const std::function<bool(int faces_added)>& progress = {});

 private:
  int midpoint_or_new(int a, int b, bool& created);
  void inherit_from_fathers(int vertex, std::initializer_list<int> fathers);
  static std::uint64_t key(int a, int b);

  QuadMesh& mesh_;
  Layers layers_;
  /// The computed modes (mode_painting.h), where the mesh has them: new
  /// vertices inherit them as they inherit the modes, so eraseModes on a
  /// refined mesh goes back to them, not to the default mode.
  OpenMesh::VPropHandleT<int> computed_;
  std::unordered_map<std::uint64_t, int> midpoints_;
};

}  // namespace mrcloth
