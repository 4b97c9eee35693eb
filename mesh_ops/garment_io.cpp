#include "garment_io.h"
#include "mode_painting.h"

#include "errors.h"
#include "garment_formats.h"
#include "garment_scan.h"
#include "garment_surface.h"
#include "om_checks.h"
#include "om_structure.h"
#include "quadtree_forest.h"
#include "texture_coords.h"
#include "units.h"

// MeshIO.hh pulls in the reader and writer modules, which register
// themselves with the IOManager.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;
using VertexHandle = OpenMesh::VertexHandle;

/// Checks every face as the reader hands it over. ImporterT would log and
/// drop bad faces, and would silently duplicate the vertices of a face that
/// does not fit the manifold built so far; we want the read to fail instead.
/// Nothing is thrown from inside OpenMesh's reader: the first problem is
/// remembered and load_garment throws once the reader has returned.
class CheckingImporter : public OpenMesh::IO::ImporterT<QuadMesh> {
 public:
  /// `lines` (kept by reference: it must outlive the importer) names the
  /// file's lines in messages.
  CheckingImporter(QuadMesh& mesh, const ElementLines& lines) : ImporterT(mesh), target_(mesh), lines_(lines) {}

  using ImporterT::add_face;

  OpenMesh::FaceHandle add_face(const VHandles& corners) override {
    const long face = next_face_++;
    // Once the load is known to fail, later faces are skipped so the reader
    // can still run to its end.
    if (problem_.found()) return OpenMesh::FaceHandle();
    if (std::string issue = corner_issue(corners); !issue.empty()) {
      problem_ = {face, lines_.face_name(face) + issue};
      return OpenMesh::FaceHandle();
    }
    const OpenMesh::FaceHandle added = target_.add_face(corners);
    if (!added.is_valid()) problem_ = {face, lines_.face_name(face) + why_not_added(corners)};
    return added;
  }

  const FaceProblem& problem() const { return problem_; }

 private:
  /// Why the mesh refused a face whose corners are valid: the first of its
  /// edges that cannot join the faces read before it, named by its vertices.
  std::string why_not_added(const VHandles& corners) const {
    const std::string expected = "; expected an oriented 2-manifold quad mesh";
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const VertexHandle a = corners[k], b = corners[(k + 1) % corners.size()];
      const std::string edge = "edge from " + lines_.vertex_name(a.idx()) + " to " + lines_.vertex_name(b.idx());
      const auto along = target_.find_halfedge(a, b), against = target_.find_halfedge(b, a);
      if (along.is_valid() && !target_.is_boundary(along)) {
        if (against.is_valid() && !target_.is_boundary(against))
          return " would be a third face on its " + edge + expected;
        return " runs its " + edge + " the way " + lines_.face_name(target_.face_handle(along).idx()) +
               " does: one of them is wound the other way round (or the surface is one-sided, a Moebius strip)" +
               expected + " (faces wound alike, as seen from one side)";
      }
    }
    return " would join the faces before it only at a vertex (a bow-tie)" + expected;
  }

  std::string corner_issue(const VHandles& corners) const {
    if (corners.size() < 3)
      return " has only " + std::to_string(corners.size()) + " corners; expected at least 3";
    const int n_vertices = static_cast<int>(target_.n_vertices());
    for (const VertexHandle v : corners) {
      if (v.idx() < 0 || v.idx() >= n_vertices)
        return " refers to vertex " + std::to_string(v.idx()) + " (counted from 0), which does not exist (the file has " +
               std::to_string(n_vertices) + " vertices)";
    }
    for (std::size_t i = 0; i < corners.size(); ++i) {
      for (std::size_t j = i + 1; j < corners.size(); ++j) {
        if (corners[i] == corners[j])
          return " uses " + lines_.vertex_name(corners[i].idx()) + " more than once; expected distinct corners";
      }
    }
    return {};
  }

  QuadMesh& target_;
  const ElementLines& lines_;
  long next_face_ = 0;
  FaceProblem problem_;
};

void require_input_file(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(with_path(path, "cannot open file (" + missing_file_reason(path) + ")"));
  if (fs::is_directory(status)) throw InputError(with_path(path, "cannot open file (it is a folder)"));
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw InputError(with_path(path, "cannot open file (it is not readable)"));
  if (probe.peek() == std::ifstream::traits_type::eof())
    throw InputError(with_path(path, "the file is empty; expected a quad mesh"));
}

/// The whole of a .om file, once its checksum and chunk structure check out
/// (the OpenMesh reader then reads the same file).
std::string read_checked_om(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>{});
  check_om_checksum(path, bytes);
  check_om_structure(path, bytes);
  return bytes;
}

/// Runs OpenMesh's reader into `importer`: on the scan's cleaned text where
/// there is one, else on the file. False where OpenMesh rejected the file.
bool read_with_openmesh(const std::string& path, const std::string& extension, Format format, const TextScan& scan,
                        CheckingImporter& importer) {
  OpenMesh::IO::Options io_options;
  QuietOpenMesh quiet;
  try {
    if (scan.text_for_reader.empty()) return OpenMesh::IO::IOManager().read(path, importer, io_options);
    std::istringstream text(scan.text_for_reader);
    if (format == Format::off) set_off_layout(path, scan.text_for_reader);
    return OpenMesh::IO::IOManager().read(text, extension, importer, io_options);
  } catch (const std::bad_alloc&) {
    // A binary header's counts misread (a big-endian OFF) or simply huge.
    throw InputError(with_path(path, std::string("cannot be read as ") + format_name(format) +
                                         ": its header asks for more elements than memory holds; expected a valid " +
                                         extension + " mesh (binary OFF: little-endian, as OpenMesh reads it)"));
  }
}

/// Refuses what the reader made of the file: the first face problem (the
/// scan's or the importer's, whichever comes first in the file), a file
/// OpenMesh rejected, no vertices or faces, a .om file cut short.
void check_read(const std::string& path, const std::string& extension, Format format, bool read, const FaceProblem& problem,
                const std::string& om_bytes, QuadMesh& mesh) {
  if (format == Format::om) check_om_counts(path, om_bytes, mesh);
  if (problem.found()) throw InputError(with_path(path, problem.text));
  if (!read)
    throw InputError(with_path(path, std::string("cannot be read as ") + format_name(format) +
                                         " (OpenMesh rejected it); expected a valid " + extension + " mesh"));
  if (mesh.n_vertices() == 0) throw InputError(with_path(path, "the file has no vertices; expected a quad mesh"));
  if (mesh.n_faces() == 0) throw InputError(with_path(path, "the file has no faces; expected a quad mesh"));
  if (format == Format::om) {
    // save_mesh writes the forest last (ensure_layers): a file holding our
    // layers but no forest was cut short, and would load as a coarse garment.
    if (quadtree(mesh).empty() && om_bytes.find("mrcloth:") != std::string::npos)
      throw InputError(with_path(path, "the file is cut short (it holds mrcloth's layers but not the refinement "
                                       "hierarchy mrcloth writes last); expected a .om file as mrcloth writes "
                                       "it, whole"));
    drop_analysis_layers_not_stored(om_bytes, mesh);
  }
}

/// Sets the mesh's points from the scan's double-precision reading where it
/// matches what OpenMesh read (true), refuses a non-finite coordinate and
/// scales every point by `scale` (metres per unit).
bool set_points(const std::string& path, Format format, const TextScan& scan, double scale, LoadResult& result) {
  QuadMesh& mesh = result.mesh;
  const bool scanned = scan_matches(scan, mesh);
  if (scanned) {
    for (const auto v : mesh.vertices()) mesh.set_point(v, scan.points[static_cast<std::size_t>(v.idx())]);
  } else if (format != Format::om && !scan.binary) {
    result.warnings.push_back(with_path(
        path, "the coordinates could not be re-read in double precision; they keep OpenMesh's single precision"));
  }
  for (const auto v : mesh.vertices()) {
    const OpenMesh::Vec3d& p = mesh.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InputError(with_path(path, "vertex " + std::to_string(v.idx()) +
                                           " has a non-finite coordinate; expected finite numbers"));
    mesh.set_point(v, p * scale);
  }
  return scanned;
}

/// A refined mesh saved by save_mesh: its forest and layers are the truth,
/// once checked.
void check_stored_refinement(const std::string& path, const std::string& om_bytes, double scale,
                             const LoadOptions& options, LoadResult& result) {
  check_stored_forest(path, result.mesh);
  // save_mesh writes metres; a scale makes another garment of it, whose
  // layers in metres (curvature, 1/m) no longer fit it.
  if (scale != 1.0 && checksum_place(om_bytes).present)
    result.warnings.push_back(with_path(
        path, "mrcloth saved this mesh in metres; units '" + options.units + "' scale it by " + number_text(scale) +
                  " (its curvature layers, in 1/m, are not rescaled): give units 'm' to load it as saved"));
}

/// A coarse garment: its surface checked (with warnings for unwelded seams
/// and concave faces), made all quads, given its forest and texture
/// coordinates. `lines` names the file's lines where the scan saw them.
void prepare_coarse_garment(const std::string& path, const TextScan& scan, const ElementLines& lines,
                            LoadResult& result) {
  QuadMesh& mesh = result.mesh;
  check_garment_surface(path, mesh, lines);
  if (std::string unwelded = unwelded_seams_warning(path, mesh, lines); !unwelded.empty())
    result.warnings.push_back(std::move(unwelded));
  if (std::string concave = concave_faces_warning(path, mesh, lines); !concave.empty())
    result.warnings.push_back(std::move(concave));
  const std::size_t faces_read = mesh.n_faces();
  std::vector<SplitQuad> split;
  make_all_quad(mesh, path, result.warnings, split);
  init_forest(mesh);
  read_texture_coords(scan, mesh, faces_read, split, path, result.warnings);
}

}  // namespace

LoadResult load_garment(const std::string& path, const LoadOptions& options) {
  const double scale = metres_per_unit(options.units);
  const std::string extension = lower_extension(path);
  const std::optional<Format> format = format_of(extension);
  // A folder, a missing or an empty file is that, whatever its name says.
  require_input_file(path);
  if (!format)
    throw InputError(with_path(path, "unknown mesh format (extension " + shown_extension(extension) +
                                         "); expected one of .obj, .off, .ply, .om"));
  const bool om = *format == Format::om;
  const TextScan scan = om ? TextScan{} : scan_text(path, *format);

  LoadResult result;
  // The OM reader fills a stored property only if the mesh already has one
  // with that name (and a matching size), so the layers must exist first.
  if (om) {
    ensure_layers(result.mesh);
    ensure_analysis_layers(result.mesh);
    ensure_record_uvs(result.mesh);
  }
  const std::string om_bytes = om ? read_checked_om(path) : std::string{};

  // The reader would abort the process on this file: the scan's first face
  // problem is the message (the importer's manifold checks, which might
  // have named an earlier face, cannot run).
  if (scan.reader_would_abort) throw InputError(with_path(path, scan.face_problem.text));
  CheckingImporter importer(result.mesh, scan.lines);
  const bool read = read_with_openmesh(path, extension, *format, scan, importer);
  check_read(path, extension, *format, read, earlier(scan.face_problem, importer.problem()), om_bytes, result.mesh);

  const bool scanned = set_points(path, *format, scan, scale, result);
  if (om && !quadtree(result.mesh).empty()) {
    check_stored_refinement(path, om_bytes, scale, options, result);
    return result;
  }
  // Lines are named only where the scan saw the vertices OpenMesh read.
  const ElementLines no_lines;
  prepare_coarse_garment(path, scan, scanned ? scan.lines : no_lines, result);
  return result;
}

}  // namespace mrcloth
