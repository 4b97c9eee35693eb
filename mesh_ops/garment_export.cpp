#include "garment_io.h"

#include "atomic_file.h"
#include "errors.h"
#include "garment_formats.h"
#include "mode_painting.h"
#include "om_checks.h"
#include "quadtree_forest.h"
#include "texture_coords.h"

// MeshIO.hh pulls in the reader and writer modules, which register
// themselves with the IOManager.
#include <OpenMesh/Core/IO/MeshIO.hh>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <limits>
#include <locale>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

/// Shortest text that reads back as exactly the same double.
std::string exact(double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc() ? std::string(buffer, end) : std::string("nan");
}

/// A polygon soup of the active surface, ready for the text writers.
struct Surface {
  std::vector<OpenMesh::Vec3d> points;
  std::vector<std::array<unsigned char, 3>> colors;  ///< one per point, or none
  std::vector<std::vector<int>> polygons;
  /// Per polygon, the texture coordinates of its corners (a vertex on a
  /// seam has one per side), or none.
  std::vector<std::vector<OpenMesh::Vec2d>> uvs;
};

Surface active_surface(const QuadMesh& mesh) {
  Surface surface;
  // Every vertex, deleted or not, so that a vertex's index is its line.
  surface.points.reserve(mesh.n_vertices());
  for (const auto v : mesh.all_vertices()) surface.points.push_back(mesh.point(v));
  surface.polygons.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {  // skips faces deleted but not yet collected
    std::vector<int> polygon;
    for (const auto v : f.vertices()) polygon.push_back(v.idx());
    surface.polygons.push_back(std::move(polygon));
  }
  surface.uvs = active_face_uvs(mesh);
  return surface;
}

double triangle_area(const OpenMesh::Vec3d& a, const OpenMesh::Vec3d& b, const OpenMesh::Vec3d& c) {
  return 0.5 * OpenMesh::cross(b - a, c - a).norm();
}

/// Fans every polygon into triangles. Hanging vertices lie on their edge, so
/// a fan from a corner next to one gives a zero-area sliver; the fan starts
/// at the corner whose smallest triangle is largest, and only when every
/// corner makes a sliver is the polygon fanned around an added centre point
/// (coloured like the polygon's first vertex). The choices are made on
/// `shape` (a point per surface point), so that every frame of one mesh,
/// chosen on its rest shape, gets the same triangles.
void triangulate(Surface& surface, const std::vector<OpenMesh::Vec3d>& shape) {
  std::vector<std::vector<int>> triangles;
  std::vector<std::vector<OpenMesh::Vec2d>> triangle_uvs;
  const bool textured = !surface.uvs.empty();
  for (std::size_t p = 0; p < surface.polygons.size(); ++p) {
    const std::vector<int>& polygon = surface.polygons[p];
    const std::size_t n = polygon.size();
    // The triangle of polygon corners i, j, k, with their texture coordinates.
    const auto add = [&](std::size_t i, std::size_t j, std::size_t k) {
      triangles.push_back({polygon[i], polygon[j], polygon[k]});
      if (textured) triangle_uvs.push_back({surface.uvs[p][i], surface.uvs[p][j], surface.uvs[p][k]});
    };
    if (n == 3) {
      add(0, 1, 2);
      continue;
    }
    double longest = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      longest = std::max(longest, (shape[polygon[(i + 1) % n]] - shape[polygon[i]]).norm());
    const double sliver = 1e-9 * longest * longest;
    std::size_t best_apex = 0;
    double best_smallest = -1.0;
    for (std::size_t apex = 0; apex < n; ++apex) {
      double smallest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 1; k + 1 < n; ++k) {
        smallest = std::min(smallest, triangle_area(shape[polygon[apex]], shape[polygon[(apex + k) % n]],
                                                    shape[polygon[(apex + k + 1) % n]]));
      }
      if (smallest > best_smallest) {
        best_smallest = smallest;
        best_apex = apex;
      }
    }
    if (best_smallest > sliver) {
      for (std::size_t k = 1; k + 1 < n; ++k) add(best_apex, (best_apex + k) % n, (best_apex + k + 1) % n);
      continue;
    }
    OpenMesh::Vec3d centre(0.0, 0.0, 0.0);
    for (const int v : polygon) centre += surface.points[static_cast<std::size_t>(v)];
    const int c = static_cast<int>(surface.points.size());
    surface.points.push_back(centre / static_cast<double>(n));
    if (!surface.colors.empty()) surface.colors.push_back(surface.colors[static_cast<std::size_t>(polygon[0])]);
    OpenMesh::Vec2d uv_centre(0.0, 0.0);
    if (textured)
      for (const OpenMesh::Vec2d& uv : surface.uvs[p]) uv_centre += uv / static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k) {
      triangles.push_back({polygon[k], polygon[(k + 1) % n], c});
      if (textured) triangle_uvs.push_back({surface.uvs[p][k], surface.uvs[p][(k + 1) % n], uv_centre});
    }
  }
  surface.polygons = std::move(triangles);
  surface.uvs = std::move(triangle_uvs);
}

void write_obj(std::ostream& out, const Surface& s) {
  out << "# mrcloth: " << s.points.size() << " vertices, " << s.polygons.size() << " faces\n";
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const OpenMesh::Vec3d& p = s.points[i];
    out << "v " << exact(p[0]) << ' ' << exact(p[1]) << ' ' << exact(p[2]);
    if (!s.colors.empty()) {
      // The common "v x y z r g b" extension, with channels in [0, 1].
      for (const unsigned char channel : s.colors[i]) out << ' ' << exact(channel / 255.0);
    }
    out << '\n';
  }
  // Texture coordinates one per polygon corner, in order: a seam needs
  // no special case.
  for (const auto& polygon : s.uvs)
    for (const OpenMesh::Vec2d& uv : polygon) out << "vt " << exact(uv[0]) << ' ' << exact(uv[1]) << '\n';
  std::size_t texcoord = 0;
  for (const std::vector<int>& polygon : s.polygons) {
    out << 'f';
    for (const int v : polygon) {
      out << ' ' << v + 1;
      if (!s.uvs.empty()) out << '/' << ++texcoord;
    }
    out << '\n';
  }
}

void write_off(std::ostream& out, const Surface& s) {
  out << "OFF\n" << s.points.size() << ' ' << s.polygons.size() << " 0\n";
  for (const OpenMesh::Vec3d& p : s.points) out << exact(p[0]) << ' ' << exact(p[1]) << ' ' << exact(p[2]) << '\n';
  for (const std::vector<int>& polygon : s.polygons) {
    out << polygon.size();
    for (const int v : polygon) out << ' ' << v;
    out << '\n';
  }
}

void write_ply(std::ostream& out, const Surface& s) {
  std::size_t widest = 0;
  for (const std::vector<int>& polygon : s.polygons) widest = std::max(widest, polygon.size());
  out << "ply\nformat ascii 1.0\ncomment written by mrcloth\nelement vertex " << s.points.size()
      << "\nproperty double x\nproperty double y\nproperty double z\n";
  if (!s.colors.empty()) out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out << "element face " << s.polygons.size() << "\nproperty list " << (widest > 255 ? "int" : "uchar")
      << " int vertex_indices\nend_header\n";
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const OpenMesh::Vec3d& p = s.points[i];
    out << exact(p[0]) << ' ' << exact(p[1]) << ' ' << exact(p[2]);
    if (!s.colors.empty()) {
      for (const unsigned char channel : s.colors[i]) out << ' ' << static_cast<int>(channel);
    }
    out << '\n';
  }
  for (const std::vector<int>& polygon : s.polygons) {
    out << polygon.size();
    for (const int v : polygon) out << ' ' << v;
    out << '\n';
  }
}

bool write_text(const std::string& file, const Surface& surface, Format format) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) return false;
  out.imbue(std::locale::classic());
  switch (format) {
    case Format::obj: write_obj(out, surface); break;
    case Format::off: write_off(out, surface); break;
    case Format::ply: write_ply(out, surface); break;
    case Format::om: return false;
  }
  out.close();
  return !out.fail();
}

bool has_deleted_elements(const QuadMesh& mesh) {
  if (mesh.has_vertex_status()) {
    for (const auto v : mesh.all_vertices())
      if (mesh.status(v).deleted()) return true;
  }
  if (mesh.has_edge_status()) {
    for (const auto e : mesh.all_edges())
      if (mesh.status(e).deleted()) return true;
  }
  if (mesh.has_face_status()) {
    for (const auto f : mesh.all_faces())
      if (mesh.status(f).deleted()) return true;
  }
  return false;
}

/// Encodes in memory, then writes the bytes with our own checks: OpenMesh's
/// OM writer asserts that every write succeeded, so a full disk aborted the
/// host instead of failing the write.
bool write_om(const QuadMesh& mesh, const std::string& file) {
  QuietOpenMesh quiet;
  std::ostringstream encoded(std::ios::binary);
  // The OM writer stores deleted-but-not-collected elements as live ones.
  if (has_deleted_elements(mesh)) {
    QuadMesh compact = copy_mesh(mesh);
    compact.garbage_collection();
    if (!OpenMesh::IO::write_mesh(compact, encoded, ".om", OpenMesh::IO::Options::Binary)) return false;
  } else if (!OpenMesh::IO::write_mesh(mesh, encoded, ".om", OpenMesh::IO::Options::Binary)) {
    return false;
  }
  std::ofstream out(file, std::ios::binary);
  std::string bytes = std::move(encoded).str();
  // The checksum layer's eight bytes take the hash of all the others.
  if (const ChecksumPlace place = checksum_place(bytes); place.present && !place.damaged) {
    const std::uint64_t hash = file_checksum(bytes, place.offset);
    for (std::size_t k = 0; k < 8; ++k) bytes[place.offset + k] = static_cast<char>((hash >> (8 * k)) & 0xff);
  }
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  return !out.fail();
}

Format output_format(const std::string& path, bool om_allowed) {
  const std::string extension = lower_extension(path);
  const std::optional<Format> format = format_of(extension);
  const bool allowed = format && (*format == Format::obj || *format == Format::ply ||
                                  (om_allowed && (*format == Format::off || *format == Format::om)));
  if (!allowed) {
    throw ArgumentError(with_path(path, "unknown output format (extension " + shown_extension(extension) +
                                            "); expected one of " +
                                            (om_allowed ? ".om, .obj, .off, .ply" : ".obj, .ply")));
  }
  return *format;
}

/// Per vertex, the finest level among the active faces around it, as the
/// previews colour faces: a coarse vertex inside a refined region is that
/// region's level (by the level that made it, it was a coarse speck there).
/// A vertex in no face keeps the level that made it.
std::vector<int> finest_face_levels(const QuadMesh& mesh) {
  std::vector<int> levels = vertex_levels(mesh);
  std::vector<int> finest(levels.size(), 0);
  const auto level = get_layers(mesh).level;
  for (const auto f : mesh.faces())
    for (const auto v : f.vertices()) {
      int& most = finest[static_cast<std::size_t>(v.idx())];
      most = std::max(most, mesh.property(level, f));
    }
  for (std::size_t v = 0; v < levels.size(); ++v)
    if (finest[v] > 0) levels[v] = finest[v];
  return levels;
}

}  // namespace

void save_mesh(const QuadMesh& mesh, const std::string& path) {
  const Format format = output_format(path, true);
  const std::string extension = lower_extension(path);
  if (format == Format::om) {
    write_file_atomically(path, extension, [&](const std::string& file) { return write_om(mesh, file); });
    return;
  }
  const Surface surface = active_surface(mesh);
  write_file_atomically(path, extension, [&](const std::string& file) { return write_text(file, surface, format); });
}

void export_surface(const QuadMesh& mesh, const std::string& path, const ExportOptions& options) {
  const Format format = output_format(path, false);
  Surface surface = active_surface(mesh);
  if (options.color_by == ColorBy::level) {
    const std::vector<int> levels = finest_face_levels(mesh);
    for (std::size_t v = 0; v < surface.points.size(); ++v)
      surface.colors.push_back(palette_color(v < levels.size() ? levels[v] : 0));
  } else if (options.color_by == ColorBy::mode) {
    const auto mode = get_layers(mesh).mode;
    for (const auto v : mesh.all_vertices()) surface.colors.push_back(palette_color(mesh.property(mode, v)));
  } else if (options.color_by == ColorBy::curvature) {
    const std::vector<double> curvature = vertex_layer(mesh, layer::mean_curvature);
    const double largest = curvature.empty() ? 0.0 : *std::max_element(curvature.begin(), curvature.end());
    for (const double k : curvature) surface.colors.push_back(sequential_color(largest > 0.0 ? k / largest : 0.0));
  }
  if (options.triangulate) {
    const QuadMesh& shape = options.triangles_of ? *options.triangles_of : mesh;
    if (shape.n_vertices() != mesh.n_vertices() || shape.n_faces() != mesh.n_faces())
      throw ArgumentError(with_path(path, "the mesh to triangulate as has " + std::to_string(shape.n_vertices()) +
                                              " vertices and " + std::to_string(shape.n_faces()) +
                                              " faces, the mesh exported " + std::to_string(mesh.n_vertices()) +
                                              " and " + std::to_string(mesh.n_faces()) +
                                              "; expected the same mesh at other positions"));
    std::vector<OpenMesh::Vec3d> shape_points;
    shape_points.reserve(shape.n_vertices());
    for (const auto v : shape.all_vertices()) shape_points.push_back(shape.point(v));
    triangulate(surface, shape_points);
  }
  write_file_atomically(path, lower_extension(path),
                        [&](const std::string& file) { return write_text(file, surface, format); });
}

}  // namespace mrcloth
