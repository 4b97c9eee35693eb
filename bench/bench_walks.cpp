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
// skinned mesh. Columns: depth (deepest vertex the solver moves below the
// body's surface at an output frame), pins (the same for pinned vertices,
// which go where the body takes them), largest edge stretch, tear (the
// largest opening of an edge at least doubled), ms per frame (dynamics,
// collision). Then a summary: runs torn more than 1 cm open, runs with
// cloth (and with pins) deeper than 2 mm, the median and largest stretch
// (of all runs, and of the refined ones), the total time. With several
// pre-rolls, a table and summary each, then one over them all: the README's
// walk table is `--prerolls 0.5,0.501,0.502`.
//
// Usage: bench_walks [--kinds LIST] [--garments LIST] [--walks LIST] [--prerolls LIST]
//                    and the run options of garment_on_character.h (--frames,
//                    --preroll, --rounds, --sweeps, --slack, --threads, ...)
//   LIST: comma-separated; kinds coarse-capsules,coarse-mesh,refined-mesh;
//   garments skirt,knee,trousers; walks 07_06,07_03,08_03,02_01 (and
//   16_15_daz: a walk on the DAZ-named skeleton, not in the default list).
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/uniform_refine.h"
#include "garment_on_character.h"
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
  std::vector<std::string> kinds{"coarse-capsules", "coarse-mesh", "refined-mesh"};
  std::vector<std::string> garments{"skirt", "knee", "trousers"};
  std::vector<std::string> walks{"07_06", "07_03", "08_03", "02_01"};
  std::vector<double> prerolls;  ///< seconds, one table each; empty: run.preroll's alone
  bench::GarmentRunOptions run;  // 60 frames at 30 fps after a 0.5 s pre-roll, the plugin's solver defaults
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
  // 16_15_daz: CMU 16_15 on the DAZ-friendly skeleton (centimetres, DAZ
  // names), renamed onto CMU names as motion.joints "auto" renames it.
  const bool daz = walk == "16_15_daz";
  BvhReadOptions bvh;
  bvh.scale = daz ? 0.01 : 0.056444;  // to metres
  bvh.skip_first_frame = false;       // make_character drops the added T-pose
  Motion clip = read_bvh(data(daz ? "motions/cmu_daz/16_15_daz.bvh" : "motions/cmu_mb/" + walk + ".bvh"), bvh);
  standardise_clip(clip);  // as motion.joints and motion.axes "auto" do
  QuadMesh mesh = load_garment(data(garment_file(garment)), {"dm"}).mesh;
  if (kind == "refined-mesh") uniform_refine(mesh, 1);
  bench::GarmentRunOptions o = w.run;
  o.makehuman_folder = data("bodies/makehuman");
  o.body = kind == "coarse-capsules" ? CharacterBodyKind::capsules : CharacterBodyKind::mesh;
  bench::GarmentRun run = bench::run_garment_on_character(mesh, clip, o);
  Result r{garment, walk, kind, run.vertices, std::move(run.report.motion)};
  return r;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// The summary line of `results` (not empty), under `label`.
void print_summary(const std::string& label, const std::vector<Result>& results, double seconds) {
  std::vector<double> stretch, refined;
  int torn = 0, deep = 0, deep_pins = 0, non_finite = 0;
  double frame_ms = 0.0, face_depth = 0.0;
  for (const Result& r : results) {
    face_depth = std::max(face_depth, r.motion.max_face_depth);
    stretch.push_back(r.motion.max_stretch);
    if (r.kind == "refined-mesh") refined.push_back(r.motion.max_stretch);
    if (r.motion.max_tear_opening > 0.01) ++torn;
    if (r.motion.max_cloth_depth > 0.002) ++deep;
    if (r.motion.max_pinned_depth > 0.002) ++deep_pins;
    if (r.motion.non_finite) ++non_finite;
    frame_ms += r.motion.mean_frame.total_ms();
  }
  std::string refined_text;
  if (!refined.empty()) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, " (refined runs: median %.0f %%, largest %.0f %%)", 100.0 * median(refined),
                  100.0 * *std::max_element(refined.begin(), refined.end()));
    refined_text = buffer;
  }
  std::printf("\n%s%zu runs: %d torn more than 1 cm open, %d with cloth deeper than 2 mm (%d with pins deeper), %d "
              "non-finite; stretch median %.0f %%, largest %.0f %%%s; face centres at most %.1f mm inside a body (only "
              "vertices collide); the runs' ms per frame summed %.1f; %.0f s in all\n",
              label.c_str(), results.size(), torn, deep, deep_pins, non_finite, 100.0 * median(stretch),
              100.0 * *std::max_element(stretch.begin(), stretch.end()), refined_text.c_str(), 1000.0 * face_depth,
              frame_ms, seconds);
}

int run_table(int argc, char** argv) {
  WalkOptions w;
  w.run.simulation.frames = 60;
  const std::string usage = std::string("usage: bench_walks [--kinds LIST] [--garments LIST] [--walks LIST] [--prerolls S,S,...] ") +
                            bench::kRunOptionsUsage + "\n";
  const int exit_code = bench::read_command_line(argc, argv, usage, w.run, [&](const std::string& key, const std::string& value) {
    if (key == "--kinds") w.kinds = split_list(value);
    else if (key == "--garments") w.garments = split_list(value);
    else if (key == "--walks") w.walks = split_list(value);
    else if (key == "--prerolls") {
      w.prerolls.clear();
      for (const std::string& item : split_list(value)) {
        char* end = nullptr;
        const double seconds = std::strtod(item.c_str(), &end);
        if (end == item.c_str() || *end != '\0' || !(seconds >= 0.0))
          throw ArgumentError("--prerolls: '" + item + "' is not a number of seconds >= 0");
        w.prerolls.push_back(seconds);
      }
    } else return false;
    return true;
  });
  if (exit_code >= 0) return exit_code;
  if (!std::filesystem::exists(data("bodies/makehuman/base.obj"))) {
    std::printf("shared data absent (%s): nothing to measure\n", data("").c_str());
    return 0;
  }
  if (w.prerolls.empty()) w.prerolls.push_back(w.run.preroll);
  std::string prerolls;
  for (const double seconds : w.prerolls) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%s%.3f", prerolls.empty() ? "" : ", ", seconds);
    prerolls += buffer;
  }
  std::printf("the walk table: %d frames at 30 fps after a pre-roll of %s s, at most %d rounds of %d limiter sweeps "
              "(acceleration %.3f%s, mass exponent %.2f), %s a step, %d thread(s)\n",
              w.run.simulation.frames, prerolls.c_str(), w.run.simulation.collision_rounds,
              w.run.simulation.strain_limit_sweeps, w.run.simulation.limiter_acceleration, w.run.simulation.acceleration_from_chain ? " or the chain's" : "",
              w.run.simulation.limiter_mass_exponent, bench::solve_description(w.run.simulation).c_str(),
              w.run.simulation.threads);
  std::vector<Result> all;
  const auto start = std::chrono::steady_clock::now();
  for (const double preroll : w.prerolls) {
    w.run.preroll = preroll;
    if (w.prerolls.size() > 1) std::printf("\n### pre-roll %.3f s\n", preroll);
    std::printf("\n| %-8s | %-5s | %-15s | %8s | %8s | %8s | %9s | %8s | %8s | %8s | %8s | %9s |\n", "garment", "walk", "kind",
                "vertices", "depth mm", "pins mm", "stretch", "tear mm", "dyn ms/f", "coll ms/f", "faces mm", "crossings");
    std::printf("|----------|-------|-----------------|----------|----------|----------|-----------|----------|----------|----------|----------|-----------|\n");
    std::vector<Result> results;
    const auto table_start = std::chrono::steady_clock::now();
    for (const std::string& garment : w.garments)
      for (const std::string& kind : w.kinds)
        for (const std::string& walk : w.walks) {
          Result r = run(garment, walk, kind, w);
          const SimulationReport& m = r.motion;
          std::printf("| %-8s | %-5s | %-15s | %8zu | %8.1f | %8.1f | %7.0f %% | %8.1f | %8.1f | %8.1f | %8.1f | %9d |%s\n",
                      garment.c_str(), walk.c_str(), kind.c_str(), r.vertices, 1000.0 * m.max_cloth_depth,
                      1000.0 * m.max_pinned_depth, 100.0 * m.max_stretch,
                      1000.0 * m.max_tear_opening, m.mean_frame.dynamics_ms, m.mean_frame.collision_ms,
                      1000.0 * m.max_face_depth, m.max_self_crossings, m.non_finite ? " NaN!" : "");
          std::fflush(stdout);
          results.push_back(std::move(r));
        }
    if (results.empty()) return 0;
    print_summary("", results, std::chrono::duration<double>(std::chrono::steady_clock::now() - table_start).count());
    all.insert(all.end(), results.begin(), results.end());
  }
  if (w.prerolls.size() > 1)
    print_summary("over every pre-roll: ", all,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
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
