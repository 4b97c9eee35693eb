// Issue 4's benchmark: the shared MakeHuman skirt, unrefined (720 vertices)
// and refined uniformly twice (11088), on CMU walk 07_06 with each body kind
// (capsules along the bones, the skinned MakeHuman mesh): ms per output frame
// split into dynamics and collision, one core, set up by the same calls as
// the plugin's multirescloth.simulate with its defaults (character_setup.h:
// fitted capsules, leg bridges, the waist on the skin, arm clearance, the
// garment cleared of the skinned body). Prints a table (depth:
// the deepest vertex below the body's surface at an output frame; tear: the
// largest opening of an edge at least doubled, SimulationReport::
// max_tear_opening), then where each row's time went (solve, limiter, posing,
// first and later collision rounds, rounds per step), then how much more
// girth than it has the body asks of the skirt on each body (the warning
// multirescloth.simulate gives before such a run).
//
// --flare 0.6 runs a copy of the skirt widened toward its hem (60 % there)
// that goes round the walking body (bench_fit --flare 0.6).
//
// Usage: bench_character [--garment coarse|refined|all] [--body capsules|mesh|all] [--flare AMOUNT] and
//                        the run options of garment_on_character.h (--frames, --preroll,
//                        --rounds, --sweeps, --slack, --step-rate, --threads, ...)
#include "mesh_ops/errors.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/uniform_refine.h"
#include "garment_on_character.h"
#include "solver/character_setup.h"
#include "solver/material.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace mrcloth;

struct BenchOptions {
  std::string garment = "all";  // coarse | refined | all: which rows to run (one row is handy under a profiler)
  std::string body = "all";     // capsules | mesh | all
  double flare = 0.0;           // the skirt widened toward its hem by this (bench::flare_skirt; 0: as shared)
  bench::GarmentRunOptions run;  // 60 frames at 30 fps (2 s of walking) after 0.5 s, one thread (the target is one core's)
};

std::string data(const std::string& relative) { return std::string(MRCLOTH_SHARED_DATA) + "/" + relative; }

struct Row {
  std::string garment, body;
  std::size_t vertices = 0;
  CharacterRunReport report;
  std::vector<HoopLevel> fit;  // bench::GarmentRun::fit
};

/// One row: `garment` (as modelled on base.obj) on a character built as
/// the plugin builds one for `body`.
Row run(const std::string& name, const QuadMesh& garment, const Motion& clip, CharacterBodyKind body,
        const BenchOptions& b) {
  bench::GarmentRunOptions o = b.run;
  o.makehuman_folder = data("bodies/makehuman");
  o.body = body;
  bench::GarmentRun r = bench::run_garment_on_character(garment, clip, o, /*fit=*/true);
  Row row;
  row.garment = name;
  row.body = body == CharacterBodyKind::mesh ? "mesh" : "capsules";
  row.vertices = r.vertices;
  row.report = std::move(r.report);
  row.fit = std::move(r.fit);
  return row;
}

void print(const Row& r) {
  const SimulationReport& m = r.report.motion;
  std::printf("| %-22s | %-8s | %8zu | %9.1f | %9.1f | %9.1f | %7.2f %% | %9.1f | %9.2f | %9d | %s |\n", r.garment.c_str(),
              r.body.c_str(), r.vertices, m.mean_frame.dynamics_ms, m.mean_frame.collision_ms, m.mean_frame.total_ms(),
              100.0 * m.max_stretch, 1000.0 * m.max_tear_opening, 1000.0 * m.max_depth, m.max_self_crossings,
              m.non_finite ? "NaN!" : "ok");
}

/// The first row's fit on each body (bench_fit measures the shared walks):
/// the skirt's most demanding level against its cloth's limit.
void print_fit(const std::vector<Row>& rows) {
  std::printf("\nthe skirt's fit (character_fit.h, as multirescloth.simulate warns before a run; cotton stretches %.0f %%)\n\n",
              100.0 * material_preset("cotton").stretch_limit);
  std::vector<std::string> bodies_done;
  for (const Row& r : rows) {
    if (r.fit.empty() || std::find(bodies_done.begin(), bodies_done.end(), r.body) != bodies_done.end()) continue;
    bodies_done.push_back(r.body);
    const int worst = most_demanding_level(r.fit);
    if (worst < 0) continue;
    const HoopLevel& level = r.fit[static_cast<std::size_t>(worst)];
    std::printf("- %s: the body needs %+.0f %% girth at level %d of %zu (output frame %d)\n", r.body.c_str(),
                100.0 * level.demand(), worst + 1, r.fit.size(), level.frame);
  }
}

/// Where each row's time went, ms per output frame: the solve and the
/// strain limiter (dynamics), posing the body, each step's first collision
/// round and the later rounds (with cloth-cloth contact's gather); and,
/// outside the frame's time, measuring the frame for the report.
void print_parts(const std::vector<Row>& rows) {
  std::printf("\nwhere the time goes, ms per frame (dynamics = solve + limiter; collision = posing + first round + later "
              "rounds; measure: the report's measuring of each frame, not in the frame's time)\n\n");
  std::printf("| %-22s | %-8s | %8s | %8s | %8s | %11s | %12s | %11s | %8s |\n", "garment", "body", "solve", "limiter",
              "posing", "first round", "later rounds", "rounds/step", "measure");
  std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(24, '-').c_str(), std::string(10, '-').c_str(),
              std::string(10, '-').c_str(), std::string(10, '-').c_str(), std::string(10, '-').c_str(),
              std::string(13, '-').c_str(), std::string(14, '-').c_str(), std::string(13, '-').c_str(),
              std::string(10, '-').c_str());
  for (const Row& r : rows) {
    const SimulationReport& m = r.report.motion;
    const FrameTiming& t = m.mean_frame;
    std::printf("| %-22s | %-8s | %8.1f | %8.1f | %8.1f | %11.1f | %12.1f | %11.2f | %8.1f |\n", r.garment.c_str(),
                r.body.c_str(), t.dynamics_ms - t.limiter_ms, t.limiter_ms, t.posing_ms, t.first_round_ms,
                t.collision_ms - t.posing_ms - t.first_round_ms, m.mean_rounds, t.measure_ms);
  }
}

/// Issue 4's target, for the refined skirt on the skinned mesh when it
/// ran: at most 100 ms per frame on one core, collision no slower than
/// dynamics (the paper's collision test took 98 % of its frame).
void print_target(const std::vector<Row>& rows, const BenchOptions& b) {
  for (const Row& r : rows) {
    if (r.garment != "skirt (uniform x2)" || r.body != "mesh") continue;
    const FrameTiming& t = r.report.motion.mean_frame;
    const bool default_rate = b.run.step_rate == CharacterSetup{}.step_rate;
    std::printf("\nthe target (issue 4), the refined skirt on the skinned mesh%s%s: %.1f ms per frame against 100 (%s); "
                "collision %.1f against dynamics %.1f ms (%s)\n",
                b.run.simulation.threads == 1 ? "" : " (not one core: the target is for one)",
                default_rate ? "" : " (not at the default step rate, the mocap rate: the target is for that)", t.total_ms(),
                t.total_ms() <= 100.0 ? "met" : "not met", t.collision_ms, t.dynamics_ms,
                t.collision_ms <= t.dynamics_ms ? "met" : "not met");
    // The solve (the springs' gradient and the factor's triangular solves)
    // is the same work every step at the default iterations, whatever the
    // cloth does: a gauge of the machine against the one the README's
    // 117.0 ms were measured on (861bb6d, 2026-11-27: solve 9.0 ms).
    constexpr double kReferenceSolveMs = 9.0;
    const IntegratorOptions defaults;
    if (b.run.simulation.iterations == defaults.iterations && b.run.simulation.newton_cg == defaults.newton_cg &&
        default_rate)
      std::printf("for scale: the solve, the same work every step, took %.1f ms per frame here and %.1f on the machine "
                  "that measured 117.0 ms per frame (861bb6d, 2026-11-27): this one ran it %.1f times slower (memory-bound parts "
                  "slow down most, the limiter and the checks less: bench/results/collision-cost.md)\n",
                  t.dynamics_ms - t.limiter_ms, kReferenceSolveMs, (t.dynamics_ms - t.limiter_ms) / kReferenceSolveMs);
  }
}

}  // namespace

int run_benchmark(int argc, char** argv) {
  BenchOptions b;
  b.run.simulation.frames = 60;
  const std::string usage = std::string("usage: bench_character [--garment coarse|refined|all] [--body capsules|mesh|all] [--flare AMOUNT] ") +
                            bench::kRunOptionsUsage + "\n";
  const int exit_code = bench::read_command_line(argc, argv, usage, b.run, [&](const std::string& key, const std::string& value) {
    if (key == "--garment") b.garment = value;
    else if (key == "--body") b.body = value;
    else if (key == "--flare") b.flare = std::atof(value.c_str());
    else return false;
    return true;
  });
  if (exit_code >= 0) return exit_code;
  const std::string skirt_path = data("garments/makehuman/skirthelper.obj");
  if (!std::filesystem::exists(skirt_path)) {
    std::printf("shared data absent (%s): nothing to measure\n", skirt_path.c_str());
    return 0;
  }
  BvhReadOptions bvh;
  bvh.scale = 0.056444;         // CMU units to metres
  bvh.skip_first_frame = false;  // make_character drops CMU's added T-pose
  const Motion clip = read_bvh(data("motions/cmu_mb/07_06.bvh"), bvh);
  QuadMesh coarse = load_garment(skirt_path, {"dm"}).mesh;
  bench::flare_skirt(coarse, b.flare);
  QuadMesh high = copy_mesh(coarse);
  uniform_refine(high, 2);
  if (b.flare != 0.0) std::printf("the skirt flared by %.2f toward its hem (bench::flare_skirt)\n", b.flare);
  std::printf("skirt on CMU 07_06, %d frames at 30 fps after a %.1f s pre-roll, %.0f Hz steps, %d thread(s), set up as "
              "multirescloth.simulate sets it up, %s a step, cloth-cloth contact %.1f mm, at most %d rounds of %d limiter sweeps "
              "(acceleration %.3f%s, mass exponent %.2f), contact slack %.2f mm, round tolerance %.3f\n\n",
              b.run.simulation.frames, b.run.preroll, b.run.step_rate, b.run.simulation.threads,
              bench::solve_description(b.run.simulation).c_str(),
              1000.0 * b.run.simulation.self_contact.thickness, b.run.simulation.collision_rounds,
              b.run.simulation.strain_limit_sweeps, b.run.simulation.limiter_acceleration, b.run.simulation.acceleration_from_chain ? " or the chain's" : "",
              b.run.simulation.limiter_mass_exponent, 1000.0 * b.run.simulation.contact_slack,
              b.run.simulation.round_tolerance);
  std::printf("| %-22s | %-8s | %8s | %9s | %9s | %9s | %9s | %9s | %9s | %9s |  |\n", "garment", "body", "vertices",
              "dyn ms/f", "coll ms/f", "total", "stretch", "tear mm", "depth mm", "crossings");
  std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|----|\n", std::string(24, '-').c_str(), std::string(10, '-').c_str(),
              std::string(10, '-').c_str(), std::string(11, '-').c_str(), std::string(11, '-').c_str(),
              std::string(11, '-').c_str(), std::string(11, '-').c_str(), std::string(11, '-').c_str(),
              std::string(11, '-').c_str(), std::string(11, '-').c_str());
  const QuadMesh* garments[] = {&coarse, &high};
  std::vector<Row> rows;
  const auto keep = [&](Row row) {  // printed as soon as it is measured
    print(row);
    rows.push_back(std::move(row));
  };
  for (const QuadMesh* g : garments) {
    const std::string name = g == &coarse ? "skirt (coarse)" : "skirt (uniform x2)";
    if (b.garment != "all" && b.garment != (g == &coarse ? "coarse" : "refined")) continue;
    if (b.body == "all" || b.body == "capsules")
      keep(run(name, *g, clip, CharacterBodyKind::capsules, b));
    if (b.body == "all" || b.body == "mesh") keep(run(name, *g, clip, CharacterBodyKind::mesh, b));
  }
  print_parts(rows);
  print_fit(rows);
  print_target(rows, b);
  return 0;
}

int main(int argc, char** argv) {
  try {
    return run_benchmark(argc, argv);
  } catch (const mrcloth::Error& error) {  // bad options or data: say what, not abort
    std::fprintf(stderr, "bench_character: %s\n", error.what());
    return 2;
  }
}
