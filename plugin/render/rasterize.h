#pragma once
// Software z-buffer rendering of a Scene into a QImage: no GPU, no window,
// so previews work headless. Needs no QGuiApplication (no text is drawn).
#include "plugin/render/camera.h"
#include "plugin/render/scene.h"

#include <QImage>

namespace mrcloth::render {

/// How render() draws. Shading is Lambert with a directional light along
/// the view direction plus ambient, scaled so that a face seen straight on
/// shows exactly its colour (which makes colours testable), two-sided
/// because cloth is a single sheet: a back face is lit with its normal
/// flipped.
/// The most samples (width x height x supersample^2) one image may take:
/// keeps the buffers within a few GB even for silly requests.
constexpr long long kMaxRenderSamples = 1LL << 27;

struct RenderOptions {
  int width = 1024;             ///< output image width in pixels (> 0)
  int height = 768;             ///< output image height in pixels (> 0)
  int supersample = 2;          ///< samples per axis per output pixel, box-filtered down; 1 = off (exact colours, for tests)
  double ambient = 0.3;         ///< brightness (0..1) of a face seen edge-on; 1 - ambient is the Lambert part
  bool smooth_shading = true;   ///< interpolate vertex normals (Gouraud) instead of one normal per polygon
  /// How far (fraction of the scene's bounding-box diagonal) a wire may lie
  /// behind the surface at its pixel and still show: lines on the surface
  /// are kept, lines on the far side of a garment are hidden.
  double wire_depth_offset = 0.003;
};

/// Renders `scene` seen by `camera` into a Format_ARGB32 image of
/// options.width x options.height. Faces with a non-finite vertex, fewer
/// than 3 vertices or zero area are skipped; geometry behind the near plane
/// is clipped. Throws std::invalid_argument for a bad image size or
/// supersampling factor, a face index out of range, or a colour list whose
/// length is neither 0 nor the vertex/face count.
QImage render(const Scene& scene, const Camera& camera, const RenderOptions& options = {});

/// Convenience: a `preset` camera with `projection`, fit() to the scene with
/// `margin` (fraction of each image side left free), then render().
QImage render_preset(const Scene& scene, Preset preset, const RenderOptions& options = {},
                     Projection projection = Projection::perspective, double margin = 0.05);

}  // namespace mrcloth::render
