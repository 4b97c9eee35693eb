#pragma once
// One shared MakeHuman garment on a CMU clip, set up as the plugin's
// multirescloth.simulate sets it up (character_setup.h: make_character,
// place_garment, character_run_options; the waist loop pinned), for the
// benchmarks that time such runs (bench_character) and count how whole
// they stay (bench_walks).
#include "mesh_ops/boundary_loops.h"
#include "solver/character_fit.h"
#include "solver/character_setup.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace mrcloth::bench {

/// What a benchmark varies about a garment run.
struct GarmentRunOptions {
  std::string makehuman_folder;  ///< bodies/makehuman of the shared data
  CharacterBodyKind body = CharacterBodyKind::mesh;
  double preroll = 0.5;                                     ///< seconds, not recorded
  double step_rate = CharacterSetup{}.step_rate;            ///< time steps per second
  double stretch_stiffness = Material{}.stretch_stiffness;  ///< N/m, the cloth's stretch springs (cotton's by default)
  bool hand_mittens = CharacterSetup{}.hand_mittens;        ///< mesh body: the hands collide as capsules
  double waist_smoothing = CharacterSetup{}.waist_smoothing;  ///< metres along a skinned waist its pins' weights are averaged over
  SimulationOptions simulation;                             ///< frames and the solver's settings
};

struct GarmentRun {
  std::size_t vertices = 0;  ///< of the placed garment
  CharacterRunReport report;
  std::vector<HoopLevel> fit;  ///< garment_fit, when asked for (run_garment_on_character)
};

/// The command-line options both benchmarks take for a run, after their own.
inline constexpr const char* kRunOptionsUsage =
    "[--frames N] [--preroll S] [--step-rate HZ] [--rounds N] [--sweeps N] [--acceleration RHO|auto] [--mass-exponent E] "
    "[--slack METRES] "
    "[--round-tolerance STRAIN] [--tethers 0|1] [--iterations N] [--newton-cg K] [--stretch-stiffness N/M] "
    "[--self-contact METRES] [--self-contact-neighbourhood METRES] [--self-contact-reach METRES] [--mittens 0|1] [--waist-smoothing METRES] [--threads N]";

/// Takes option `key` with `value` into `o` when it is one of
/// kRunOptionsUsage's; false when it is not.
inline bool take_run_option(const std::string& key, const char* value, GarmentRunOptions& o) {
  SimulationOptions& s = o.simulation;
  if (key == "--frames") s.frames = std::atoi(value);
  else if (key == "--preroll") o.preroll = std::atof(value);
  else if (key == "--step-rate") o.step_rate = std::atof(value);
  else if (key == "--rounds") s.collision_rounds = std::atoi(value);
  else if (key == "--sweeps") s.strain_limit_sweeps = std::atoi(value);
  else if (key == "--acceleration" && std::string(value) == "auto") s.acceleration_from_chain = true;
  else if (key == "--acceleration") {
    s.limiter_acceleration = std::atof(value);
    s.acceleration_from_chain = false;
  }
  else if (key == "--mass-exponent") s.limiter_mass_exponent = std::atof(value);
  else if (key == "--slack") s.contact_slack = std::atof(value);
  else if (key == "--round-tolerance") s.round_tolerance = std::atof(value);
  else if (key == "--tethers") s.tethers = std::atoi(value) != 0;
  else if (key == "--iterations") s.iterations = std::atoi(value);
  else if (key == "--newton-cg") s.newton_cg = std::atoi(value);
  else if (key == "--stretch-stiffness") o.stretch_stiffness = std::atof(value);
  else if (key == "--self-contact") s.self_contact.thickness = std::atof(value);
  else if (key == "--self-contact-neighbourhood") s.self_contact.neighbourhood = std::atof(value);
  else if (key == "--self-contact-reach") s.self_contact.reach = std::atof(value);
  else if (key == "--threads") s.threads = std::atoi(value);
  else if (key == "--mittens") o.hand_mittens = std::atoi(value) != 0;
  else if (key == "--waist-smoothing") o.waist_smoothing = std::atof(value);
  else return false;
  return true;
}

/// The solve a run takes per step, for the benchmarks' headers: "2 iterations", or
/// "2 Newton iterations of 1 CG".
inline std::string solve_description(const SimulationOptions& s) {
  return std::to_string(s.iterations) +
         (s.newton_cg > 0 ? " Newton iterations of " + std::to_string(s.newton_cg) + " CG" : " iterations");
}

/// Reads "--key value" pairs: `own(key, value)` takes a benchmark's own
/// options (false: not one of them), then take_run_option the run's into
/// `run`. Returns -1 to go on, else the exit code: 0 after --help, 2 after
/// a bad command line (said on stderr with the usage).
template <typename Own>
int read_command_line(int argc, char** argv, const std::string& usage, GarmentRunOptions& run, Own own) {
  for (int a = 1; a < argc; a += 2) {
    const std::string key = argv[a];
    if (key == "--help" || key == "-h") {
      std::printf("%s", usage.c_str());
      return 0;
    }
    if (a + 1 == argc) {
      std::fprintf(stderr, "option %s needs a value\n%s", argv[a], usage.c_str());
      return 2;
    }
    if (!own(key, std::string(argv[a + 1])) && !take_run_option(key, argv[a + 1], run)) {
      std::fprintf(stderr, "unknown option %s\n%s", argv[a], usage.c_str());
      return 2;
    }
  }
  return -1;
}

/// Widens a skirt toward its hem (the fit experiment): each vertex moves
/// away from the vertical line through the mean of all of them, by the
/// factor 1 + amount s^2 at the fraction s of the way from its top (0) to
/// its bottom (1): 0 leaves it as it is, 0.6 makes its hem 60 % wider.
inline void flare_skirt(QuadMesh& skirt, double amount) {
  if (amount == 0.0) return;
  double cx = 0.0, cz = 0.0, top = -1e300, bottom = 1e300;
  for (const auto v : skirt.vertices()) {
    const auto p = skirt.point(v);
    cx += p[0];
    cz += p[2];
    top = std::max<double>(top, p[1]);
    bottom = std::min<double>(bottom, p[1]);
  }
  cx /= static_cast<double>(skirt.n_vertices());
  cz /= static_cast<double>(skirt.n_vertices());
  for (const auto v : skirt.vertices()) {
    auto p = skirt.point(v);
    const double s = (top - p[1]) / (top - bottom), factor = 1.0 + amount * s * s;
    p[0] = cx + factor * (p[0] - cx);
    p[2] = cz + factor * (p[2] - cz);
    skirt.set_point(v, p);
  }
}

/// A garment placed on a character as multirescloth.simulate places it,
/// with its model and run settings.
struct PreparedGarment {
  Character character;
  PlacedGarment placed;
  DynamicsModel model;
  CharacterRunOptions run;
};

/// `garment` (as modelled on base.obj, metres) placed on `clip` (as read,
/// frame 0 kept) with the waist loop pinned.
inline PreparedGarment prepare_garment_on_character(const QuadMesh& garment, const Motion& clip,
                                                    const GarmentRunOptions& o) {
  CharacterSetup setup;
  setup.body = o.body;
  setup.makehuman = makehuman_files(o.makehuman_folder);
  setup.place = GarmentPlacement::makehuman;
  setup.preroll_seconds = o.preroll;
  setup.step_rate = o.step_rate;
  setup.hand_mittens = o.hand_mittens;
  setup.waist_smoothing = o.waist_smoothing;
  PreparedGarment g{make_character(clip, setup, garment), {}, {}, {}};
  g.placed = place_garment(g.character, setup, garment);
  DynamicsOptions d;
  d.pinned = boundary_loop_by_name(g.placed.mesh, "top");
  d.material.stretch_stiffness = o.stretch_stiffness;
  g.model = build_dynamics(g.placed.mesh, d);
  g.run = character_run_options(g.character, setup, g.model, o.simulation);
  return g;
}

/// What multirescloth.simulate measures of a prepared tube garment's fit
/// before its run (run_hoop_demand; empty for other garments).
inline std::vector<HoopLevel> garment_fit(const PreparedGarment& g) {
  return run_hoop_demand(*g.character.motion, *g.character.body, g.run, g.placed.mesh);
}

/// Runs `garment` (as modelled on base.obj, metres) on `clip` (as read,
/// frame 0 kept); with `fit`, also measures garment_fit first.
inline GarmentRun run_garment_on_character(const QuadMesh& garment, const Motion& clip, const GarmentRunOptions& o,
                                           bool fit = false) {
  PreparedGarment g = prepare_garment_on_character(garment, clip, o);
  ClothState state = rest_state(g.model);
  GarmentRun out;
  out.vertices = g.placed.mesh.n_vertices();
  if (fit) out.fit = garment_fit(g);
  out.report = simulate_on_character(g.model, state, *g.character.motion, *g.character.body, g.run);
  return out;
}

}  // namespace mrcloth::bench
