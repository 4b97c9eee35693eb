#include "preview_scene.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/mode_painting.h"
#include "plugin/render/rasterize.h"
#include "solver/point_cache.h"

#include <QPainter>

#include <algorithm>
#include <map>
#include <set>
#include <string>

namespace mrcloth::preview {
namespace {

QColor to_qcolor(const std::array<unsigned char, 3>& rgb) { return QColor(rgb[0], rgb[1], rgb[2]); }

/// The garment's colour when it is coloured by nothing: a light cloth blue.
const QColor kClothColor(176, 196, 222);
const QColor kBodyColor(205, 200, 195);

}  // namespace

GarmentLayer garment_layer(const QuadMesh& mesh, const Eigen::MatrixX3d& positions, ColorBy color_by) {
  const auto vertex_count = static_cast<Eigen::Index>(mesh.n_vertices());
  if (positions.rows() != 0 && positions.rows() != vertex_count)
    throw ArgumentError("the positions have " + std::to_string(positions.rows()) + " points, the mesh has " +
                        std::to_string(vertex_count) + " vertices");
  GarmentLayer result;
  render::Surface& surface = result.surface;
  if (positions.rows() != 0) {
    surface.positions = positions;
  } else {
    surface.positions.resize(vertex_count, 3);
    for (const auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      surface.positions.row(v.idx()) << p[0], p[1], p[2];
    }
  }
  surface.faces = active_face_polygons(mesh);
  surface.color = kClothColor;

  switch (color_by) {
    case ColorBy::none:
      break;
    case ColorBy::mode: {
      const Layers layers = get_layers(mesh);
      std::set<int> present;
      for (const auto v : mesh.vertices()) {
        const int mode = mesh.property(layers.mode, v);
        surface.vertex_colors.push_back(to_qcolor(palette_color(mode)));
        present.insert(mode);
      }
      for (const int mode : present)
        result.legend.push_back({to_qcolor(palette_color(mode)), QStringLiteral("mode %1").arg(mode)});
      break;
    }
    case ColorBy::level: {
      const Layers layers = get_layers(mesh);
      std::map<int, int> faces_per_level;
      for (const auto f : mesh.faces()) {
        const int level = mesh.property(layers.level, f);
        surface.face_colors.push_back(to_qcolor(palette_color(level)));
        ++faces_per_level[level];
      }
      for (const auto& [level, count] : faces_per_level)
        result.legend.push_back({to_qcolor(palette_color(level)), QStringLiteral("level %1 (%2 faces)").arg(level).arg(count)});
      break;
    }
    case ColorBy::curvature: {
      const double largest = largest_curvature(mesh);
      const std::vector<double> curvature = vertex_layer(mesh, layer::mean_curvature);
      for (const double k : curvature)
        surface.vertex_colors.push_back(to_qcolor(sequential_color(largest > 0.0 ? k / largest : 0.0)));
      render::ColorBar bar;
      bar.color_map = [](double t) { return to_qcolor(sequential_color(t)); };
      bar.min_value = 0.0;
      bar.max_value = largest;
      bar.label = QStringLiteral("mean curvature (1/m)");
      result.color_bar = bar;
      break;
    }
  }
  return result;
}

QImage draw_picture(const render::Scene& scene, const render::BoundingBox& box, const GarmentLayer& garment,
                    const PictureOptions& options) {
  const bool legend = options.legend && std::min(options.width, options.height) >= kLeastLegendSide &&
                      (!garment.legend.empty() || garment.color_bar);
  const render::LegendStyle style;
  int column = 0;
  if (legend) {
    const int widest = std::max(render::legend_size(garment.legend, style).width(),
                                garment.color_bar ? render::color_bar_size(*garment.color_bar, style).width() : 0);
    column = widest + 2 * style.margin;
    if (column > 0.45 * options.width) column = 0;
  }
  // Likewise the title's band at the top (it covered the garment's top on
  // short pictures), unless it would take half the height.
  int band = render::title_band(options.title, style);
  if (band > options.height / 2) band = 0;
  render::Camera camera = render::preset_camera(options.camera, options.projection);
  render::fit(camera, box, options.width - column, options.height - band, options.margin);
  render::RenderOptions rendering;
  rendering.width = options.width - column;
  rendering.height = options.height - band;
  rendering.supersample = options.supersample;
  QImage image = render::render(scene, camera, rendering);
  if (column > 0 || band > 0) {
    QImage whole(options.width, options.height, image.format());
    whole.fill(scene.background);
    QPainter(&whole).drawImage(0, band, image);
    image = whole;
  }
  // The legend goes below the title: on a narrow image they would overlap.
  QRect below_title = image.rect();
  if (!options.title.isEmpty()) below_title.setTop(render::draw_title(image, options.title, style).bottom() + 1);
  if (legend) {
    QPainter painter(&image);
    render::draw_legend(painter, below_title, garment.legend, render::Corner::top_right, style);
    if (garment.color_bar)
      render::draw_color_bar(painter, below_title, *garment.color_bar, render::Corner::bottom_right, style);
  }
  return image;
}

double largest_curvature(const QuadMesh& mesh) {
  OpenMesh::VPropHandleT<double> handle;
  if (!mesh.get_property_handle(handle, layer::mean_curvature))
    throw ArgumentError("the mesh has no mean_curvature layer: run multirescloth.extractModes on it first");
  const std::vector<double> curvature = vertex_layer(mesh, layer::mean_curvature);
  return curvature.empty() ? 0.0 : *std::max_element(curvature.begin(), curvature.end());
}

Eigen::MatrixX3d cache_frame(const std::string& cache_path, int frame, int expected_points) {
  Pc2Reader reader(cache_path);
  if (expected_points >= 0 && reader.num_points() != expected_points)
    throw ArgumentError(cache_path + ": the cache has " + std::to_string(reader.num_points()) +
                        " points, the mesh has " + std::to_string(expected_points) + " vertices");
  if (frame < 0 || frame >= reader.num_frames())
    throw ArgumentError(cache_path + ": frame " + std::to_string(frame) + " out of range (the cache has " +
                        std::to_string(reader.num_frames()) + " frames, 0 .. " + std::to_string(reader.num_frames() - 1) +
                        ")");
  return reader.finite_frame(frame);
}

int cache_frames(const std::string& cache_path) { return Pc2Reader(cache_path).num_frames(); }

BodyFrames::BodyFrames(const std::string& obj_path, const std::string& cache_path) : cache_path_(cache_path) {
  ObjMesh mesh = read_obj(obj_path);
  points_ = static_cast<int>(mesh.positions.rows());
  faces_.faces = std::move(mesh.faces);
  faces_.color = kBodyColor;
  faces_.wireframe = false;
}

render::Surface BodyFrames::at(int frame) const {
  render::Surface surface = faces_;
  surface.positions = cache_frame(cache_path_, frame, points_);
  return surface;
}

}  // namespace mrcloth::preview
