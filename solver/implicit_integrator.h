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
// stay exact. After the iterations, Gauss-Seidel sweeps bound every stretch
// spring to (1 + stretch_limit) of its rest length (strain limiting, in free
// coordinates, so T-nodes stay exact), then collisions are resolved.
// Collisions and strain limiting alternate in rounds; every collision
// push-out leaves a contact plane (the pushed point, the push direction)
// that the strain limiter keeps its vertex (or T-node) in front of for the
// rest of the step, so the limiter cannot pull cloth back into what pushed
// it and the stretch goes to the cloth that is free to move.
//
// Accuracy trade-off: with few iterations the step is a damped
// approximation of implicit Euler (energy is lost in stiff directions,
// which also makes it stable at any time step); stretch is bounded by the
// strain limit rather than by convergence.
#include "collision_scene.h"
#include "dynamics_model.h"
#include "self_contact.h"
#include "sparse_ldlt3.h"
#include "worker_pool.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace mrcloth {

struct IntegratorOptions {
  double time_step = 1.0 / 120.0;               ///< seconds, > 0
  int iterations = 2;                           ///< local/global iterations per step, >= 1 (more: stiffer, less damped)
  int strain_limit_sweeps = 6;                  ///< Gauss-Seidel sweeps over stretch springs per round, >= 0
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};     ///< m/s^2
  int collision_rounds = 8;                     ///< at most this many rounds of (strain limiting, collisions) per step, >= 1
  double round_tolerance = 0.01;                ///< another round only while a spring starts it this much strain beyond the limit (0.01 = 1 %)
  double settle_tolerance = 0.0;                ///< metres, >= 0: in the rounds between a step's first and last, a point the limiter moved less than this since its own last resolve waits for the last round (which resolves every moved point); 0: every moved point in every round (1 mm: a quarter less collision time, more stretch; see README)
  bool contact_planes = true;                   ///< the strain limiter keeps pushed points in front of their contact planes (see above)
  SelfContactOptions self_contact;              ///< cloth-cloth contact (self_contact.h), projected in every round before the body collisions; thickness 0: off
  bool active_set = true;                       ///< the limiter evaluates only springs whose vertices moved since their last evaluation (same bits, less work); false: every spring every sweep
  int threads = 1;                              ///< threads resolving the vertices' collisions, >= 1; the same bits for any count (each vertex's resolve is its own)
};

/// State in free coordinates (rows follow DynamicsModel::free_vertices).
struct ClothState {
  Positions positions;   ///< #free x 3, metres
  Positions velocities;  ///< #free x 3, m/s
  Positions pinned;      ///< #pinned x 3, current pinned targets, metres
  double time = 0.0;     ///< seconds
};

/// The rest state of a model at rest velocity 0, pinned at their rest positions.
ClothState rest_state(const DynamicsModel& model);

struct StepReport {
  double dynamics_ms = 0.0;        ///< local/global iterations and strain limiting
  double collision_ms = 0.0;       ///< collision resolution, bodies and cloth-cloth contact
  double limiter_ms = 0.0;         ///< of dynamics_ms: strain limiting, all rounds
  double first_round_ms = 0.0;     ///< of collision_ms: the first round (every vertex against the new pose)
  double max_correction = 0.0;     ///< largest collision push-out this step, metres
  int rounds = 0;                  ///< rounds of (strain limiting, collisions) taken
  bool finite = true;              ///< false if any position became NaN or infinite
};

class ImplicitIntegrator {
 public:
  /// Assembles and factorises Q for `model` (kept by reference: it must
  /// outlive the integrator) and the options. Throws ArgumentError for bad options.
  void precompute(const DynamicsModel& model, const IntegratorOptions& options);

  /// Advances `state` by one time step to time + h, with the pinned vertices
  /// moving to `pinned_next` (#pinned x 3), colliding with `scene` as posed
  /// for the end of the step.
  StepReport step(ClothState& state, const Positions& pinned_next, const CollisionScene& scene);
  /// The same with a fixed set of analytic colliders.
  StepReport step(ClothState& state, const Positions& pinned_next, const std::vector<Collider>& colliders);

  const IntegratorOptions& options() const { return options_; }
  std::size_t factor_nonzeros() const { return solver_.factor_nonzeros(); }
  /// The threads options().threads asked for (null for one): callers may
  /// run their own per-vertex loops on it between steps.
  WorkerPool* pool() const { return pool_.get(); }

 private:
  void gradient(const Positions& q, const Positions& y, Positions& grad) const;
  /// Returns the largest strain beyond the limit it met (0 when none).
  double limit_strain(Positions& q) const;
  /// Resolves every free vertex and T-node of q; with `settled` (the last
  /// round's result), only those that have moved since, and of those, with
  /// `tolerance` (metres, > 0 in all but a step's last round), only those
  /// moved at least that far since their own last resolve.
  double resolve_collisions(const Positions& q_previous, Positions& q, const CollisionScene& scene, bool friction,
                            const Positions* settled = nullptr, double tolerance = 0.0) const;
  Eigen::Vector3d position_of(int vertex, const Positions& q) const;
  /// Records the contact plane of a push of free vertex `f` (or T-node
  /// `f - #free`) from `before` to `after` (no plane when they are equal).
  void remember_plane(Eigen::Index f, const Eigen::Vector3d& before, const Eigen::Vector3d& after) const;
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

  const DynamicsModel* model_ = nullptr;
  IntegratorOptions options_;
  SparseLdlt3 solver_;
  SelfContact self_contact_;
  Positions pinned_part_;              // P p for the step being taken (#V x 3)
  mutable Positions full_, force_;     // scratch, #V x 3
  Positions settled_;                  // scratch: q after the last collision round of this step
  mutable Positions resolved_;         // scratch: each free vertex where its last resolve of this step left it
  mutable std::vector<char> pending_;  // per free vertex: moved within settle_tolerance since its last resolve, which the last round owes it
  mutable std::vector<ContactMemo> memos_;  // per free vertex, then per T-node: what the scene remembers between rounds
  /// Threads for the free vertices' resolves (null: options_.threads is 1);
  /// shared so the integrator stays copyable (copies take turns, never
  /// running two loops at once).
  std::shared_ptr<WorkerPool> pool_;
  /// A collision push found by a pool part, recorded as a contact plane
  /// after the loop (remember_plane appends to planes_).
  struct Push {
    Eigen::Index free;
    Eigen::Vector3d before, after;
  };
  mutable std::vector<std::vector<Push>> part_pushes_;  // per pool part
  mutable std::vector<double> part_largest_;            // per pool part: its largest correction
  mutable std::vector<char> moved_, check_;  // per free vertex: moved by a T-node's push (reused, not reallocated per round)
  // Per free vertex, then per T-node: the contact plane of its last push
  // this step (point on it, unit outward normal); has_plane_ marks those
  // with one, planes_ lists them for clearing.
  mutable Positions plane_point_, plane_normal_;
  mutable std::vector<char> has_plane_;
  mutable std::vector<int> planes_;
  mutable std::vector<int> t_node_planes_;  // T-node indices (into hanging_vertices) with a plane
  /// A stretch spring as the limiter reads it, in sweep order: one
  /// contiguous read where the spring, its ends' free indices and its kind
  /// were four scattered ones (the limiter visits about a million per step
  /// on an 11088-vertex skirt).
  struct LimitedSpring {
    int fi = -1;              // free index of end i if both ends are free vertices; -1: a general spring
    int fj = -1;              // free index of end j; for a general spring, its index in model.springs
    double max_length = 0.0;  // (1 + stretch limit) * rest, metres
    double rest = 0.0;        // metres
  };
  std::vector<LimitedSpring> sweep_;   // stretch springs in strain-limiting order
  // The limiter's active set (see limit_strain): per free vertex, moved
  // since its springs were last evaluated / moved in the current sweep; q
  // as the last pass left it; whether the next pass is the step's first.
  mutable std::vector<char> dirty_, swept_;
  mutable Positions limited_;
  mutable bool fresh_pass_ = true;
  std::vector<int> direct_free_;       // per vertex: its free index if it is exactly one free vertex, else -1
  /// A spring with a T-node or pinned end, as the constraint sees it: the
  /// free vertices its length depends on, each once (a T-node's spring to
  /// its own parent shares a free vertex between both ends), and the
  /// mass-weighted denominator of its projection.
  struct GeneralTerm {
    int free;
    double weight;  // d(spring vector) / d(free vertex position)
  };
  struct GeneralSpring {
    int first = 0, count = 0;  // its terms in general_terms_
    double denominator = 0.0;  // sum of weight^2 / mass; 0 when both ends are pinned
  };
  std::vector<int> general_of_;                // per spring: its index in general_, or -1 (both ends free vertices)
  std::vector<GeneralSpring> general_;
  std::vector<GeneralTerm> general_terms_;
  Eigen::VectorXd inverse_mass_;       // per free vertex, 1/kg
};

}  // namespace mrcloth
