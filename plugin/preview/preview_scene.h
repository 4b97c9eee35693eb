#pragma once
// From mrcloth's data to what the renderer draws: a garment (an object of
// the store, at rest or at a frame of its PC2 cache) coloured by one of its
// layers, with the legend that explains the colours, and a body from its
// cache (the rest OBJ and PC2 that simulate's bodyOutput writes).
#include "mesh_ops/garment_io.h"
#include "mesh_ops/quad_mesh.h"
#include "plugin/render/camera.h"
#include "plugin/render/legend.h"
#include "plugin/render/scene.h"

#include <QImage>
#include <QString>

#include <optional>
#include <string>
#include <vector>

namespace mrcloth::preview {

/// A garment ready to draw and the key to its colours.
struct GarmentLayer {
  render::Surface surface;
  std::vector<render::LegendEntry> legend;  ///< modes or levels present; empty for none / curvature
  std::optional<render::ColorBar> color_bar;  ///< curvature only: 0 .. the largest mean curvature, 1/m
};

/// The active faces of `mesh` at `positions` (#vertices x 3, metres; empty:
/// the mesh's own points) coloured by `color_by`: modes and curvature per
/// vertex (the mesh's mode / mean_curvature layers), levels per face, with
/// the palette of the PLY exports (palette_color, sequential_color).
/// Throws ArgumentError when positions do not match the vertex count, and
/// when curvature is asked of a mesh without the mean_curvature layer.
GarmentLayer garment_layer(const QuadMesh& mesh, const Eigen::MatrixX3d& positions, ColorBy color_by);

/// How a picture of a scene is framed and annotated.
struct PictureOptions {
  int width = 800;                                             ///< pixels
  int height = 800;                                            ///< pixels
  int supersample = 2;                                         ///< samples per pixel along each side
  render::Preset camera = render::Preset::front;               ///< where the camera looks from
  render::Projection projection = render::Projection::perspective;
  double margin = 0.08;                                        ///< fraction of the framed area left free
  QString title;                                               ///< centred at the top; empty = none
  bool legend = true;                                          ///< the garment's legend or colour bar, from 240 pixels
};

/// Smallest side (pixels) a picture draws its legend at: on a thumbnail it
/// would cover the garment.
inline constexpr int kLeastLegendSide = 240;

/// `scene` seen by `options.camera` fitted to `box`, with the title and
/// `garment`'s legend (top right) or colour bar (bottom right). The legend
/// takes a column of its own on the right and the title a band at the top,
/// the garment framed in the rest (they covered it on small pictures),
/// unless the column would take more than 45 % of the width or the band
/// half the height (then they are drawn over the picture).
QImage draw_picture(const render::Scene& scene, const render::BoundingBox& box, const GarmentLayer& garment,
                    const PictureOptions& options);

/// The largest value of the mesh's mean_curvature layer (1/m); throws
/// ArgumentError naming extractModes when the mesh has no such layer.
double largest_curvature(const QuadMesh& mesh);

/// The positions of frame `frame` (0-based) of a PC2 cache; InputError
/// naming the file for a bad cache, ArgumentError for a frame out of range
/// or a point count other than `expected_points` (when >= 0).
Eigen::MatrixX3d cache_frame(const std::string& cache_path, int frame, int expected_points = -1);

/// Number of frames in a PC2 cache.
int cache_frames(const std::string& cache_path);

/// A body cache's frames drawn in grey without wireframe: the faces of its
/// rest OBJ, read once (a skinned body's is megabytes: reading it took
/// most of a sequence's time per frame), at any frame of the cache.
class BodyFrames {
 public:
  /// obj_path: the rest OBJ written beside the body cache; cache_path: the PC2.
  BodyFrames(const std::string& obj_path, const std::string& cache_path);
  /// The body at frame `frame` (0-based); ArgumentError when out of range.
  render::Surface at(int frame) const;

 private:
  std::string cache_path_;
  int points_ = 0;          ///< the rest OBJ's vertex count, which every frame must have
  render::Surface faces_;   ///< its faces and how they are drawn; positions come from each frame
};

}  // namespace mrcloth::preview
