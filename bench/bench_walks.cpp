// The walk table: how whole the shared garments stay on the shared walks,
// the quality side of bench_character's speed. Every run is set up as the
// plugin's multirescloth.simulate sets it up (character_setup.h), so a
// change to the solver can be judged over many runs instead of one: the
// runs are chaotic (a millisecond more pre-roll can double one run's
// largest stretch), so what counts is how many runs tear and how the
// stretch is spread, not any single number.
//
// Rows: each garment (the shared skirt, the knee-length skirt, the
// trousers) on each walk (07_06, 07_03, 08_03, 02_01) in three kinds: coarse
// on fitted capsules, coarse on the skinned mesh, refined once on the
// skinned mesh. Columns: depth (deepest vertex below the body's surface at
// an output frame), largest edge stretch, tear (the largest opening of an
// edge at least doubled), ms per frame (dynamics, collision). Then a
// summary: runs torn more than 1 cm open, runs deeper than 2 mm, the median
// and largest stretch, the total time.
//
// Usage: bench_walks [--frames N] [--preroll S] [--kinds LIST] [--garments LIST] [--walks LIST]
//                    [--rounds N] [--sweeps N] [--threads N]
//   LIST: comma-separated; kinds coarse-capsules,coarse-mesh,refined-mesh;
//   garments skirt,knee,trousers; walks 07_06,07_03,08_03,02_01.
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/uniform_refine.h"
#include "solver/character_setup.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace mrcloth;

struct WalkOptions {
  int frames = 60;        // output frames at 30 fps after the pre-roll
  double preroll = 0.5;   // seconds
  std::vector<std::string> kinds{"coarse-capsules", "coarse-mesh", "refined-mesh"};
  std::vector<std::string> garments{"skirt", "knee", "trousers"};
  std::vector<std::string> walks{"07_06", "07_03", "08_03", "02_01"};
  SimulationOptions simulation;  // the solver's settings (the plugin's defaults unless overridden)
  double stretch_stiffness = Material{}.stretch_stiffness;  // N/m, the cloth's stretch springs (cotton's by default)
};

std::string data(const std::string& relative) { return std::string(MRCLOTH_SHARED_DATA) + "/" + relative; }

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string garment_file(const std::string& garment) {
  if (garment == "skirt") return "garments/makehuman/skirthelper.obj";
  if (garment == "knee") return "garments/makehuman/female_elegantsuit01_skirt_on_base.obj";
  if (garment == "trousers") return "garments/makehuman/male_casualsuit04_pants_on_base.obj";
  throw ArgumentError("unknown garment '" + garment + "'; expected skirt, knee or trousers");
}

struct Result {
  std::string garment, walk, kind;
  std::size_t vertices = 0;
  SimulationReport motion;
};

Result run(const std::string& garment, const std::string& walk, const std::string& kind, const WalkOptions& w) {
  if (kind != "coarse-capsules" && kind != "coarse-mesh" && kind != "refined-mesh")
    throw ArgumentError("unknown kind '" + kind + "'; expected coarse-capsules, coarse-mesh or refined-mesh");
  BvhReadOptions bvh;
  bvh.scale = 0.056444;          // CMU units to metres
  bvh.skip_first_frame = false;  // make_character drops CMU's added T-pose
  const Motion clip = read_bvh(data("motions/cmu_mb/" + walk + ".bvh"), bvh);
  QuadMesh mesh = load_garment(data(garment_file(garment)), {"dm"}).mesh;
  if (kind == "refined-mesh") uniform_refine(mesh, 1);
  CharacterSetup setup;
  setup.body = kind == "coarse-capsules" ? CharacterBodyKind::capsules : CharacterBodyKind::mesh;
  setup.makehuman = makehuman_files(data("bodies/makehuman"));
  setup.place = GarmentPlacement::makehuman;
  setup.preroll_seconds = w.preroll;
  Character character = make_character(clip, setup, mesh);
  const PlacedGarment placed = place_garment(character, setup, mesh);
  DynamicsOptions d;
  d.pinned = boundary_loop_by_name(placed.mesh, "top");
  d.material.stretch_stiffness = w.stretch_stiffness;
  const DynamicsModel model = build_dynamics(placed.mesh, d);
  ClothState state = rest_state(model);
  SimulationOptions simulation = w.simulation;
  simulation.frames = w.frames;
  const CharacterRunOptions o = character_run_options(character, setup, model, simulation);
  Result r{garment, walk, kind, placed.mesh.n_vertices(), {}};
  r.motion = simulate_on_character(model, state, *character.motion, *character.body, o).motion;
  return r;
}

int run_table(int argc, char** argv) {
  WalkOptions w;
  const char* usage =
      "usage: bench_walks [--frames N] [--preroll S] [--kinds LIST] [--garments LIST] [--walks LIST] "
      "[--rounds N] [--sweeps N] [--threads N]\n";
  for (int a = 1; a < argc; a += 2) {
    const std::string key = argv[a];
    if (key == "--help" || key == "-h") {
      std::printf("%s", usage);
      return 0;
    }
    if (a + 1 == argc) {
      std::fprintf(stderr, "option %s needs a value\n%s", argv[a], usage);
      return 2;
    }
    const std::string value = argv[a + 1];
    if (key == "--frames") w.frames = std::atoi(value.c_str());
    else if (key == "--preroll") w.preroll = std::atof(value.c_str());
    else if (key == "--kinds") w.kinds = split_list(value);
    else if (key == "--garments") w.garments = split_list(value);
    else if (key == "--walks") w.walks = split_list(value);
    else if (key == "--rounds") w.simulation.collision_rounds = std::atoi(value.c_str());
    else if (key == "--sweeps") w.simulation.strain_limit_sweeps = std::atoi(value.c_str());
    else if (key == "--threads") w.simulation.threads = std::atoi(value.c_str());
    else if (key == "--slack") w.simulation.contact_slack = std::atof(value.c_str());
    else if (key == "--tethers") w.simulation.tethers = std::atoi(value.c_str()) != 0;
    else if (key == "--iterations") w.simulation.iterations = std::atoi(value.c_str());
    else if (key == "--stretch-stiffness") w.stretch_stiffness = std::atof(value.c_str());
    else if (key == "--round-tolerance") w.simulation.round_tolerance = std::atof(value.c_str());
    else {
      std::fprintf(stderr, "unknown option %s\n%s", argv[a], usage);
      return 2;
    }
  }
  if (!std::filesystem::exists(data("bodies/makehuman/base.obj"))) {
    std::printf("shared data absent (%s): nothing to measure\n", data("").c_str());
    return 0;
  }
  std::printf("the walk table: %d frames at 30 fps after a %.3f s pre-roll, at most %d rounds of %d limiter sweeps, "
              "%d thread(s)\n\n",
              w.frames, w.preroll, w.simulation.collision_rounds, w.simulation.strain_limit_sweeps, w.simulation.threads);
  std::printf("| %-8s | %-5s | %-15s | %8s | %8s | %9s | %8s | %8s | %8s |\n", "garment", "walk", "kind", "vertices",
              "depth mm", "stretch", "tear mm", "dyn ms/f", "coll ms/f");
  std::printf("|----------|-------|-----------------|----------|----------|-----------|----------|----------|----------|\n");
  std::vector<Result> results;
  const auto start = std::chrono::steady_clock::now();
  for (const std::string& garment : w.garments)
    for (const std::string& kind : w.kinds)
      for (const std::string& walk : w.walks) {
        Result r = run(garment, walk, kind, w);
        const SimulationReport& m = r.motion;
        std::printf("| %-8s | %-5s | %-15s | %8zu | %8.1f | %7.0f %% | %8.1f | %8.1f | %8.1f |%s\n", garment.c_str(),
                    walk.c_str(), kind.c_str(), r.vertices, 1000.0 * m.max_depth, 100.0 * m.max_stretch,
                    1000.0 * m.max_tear_opening, m.mean_frame.dynamics_ms, m.mean_frame.collision_ms,
                    m.non_finite ? " NaN!" : "");
        std::fflush(stdout);
        results.push_back(std::move(r));
      }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<double> stretch;
  int torn = 0, deep = 0, non_finite = 0;
  double frame_ms = 0.0;
  for (const Result& r : results) {
    stretch.push_back(r.motion.max_stretch);
    if (r.motion.max_tear_opening > 0.01) ++torn;
    if (r.motion.max_depth > 0.002) ++deep;
    if (r.motion.non_finite) ++non_finite;
    frame_ms += r.motion.mean_frame.total_ms();
  }
  if (results.empty()) return 0;
  std::sort(stretch.begin(), stretch.end());
  const double median = stretch.size() % 2 ? stretch[stretch.size() / 2]
                                           : 0.5 * (stretch[stretch.size() / 2 - 1] + stretch[stretch.size() / 2]);
  std::printf("\n%zu runs: %d torn more than 1 cm open, %d deeper than 2 mm, %d non-finite; stretch median %.0f %%, "
              "largest %.0f %%; the runs' ms per frame summed %.1f; %.0f s in all\n",
              results.size(), torn, deep, non_finite, 100.0 * median, 100.0 * stretch.back(), frame_ms, seconds);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_table(argc, argv);
  } catch (const mrcloth::Error& error) {  // bad options or data: say what, not abort
    std::fprintf(stderr, "bench_walks: %s\n", error.what());
    return 2;
  }
}
