#pragma once
// Implicit Euler for the multi-resolution mass-spring system, solved as in
// Liu et al. 2013 ("Fast Simulation of Mass-Spring Systems"): a few
// local/global iterations per step, each a spring-direction projection
// (local) and one solve with a matrix that is factorised once (global).
//
// In free coordinates q (x = S q + P p) a step minimises
//   1/(2h^2) |q - y|^2_M + E_springs(S q + P p_next),  y = q_n + h v_n + h^2 g / 2,
// then v = damped (q - q_n) / h + h g / 2: gravity, a constant acceleration,
// is integrated exactly (free fall is the true parabola, and at rest the
// springs carry the full weight), the springs implicitly.
// Each iteration takes q += -Q^-1 grad, with the constant
//   Q = M/h^2 + S^T (L_stretch + L_shear + L_bend') S,
// L the spring Laplacians weighted by stiffness. For stretch and shear this
// is exactly Liu et al.'s global step. A bend spring i-k through its middle
// vertex j enters Q as two springs i-j and j-k of twice its stiffness: this
// keeps the factor's fill that of the one-ring, and since
// |xi - xk|^2 <= 2 (|xi - xj|^2 + |xj - xk|^2) the matrix dominates the true
// one, so the iteration still converges (monotonically) and translations
// stay exact.
//
// Then contacts, found once per step: every free vertex and T-node is
// resolved against the scene (posed for the end of the step, so it does
// not move within it), with friction on the step's motion, and keeps a
// contact plane for the rest of the step: across its push where it was
// pushed, else the tangent plane of a surface within reach. Gauss-Seidel
// sweeps (Chebyshev-accelerated while they meet springs far beyond the
// limit) then bound every stretch spring to (1 + stretch_limit) of its rest
// length (strain limiting, in free coordinates, so T-nodes stay exact),
// keeping each point in front of its plane, so the limiter pulls cloth
// along the body rather than into it and the stretch goes to the cloth that
// is free to move; each sweep starts with tethers that keep every free
// vertex within the cloth's reach of its nearest pinned vertex. A point the
// limiter moved farther than its slack (its clearance, or contact_slack
// along a plane, less where another part of the body lies just behind) from
// where it was checked is checked again, and limiting and checking
// alternate in rounds while checks or cloth-cloth contact move points or
// springs the limiter can move (not those between two pins) stay beyond the
// round tolerance.
//
// With newton_cg k >= 1 each iteration is instead a Newton step: the
// springs' Hessian at the iterate (each spring's negative part dropped),
// solved by k conjugate-gradient iterations preconditioned by Q. Q
// overstates the sideways stiffness of every spring (k for a taut spring
// whose true sideways stiffness is its tension over its length), so the
// plain iteration moves the cloth's slow bending and swinging motion only
// a small part of the way per iteration; conjugate gradients scale each
// direction by the true curvature. The solve costs about 1.4 times the
// plain one on a body, twice in a free swing; less numerical damping
// (README, The free swing).
//
// Accuracy trade-off: with few iterations the step is a damped
// approximation of implicit Euler (energy is lost in stiff directions,
// which also makes it stable at any time step); stretch is bounded by the
// strain limit rather than by convergence.
#include "collision_scene.h"
#include "dynamics_model.h"
#include "self_contact.h"
#include "sparse_ldlt3.h"
#include "spring_energy.h"
#include "worker_pool.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace mrcloth {

struct IntegratorOptions {
  double time_step = 1.0 / 120.0;               ///< seconds, > 0
  int iterations = 2;                           ///< local/global iterations per step, >= 1 (more: stiffer, less damped)
  int newton_cg = 0;                            ///< >= 0; 0: each iteration steps by Q^-1 grad (Liu et al.); k: each is a Newton step solved by k conjugate-gradient iterations preconditioned by Q (less damped per iteration, see above)
  int strain_limit_sweeps = 6;                  ///< Gauss-Seidel sweeps over stretch springs (and tethers) per round, >= 0
  double limiter_acceleration = 0.97;           ///< spectral radius estimate rho in [0, 1) for Chebyshev acceleration of a round's sweeps (see limit_strain); 0: plain sweeps
  bool acceleration_from_chain = true;          ///< raise rho to chain_spectral_radius(model) (see there) in rounds not near rest (see limit_strain); with limiter_acceleration 0 still plain sweeps
  double limiter_mass_exponent = 0.5;           ///< the limiter moves a vertex in proportion to mass^-exponent, in [0, 1]: 1 mass-weighted (momentum-conserving), 0 equal; 0.5 converges on multi-resolution meshes, whose masses differ up to 16-fold (see projection_weights in integrator_setup.cpp; README, Limiter weights)
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};     ///< m/s^2
  int collision_rounds = 8;                     ///< at most this many rounds of (strain limiting, collision checks) per step, >= 1
  double round_tolerance = 0.01;                ///< another round also while a spring starts it this much strain beyond the limit (0.01 = 1 %)
  double contact_slack = 0.002;                 ///< metres, >= 0: how far the limiter may move a point along its contact plane before the point is checked against the scene again
  bool contact_planes = true;                   ///< the strain limiter keeps points in front of their contact planes (see above)
  bool tethers = true;                          ///< the strain limiter also keeps each free vertex within the cloth's reach of its nearest pinned vertex
  SelfContactOptions self_contact;              ///< cloth-cloth contact (self_contact.h), projected in every round before the body collisions; thickness 0: off
  bool active_set = true;                       ///< the limiter evaluates only springs whose vertices moved since their last evaluation (same bits, less work); false: every spring every sweep
  bool t_node_sag = false;                      ///< experimental: the limiter reads a spring from a T-node into the finer side from the T-node moved by the bulge of the fine row beside it (fine_row_bulge), as the fine cloth would measure it, not from its coarse edge's chord (README, The drape on a still body)
  int threads = 1;                              ///< threads resolving the vertices' collisions, >= 1; the same bits for any count (each vertex's resolve is its own)
};

/// State in free coordinates (rows follow DynamicsModel::free_vertices).
struct ClothState {
  Positions positions;   ///< #free x 3, metres
  Positions velocities;  ///< #free x 3, m/s
  Positions pinned;      ///< #pinned x 3, current pinned targets, metres
  double time = 0.0;     ///< seconds
};

/// The weight of Chebyshev semi-iterative acceleration after iteration
/// `iteration` (0-based) of an iteration whose error shrinks by about `rho`
/// (in [0, 1)) per step, given the weight after the one before: 1, then
/// 2 / (2 - rho^2), then 4 / (4 - rho^2 previous), rising to
/// 2 / (1 + sqrt(1 - rho^2)). The accelerated iterate is
/// older + weight (new - older), older the iterate two iterations back.
double chebyshev_weight(int iteration, double rho, double previous);

/// How far the middle `c` of a fine row bulges off the chord of its two
/// neighbours `ca`, `cb` (metres): c - (ca + cb) / 2, shortened to at most
/// `cap` metres. Added to a T-node on the coarse edge beside that row it
/// puts the T-node where the fine cloth would have its vertex: on a
/// cylinder curved along the edge, exactly on the cylinder.
Eigen::Vector3d fine_row_bulge(const Eigen::Vector3d& c, const Eigen::Vector3d& ca, const Eigen::Vector3d& cb, double cap);

/// A spring from a T-node into the finer side, with the fine row beside
/// the T-node's coarse edge that t_node_sag reads it by (full vertex ids).
struct FineRow {
  int spring = -1;          ///< index in DynamicsModel::springs (a stretch spring)
  int t_node = -1;          ///< its end on the coarse edge, halfway between two free parents a and b
  int c = -1;               ///< its other end, off the coarse edge
  int ca = -1, cb = -1;     ///< c's neighbours joined to a and to b (free, pinned or T-nodes)
};

/// Every stretch spring of `model` from a T-node halfway between two free
/// parents to a vertex off their edge whose fine row is found (c has
/// neighbours joined to both parents), in spring order.
std::vector<FineRow> t_node_fine_rows(const DynamicsModel& model);

/// The spectral radius of Gauss-Seidel sweeps along a chain as long as the
/// model's longest: cos^2(pi / (n + 1)), n the most stretch springs between
/// a pin and any vertex (along the shortest way). The strain limiter's
/// corrections cross a garment like that chain, so this is the Chebyshev
/// estimate its sweeps need: 0.9755 for the shared skirt (19 links), 0.9935
/// refined once, 0.998 twice. 0 without pins.
double chain_spectral_radius(const DynamicsModel& model);

/// The rest state of a model at rest velocity 0, pinned at their rest positions.
ClothState rest_state(const DynamicsModel& model);

struct StepReport {
  double dynamics_ms = 0.0;        ///< local/global iterations and strain limiting
  double collision_ms = 0.0;       ///< collision checks, bodies and cloth-cloth contact
  double limiter_ms = 0.0;         ///< of dynamics_ms: strain limiting, all rounds
  double first_round_ms = 0.0;     ///< of collision_ms: the first check (every vertex against the new pose)
  double max_correction = 0.0;     ///< largest collision push-out this step, metres
  int rounds = 0;                  ///< rounds of (strain limiting, collision checks) taken
  bool finite = true;              ///< false if any position became NaN or infinite
};

class ImplicitIntegrator {
 public:
  /// Consulted between precompute's phases (after assembling the system,
  /// after ordering it, after factorising it, after the contact set-up);
  /// returns false to stop.
  using KeepGoing = std::function<bool()>;

  /// Assembles and factorises Q for `model` (kept by reference: it must
  /// outlive the integrator) and the options. Throws ArgumentError for bad
  /// options. Returns false when `keep_going` stopped it: the integrator is
  /// then not ready and must not step. The callback changes nothing else.
  bool precompute(const DynamicsModel& model, const IntegratorOptions& options, const KeepGoing& keep_going = {});

  /// The Chebyshev estimate the limiter uses: the options', raised to the
  /// chain's with acceleration_from_chain (valid after precompute).
  double limiter_acceleration() const { return rho_; }
  /// Advances `state` by one time step to time + h, with the pinned vertices
  /// moving to `pinned_next` (#pinned x 3), colliding with `scene` as posed
  /// for the end of the step.
  StepReport step(ClothState& state, const Positions& pinned_next, const CollisionScene& scene);
  /// The same with a fixed set of analytic colliders.
  StepReport step(ClothState& state, const Positions& pinned_next, const std::vector<Collider>& colliders);

  const IntegratorOptions& options() const { return options_; }

  /// A free vertex kept within `max_length` (metres) of a pinned vertex.
  struct Tether {
    int free = -1;            ///< free index
    int pinned = -1;          ///< the pinned vertex's full index
    double max_length = 0.0;  ///< (1 + stretch limit) x its distance over the cloth at rest
  };
  std::size_t factor_nonzeros() const { return solver_.factor_nonzeros(); }
  /// The threads options().threads asked for (null for one): callers may
  /// run their own per-vertex loops on it between steps.
  WorkerPool* pool() const { return pool_.get(); }

 private:
  /// Also keeps each spring's projected Hessian at q when newton_cg > 0.
  void gradient(const Positions& q, const Positions& y, Positions& grad) const;
  /// delta ~ H^-1 grad (H = M/h^2 + S^T K S, K the springs' projected
  /// Hessians from the last gradient) by newton_cg preconditioned CG iterations.
  void newton_direction(const Positions& grad, Positions& delta) const;
  /// out = H v (free coordinates, #free x 3).
  void hessian_product(const Positions& v, Positions& out) const;
  /// The step's local/global iterations from the inertial prediction y
  /// (#free x 3): q, warm-started, becomes the solve's result.
  void solve_dynamics(const Positions& y, Positions& q) const;
  /// The step's collision checks and strain-limiting rounds on the solved
  /// q, from q_previous (the step's start); adds their times and counts to
  /// `report`.
  void collide_and_limit(const Positions& q_previous, Positions& q, const CollisionScene& scene, StepReport& report);
  /// Returns the largest strain beyond the limit it met (0 when none).
  double limit_strain(Positions& q) const;
  /// Chebyshev extrapolation after a limiter sweep (see limit_strain): each
  /// free vertex moved over the last two sweeps goes to older_ + weight
  /// (q - older_), kept in front of its plane and flagged in `moved`.
  void extrapolate(Positions& q, double weight, std::vector<char>& moved) const;
  /// Checks the free vertices and T-nodes of q against the scene: every one
  /// in the step's `first` check (with friction), else those moved beyond
  /// their slack since their last check. Sets their contact planes and
  /// slack; raises `largest` to the largest correction. Returns how many
  /// were checked.
  int check_contacts(const Positions& q_previous, Positions& q, const CollisionScene& scene, bool first,
                     double& largest) const;
  /// One check_contacts call's points, scene and tallies, shared by its steps.
  struct ContactPass {
    const Positions& q_previous;  // #free x 3, metres: the step's start (the side a point was on; friction)
    Positions& q;                 // #free x 3, metres: checked and moved in place
    const CollisionScene& scene;
    bool first;                   // the step's first check: every point, with friction
    double& largest;              // metres, raised to the largest correction
    int checked = 0;              // points checked so far
  };
  /// Whether point `row` (free vertex, then T-node), now at `x`, needs a
  /// check: every one in the step's `first`, else one moved beyond its
  /// slack from where its last check left it.
  bool needs_check(Eigen::Index row, const Eigen::Vector3d& x, bool first) const;
  /// Resolves free vertex f if it needs it (or `forced`); returns the
  /// correction in metres (-1: not checked).
  double check_vertex(Eigen::Index f, bool forced, const ContactPass& pass) const;
  /// Checks the free vertices that need it (on the pool when there is
  /// one), or with `only` every free vertex flagged there.
  void check_free_vertices(const std::vector<char>* only, ContactPass& pass) const;
  /// Checks the T-nodes: with `only` null every one that needs it, else
  /// those with a free stencil vertex flagged there; flags the free
  /// vertices a push moves in moved_. Returns whether any was pushed.
  bool check_t_nodes(const std::vector<char>* only, ContactPass& pass) const;
  /// Lists in t_node_planes_ the T-nodes with a contact plane.
  void list_t_node_planes(Eigen::Index free_count) const;
  Eigen::Vector3d position_of(int vertex, const Positions& q) const;
  /// The contact plane of free vertex `row` (or T-node `row - #free`) after
  /// a check moved it from `before` to `after`: across the push when it was
  /// pushed, else the nearby surface's tangent plane, else none.
  void set_plane(Eigen::Index row, const Eigen::Vector3d& before, const Eigen::Vector3d& after,
                 const SurfaceNearby& nearby) const;
  /// How far a checked point may move before it needs another check.
  double slack_of(const SurfaceNearby& nearby, bool planed) const;
  /// Moves free vertex f back onto its contact plane if it is behind it.
  /// (Inline: the strain limiter calls it after every projection.)
  void keep_in_front(Eigen::Index f, Positions& q) const {
    if (!has_plane_[static_cast<std::size_t>(f)]) return;
    double behind = 0.0;
    for (int c = 0; c < 3; ++c) behind += (q(f, c) - plane_point_(f, c)) * plane_normal_(f, c);
    if (behind >= 0.0) return;
    for (int c = 0; c < 3; ++c) q(f, c) -= behind * plane_normal_(f, c);
  }
  /// The same for every T-node with a plane, through its free stencil
  /// (flagging the free vertices it moves in `moved`).
  void keep_t_nodes_in_front(Positions& q, std::vector<char>& moved) const;
  /// Moves T-node h (index into hanging_vertices) by `delta` through its
  /// free stencil, mass-weighted; flags the moved free vertices in `moved`
  /// when given. False when it has no free stencil.
  bool move_t_node(std::size_t h, const Eigen::Vector3d& delta, Positions& q, std::vector<char>* moved) const;

  // precompute's steps after it has set model_ and options_, in its order.
  /// Starts the worker pool, sizes the scratch every step reuses and zeroes
  /// pinned_part_ (without pins it stays zero).
  void prepare_step_scratch();
  /// Fills sweep_ with every stretch spring in wavefront order; fj is a
  /// general spring's index in model_->springs until build_general_springs.
  void build_sweep();
  /// Puts the free vertices in the order the collision checks visit them
  /// (check_order_, near each other at rest) and memo_slot_ to match.
  void order_checks();
  /// Sizes the contact planes, anchors and slacks: per free vertex, then per T-node.
  void size_contact_buffers();
  /// Turns each general spring of sweep_ into a GeneralSpring (in sweep
  /// order) and points its fj at it.
  void build_general_springs();
  /// Appends spring `s` to general_ (its fine row `row` with t_node_sag,
  /// else null); returns its index there.
  int add_general_spring(const Spring& s, const FineRow* row);
  /// Leaves the springs with both ends pinned out of sweep_.
  void drop_pinned_springs();
  /// Per free vertex, the sweep_ slots of the springs it moves (see
  /// limit_strain's active set), in sweep order.
  std::vector<std::vector<int>> sweep_dependents() const;
  /// Packs sweep_dependents into dependent_start_ / dependent_slots_ and sizes due_.
  void build_dependents();

  const DynamicsModel* model_ = nullptr;
  IntegratorOptions options_;
  SparseLdlt3 solver_;
  SelfContact self_contact_;
  Positions pinned_part_;              // P p for the step being taken (#V x 3)
  mutable Positions full_, force_;     // scratch, #V x 3
  mutable std::vector<ProjectedSpringHessian> hessians_;  // per spring, at the last gradient (newton_cg only)
  mutable Positions cg_residual_, cg_direction_, cg_product_;  // newton_direction's scratch, #free x 3
  mutable std::vector<ContactMemo> memos_;  // per free vertex (at memo_slot_), then per T-node: what the scene remembers between checks
  // Per free vertex, then per T-node: where its last check left it, and
  // how far it may move from there before it needs another.
  mutable Positions anchor_;
  mutable std::vector<double> slack_;
  /// Threads for the free vertices' resolves (null: options_.threads is 1);
  /// shared so the integrator stays copyable (copies take turns, never
  /// running two loops at once).
  std::shared_ptr<WorkerPool> pool_;
  mutable std::vector<double> part_largest_;  // per pool part: its largest correction
  mutable std::vector<int> part_checked_;     // per pool part: the points it checked
  mutable std::vector<char> moved_, check_;  // per free vertex: moved by a T-node's push (reused, not reallocated per round)
  // Per free vertex, then per T-node: its contact plane this step (point on
  // it, unit outward normal); has_plane_ marks those with one.
  mutable Positions plane_point_, plane_normal_;
  mutable std::vector<char> has_plane_;
  mutable std::vector<int> t_node_planes_;  // T-node indices (into hanging_vertices) with a plane
  /// A stretch spring as the limiter reads it, in sweep order: one
  /// contiguous read where the spring, its ends' free indices and its kind
  /// were four scattered ones (the limiter visits about a million per step
  /// on an 11088-vertex skirt).
  struct LimitedSpring {
    int fi = -1;              // free index of end i if both ends are free vertices; -1: a general spring
    int fj = -1;              // free index of end j; for a general spring, its index in general_
    double max_length = 0.0;  // (1 + stretch limit) * rest, metres
    double rest = 0.0;        // metres
  };
  std::vector<LimitedSpring> sweep_;   // stretch springs in strain-limiting order
  std::vector<Tether> tethers_;
  std::vector<int> check_order_;       // free vertices in the order they are checked (near each other in space)
  std::vector<int> memo_slot_;         // per free vertex, its memo's index in memos_: its place in check_order_, so a check reads the memos in sequence
  // The limiter's active set (see limit_strain): per free vertex, moved
  // since its springs were last evaluated / moved in the current sweep; q
  // as the last pass left it; whether the next pass is the step's first.
  mutable std::vector<char> dirty_, swept_;
  double rho_ = 0.0;  // the limiter's Chebyshev estimate (limiter_acceleration())
  // Per free vertex, the sweep_ slots of the springs it moves (the limiter's
  // dependents: both ends of a direct spring, a general one's terms), in
  // CSR form.
  std::vector<int> dependent_start_, dependent_slots_;
  mutable std::vector<std::uint64_t> due_;  // per sweep_ slot, one bit: a vertex it depends on is dirty
  mutable Positions limited_;
  mutable Positions older_, previous_;  // the limiter's iterates two sweeps and one sweep back (Chebyshev acceleration)
  mutable bool fresh_pass_ = true;
  std::vector<int> direct_free_;       // per vertex: its free index if it is exactly one free vertex, else -1
  /// A spring with a T-node or pinned end, as the constraint sees it: the
  /// free vertices its length depends on, each once (a T-node's spring to
  /// its own parent shares a free vertex between both ends), and the
  /// denominator of its projection, weighted as the limiter weighs (projection_weight_).
  struct GeneralTerm {
    int free;
    double weight;  // d(spring vector) / d(free vertex position)
  };
  struct GeneralSpring {
    int first = 0, count = 0;  // its terms in general_terms_
    double denominator = 0.0;  // sum of weight^2 / mass (> 0: springs with both ends pinned are not limited)
    // Its ends as position_of reads them, in one place: vertices i and j
    // (their pinned parts), then their stencils in general_ends_ (i's
    // count_i terms, then j's count_j).
    int i = -1, j = -1;
    int ends_first = 0, count_i = 0, count_j = 0;
    double rest = 0.0;  // metres
    // With t_node_sag, for a spring from a T-node (full id sag_t) into the
    // finer side: the neighbours of its fine end (the row's middle) along
    // the row beside the coarse edge (full ids, read as position_of reads
    // them: a neighbour may be a T-node or pinned); sag_t < 0: none.
    int sag_t = -1, sag_ca = -1, sag_cb = -1;
  };
  std::vector<GeneralSpring> general_;
  std::vector<GeneralTerm> general_terms_;
  std::vector<StencilTerm> general_ends_;
  Eigen::VectorXd projection_weight_;  // per free vertex, the limiter's: mass^-limiter_mass_exponent (1/kg when 1)
};

}  // namespace mrcloth
