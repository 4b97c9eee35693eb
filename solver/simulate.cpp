#include "simulate.h"

#include "point_cache.h"

#include "mesh_ops/errors.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace mrcloth {
namespace {

void check(const SimulationOptions& o) {
  if (o.frames < 1) throw ArgumentError("frames must be >= 1, got " + std::to_string(o.frames));
  if (!(o.fps > 0.0) || !std::isfinite(o.fps)) throw ArgumentError("fps must be > 0");
  if (o.substeps < 1) throw ArgumentError("substeps must be >= 1, got " + std::to_string(o.substeps));
  validate_colliders(o.colliders);
}

/// How deep a point on a surface may measure from round-off (metres): far
/// below any overlap of two body parts, far above the error of the search.
constexpr double kOnSurfaceTolerance = 1e-7;

/// Moves each pinned target that lies below a surface of `scene` (posed for
/// the step's end) out onto it, and returns the farthest move (metres).
/// `start` (#pinned x 3) is where the pins began the step, the side they
/// came from; `hints`, one per pin, start each search where the last ended.
/// Onto the surface, not out to the thickness as cloth is pushed: a pin then
/// leaves its target continuously as the body rises into it.
double yield_pins_to_surfaces(const CollisionScene& scene, const Positions& start, Positions& pinned,
                              std::vector<int>& hints) {
  double farthest = 0.0;
  for (Eigen::Index r = 0; r < pinned.rows(); ++r) {
    const Eigen::Vector3d target = pinned.row(r).transpose();
    const double depth = scene.depths(target, &hints[static_cast<std::size_t>(r)]).depth;
    if (!(depth > 0.0)) continue;
    Eigen::Vector3d out = target;  // out to the thickness from every surface, as cloth is pushed
    scene.resolve(start.row(r).transpose(), out, /*friction=*/false);
    const Eigen::Vector3d push = out - target;
    const double length = push.norm();
    if (!(length > 0.0)) continue;
    // Back along the push to the surface, unless that lies inside another
    // part of the body (two capsules overlapping): then where it was pushed.
    // The surface point itself measures a round-off's depth half the time,
    // which is not another part: taken as such, the pin jumped by the
    // thickness at random (a scene moved by 0.3 m yielded 2 mm farther).
    Eigen::Vector3d onto = target + std::min(depth, length) / length * push;
    if (scene.depths(onto).depth > kOnSurfaceTolerance) onto = out;
    pinned.row(r) = onto.transpose();
    farthest = std::max(farthest, (onto - target).norm());
  }
  return farthest;
}

/// The deepest penetration of the vertices the solver moves: what its first
/// step pushes out (pins are not pushed as cloth is, and their depth is
/// measured apart at every output frame).
double deepest_cloth_penetration(const CollisionScene& scene, const DynamicsModel& model, const Positions& x) {
  double deepest = 0.0;
  if (scene.empty()) return deepest;
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    if (!model.stencil[static_cast<std::size_t>(v)].empty())
      deepest = std::max(deepest, scene.penetration(x.row(v).transpose()));
  return deepest;
}

/// Per measured point (each vertex, then each face centre), the scene's
/// hint from the frame before (CollisionScene::depths): each point starts
/// its search where the last frame's ended.
struct MeasureHints {
  std::vector<int> vertices, faces;
};

// Stretch, penetration (against surface + thickness) and depth (below the
// surface) of one output frame, keeping where the worst of the run was.
// `pool` (null: one thread) measures the vertices in parts; the worst is
// the same as one thread finds (parts merged in order, the first vertex
// wins a tie).
void measure_frame(const CollisionScene& scene, const DynamicsModel& model, const ContactSurface& surface,
                   const Positions& x, int frame, SimulationReport& report, WorkerPool* pool, MeasureHints& hints) {
  report.max_self_crossings = std::max(report.max_self_crossings, count_self_crossings(surface, x, pool));
  const StretchPeak peak = most_stretched(model, x);
  report.max_tear_opening = std::max(report.max_tear_opening, peak.tear_opening);
  report.max_cloth_stretch = std::max(report.max_cloth_stretch, peak.cloth_strain);
  report.max_pinned_stretch = std::max(report.max_pinned_stretch, peak.pinned_strain);
  if (peak.strain > report.max_stretch) {
    report.max_stretch = peak.strain;
    report.stretch_vertices[0] = peak.i;
    report.stretch_vertices[1] = peak.j;
    report.stretch_frame = frame;
  }
  if (scene.empty()) return;
  // The cloth's and the pins' apart: a pinned vertex (no free term in its
  // stencil) goes where what drives the pins takes it, and no step pushes
  // it out (a waist pinned to the pelvis that a thigh rises into in a squat).
  struct Worst {
    double depth = 0.0, penetration = 0.0, cloth_depth = 0.0, cloth_penetration = 0.0, pinned_depth = 0.0;
    int vertex = -1;
  };
  std::vector<Worst> parts(pool ? static_cast<std::size_t>(pool->workers()) : 1);
  const auto measure = [&](int part, std::size_t begin, std::size_t end) {
    Worst& worst = parts[static_cast<std::size_t>(part)];
    for (auto v = static_cast<Eigen::Index>(begin); v < static_cast<Eigen::Index>(end); ++v) {
      const Eigen::Vector3d p = x.row(v).transpose();
      const PointDepths inside = scene.depths(p, &hints.vertices[static_cast<std::size_t>(v)]);
      if (inside.penetration <= 0.0) continue;  // outside surface + thickness, so outside the surface
      worst.depth = std::max(worst.depth, inside.depth);
      if (inside.penetration > worst.penetration) {
        worst.penetration = inside.penetration;
        worst.vertex = static_cast<int>(v);
      }
      if (model.stencil[static_cast<std::size_t>(v)].empty()) {
        worst.pinned_depth = std::max(worst.pinned_depth, inside.depth);
      } else {
        worst.cloth_depth = std::max(worst.cloth_depth, inside.depth);
        worst.cloth_penetration = std::max(worst.cloth_penetration, inside.penetration);
      }
    }
  };
  if (pool) pool->run(static_cast<std::size_t>(x.rows()), measure);
  else measure(0, 0, static_cast<std::size_t>(x.rows()));
  for (std::size_t f = 0; f < model.corners.size(); ++f) {
    const auto& face = model.corners[f];
    const Eigen::Vector3d centre =
        0.25 * (x.row(face[0]) + x.row(face[1]) + x.row(face[2]) + x.row(face[3])).transpose();
    report.max_face_depth = std::max(report.max_face_depth, scene.depths(centre, &hints.faces[f]).depth);  // 0 outside
  }
  for (const Worst& worst : parts) {
    report.max_depth = std::max(report.max_depth, worst.depth);
    report.max_cloth_depth = std::max(report.max_cloth_depth, worst.cloth_depth);
    report.max_cloth_penetration = std::max(report.max_cloth_penetration, worst.cloth_penetration);
    if (worst.pinned_depth > report.max_pinned_depth) {
      report.max_pinned_depth = worst.pinned_depth;
      report.pinned_depth_frame = frame;
    }
    if (worst.vertex >= 0 && worst.penetration > report.max_penetration) {
      report.max_penetration = worst.penetration;
      report.deepest_vertex = worst.vertex;
      report.deepest_frame = frame;
    }
  }
}

}  // namespace

IntegratorOptions integrator_options(const SimulationOptions& options) {
  IntegratorOptions io;
  io.time_step = 1.0 / (options.fps * options.substeps);
  io.iterations = options.iterations;
  io.newton_cg = options.newton_cg;
  io.strain_limit_sweeps = options.strain_limit_sweeps;
  io.limiter_acceleration = options.limiter_acceleration;
  io.acceleration_from_chain = options.acceleration_from_chain;
  io.limiter_mass_exponent = options.limiter_mass_exponent;
  io.t_node_sag = options.t_node_sag;
  io.collision_rounds = options.collision_rounds;
  io.contact_slack = options.contact_slack;
  io.round_tolerance = options.round_tolerance;
  io.tethers = options.tethers;
  io.threads = options.threads;
  io.gravity = options.gravity;
  io.self_contact = options.self_contact;
  return io;
}

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// Sets `integrator` up for the run: a copy of `prepared` when given (it must
/// step as `io` does), else precomputed for `model`. False when `progress`
/// stopped the set-up, which is no frame but can be stopped between phases.
bool set_up_integrator(ImplicitIntegrator& integrator, const DynamicsModel& model, const IntegratorOptions& io,
                       const ImplicitIntegrator* prepared, const SimulationProgress& progress, int frames) {
  if (prepared && prepared->options().time_step != io.time_step)
    throw std::logic_error("simulate: the prepared integrator steps " + std::to_string(prepared->options().time_step) +
                           " s, this run " + std::to_string(io.time_step));
  if (prepared) {
    integrator = *prepared;
    return true;
  }
  const auto keep_going = [&] { return !progress || progress(0, frames); };
  return keep_going() && integrator.precompute(model, io, keep_going);
}

/// Takes one output frame's time steps: pins to their trajectory, bodies
/// posed, pins yielding to the bodies, the integrator's step.
class FrameStepper {
 public:
  FrameStepper(ImplicitIntegrator& integrator, const SimulationOptions& options, const PinTrajectory& pins,
               const MovingBodies& bodies, const CollisionScene& scene, const Positions& rest_pinned)
      : integrator_(integrator),
        options_(options),
        pins_(pins),
        bodies_(bodies),
        scene_(scene),
        rest_pinned_(rest_pinned),
        pinned_next_(rest_pinned),
        pin_hints_(static_cast<std::size_t>(rest_pinned.rows()), -1) {}

  /// Advances `state` by options.substeps steps of output frame `frame`,
  /// adding their times to `timing` and their counts (steps, rounds, the
  /// pins' largest yield) to `report`. False, with report.non_finite set,
  /// once a step leaves a non-finite value.
  bool advance(ClothState& state, int frame, FrameTiming& timing, SimulationReport& report) {
    const double h = integrator_.options().time_step;
    for (int sub = 0; sub < options_.substeps; ++sub) {
      pinned_next_ = rest_pinned_;
      if (pins_) pins_(state.time + h, pinned_next_);
      if (bodies_.pose) {
        // Posing a body (a skinned mesh: skinning, turned triangles, the
        // tree's refit) is part of what collision costs.
        const auto pose_start = std::chrono::steady_clock::now();
        bodies_.pose(state.time + h);
        const double posing_ms = ms_since(pose_start);
        timing.collision_ms += posing_ms;
        timing.posing_ms += posing_ms;
      }
      if (options_.pins_yield && !scene_.empty()) {
        const auto yield_start = std::chrono::steady_clock::now();
        const double moved = yield_pins_to_surfaces(scene_, state.pinned, pinned_next_, pin_hints_);
        if (moved > report.max_pin_yield) {
          report.max_pin_yield = moved;
          report.pin_yield_frame = frame;
        }
        timing.collision_ms += ms_since(yield_start);
      }
      const StepReport step = integrator_.step(state, pinned_next_, scene_);
      timing.dynamics_ms += step.dynamics_ms;
      timing.collision_ms += step.collision_ms;
      timing.limiter_ms += step.limiter_ms;
      timing.first_round_ms += step.first_round_ms;
      report.mean_rounds += step.rounds;
      ++report.steps;
      if (!step.finite) {
        report.non_finite = true;
        return false;
      }
    }
    return true;
  }

 private:
  ImplicitIntegrator& integrator_;
  const SimulationOptions& options_;
  const PinTrajectory& pins_;
  const MovingBodies& bodies_;
  const CollisionScene& scene_;
  const Positions& rest_pinned_;
  Positions pinned_next_;
  std::vector<int> pin_hints_;  // one per pin: where its last search ended
};

/// The mean of each part of `per_frame` (zeros when empty).
FrameTiming mean_timing(const std::vector<FrameTiming>& per_frame) {
  FrameTiming mean;
  for (const FrameTiming& t : per_frame) {
    mean.dynamics_ms += t.dynamics_ms;
    mean.collision_ms += t.collision_ms;
    mean.limiter_ms += t.limiter_ms;
    mean.posing_ms += t.posing_ms;
    mean.first_round_ms += t.first_round_ms;
    mean.measure_ms += t.measure_ms;
  }
  if (!per_frame.empty()) {
    for (double* part : {&mean.dynamics_ms, &mean.collision_ms, &mean.limiter_ms, &mean.posing_ms, &mean.first_round_ms,
                         &mean.measure_ms})
      *part /= static_cast<double>(per_frame.size());
  }
  return mean;
}

}  // namespace

SimulationReport simulate(const DynamicsModel& model, ClothState& state, const SimulationOptions& options,
                          const PinTrajectory& pins, const SimulationProgress& progress,
                          std::vector<Positions>* frames_out, const MovingBodies& bodies,
                          const ImplicitIntegrator* prepared) {
  check(options);
  const AnalyticScene fixed(options.colliders);
  CompositeScene scene;
  scene.add(&fixed);
  if (bodies.scene) scene.add(bodies.scene);
  SimulationReport report;
  const IntegratorOptions io = integrator_options(options);
  report.time_step = io.time_step;

  const auto start = std::chrono::steady_clock::now();
  ImplicitIntegrator integrator;
  if (!set_up_integrator(integrator, model, io, prepared, progress, options.frames)) {
    report.cancelled = true;
    return report;
  }
  report.limiter_acceleration = integrator.limiter_acceleration();
  report.precompute_ms = ms_since(start);

  std::unique_ptr<Pc2Writer> cache;
  if (!options.cache_path.empty())
    cache = std::make_unique<Pc2Writer>(options.cache_path, model.num_vertices, 1.0, 1.0);

  if (bodies.pose) bodies.pose(state.time);
  report.initial_penetration = deepest_cloth_penetration(scene, model, full_positions(model, state.positions, state.pinned));
  const Positions rest_pinned = pinned_rows(model, model.rest);
  const ContactSurface surface = contact_surface(model);
  MeasureHints hints{std::vector<int>(static_cast<std::size_t>(model.num_vertices), -1),
                     std::vector<int>(model.corners.size(), -1)};
  FrameStepper stepper(integrator, options, pins, bodies, scene, rest_pinned);
  for (int frame = 0; frame < options.frames; ++frame) {
    FrameTiming timing;
    if (!stepper.advance(state, frame, timing, report)) break;
    const Positions x = full_positions(model, state.positions, state.pinned);
    const auto measure_start = std::chrono::steady_clock::now();
    measure_frame(scene, model, surface, x, report.frames, report, integrator.pool(), hints);
    timing.measure_ms = ms_since(measure_start);
    if (cache) cache->add_frame(x);
    if (frames_out) frames_out->push_back(x);
    report.per_frame.push_back(timing);
    ++report.frames;
    if (progress && !progress(report.frames, options.frames)) {
      report.cancelled = true;
      break;
    }
  }
  report.mean_frame = mean_timing(report.per_frame);
  if (report.steps > 0) report.mean_rounds /= report.steps;
  // Only a complete, finite run leaves a cache; the writer removes its
  // temporary file otherwise.
  if (cache && !report.cancelled && !report.non_finite) {
    cache->finish();
    report.cache_path = options.cache_path;
  }
  return report;
}

}  // namespace mrcloth
