// Issue 7's "closer to the high-resolution result than the uniform mesh",
// without a body: every model of a pipeline run hangs from its waist
// (the boundary loop "top", pinned) for a second and then swings as a
// waist sways (10 cm side to side and 20 degrees about the vertical at
// 0.9 Hz, like a walking hip), with no collider. Nothing is chaotic and
// nothing touches, so what is left of the distance to the high-resolution
// mesh is how differently the meshes themselves move. The distance is the
// pipeline's: each model evaluated at the high-resolution mesh's material
// points, RMS per frame, mean over the swing's frames; and the RMS over
// the points where one multi-resolution mesh (--regions, by default the
// first multires_* by name) is at level 1, 2 or 3, the same points for
// every model, to see where it comes from.
//
// `--curtain` instead of a folder swings meshes built here, with no data:
// a 0.6 m square curtain of 12 x 12 quads hung by its top row, refined
// uniformly once (L1) and twice (high; `--curtain-levels N`: N times, and
// L1 .. L(N-1) are models), and with a level-3 patch painted on the
// coarse curtain (patch) and on L1 (L1+patch).
//
// Usage: bench_swing <pipeline output>/<garment>/meshes | --curtain [--curtain-levels N] [--frames N] [--iterations K] [--newton-cg K] [--substeps N]
//                    [--sweeps S] [--alpha A] [--alpha-bend A] [--bend-stiffness K] [--bend-model distance|second-difference] [--t-node-sag 0|1] [--regions MODEL]
//                    [--smooth PASSES] [--twin 0|1]
// (the folder holds high.om, coarse_modes.om, uniform_equal.om and
// multires_*.om, as `mrcloth pipeline` writes them).
#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/quad_mesh.h"
#include "mesh_ops/quadtree_forest.h"
#include "mesh_ops/uniform_refine.h"
#include "solver/detail_measures.h"
#include "solver/simulate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace mrcloth;

struct BenchOptions {
  int frames = 120;          // output frames at 30 fps: 1 s hanging still, then the swing
  int iterations = 2;        // local/global iterations per step (the library default)
  int newton_cg = 0;         // SimulationOptions::newton_cg (0: the plain iteration, the library default)
  int substeps = 4;          // steps per 30 fps frame: 120 per second (the library default)
  int sweeps = 6;            // strain-limiting sweeps per round (the library default)
  double alpha = DynamicsOptions{}.alpha;            // stretch and shear stiffness per level exponent
  double alpha_bend = DynamicsOptions{}.alpha_bend;  // bend stiffness per level exponent
  double bend_stiffness = DynamicsOptions{}.material.bend_stiffness;  // N/m at level 1, >= 0
  BendModel bend_model = BendModel::distance;  // DynamicsOptions::bend_model
  bool t_node_sag = false;   // SimulationOptions::t_node_sag
  std::string regions;       // the mesh whose levels partition the points ("": the first multires_*)
  int smooth = 0;            // umbrella passes over the high mesh applied to each frame's error before it is measured (0: none)
  bool curtain = false;      // swing the built curtain instead of a pipeline run's meshes
  int curtain_levels = 2;    // the curtain's high-resolution mesh: refined uniformly this many times (>= 2)
  bool twin = false;         // also swing the high mesh with every rest position moved by up to 1e-7 m (the noise floor)
};

constexpr double kStill = 1.0;          // seconds hanging before the swing
constexpr double kSway = 0.10;          // metres side to side
constexpr double kYaw = 0.35;           // radians about the vertical
constexpr double kFrequency = 0.9;      // Hz
constexpr int kSkippedFrames = 30;      // the still second is not measured

// The pinned vertices: a garment's waist (boundary loop "top"), or the
// curtain's top row (the vertices at its greatest height).
std::vector<int> pinned_vertices(const QuadMesh& mesh, bool curtain) {
  if (!curtain) return boundary_loop_by_name(mesh, "top");
  double top = -std::numeric_limits<double>::infinity();
  for (auto v : mesh.vertices()) top = std::max(top, static_cast<double>(mesh.point(v)[1]));
  std::vector<int> row;
  for (auto v : mesh.vertices())
    if (mesh.point(v)[1] > top - 1e-6) row.push_back(v.idx());  // 1e-6: a nudged twin keeps its row
  return row;
}

// Every output frame of `mesh` swung by its waist (#V x 3 each, metres).
std::vector<Positions> swing(const QuadMesh& mesh, const BenchOptions& b, double* ms_per_frame) {
  DynamicsOptions d;
  d.alpha = b.alpha;
  d.alpha_bend = b.alpha_bend;
  d.bend_model = b.bend_model;
  d.material.bend_stiffness = b.bend_stiffness;
  d.pinned = pinned_vertices(mesh, b.curtain);
  const DynamicsModel model = build_dynamics(mesh, d);
  ClothState state = rest_state(model);
  SimulationOptions s;
  s.frames = b.frames;
  s.iterations = b.iterations;
  s.newton_cg = b.newton_cg;
  s.substeps = b.substeps;
  s.strain_limit_sweeps = b.sweeps;
  s.t_node_sag = b.t_node_sag;
  const Positions rest = state.pinned;
  const Eigen::RowVector3d centre = rest.colwise().mean();
  const PinTrajectory waist = [&](double time, Positions& pinned) {
    const double phase = time < kStill ? 0.0 : std::sin(2.0 * M_PI * kFrequency * (time - kStill));
    const double c = std::cos(kYaw * phase), sn = std::sin(kYaw * phase);
    for (Eigen::Index k = 0; k < pinned.rows(); ++k) {
      const Eigen::RowVector3d r = rest.row(k) - centre;
      pinned(k, 0) = centre(0) + c * r(0) + sn * r(2) + kSway * phase;
      pinned(k, 1) = rest(k, 1);
      pinned(k, 2) = centre(2) - sn * r(0) + c * r(2);
    }
  };
  std::vector<Positions> frames;
  const SimulationReport report = simulate(model, state, s, waist, {}, &frames);
  *ms_per_frame = report.mean_frame.total_ms();
  return frames;
}

// Per point, the level (1..3, 3 for 3 and finer) of the active face of
// `mesh` that holds it.
std::vector<int> levels_at(const QuadMesh& mesh, const std::vector<MaterialPoint>& points) {
  const MaterialBinding binding = MaterialEvaluator(mesh).bind(points);
  const std::vector<QuadRecord>& forest = quadtree(mesh);
  std::vector<int> level(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) level[k] = std::min(3, forest[static_cast<std::size_t>(binding.leaf[k])].level);
  return level;
}

struct Measured {
  double mean_rms = 0.0;                  // metres
  std::array<double, 4> rms_at_level{};   // metres, over the points in each region (1..3)
  std::array<double, 4> share{};          // fraction of the points in that region
};

// Each high vertex's edge neighbours (the material points are the high
// mesh's vertices, in order).
std::vector<std::vector<int>> neighbours_of(const QuadMesh& high) {
  std::vector<std::vector<int>> neighbours(high.n_vertices());
  for (auto v : high.vertices())
    for (auto w : high.vv_range(v)) neighbours[static_cast<std::size_t>(v.idx())].push_back(w.idx());
  return neighbours;
}

// `passes` Jacobi passes of the umbrella average (each point halfway to its
// neighbours' mean): keeps what varies over many edges, removes what varies
// over a few (wrinkles), so the error left is the large-scale one.
Eigen::MatrixX3d smoothed(Eigen::MatrixX3d error, const std::vector<std::vector<int>>& neighbours, int passes) {
  Eigen::MatrixX3d next(error.rows(), 3);
  for (int pass = 0; pass < passes; ++pass) {
    for (Eigen::Index k = 0; k < error.rows(); ++k) {
      const auto& around = neighbours[static_cast<std::size_t>(k)];
      if (around.empty()) { next.row(k) = error.row(k); continue; }
      Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
      for (int n : around) mean += error.row(n);
      next.row(k) = 0.5 * error.row(k) + 0.5 * mean / static_cast<double>(around.size());
    }
    error.swap(next);
  }
  return error;
}

Measured measure(const QuadMesh& mesh, const std::vector<Positions>& frames, const std::vector<MaterialPoint>& points,
                 const std::vector<int>& level, const std::vector<Positions>& high,
                 const std::vector<std::vector<int>>& neighbours, int smooth) {
  const MaterialEvaluator evaluator(mesh);
  const MaterialBinding binding = evaluator.bind(points);
  Measured m;
  std::array<double, 4> sum{};
  std::array<long, 4> count{};
  int measured = 0;
  for (std::size_t f = kSkippedFrames; f < frames.size() && f < high.size(); ++f) {
    Eigen::MatrixX3d error = evaluator.evaluate(binding, frames[f]) - high[f];
    if (smooth > 0) error = smoothed(std::move(error), neighbours, smooth);
    double frame_sum = 0.0;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const double d2 = error.row(static_cast<Eigen::Index>(k)).squaredNorm();
      frame_sum += d2;
      sum[static_cast<std::size_t>(level[k])] += d2;
      ++count[static_cast<std::size_t>(level[k])];
    }
    m.mean_rms += std::sqrt(frame_sum / static_cast<double>(points.size()));
    ++measured;
  }
  if (measured > 0) m.mean_rms /= measured;
  long total = 0;
  for (long c : count) total += c;
  for (std::size_t l = 1; l < 4; ++l) {
    m.rms_at_level[l] = count[l] > 0 ? std::sqrt(sum[l] / static_cast<double>(count[l])) : 0.0;
    m.share[l] = total > 0 ? static_cast<double>(count[l]) / static_cast<double>(total) : 0.0;
  }
  return m;
}

// The curtain's models, high last: a vertical 0.6 m square of 12 x 12
// quads in the x-y plane, its top row at y = 0.6; high is it refined
// uniformly `levels` times, and the uniform ones between are models too.
std::vector<std::pair<std::string, QuadMesh>> curtain_models(int levels) {
  constexpr int kQuads = 12;
  constexpr double kSpacing = 0.05;
  QuadMesh coarse;
  for (int j = 0; j <= kQuads; ++j)
    for (int i = 0; i <= kQuads; ++i) coarse.add_vertex(QuadMesh::Point(i * kSpacing, j * kSpacing, 0.0));
  const auto vertex = [&](int i, int j) { return coarse.vertex_handle(j * (kQuads + 1) + i); };
  for (int j = 0; j < kQuads; ++j)
    for (int i = 0; i < kQuads; ++i) coarse.add_face(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1));
  init_forest(coarse);
  const auto refined = [&](int times) {
    QuadMesh mesh = coarse;
    uniform_refine(mesh, times);
    return mesh;
  };
  const auto with_patch = [&](QuadMesh mesh) {  // level 3 within 15 cm of the middle, balanced
    paint_modes_sphere(mesh, {0.3, 0.3, 0.0}, 0.15, 4);
    adaptive_refine(mesh, {8.0, 3, true});
    return mesh;
  };
  std::vector<std::pair<std::string, QuadMesh>> models{{"coarse", coarse}};
  for (int level = 1; level < levels; ++level) models.emplace_back("L" + std::to_string(level), refined(level));
  models.emplace_back("patch", with_patch(coarse));
  models.emplace_back("L1+patch", with_patch(refined(1)));
  models.emplace_back("high", refined(levels));
  return models;
}

// `mesh` with every rest position moved by a pseudo-random offset of up to
// 1e-7 m per coordinate (fixed seed): how far such a hair moves the swing
// is the floor under every other distance.
QuadMesh nudged(const QuadMesh& mesh) {
  QuadMesh twin = mesh;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> offset(-1e-7, 1e-7);
  for (auto v : twin.vertices()) {
    QuadMesh::Point p = twin.point(v);
    for (int c = 0; c < 3; ++c) p[c] += offset(rng);
    twin.set_point(v, p);
  }
  return twin;
}

int usage(const char* why) {
  std::fprintf(stderr,
               "%s\nusage: bench_swing <pipeline output>/<garment>/meshes | --curtain [--curtain-levels N] [--frames N] [--iterations K] [--newton-cg K] [--substeps N] [--sweeps S] "
               "[--alpha A] [--alpha-bend A] [--bend-stiffness K] [--bend-model distance|second-difference] [--t-node-sag 0|1] [--regions MODEL] [--smooth PASSES] [--twin 0|1]\n",
               why);
  return 2;
}

int run_bench(int argc, char** argv) {
  if (argc < 2) return usage("no meshes folder given");
  BenchOptions b;
  b.curtain = std::string(argv[1]) == "--curtain";
  const std::filesystem::path folder = b.curtain ? std::filesystem::path() : std::filesystem::path(argv[1]);
  for (int a = 2; a + 1 < argc; a += 2) {
    const std::string key = argv[a], value = argv[a + 1];
    if (key == "--frames") b.frames = std::atoi(value.c_str());
    else if (key == "--iterations") b.iterations = std::atoi(value.c_str());
    else if (key == "--newton-cg") b.newton_cg = std::atoi(value.c_str());
    else if (key == "--curtain-levels") b.curtain_levels = std::atoi(value.c_str());
    else if (key == "--twin") b.twin = value == "1";
    else if (key == "--substeps") b.substeps = std::atoi(value.c_str());
    else if (key == "--sweeps") b.sweeps = std::atoi(value.c_str());
    else if (key == "--alpha") b.alpha = std::atof(value.c_str());
    else if (key == "--alpha-bend") b.alpha_bend = std::atof(value.c_str());
    else if (key == "--bend-model") {
      if (value != "distance" && value != "second-difference")
        return usage(("--bend-model must be distance or second-difference, got " + value).c_str());
      b.bend_model = value == "distance" ? BendModel::distance : BendModel::second_difference;
    }
    else if (key == "--bend-stiffness") b.bend_stiffness = std::atof(value.c_str());
    else if (key == "--t-node-sag") b.t_node_sag = value == "1";
    else if (key == "--regions") b.regions = value;
    else if (key == "--smooth") b.smooth = std::atoi(value.c_str());
    else return usage(("unknown option " + key).c_str());
  }
  if (b.frames <= kSkippedFrames) return usage("--frames must exceed the 30 still frames");
  if (b.substeps < 1 || b.iterations < 1) return usage("--substeps and --iterations must be at least 1");
  if (b.newton_cg < 0) return usage("--newton-cg must be at least 0");
  if (b.curtain_levels < 2 || b.curtain_levels > 4) return usage("--curtain-levels must be 2, 3 or 4");
  if (b.smooth < 0) return usage("--smooth must be at least 0");

  // The compared models and the high-resolution mesh, by name.
  std::vector<std::pair<std::string, QuadMesh>> models;
  QuadMesh high;
  if (b.curtain) {
    models = curtain_models(b.curtain_levels);
    high = std::move(models.back().second);
    models.pop_back();
  } else {
    if (!std::filesystem::exists(folder / "high.om"))
      return usage(("no high.om in " + folder.string() + "; expected a `mrcloth pipeline` run's meshes folder").c_str());
    std::vector<std::string> names{"coarse_modes", "uniform_equal"};
    std::vector<std::string> multires;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      const std::string name = entry.path().stem().string();
      if (entry.path().extension() == ".om" && name.rfind("multires_", 0) == 0) multires.push_back(name);
    }
    std::sort(multires.begin(), multires.end());
    names.insert(names.end(), multires.begin(), multires.end());
    const auto load = [&](const std::string& name) { return load_garment((folder / (name + ".om")).string(), {"m"}).mesh; };
    for (const std::string& name : names) models.emplace_back(name, load(name));
    high = load("high");
  }
  if (b.twin) models.emplace_back("high, moved 1e-7", nudged(high));
  if (b.regions.empty()) b.regions = models.size() > 2 ? models[2].first : models.back().first;
  const auto region_model = std::find_if(models.begin(), models.end(), [&](const auto& m) { return m.first == b.regions; });
  if (region_model == models.end()) return usage(("no model named " + b.regions + " to take the regions from").c_str());
  const std::vector<MaterialPoint> points = material_points(high);
  const std::vector<int> level = levels_at(region_model->second, points);
  const std::vector<std::vector<int>> neighbours = neighbours_of(high);
  double high_ms = 0.0;
  const std::vector<Positions> reference = swing(high, b, &high_ms);

  std::printf("swing: each model of %s hangs from its %s for %.0f s, then that sways %.0f cm and %.0f degrees at "
              "%.1f Hz; %d frames at 30 fps, %d steps a second, no collider; %d iterations%s, %d sweeps, alpha %.2f, alphaBend %.2f, bend %.3f N/m (%s springs), tNodeSag %s\n\n",
              b.curtain ? "the built curtain" : folder.string().c_str(), b.curtain ? "top row" : "waist", kStill, 100 * kSway, kYaw * 180 / M_PI, kFrequency, b.frames, 30 * b.substeps, b.iterations,
              b.newton_cg > 0 ? (" (Newton, " + std::to_string(b.newton_cg) + " CG each)").c_str() : "", b.sweeps,
              b.alpha, b.alpha_bend, b.bend_stiffness, b.bend_model == BendModel::distance ? "distance" : "second-difference",
              b.t_node_sag ? "on" : "off");
  std::printf("mean RMS to the high-resolution swing at its material points, mm; then over the points where %s is "
              "at each level (share of the points; RMS over all their frames)%s\n\n", b.regions.c_str(),
              b.smooth > 0 ? (", of the error smoothed by " + std::to_string(b.smooth) +
                              " umbrella passes over the high mesh (its large-scale part)").c_str() : "");
  std::printf("| %-16s | %8s | %8s | %9s | %-16s | %-16s | %-16s |\n", "model", "vertices", "ms/frame", "mean RMS",
              "its level 1", "its level 2", "its level 3+");
  std::printf("|%s|%s|%s|%s|%s|%s|%s|\n", std::string(18, '-').c_str(), std::string(10, '-').c_str(),
              std::string(10, '-').c_str(), std::string(11, '-').c_str(), std::string(18, '-').c_str(),
              std::string(18, '-').c_str(), std::string(18, '-').c_str());
  for (const auto& [name, mesh] : models) {
    double ms = 0.0;
    const Measured m = measure(mesh, swing(mesh, b, &ms), points, level, reference, neighbours, b.smooth);
    std::array<std::string, 4> cells;
    for (std::size_t l = 1; l < 4; ++l) {
      char cell[32];
      if (m.share[l] > 0.0) std::snprintf(cell, sizeof cell, "%5.1f (%3.0f %%)", 1000 * m.rms_at_level[l], 100 * m.share[l]);
      else std::snprintf(cell, sizeof cell, "-");
      cells[l] = cell;
    }
    std::printf("| %-16s | %8zu | %8.1f | %9.1f | %-16s | %-16s | %-16s |\n", name.c_str(), mesh.n_vertices(), ms,
                1000 * m.mean_rms, cells[1].c_str(), cells[2].c_str(), cells[3].c_str());
  }
  std::printf("| %-16s | %8zu | %8.1f | %9.1f | %-16s | %-16s | %-16s |\n", "high", high.n_vertices(), high_ms, 0.0, "0.0", "0.0",
              "0.0");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_bench(argc, argv);
  } catch (const mrcloth::Error& error) {  // bad options or data: say what, not abort
    std::fprintf(stderr, "bench_swing: %s\n", error.what());
    return 1;
  }
}
