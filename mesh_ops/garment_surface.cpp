#include "garment_surface.h"

#include "errors.h"
#include "texture_coords.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

using VertexHandle = OpenMesh::VertexHandle;

/// One midpoint split of every face: an n-gon becomes n quads around its
/// vertex centroid. Splitting the quads too keeps the result conforming.
/// Vertices: the input's (same indices), then one midpoint per edge in edge
/// order, then one centre per face in face order. `origins`, if given,
/// receives each new quad's origin, in face order.
QuadMesh split_into_quads(const QuadMesh& in, std::vector<SplitQuad>* origins = nullptr) {
  QuadMesh out;
  out.reserve(in.n_vertices() + in.n_edges() + in.n_faces(), 4 * in.n_edges(), 2 * in.n_edges());
  for (const auto v : in.vertices()) out.add_vertex(in.point(v));
  std::vector<VertexHandle> midpoint(in.n_edges());
  for (const auto e : in.edges())
    midpoint[static_cast<std::size_t>(e.idx())] = out.add_vertex(0.5 * (in.point(e.v0()) + in.point(e.v1())));
  std::vector<VertexHandle> centre(in.n_faces());
  for (const auto f : in.faces()) {
    OpenMesh::Vec3d sum(0.0, 0.0, 0.0);
    double n = 0.0;
    for (const auto v : f.vertices()) {
      sum += in.point(v);
      n += 1.0;
    }
    centre[static_cast<std::size_t>(f.idx())] = out.add_vertex(sum / n);
  }
  for (const auto f : in.faces()) {
    std::vector<OpenMesh::SmartHalfedgeHandle> sides(f.halfedges().begin(), f.halfedges().end());
    for (std::size_t i = 0; i < sides.size(); ++i) {
      const auto& incoming = sides[(i + sides.size() - 1) % sides.size()];
      const auto& outgoing = sides[i];
      const VertexHandle corner = outgoing.from();
      const VertexHandle corners[4] = {corner, midpoint[static_cast<std::size_t>(outgoing.edge().idx())],
                                       centre[static_cast<std::size_t>(f.idx())],
                                       midpoint[static_cast<std::size_t>(incoming.edge().idx())]};
      const OpenMesh::FaceHandle quad = out.add_face(corners[0], corners[1], corners[2], corners[3]);
      if (!quad.is_valid()) throw Error("split_into_quads: a quad of face " + std::to_string(f.idx()) + " was refused");
      if (origins)
        origins->push_back({f.idx(), incoming.from().idx(), corner.idx(), outgoing.to().idx(),
                            {corners[0].idx(), corners[1].idx(), corners[2].idx(), corners[3].idx()}});
    }
  }
  return out;
}

std::string plural(std::size_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

}  // namespace

void make_all_quad(QuadMesh& mesh, const std::string& path, std::vector<std::string>& warnings,
                   std::vector<SplitQuad>& origins) {
  std::size_t triangles = 0;
  std::size_t ngons = 0;
  for (const auto f : mesh.faces()) {
    const auto valence = f.valence();
    if (valence == 3) ++triangles;
    if (valence > 4) ++ngons;
  }
  if (triangles == 0 && ngons == 0) return;
  const std::size_t before = mesh.n_vertices();
  mesh = split_into_quads(mesh, &origins);
  warnings.push_back(with_path(
      path, plural(triangles, "triangle") + " and " + plural(ngons, "n-gon") +
                " (n > 4) found; every face was split into quads at its centre and edge midpoints, so the mesh "
                "now has " +
                std::to_string(mesh.n_vertices()) + " vertices instead of " + std::to_string(before) + " and " +
                std::to_string(mesh.n_faces()) + " faces"));
}

void read_texture_coords(const TextScan& scan, QuadMesh& mesh, std::size_t faces_read,
                         const std::vector<SplitQuad>& split, const std::string& path,
                         std::vector<std::string>& warnings) {
  if (scan.texcoords.empty()) return;
  const auto skip = [&](const std::string& why) {
    warnings.push_back(with_path(path, "its texture coordinates (vt) are not kept: " + why));
  };
  if (!scan.uv_readable) return skip("a vt line or a face's texture index could not be read");
  if (scan.face_corners.size() != faces_read) return skip("the file's faces could not be matched to the mesh's");
  // The UV file face `face` gives its corner at vertex `vertex` (false: none).
  const auto uv_at = [&](std::size_t face, int vertex, OpenMesh::Vec2d& uv) {
    const auto& corners = scan.face_corners[face];
    const auto found = std::find_if(corners.begin(), corners.end(), [&](const auto& c) { return c.first == vertex; });
    if (found == corners.end() || found->second < 0) return false;
    uv = scan.texcoords[static_cast<std::size_t>(found->second)];
    return true;
  };
  const auto& forest = quadtree(mesh);
  std::vector<RecordUV> uvs(forest.size());
  for (std::size_t i = 0; i < forest.size(); ++i) {
    // Per quad vertex, its UV: the file's, or (a quad of a split face) the
    // mean of its face's corners' at an edge midpoint or the centre, as its
    // position was made.
    std::array<std::pair<int, OpenMesh::Vec2d>, 4> known;
    bool complete = true;
    if (split.empty()) {
      for (int k = 0; k < 4; ++k) {
        const int v = forest[i].corners[static_cast<std::size_t>(k)];
        known[static_cast<std::size_t>(k)].first = v;
        complete = complete && uv_at(i, v, known[static_cast<std::size_t>(k)].second);
      }
    } else {
      const SplitQuad& q = split[i];
      const auto face = static_cast<std::size_t>(q.face);
      OpenMesh::Vec2d previous, corner, next, centre(0.0, 0.0);
      complete = uv_at(face, q.corner, corner) && uv_at(face, q.previous, previous) && uv_at(face, q.next, next);
      const auto& corners = scan.face_corners[face];
      for (const auto& c : corners) {
        OpenMesh::Vec2d uv;
        complete = complete && uv_at(face, static_cast<int>(c.first), uv);
        centre += uv / static_cast<double>(corners.size());
      }
      known = {{{q.vertices[0], corner}, {q.vertices[1], 0.5 * (corner + next)}, {q.vertices[2], centre},
                {q.vertices[3], 0.5 * (corner + previous)}}};
    }
    if (!complete)
      return skip("face " + std::to_string(split.empty() ? i : static_cast<std::size_t>(split[i].face)) +
                  " has a corner without one; expected one at every corner");
    for (int k = 0; k < 4; ++k) {
      const int v = forest[i].corners[static_cast<std::size_t>(k)];
      const auto at = std::find_if(known.begin(), known.end(), [&](const auto& entry) { return entry.first == v; });
      if (at == known.end()) return skip("the file's faces could not be matched to the mesh's");
      uvs[i].corner[static_cast<std::size_t>(k)] = at->second;
    }
  }
  set_record_uvs(mesh, std::move(uvs));
}

void check_garment_surface(const std::string& path, const QuadMesh& mesh, const ElementLines& lines) {
  for (const auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) {
      std::size_t loose = 0;
      for (const auto u : mesh.vertices()) loose += mesh.is_isolated(u) ? 1 : 0;
      throw InputError(with_path(path, lines.vertex_name(v.idx()) + " belongs to no face" +
                                           (loose > 1 ? " (nor do " + std::to_string(loose - 1) + " more)" : "") +
                                           "; expected every vertex in a face (delete loose vertices)"));
    }
    if (!mesh.is_manifold(v))
      throw InputError(with_path(path, lines.vertex_name(v.idx()) +
                                           " is non-manifold (two fans of faces meet only at it, a bow-tie); "
                                           "expected an oriented 2-manifold quad mesh"));
  }
  for (const auto f : mesh.faces()) {
    // Twice the polygon's vector area (Newell), against its longest edge:
    // zero up to round-off (exact zeros, underflow), not merely thin.
    OpenMesh::Vec3d twice_area(0, 0, 0);
    double longest2 = 0.0;
    for (const auto h : mesh.fh_range(f)) {
      const OpenMesh::Vec3d a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h));
      twice_area += OpenMesh::cross(a, b);
      longest2 = std::max(longest2, (b - a).sqrnorm());
    }
    if (!(twice_area.norm() > 1e-24 * longest2))
      throw InputError(with_path(path, lines.face_name(f.idx()) +
                                           " has no area (its corners coincide, lie on a line, or cross as a "
                                           "bow-tie); expected faces with area"));
  }
}

std::string concave_faces_warning(const std::string& path, const QuadMesh& mesh, const ElementLines& lines) {
  std::size_t concave = 0;
  int first_face = -1, first_corner = -1;
  for (const auto f : mesh.faces()) {
    std::vector<OpenMesh::Vec3d> p;
    for (const auto v : mesh.fv_range(f)) p.push_back(mesh.point(v));
    OpenMesh::Vec3d normal(0, 0, 0);  // Newell's
    for (std::size_t k = 0; k < p.size(); ++k) normal += OpenMesh::cross(p[k], p[(k + 1) % p.size()]);
    for (std::size_t k = 0; k < p.size(); ++k) {
      const OpenMesh::Vec3d& before = p[(k + p.size() - 1) % p.size()];
      const OpenMesh::Vec3d& after = p[(k + 1) % p.size()];
      // Turned against the face, beyond round-off (a T-node's corner, on a
      // straight edge, turns by nothing).
      const OpenMesh::Vec3d in = p[k] - before, out = after - p[k];
      if (OpenMesh::dot(OpenMesh::cross(in, out), normal) < -1e-9 * in.norm() * out.norm() * normal.norm()) {
        if (concave++ == 0) {
          first_face = f.idx();
          first_corner = static_cast<int>(k);
        }
        break;
      }
    }
  }
  if (concave == 0) return {};
  return with_path(path, lines.face_name(first_face) + " is concave at its corner " + std::to_string(first_corner) +
                             (concave > 1 ? " (and " + std::to_string(concave - 1) + " more faces are concave)" : "") +
                             ": refining it folds a child face over another; expected convex faces (split or "
                             "reshape darts)");
}

std::string unwelded_seams_warning(const std::string& path, const QuadMesh& mesh, const ElementLines& lines) {
  std::vector<std::pair<OpenMesh::Vec3d, int>> rim;
  for (const auto v : mesh.vertices())
    if (mesh.is_boundary(v)) rim.emplace_back(mesh.point(v), v.idx());
  std::vector<double> lengths;
  for (const auto e : mesh.edges()) lengths.push_back(mesh.calc_edge_length(e));
  if (rim.empty() || lengths.empty()) return {};
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  const double tolerance = 1e-6 * lengths[lengths.size() / 2];
  // Sorted along x, each vertex meets only those within the tolerance there.
  std::sort(rim.begin(), rim.end(), [](const auto& a, const auto& b) { return a.first[0] < b.first[0]; });
  std::size_t pairs = 0;
  int first_a = -1, first_b = -1;
  for (std::size_t i = 0; i < rim.size(); ++i)
    for (std::size_t j = i + 1; j < rim.size() && rim[j].first[0] - rim[i].first[0] <= tolerance; ++j)
      if ((rim[j].first - rim[i].first).norm() <= tolerance &&
          // Ends of one (very short) edge are no seam to weld: merging them would collapse faces.
          !mesh.find_halfedge(mesh.vertex_handle(static_cast<unsigned>(rim[i].second)),
                              mesh.vertex_handle(static_cast<unsigned>(rim[j].second))).is_valid()) {
        if (pairs++ == 0) std::tie(first_a, first_b) = std::minmax(rim[i].second, rim[j].second);
      }
  if (pairs == 0) return {};
  return with_path(path, std::to_string(pairs) + " pair" + (pairs > 1 ? "s" : "") +
                             " of boundary vertices lie on one another" + (pairs > 1 ? ", the first " : ": ") +
                             lines.vertex_name(first_a) + " on " + lines.vertex_name(first_b) +
                             ": seams that are not welded, along which the garment falls apart; weld them (merge "
                             "by distance) before simulating");
}

}  // namespace mrcloth
