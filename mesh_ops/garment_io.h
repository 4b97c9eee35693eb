#pragma once
// Reading garments and writing refined meshes. Every write goes to a
// temporary file in the target folder that is renamed into place only when
// complete, so no half-written file is ever left behind.
#include "colors.h"  // palette_color, sequential_color: the colours export_surface writes
#include "quad_mesh.h"

#include <string>
#include <vector>

namespace mrcloth {

struct LoadOptions {
  std::string units = "m";  ///< unit of the file's coordinates: m, dm, cm, mm, inch
};

struct LoadResult {
  QuadMesh mesh;                      ///< refinable, all-quad, in metres, forest initialised
  std::vector<std::string> warnings;  ///< e.g. "3 triangles and 1 n-gon were split into quads"
};

/// Loads an OBJ, OFF, PLY or OM garment through OpenMesh IO and makes it
/// refinable (init_forest). Coordinates are scaled to metres. A mesh with
/// triangles or n-gons is made all-quad by one midpoint split of every face
/// (face centre + edge midpoints), with a warning. A `.om` file written by
/// save_mesh is restored with its forest and layers untouched (no scaling
/// unless units is not "m", which is warned of: its layers stay in metres).
/// Throws InputError, naming the file and the problem, for: a missing or
/// unreadable file, an unknown extension, no vertices or no faces, a
/// non-finite coordinate or one beyond float range (naming the vertex), a
/// non-manifold edge or vertex, a vertex in no face, a face with repeated
/// vertices or without area (naming the face), an OFF or PLY header
/// OpenMesh would misread or hang on, and a `.om` whose stored hierarchy is
/// damaged. Warns of boundary vertices lying on one another (unwelded seams).
LoadResult load_garment(const std::string& path, const LoadOptions& options = {});

/// Saves the whole refinable mesh with forest and every layer. `.om` keeps
/// everything; `.obj`/`.off`/`.ply` keep the active surface only. Atomic.
/// Throws OutputError (naming the path) on failure, ArgumentError for an
/// unknown extension.
void save_mesh(const QuadMesh& mesh, const std::string& path);

enum class ColorBy { none, level, mode, curvature };

struct ExportOptions {
  ColorBy color_by = ColorBy::none;  ///< vertex colours: by level (the finest of the vertex's faces), by
                                     ///< mode, or by the mean_curvature layer (sequential_color of value /
                                     ///< the largest; needs the layer)
  bool triangulate = false;          ///< fan-split polygons; forced for formats that need triangles
  /// Triangulate as this mesh does (the same mesh at its rest positions,
  /// when the one exported is a simulated frame of it), so that every frame
  /// gets the same triangles; null = as the exported mesh itself does.
  const QuadMesh* triangles_of = nullptr;
};

/// Exports the active surface (faces with hanging vertices stay polygons
/// unless triangulated) to OBJ or PLY (PLY stores vertex colours; OBJ writes
/// them as `v x y z r g b`). Atomic. Throws OutputError / ArgumentError.
void export_surface(const QuadMesh& mesh, const std::string& path, const ExportOptions& options = {});

}  // namespace mrcloth
