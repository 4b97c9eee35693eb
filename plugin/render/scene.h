#pragma once
// What a preview shows: surfaces as plain arrays (no OpenMesh here, so the
// library stays independent of the mesh types) and a background colour.
#include <Eigen/Core>
#include <QColor>

#include <limits>
#include <vector>

namespace mrcloth::render {

/// One mesh to draw. Colour precedence: face_colors if not empty, else
/// vertex_colors if not empty, else color.
struct Surface {
  Eigen::MatrixX3d positions;  ///< one row per vertex: x, y, z in metres, y up
  /// Polygons as vertex indices into `positions`, any winding. Quads and
  /// polygons with extra "hanging" vertices on their edges (adaptive
  /// refinement) are filled by a fan, so they must be convex; the wireframe
  /// follows the polygon's own edges, hanging vertices included.
  std::vector<std::vector<int>> faces;
  QColor color = QColor(190, 190, 200);  ///< the colour of every face when no per-vertex/per-face colours are given
  std::vector<QColor> vertex_colors;     ///< empty, or one per vertex (interpolated across triangles)
  std::vector<QColor> face_colors;       ///< empty, or one per face (wins over vertex_colors)
  bool wireframe = true;                 ///< draw the polygons' edges
  QColor wire_color = QColor(40, 40, 40);  ///< colour of the wireframe lines
  double wire_width = 1.0;                 ///< line width in output pixels (supersampling scales it)
};

/// Everything drawn in one image.
struct Scene {
  std::vector<Surface> surfaces;         ///< drawn with a shared depth buffer, so their order does not matter
  QColor background = QColor(255, 255, 255);  ///< colour where no surface is
};

/// Axis-aligned box in metres; empty (min > max) until something is added.
struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return !(min.array() <= max.array()).all(); }
  void add(const Eigen::Vector3d& p);  ///< ignores points with a NaN or infinite coordinate
  Eigen::Vector3d center() const { return 0.5 * (min + max); }
  double diagonal() const { return empty() ? 0.0 : (max - min).norm(); }
};

/// Box of the vertices that faces use (unused and non-finite vertices are
/// ignored, so a stray NaN or far-away unused point cannot spoil a fit).
BoundingBox bounds(const Surface& surface);
/// Box of all surfaces; empty when no surface has a usable vertex.
BoundingBox bounds(const Scene& scene);

}  // namespace mrcloth::render
