#pragma once
// Mode painting beside the computed modes (SPEC stage 5): an artist's
// brushes write the mode layer (what refinement reads); the modes an
// analysis computed stay in their own layer, so any painted vertex can be
// erased back to them. Per-vertex analysis values (mean curvature, its
// deviation) are layers too, for threshold fills. All layers are
// persistent OpenMesh properties: they save and load with the mesh (.om),
// and as a plain CSV file other tools read.
#include "quad_mesh.h"

#include <string>
#include <vector>

namespace mrcloth {

namespace layer {
/// vertex int: the analysis's (or mapModes') mode, 0..kLargestMode; a mesh never analysed has no such layer
inline constexpr const char* computed_mode = "mrcloth:computed_mode";
inline constexpr const char* mean_curvature = "mrcloth:mean_curvature";            ///< vertex double, 1/m
inline constexpr const char* curvature_deviation = "mrcloth:curvature_deviation";  ///< vertex double, 1/m
}  // namespace layer

/// Creates the analysis layers that .om files keep (computed_mode,
/// mean_curvature, curvature_deviation; 0 where unset), persistent. The
/// .om reader only fills layers that exist before reading, so load_garment
/// calls this; other double layers travel in the CSV file.
void ensure_analysis_layers(QuadMesh& mesh);

/// Stores an analysis's modes (one per vertex, 1..kLargestMode) as the
/// computed layer and as the current modes (painting starts from them).
/// Throws ArgumentError naming the first vertex out of range; nothing changes then.
void set_computed_modes(QuadMesh& mesh, const std::vector<int>& modes);

/// Sets only the computed modes (one per vertex, 0..kLargestMode: a mode
/// mapped from a painted 0 is 0; the current modes untouched): what
/// eraseModes goes back to. ArgumentError naming the first vertex out of
/// range; nothing changes then.
void set_computed_layer(QuadMesh& mesh, const std::vector<int>& modes);

/// What erase_modes goes back to, per vertex: the computed modes, or
/// kDefaultMode everywhere when the mesh has never been analysed.
std::vector<int> computed_modes(const QuadMesh& mesh);

/// Sets a persistent per-vertex double layer `name` (one value per vertex),
/// creating it if needed. ArgumentError for a wrong count or a reserved name.
void set_vertex_layer(QuadMesh& mesh, const std::string& name, const std::vector<double>& values);

/// Values of a per-vertex layer: the double layers set above, or "mode" and
/// "computed_mode" as numbers. ArgumentError naming the layers there are.
std::vector<double> vertex_layer(const QuadMesh& mesh, const std::string& name);

/// Names vertex_layer accepts on this mesh (mode first).
std::vector<std::string> vertex_layer_names(const QuadMesh& mesh);

/// Sets `mode` on every vertex whose shortest path along the mesh's edges
/// (metres) from any of `seeds` is at most `radius`, the seeds included.
/// Returns how many. ArgumentError for a bad seed, radius or mode.
std::size_t paint_modes_geodesic(QuadMesh& mesh, const std::vector<int>& seeds, double radius, int mode);

/// Sets `mode` on every vertex whose value in layer `name` is >= threshold
/// (or <= with `above` false). Returns how many.
std::size_t fill_modes_threshold(QuadMesh& mesh, const std::string& name, double threshold, int mode, bool above = true);

/// Puts the given vertices (all of them when `vertex_ids` is empty) back to
/// their computed modes (the default mode on a mesh never analysed).
/// Returns how many changed.
std::size_t erase_modes(QuadMesh& mesh, const std::vector<int>& vertex_ids = {});

/// Writes "vertex,x,y,z,mode,computed_mode" plus one column per double
/// layer, one row per vertex, atomically. OutputError naming the path.
void write_vertex_layers_csv(const QuadMesh& mesh, const std::string& path);

/// What read_modes_csv set, and how well the file's positions (its x, y, z
/// columns, where it has them) fit the mesh: a file of another mesh, or of
/// this one with its vertices in another order, sets modes on the wrong
/// vertices without any malformed line.
struct ModesCsvRead {
  std::size_t set = 0;             ///< vertices whose mode the file set
  std::size_t misplaced = 0;       ///< rows whose x, y, z lie farther than kCsvPositionTolerance from their vertex
  double farthest = 0.0;           ///< metres: the largest such distance
  int farthest_vertex = -1;        ///< its vertex (-1: none misplaced)
  int farthest_line = 0;           ///< its line in the file
};
/// Metres a row's position may differ from its vertex's: the 17 digits
/// saveLayers writes round-trip exactly; a mesh saved in a text format in
/// between keeps micrometres.
inline constexpr double kCsvPositionTolerance = 1e-4;

/// Reads modes from a CSV with a header naming a "vertex" and a "mode"
/// column (case and spaces ignored, a byte-order mark skipped; other
/// columns ignored but x, y, z, which are compared with the mesh's positions
/// in metres, as write_vertex_layers_csv writes them) and sets them;
/// vertices not listed keep theirs. InputError naming the file and line for
/// anything malformed, a vertex given twice included; nothing changes then.
ModesCsvRead read_modes_csv(QuadMesh& mesh, const std::string& path);

}  // namespace mrcloth
