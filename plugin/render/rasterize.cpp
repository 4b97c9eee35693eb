#include "plugin/render/rasterize.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_set>

namespace mrcloth::render {
namespace {


struct Rgb {
  double r = 0, g = 0, b = 0;
};

Rgb operator*(const Rgb& c, double k) { return {c.r * k, c.g * k, c.b * k}; }
Rgb operator+(const Rgb& a, const Rgb& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }

Rgb to_rgb(const QColor& c) { return {double(c.red()), double(c.green()), double(c.blue())}; }

int channel(double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 255.0))); }

// The supersampled frame: packed colours and view depth (metres ahead of the eye).
struct Frame {
  int width = 0, height = 0;
  std::vector<QRgb> color;
  std::vector<float> depth;
};

// A triangle corner in view space with its shaded colour.
struct Corner {
  Eigen::Vector3d view;
  Rgb color;
};

// A projected corner: pixel position, view depth, colour.
struct Projected {
  double x, y, z;
  Rgb color;
};

void fill_triangle(Frame& frame, const Projector& projector, const std::array<Projected, 3>& v) {
  const double area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
  if (!(std::abs(area) > 1e-12) || !std::isfinite(area)) return;
  // Barycentric coordinate k as a linear function a*x + b*y + c of the pixel position.
  std::array<double, 3> a{}, b{}, c{};
  for (int k = 0; k < 3; ++k) {
    const Projected& p = v[(k + 1) % 3];
    const Projected& q = v[(k + 2) % 3];
    a[k] = (p.y - q.y) / area;
    b[k] = (q.x - p.x) / area;
    c[k] = (p.x * q.y - q.x * p.y) / area;
  }
  const bool perspective = projector.perspective();
  // Perspective-correct interpolation: 1/z and attribute/z are linear on screen.
  std::array<double, 3> w{}, z{};
  std::array<Rgb, 3> col{};
  for (int k = 0; k < 3; ++k) {
    w[k] = perspective ? 1.0 / v[k].z : 1.0;
    z[k] = perspective ? w[k] : v[k].z;
    col[k] = v[k].color * w[k];
  }

  const double min_y = std::min({v[0].y, v[1].y, v[2].y});
  const double max_y = std::max({v[0].y, v[1].y, v[2].y});
  const int row_begin = static_cast<int>(std::max(0.0, std::ceil(min_y - 0.5)));
  const int row_end = static_cast<int>(std::min(double(frame.height - 1), std::floor(max_y - 0.5)));
  // Slightly inclusive, so pixel centres on an edge shared by two triangles are never missed by both.
  constexpr double eps = 1e-9;
  for (int j = row_begin; j <= row_end; ++j) {
    const double py = j + 0.5;
    double lo = 0.0, hi = frame.width - 1.0;  // pixel-centre x range, as indices
    bool empty = false;
    for (int k = 0; k < 3 && !empty; ++k) {
      const double r = b[k] * py + c[k];
      if (a[k] > 0)
        lo = std::max(lo, std::ceil((-eps - r) / a[k] - 0.5));
      else if (a[k] < 0)
        hi = std::min(hi, std::floor((-eps - r) / a[k] - 0.5));
      else if (r < -eps)
        empty = true;
    }
    if (empty || !(lo <= hi)) continue;
    const int i_begin = static_cast<int>(lo), i_end = static_cast<int>(hi);
    QRgb* color_row = frame.color.data() + std::size_t(j) * frame.width;
    float* depth_row = frame.depth.data() + std::size_t(j) * frame.width;
    for (int i = i_begin; i <= i_end; ++i) {
      const double px = i + 0.5;
      const double b0 = a[0] * px + b[0] * py + c[0];
      const double b1 = a[1] * px + b[1] * py + c[1];
      const double b2 = 1.0 - b0 - b1;
      const double zi = b0 * z[0] + b1 * z[1] + b2 * z[2];
      const double depth = perspective ? 1.0 / zi : zi;
      if (!(depth < depth_row[i])) continue;
      const double norm = perspective ? depth : 1.0;
      depth_row[i] = static_cast<float>(std::min(depth, double(std::numeric_limits<float>::max())));
      color_row[i] = qRgb(channel((b0 * col[0].r + b1 * col[1].r + b2 * col[2].r) * norm),
                          channel((b0 * col[0].g + b1 * col[1].g + b2 * col[2].g) * norm),
                          channel((b0 * col[0].b + b1 * col[1].b + b2 * col[2].b) * norm));
    }
  }
}

Corner lerp(const Corner& p, const Corner& q, double t) {
  return {p.view + t * (q.view - p.view), p.color * (1.0 - t) + q.color * t};
}

// Clips against the near plane (Sutherland-Hodgman on one plane: at most 4
// corners come out), projects, and fills as a fan.
void draw_triangle(Frame& frame, const Projector& projector, const std::array<Corner, 3>& tri) {
  const double near = projector.near_plane();
  std::array<Corner, 4> clipped;
  int count = 0;
  const bool all_in = tri[0].view.z() >= near && tri[1].view.z() >= near && tri[2].view.z() >= near;
  if (all_in) {
    for (int k = 0; k < 3; ++k) clipped[count++] = tri[k];
  } else {
    for (int k = 0; k < 3; ++k) {
      const Corner& p = tri[k];
      const Corner& q = tri[(k + 1) % 3];
      const bool p_in = p.view.z() >= near, q_in = q.view.z() >= near;
      if (p_in) clipped[count++] = p;
      if (p_in != q_in) clipped[count++] = lerp(p, q, (near - p.view.z()) / (q.view.z() - p.view.z()));
    }
  }
  if (count < 3) return;
  std::array<Projected, 4> projected;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d pixel = projector.view_to_pixel(clipped[k].view);
    projected[k] = {pixel.x(), pixel.y(), clipped[k].view.z(), clipped[k].color};
  }
  for (int k = 1; k + 1 < count; ++k)
    fill_triangle(frame, projector, {projected[0], projected[k], projected[k + 1]});
}

// A line of `width` pixels from p to q (pixel x, y, view depth), drawn where
// its depth is at most the surface's plus `offset`; depth is not written, so
// lines never hide each other or the surfaces.
void draw_line(Frame& frame, bool perspective, Eigen::Vector3d p, Eigen::Vector3d q, double width, QRgb color,
               double offset) {
  const double half = 0.5 * width;
  bool x_major = std::abs(q.x() - p.x()) >= std::abs(q.y() - p.y());
  // Work in (major, minor) coordinates so one loop serves both orientations.
  if (!x_major) {
    std::swap(p.x(), p.y());
    std::swap(q.x(), q.y());
  }
  if (p.x() > q.x()) std::swap(p, q);
  const int major_size = x_major ? frame.width : frame.height;
  const int minor_size = x_major ? frame.height : frame.width;
  const double d_major = q.x() - p.x();
  const double slope = d_major > 1e-12 ? (q.y() - p.y()) / d_major : 0.0;
  const double half_minor = half * std::sqrt(1.0 + slope * slope);
  const double begin = std::max(0.0, std::ceil(p.x() - half - 0.5));
  const double end = std::min(major_size - 1.0, std::ceil(q.x() + half - 0.5) - 1.0);
  for (double m = begin; m <= end; m += 1.0) {
    const double t = d_major > 1e-12 ? std::clamp((m + 0.5 - p.x()) / d_major, 0.0, 1.0) : 0.0;
    const double center = p.y() + t * (q.y() - p.y());
    if (!std::isfinite(center)) continue;
    const double depth = perspective ? 1.0 / ((1.0 - t) / p.z() + t / q.z()) : p.z() + t * (q.z() - p.z());
    const double n_begin = std::max(0.0, std::ceil(center - half_minor - 0.5));
    const double n_end = std::min(minor_size - 1.0, std::ceil(center + half_minor - 0.5) - 1.0);
    for (double n = n_begin; n <= n_end; n += 1.0) {
      const int i = static_cast<int>(x_major ? m : n), j = static_cast<int>(x_major ? n : m);
      const std::size_t index = std::size_t(j) * frame.width + i;
      if (depth <= frame.depth[index] + offset) frame.color[index] = color;
    }
  }
}

void draw_edge(Frame& frame, const Projector& projector, Eigen::Vector3d a, Eigen::Vector3d b, double width,
               QRgb color, double offset) {
  const double near = projector.near_plane();
  if (a.z() < near && b.z() < near) return;
  if (a.z() < near) a = a + (near - a.z()) / (b.z() - a.z()) * (b - a);
  if (b.z() < near) b = b + (near - b.z()) / (a.z() - b.z()) * (a - b);
  Eigen::Vector2d pa = projector.view_to_pixel(a), pb = projector.view_to_pixel(b);
  if (!pa.allFinite() || !pb.allFinite()) return;
  // Clip to the image (plus the line width) so huge coordinates from points
  // near the eye cannot overflow the line's arithmetic (Liang-Barsky).
  const Eigen::Vector2d lo(-width - 1.0, -width - 1.0);
  const Eigen::Vector2d hi(frame.width + width + 1.0, frame.height + width + 1.0);
  const Eigen::Vector2d d = pb - pa;
  double t0 = 0.0, t1 = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) {
      if (pa[axis] < lo[axis] || pa[axis] > hi[axis]) return;
      continue;
    }
    double ta = (lo[axis] - pa[axis]) / d[axis], tb = (hi[axis] - pa[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return;
  // Depth along the screen segment: 1/z is linear in perspective, z in orthographic.
  auto depth_at = [&](double t) {
    return projector.perspective() ? 1.0 / ((1.0 - t) / a.z() + t / b.z()) : a.z() + t * (b.z() - a.z());
  };
  const Eigen::Vector2d qa = pa + t0 * d, qb = pa + t1 * d;
  if (!qa.allFinite() || !qb.allFinite()) return;
  draw_line(frame, projector.perspective(), {qa.x(), qa.y(), depth_at(t0)}, {qb.x(), qb.y(), depth_at(t1)}, width,
            color, offset);
}

void validate(const Surface& surface, std::size_t index) {
  const auto rows = surface.positions.rows();
  const std::string name = "render: surface " + std::to_string(index);
  for (std::size_t f = 0; f < surface.faces.size(); ++f)
    for (int v : surface.faces[f])
      if (v < 0 || v >= rows)
        throw std::invalid_argument(name + ", face " + std::to_string(f) + ": vertex index " + std::to_string(v) +
                                    " out of range (" + std::to_string(rows) + " vertices)");
  if (!surface.vertex_colors.empty() && surface.vertex_colors.size() != std::size_t(rows))
    throw std::invalid_argument(name + ": " + std::to_string(surface.vertex_colors.size()) +
                                " vertex colours for " + std::to_string(rows) + " vertices");
  if (!surface.face_colors.empty() && surface.face_colors.size() != surface.faces.size())
    throw std::invalid_argument(name + ": " + std::to_string(surface.face_colors.size()) + " face colours for " +
                                std::to_string(surface.faces.size()) + " faces");
}

// Newell's normal: robust for polygons with collinear (hanging) vertices;
// its length is twice the polygon's area, which weights vertex normals.
Eigen::Vector3d polygon_normal(const Surface& surface, const std::vector<int>& face) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < face.size(); ++k) {
    const Eigen::Vector3d p = surface.positions.row(face[k]).transpose();
    const Eigen::Vector3d q = surface.positions.row(face[(k + 1) % face.size()]).transpose();
    n += (p - q).cross(p + q) * 0.5;
  }
  return n;
}

bool face_usable(const std::vector<int>& face, const std::vector<char>& finite) {
  if (face.size() < 3) return false;
  for (int v : face)
    if (!finite[v]) return false;
  return true;
}

/// Every vertex in view space, and whether it was finite (non-finite ones are skipped, not projected).
void to_view_space(const Projector& projector, const Surface& surface, std::vector<Eigen::Vector3d>& view,
                   std::vector<char>& finite) {
  const auto rows = static_cast<int>(surface.positions.rows());
  view.assign(rows, Eigen::Vector3d::Zero());
  finite.assign(rows, 0);
  for (int v = 0; v < rows; ++v) {
    const Eigen::Vector3d p = surface.positions.row(v).transpose();
    finite[v] = p.allFinite();
    if (finite[v]) view[v] = projector.to_view(p);
  }
}

void draw_surface(Frame& frame, const Projector& projector, const Surface& surface, const RenderOptions& options) {
  const auto rows = static_cast<int>(surface.positions.rows());
  std::vector<Eigen::Vector3d> view;
  std::vector<char> finite;
  to_view_space(projector, surface, view, finite);
  const Eigen::Vector3d light = -projector.forward();
  const double ambient = std::clamp(options.ambient, 0.0, 1.0);
  auto intensity = [&](const Eigen::Vector3d& normal) {
    const double length = normal.norm();
    if (!(length > 0.0)) return ambient;
    return ambient + (1.0 - ambient) * std::min(1.0, std::abs(normal.dot(light)) / length);
  };

  std::vector<Eigen::Vector3d> face_normals(surface.faces.size(), Eigen::Vector3d::Zero());
  for (std::size_t f = 0; f < surface.faces.size(); ++f)
    if (face_usable(surface.faces[f], finite)) face_normals[f] = polygon_normal(surface, surface.faces[f]);

  std::vector<double> vertex_intensity;
  if (options.smooth_shading) {
    std::vector<Eigen::Vector3d> normals(rows, Eigen::Vector3d::Zero());
    for (std::size_t f = 0; f < surface.faces.size(); ++f) {
      // Two-sided shading uses |n . l| anyway; orienting each face's normal
      // towards the light keeps inconsistently wound neighbours from cancelling.
      const Eigen::Vector3d n = face_normals[f].dot(light) < 0 ? -face_normals[f] : face_normals[f];
      for (int v : surface.faces[f]) normals[v] += n;
    }
    vertex_intensity.resize(rows);
    for (int v = 0; v < rows; ++v) vertex_intensity[v] = intensity(normals[v]);
  }

  const Rgb uniform = to_rgb(surface.color);
  std::vector<Rgb> vertex_rgb;
  for (const QColor& c : surface.vertex_colors) vertex_rgb.push_back(to_rgb(c));

  for (std::size_t f = 0; f < surface.faces.size(); ++f) {
    const auto& face = surface.faces[f];
    if (!face_usable(face, finite)) continue;
    const double face_intensity = intensity(face_normals[f]);
    const Rgb face_rgb = surface.face_colors.empty() ? uniform : to_rgb(surface.face_colors[f]);
    auto corner = [&](int v) {
      const Rgb base = (!surface.face_colors.empty() || vertex_rgb.empty()) ? face_rgb : vertex_rgb[v];
      const double k = options.smooth_shading ? vertex_intensity[v] : face_intensity;
      return Corner{view[v], base * k};
    };
    const Corner first = corner(face[0]);
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
      draw_triangle(frame, projector, {first, corner(face[k]), corner(face[k + 1])});
  }
}

void draw_wireframe(Frame& frame, const Projector& projector, const Surface& surface, double width, double offset) {
  std::vector<Eigen::Vector3d> view;
  std::vector<char> finite;
  to_view_space(projector, surface, view, finite);
  const QRgb color = qRgb(surface.wire_color.red(), surface.wire_color.green(), surface.wire_color.blue());
  std::unordered_set<std::uint64_t> drawn;  // shared edges once: halves the work
  drawn.reserve(surface.faces.size() * 2);
  for (const auto& face : surface.faces) {
    if (!face_usable(face, finite)) continue;
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int a = face[k], b = face[(k + 1) % face.size()];
      if (a == b) continue;
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint32_t(std::max(a, b));
      if (!drawn.insert(key).second) continue;
      draw_edge(frame, projector, view[a], view[b], width, color, offset);
    }
  }
}

QImage downsample(const Frame& frame, int factor, int width, int height) {
  QImage image(width, height, QImage::Format_ARGB32);
  const int count = factor * factor;
  for (int y = 0; y < height; ++y) {
    auto* out = reinterpret_cast<QRgb*>(image.scanLine(y));
    for (int x = 0; x < width; ++x) {
      int r = 0, g = 0, b = 0, a = 0;
      for (int sy = 0; sy < factor; ++sy) {
        const QRgb* in = frame.color.data() + std::size_t(y * factor + sy) * frame.width + std::size_t(x) * factor;
        for (int sx = 0; sx < factor; ++sx) {
          r += qRed(in[sx]);
          g += qGreen(in[sx]);
          b += qBlue(in[sx]);
          a += qAlpha(in[sx]);
        }
      }
      const int h = count / 2;  // round to nearest
      out[x] = qRgba((r + h) / count, (g + h) / count, (b + h) / count, (a + h) / count);
    }
  }
  return image;
}

}  // namespace

QImage render(const Scene& scene, const Camera& camera, const RenderOptions& options) {
  if (options.width <= 0 || options.height <= 0)
    throw std::invalid_argument("render: image size must be positive, got " + std::to_string(options.width) + " x " +
                                std::to_string(options.height));
  if (options.supersample < 1 || options.supersample > 8)
    throw std::invalid_argument("render: supersample must be 1..8, got " + std::to_string(options.supersample));
  const int factor = options.supersample;
  if (static_cast<long long>(options.width) * options.height * factor * factor > kMaxRenderSamples)
    throw std::invalid_argument("render: image too large (" + std::to_string(options.width) + " x " +
                                std::to_string(options.height) + " at " + std::to_string(factor) +
                                "x supersampling)");
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) validate(scene.surfaces[s], s);

  Frame frame;
  frame.width = options.width * factor;
  frame.height = options.height * factor;
  const QColor& bg = scene.background;
  frame.color.assign(std::size_t(frame.width) * frame.height, qRgba(bg.red(), bg.green(), bg.blue(), bg.alpha()));
  frame.depth.assign(frame.color.size(), std::numeric_limits<float>::infinity());

  const Projector projector(camera, frame.width, frame.height);
  for (const auto& surface : scene.surfaces) draw_surface(frame, projector, surface, options);
  // Wires after every fill, so the depth test sees all surfaces.
  const double offset = std::max(0.0, options.wire_depth_offset) * std::max(bounds(scene).diagonal(), 1e-9);
  for (const auto& surface : scene.surfaces)
    if (surface.wireframe && surface.wire_width > 0)
      draw_wireframe(frame, projector, surface, surface.wire_width * factor, offset);

  return downsample(frame, factor, options.width, options.height);
}

QImage render_preset(const Scene& scene, Preset preset, const RenderOptions& options, Projection projection,
                     double margin) {
  Camera camera = preset_camera(preset, projection);
  fit(camera, scene, options.width, options.height, margin);
  return render(scene, camera, options);
}

}  // namespace mrcloth::render
