#pragma once
// What a collision body looks like: a polygon mesh of its surface in a pose,
// for previews and for the body cache written beside a garment's (a DCC tool
// shows the garment on its body). Drawing only; collisions use the exact shapes.
#include "colliders.h"
#include "point_cache.h"

#include <vector>

namespace mrcloth {

struct BodySurface {
  FramePositions vertices;               ///< #V x 3, metres
  std::vector<std::vector<int>> faces;   ///< 0-based polygons (quads and triangles), outward facing
  FaceUVs uvs;                           ///< per face corner, its texture coordinates (the body file's); empty: none
};

/// The capsules among `colliders` (planes and spheres are skipped) as closed
/// surfaces: each tapered capsule is its two end spheres joined by their
/// common tangent cone, with `segments` vertices around the axis (>= 3) and
/// `rings` rings per end cap (>= 1). A capsule whose one sphere contains the
/// other is drawn as the larger sphere. Topology depends only on the number
/// of capsules and the counts, so every pose of a rig has the same faces.
BodySurface capsule_surface(const std::vector<Collider>& colliders, int segments = 16, int rings = 4);

/// Appends `more` to `surface` (indices shifted).
void append_surface(BodySurface& surface, const BodySurface& more);

/// The vertices `surface`'s faces use, in increasing order. A body cache
/// keeps only these: DCC importers (Blender's OBJ reader) drop vertices no
/// face uses, and a point cache must match the count they import.
std::vector<int> used_vertices(const BodySurface& surface);

/// `surface` with only the rows `kept` (as used_vertices gives: every vertex
/// a face uses, increasing), its faces renumbered to them.
BodySurface keep_vertices(const BodySurface& surface, const std::vector<int>& kept);

}  // namespace mrcloth
