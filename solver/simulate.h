#pragma once
// Runs a dynamics model over frames: substeps, moving pins, colliders,
// recording to a PC2 cache, timings, progress and cancellation.
#include "collision_scene.h"
#include "dynamics_model.h"
#include "implicit_integrator.h"

#include <functional>
#include <string>
#include <vector>

namespace mrcloth {

struct SimulationOptions {
  int frames = 60;                            ///< output frames to simulate, >= 1
  double fps = 30.0;                          ///< output frames per second, > 0
  int substeps = 4;                           ///< time steps per output frame (h = 1 / (fps * substeps)), >= 1
  int iterations = 2;                         ///< local/global iterations per step
  int newton_cg = IntegratorOptions{}.newton_cg;  ///< see IntegratorOptions: 0 plain iterations, k: Newton steps by k preconditioned CG iterations
  int strain_limit_sweeps = 6;                ///< see IntegratorOptions
  double limiter_acceleration = IntegratorOptions{}.limiter_acceleration;  ///< see IntegratorOptions: rho in [0, 1), 0 plain sweeps
  bool acceleration_from_chain = IntegratorOptions{}.acceleration_from_chain;  ///< see IntegratorOptions
  double limiter_mass_exponent = IntegratorOptions{}.limiter_mass_exponent;  ///< see IntegratorOptions: in [0, 1], 1 mass-weighted projections
  bool t_node_sag = IntegratorOptions{}.t_node_sag;  ///< see IntegratorOptions (experimental, off)
  int collision_rounds = 8;                   ///< see IntegratorOptions
  double contact_slack = 0.002;               ///< metres, see IntegratorOptions
  double round_tolerance = 0.01;              ///< see IntegratorOptions
  bool tethers = true;                        ///< see IntegratorOptions
  int threads = 1;                            ///< see IntegratorOptions (the same bits for any count)
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};   ///< m/s^2
  std::vector<Collider> colliders;            ///< analytic colliders
  SelfContactOptions self_contact;            ///< cloth-cloth contact (self_contact.h); thickness 0: off
  /// A pin whose target lies below a collider's surface is moved out onto
  /// that surface for the step (a thigh rising into a waistband pinned to
  /// the pelvis pushes it, as it pushes the cloth); false: pins exactly at
  /// their targets, inside a body or not.
  bool pins_yield = true;
  std::string cache_path;                     ///< PC2 file of all vertices per frame; empty: none
};

/// Pinned targets at a time: fills `pinned` (#pinned x 3, metres; it holds
/// the rest positions of the pinned vertices on entry). Empty: pins stay at rest.
using PinTrajectory = std::function<void(double time, Positions& pinned)>;

/// Called after every output frame with frames done and total; return false to cancel.
/// Also called with 0 frames done before and between the phases of the set-up
/// (assembly, factorisation: seconds on a large mesh) where a run does its own:
/// false there stops it before its first frame (cancelled, 0 frames, no cache).
using SimulationProgress = std::function<bool(int frames_done, int frames_total)>;

/// Moving bodies: `pose(time)` is called before every step with the time
/// the step ends at, and must leave `scene` posed for that time. The scene
/// is collided with in addition to SimulationOptions::colliders.
struct MovingBodies {
  std::function<void(double time)> pose;
  const CollisionScene* scene = nullptr;
};

struct FrameTiming {
  double dynamics_ms = 0.0;    ///< local/global iterations and strain limiting
  double collision_ms = 0.0;   ///< posing the moving bodies (skinning, refitting the tree) and resolving contacts
  // Parts of the two, for finding where the time goes:
  double limiter_ms = 0.0;      ///< of dynamics_ms: strain limiting
  double posing_ms = 0.0;       ///< of collision_ms: posing the moving bodies
  double first_round_ms = 0.0;  ///< of collision_ms: each step's first round (every vertex against the new pose)
  /// Not part of the simulation (nor of total_ms): measuring the output frame
  /// for the report (stretch, depths against the bodies, self-crossings).
  double measure_ms = 0.0;
  double total_ms() const { return dynamics_ms + collision_ms; }
};

struct SimulationReport {
  int frames = 0;                      ///< output frames completed
  int steps = 0;                       ///< time steps taken
  double time_step = 0.0;              ///< seconds
  double precompute_ms = 0.0;          ///< model factorisation
  double max_stretch = 0.0;            ///< largest stretch-spring strain at any output frame
  double max_cloth_stretch = 0.0;      ///< the same over springs with an end the solver moves (StretchPeak::cloth_strain)
  double max_pinned_stretch = 0.0;     ///< the same over springs whose ends both follow pins (StretchPeak::pinned_strain): set by what drives the pins
  double max_tear_opening = 0.0;       ///< largest StretchPeak::tear_opening at any output frame, metres (0: no spring ever doubled)
  double max_penetration = 0.0;        ///< deepest vertex inside collider + thickness at any output frame, metres
  double initial_penetration = 0.0;    ///< the same for the start state, over the vertices the solver moves: > 0 means the cloth began inside a collider
  double max_depth = 0.0;              ///< deepest vertex below a collider's surface itself (thickness not counted) at any output frame, metres
  double max_cloth_penetration = 0.0;  ///< max_penetration over the vertices the solver moves (a free term in their stencil), metres
  double max_cloth_depth = 0.0;        ///< max_depth over those, metres
  double max_pinned_depth = 0.0;       ///< max_depth over the vertices that follow pins alone (what drives the pins put them there), metres
  int pinned_depth_frame = -1;         ///< output frame (0-based) of max_pinned_depth (-1: no pin ever below a surface)
  double max_pin_yield = 0.0;          ///< farthest a pin was moved off its target onto a surface (pins_yield), metres
  int pin_yield_frame = -1;            ///< the output frame (0-based) whose steps did that (-1: no pin ever yielded)
  /// Deepest face centre (the mean of an active face's four corners) below
  /// a collider's surface itself at any output frame, metres: only vertices
  /// collide, so a large face resting on a curved body sinks into it
  /// between its corners (the body shows through the cloth).
  double max_face_depth = 0.0;
  int max_self_crossings = 0;          ///< most edge-triangle crossings of the cloth with itself at any output frame (count_self_crossings)
  int deepest_vertex = -1;             ///< where max_penetration was met: full vertex id (-1: never within thickness)
  int deepest_frame = -1;              ///< and output frame (0-based)
  /// Whether that vertex follows pins alone.
  bool penetration_pinned() const { return max_penetration > max_cloth_penetration; }
  int stretch_vertices[2] = {-1, -1};  ///< the ends of the spring that had max_stretch (-1: never stretched)
  int stretch_frame = -1;              ///< and output frame (0-based)
  /// Whether that spring's ends both follow pins.
  bool stretch_pinned() const { return max_pinned_stretch > max_cloth_stretch; }
  double limiter_acceleration = 0.0;   ///< the Chebyshev estimate the limiter used (ImplicitIntegrator::limiter_acceleration)
  double mean_rounds = 0.0;            ///< strain-limiting/collision rounds per step, mean (1 .. collision_rounds): what a step's dynamics cost grows with
  bool non_finite = false;             ///< a NaN or infinity appeared (the run stops there)
  bool cancelled = false;              ///< the progress callback asked to stop (no cache is written)
  std::vector<FrameTiming> per_frame;  ///< timings of every output frame
  FrameTiming mean_frame;              ///< their mean, ms per frame
  std::string cache_path;              ///< the PC2 written, empty if none
};

/// Simulates from `initial` (advanced in place) for options.frames frames.
/// The PC2 cache (if asked) holds one sample per output frame, sample k at
/// time (k + 1) / fps, of all vertices (hanging and pinned included). It
/// appears only when the run completes; a cancelled or failed run leaves none.
/// `frames_out`, if given, receives the full positions of every output frame.
/// `prepared`, if given, is an integrator precomputed for `model` with
/// integrator_options(options), which the run copies instead of factorising
/// again (a character's pre-roll and motion share one; the same bits):
/// its precompute_ms is then the copy's.
SimulationReport simulate(const DynamicsModel& model, ClothState& initial, const SimulationOptions& options,
                          const PinTrajectory& pins = {}, const SimulationProgress& progress = {},
                          std::vector<Positions>* frames_out = nullptr, const MovingBodies& bodies = {},
                          const ImplicitIntegrator* prepared = nullptr);

/// The integrator's options for a run with `options` (its step: 1 / (fps x substeps)).
IntegratorOptions integrator_options(const SimulationOptions& options);

}  // namespace mrcloth
