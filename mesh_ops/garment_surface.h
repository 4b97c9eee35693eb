#pragma once
// A garment as read, held to what the cloth needs beyond what OpenMesh's
// reader checks: faces with area around manifold vertices, seams welded,
// convex faces, and all quads (any other face split, the OBJ's texture
// coordinates carried along).
#include "garment_scan.h"
#include "quad_mesh.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace mrcloth {

/// Where a quad of split_into_quads came from: input face `face`, around
/// its vertex `corner` (between `previous` and `next` on that face), and
/// its own vertices (corner, the midpoint towards next, the centre, the
/// midpoint towards previous).
struct SplitQuad {
  int face = -1;
  int previous = -1, corner = -1, next = -1;
  std::array<int, 4> vertices{};
};

/// Makes an all-quad mesh of any mesh, with a warning when it had to split;
/// `origins` receives where each new quad came from (none when nothing was split).
/// `path` is named in the warning, which is appended to `warnings`.
void make_all_quad(QuadMesh& mesh, const std::string& path, std::vector<std::string>& warnings,
                   std::vector<SplitQuad>& origins);

/// The OBJ's texture coordinates onto the new forest's records (record i is
/// face i, as init_forest makes them), when every corner of every face has
/// one and the faces are the file's; otherwise none, with a warning where
/// the file had some.
/// `scan`: scan_text's of the file; `mesh`: its garment, forest
/// initialised; `faces_read`: the faces it had before make_all_quad;
/// `split`: make_all_quad's origins (empty when nothing was split); a
/// warning naming `path` is appended to `warnings`.
void read_texture_coords(const TextScan& scan, QuadMesh& mesh, std::size_t faces_read,
                         const std::vector<SplitQuad>& split, const std::string& path,
                         std::vector<std::string>& warnings);

/// What the reader accepts but a garment cannot be: a vertex where two fans
/// of faces meet (a bow-tie, which the boundary loops and the waist would
/// pass twice), a vertex in no face (no mass: the solver refuses it), or a
/// face without area (the same: its corners coincide, lie on a line or
/// cross). Faces are named in file order, vertices by their index.
/// Throws InputError naming `path` and the element (by its line in `lines`
/// where known).
void check_garment_surface(const std::string& path, const QuadMesh& mesh, const ElementLines& lines);

/// A warning when a face is concave (a dart: one corner turned inwards):
/// its bilinear split folds a child face over another, the surface
/// overlapping itself. Empty when every face is convex.
/// The warning names `path` and the face (by its line in `lines` where known).
std::string concave_faces_warning(const std::string& path, const QuadMesh& mesh, const ElementLines& lines);

/// A warning when boundary vertices lie on one another (within a
/// millionth of the median edge): panels exported with their seams not
/// welded, which the simulation would let fall apart, only the pinned
/// piece staying up. Empty when there are none.
/// The warning names `path` and the first pair (by their lines in `lines`
/// where known).
std::string unwelded_seams_warning(const std::string& path, const QuadMesh& mesh, const ElementLines& lines);

}  // namespace mrcloth
