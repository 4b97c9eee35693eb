#include "implicit_integrator.h"

#include "integrator_setup.h"
#include "mesh_ops/errors.h"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

namespace mrcloth {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void check(const IntegratorOptions& o) {
  if (!(o.time_step > 0.0) || !std::isfinite(o.time_step)) throw ArgumentError("time step must be > 0 seconds");
  if (o.iterations < 1) throw ArgumentError("iterations must be >= 1");
  if (o.newton_cg < 0) throw ArgumentError("newton_cg (conjugate-gradient iterations per Newton step) must be >= 0");
  if (o.strain_limit_sweeps < 0) throw ArgumentError("strain limit sweeps must be >= 0");
  if (!(o.limiter_acceleration >= 0.0 && o.limiter_acceleration < 1.0))
    throw ArgumentError("the limiter acceleration (a spectral radius estimate) must be >= 0 and < 1");
  if (!(o.limiter_mass_exponent >= 0.0 && o.limiter_mass_exponent <= 1.0))
    throw ArgumentError("the limiter mass exponent must be >= 0 and <= 1");
  if (o.collision_rounds < 1) throw ArgumentError("collision rounds must be >= 1");
  if (!(o.round_tolerance >= 0.0)) throw ArgumentError("the round tolerance must be >= 0");
  if (!(o.contact_slack >= 0.0) || !std::isfinite(o.contact_slack))
    throw ArgumentError("the contact slack must be a finite number >= 0 metres");
  if (!o.gravity.allFinite()) throw ArgumentError("gravity must be finite");
  if (o.threads < 1) throw ArgumentError("threads must be >= 1");
}

}  // namespace

Eigen::Vector3d fine_row_bulge(const Eigen::Vector3d& c, const Eigen::Vector3d& ca, const Eigen::Vector3d& cb, double cap) {
  Eigen::Vector3d bulge = c - 0.5 * (ca + cb);
  const double length = bulge.norm();
  if (length > cap) bulge *= cap / length;
  return bulge;
}

double chebyshev_weight(int iteration, double rho, double previous) {
  if (iteration <= 0) return 1.0;
  if (iteration == 1) return 2.0 / (2.0 - rho * rho);
  return 4.0 / (4.0 - rho * rho * previous);
}

ClothState rest_state(const DynamicsModel& model) {
  ClothState state;
  state.positions = free_rows(model, model.rest);
  state.velocities = Positions::Zero(state.positions.rows(), 3);
  state.pinned = pinned_rows(model, model.rest);
  return state;
}

bool ImplicitIntegrator::precompute(const DynamicsModel& model, const IntegratorOptions& options,
                                    const KeepGoing& keep_going) {
  const auto stopped = [&] { return keep_going && !keep_going(); };
  check(options);
  model_ = &model;
  options_ = options;
  const Eigen::SparseMatrix<double> Q = system_matrix(model, options.time_step);
  if (stopped()) return false;
  if (!solver_.factorize(Q, keep_going) || stopped()) return false;
  prepare_step_scratch();
  self_contact_.precompute(model, options.self_contact);
  if (stopped()) return false;
  direct_free_ = direct_free_indices(model);
  projection_weight_ = projection_weights(model.free_mass, options.limiter_mass_exponent);
  build_sweep();
  rho_ = options.limiter_acceleration;
  if (options.acceleration_from_chain && rho_ > 0.0) rho_ = std::max(rho_, chain_spectral_radius(model));
  tethers_ = options.tethers ? tethers_to_pins(model, direct_free_) : std::vector<Tether>{};
  order_checks();
  size_contact_buffers();
  build_general_springs();
  drop_pinned_springs();
  build_dependents();
  return true;
}

void ImplicitIntegrator::prepare_step_scratch() {
  pool_ = options_.threads > 1 ? std::make_shared<WorkerPool>(options_.threads) : nullptr;
  part_largest_.assign(static_cast<std::size_t>(options_.threads), 0.0);
  part_checked_.assign(static_cast<std::size_t>(options_.threads), 0);
  full_.resize(model_->num_vertices, 3);
  force_.resize(model_->num_vertices, 3);
  pinned_part_ = Positions::Zero(model_->num_vertices, 3);
}

void ImplicitIntegrator::build_sweep() {
  const DynamicsModel& model = *model_;
  const double limit = 1.0 + model.material.stretch_limit;
  sweep_.clear();
  for (int k : wavefront_order(model)) {
    const Spring& s = model.springs[static_cast<std::size_t>(k)];
    LimitedSpring l;
    const bool direct = direct_free_[s.i] >= 0 && direct_free_[s.j] >= 0;
    l.fi = direct ? direct_free_[s.i] : -1;
    l.fj = direct ? direct_free_[s.j] : k;
    l.max_length = limit * s.rest;
    l.rest = s.rest;
    sweep_.push_back(l);
  }
}

void ImplicitIntegrator::order_checks() {
  check_order_ = spatial_order(free_rows(*model_, model_->rest));
  memo_slot_.assign(check_order_.size(), 0);
  for (std::size_t k = 0; k < check_order_.size(); ++k) memo_slot_[static_cast<std::size_t>(check_order_[k])] = static_cast<int>(k);
}

void ImplicitIntegrator::size_contact_buffers() {
  const Eigen::Index plane_rows = static_cast<Eigen::Index>(model_->free_vertices.size() + model_->hanging_vertices.size());
  plane_point_.resize(plane_rows, 3);
  plane_normal_.resize(plane_rows, 3);
  has_plane_.assign(static_cast<std::size_t>(plane_rows), 0);
  t_node_planes_.clear();
  anchor_.resize(plane_rows, 3);
  slack_.assign(static_cast<std::size_t>(plane_rows), 0.0);
}

void ImplicitIntegrator::build_general_springs() {
  const DynamicsModel& model = *model_;
  // The limiter's general springs in sweep order, so a sweep reads them in
  // sequence (in either direction) rather than scattered.
  general_.clear();
  general_terms_.clear();
  general_ends_.clear();
  // Per spring, its fine row (t_node_sag; empty when off).
  const std::vector<FineRow> rows = options_.t_node_sag ? t_node_fine_rows(model) : std::vector<FineRow>{};
  std::vector<const FineRow*> row_of_spring(rows.empty() ? 0 : model.springs.size(), nullptr);
  for (const FineRow& row : rows) row_of_spring[static_cast<std::size_t>(row.spring)] = &row;
  for (LimitedSpring& l : sweep_) {
    if (l.fi >= 0) continue;
    const auto k = static_cast<std::size_t>(l.fj);
    l.fj = add_general_spring(model.springs[k], row_of_spring.empty() ? nullptr : row_of_spring[k]);
  }
}

int ImplicitIntegrator::add_general_spring(const Spring& s, const FineRow* row) {
  const DynamicsModel& model = *model_;
  GeneralSpring g;
  g.first = static_cast<int>(general_terms_.size());
  for (const auto& [free, weight] : merged_stencil_terms(model, s)) {
    if (weight == 0.0) continue;
    general_terms_.push_back({free, weight});
    g.denominator += weight * weight * projection_weight_[free];
  }
  g.count = static_cast<int>(general_terms_.size()) - g.first;
  g.i = s.i;
  g.j = s.j;
  g.rest = s.rest;
  g.ends_first = static_cast<int>(general_ends_.size());
  general_ends_.insert(general_ends_.end(), model.stencil[s.i].begin(), model.stencil[s.i].end());
  general_ends_.insert(general_ends_.end(), model.stencil[s.j].begin(), model.stencil[s.j].end());
  g.count_i = static_cast<int>(model.stencil[s.i].size());
  g.count_j = static_cast<int>(model.stencil[s.j].size());
  if (row) {
    g.sag_t = row->t_node;
    g.sag_ca = row->ca;
    g.sag_cb = row->cb;
  }
  general_.push_back(g);
  return static_cast<int>(general_.size()) - 1;
}

void ImplicitIntegrator::drop_pinned_springs() {
  // A spring with both ends pinned: the pins set its length, so no sweep
  // can move it and it must not ask for another round (a waistband the
  // skinned pelvis stretches beyond the limit held every step of the
  // trousers at all eight rounds). Left out of the sweep.
  sweep_.erase(std::remove_if(sweep_.begin(), sweep_.end(),
                              [&](const LimitedSpring& l) { return l.fi < 0 && general_[static_cast<std::size_t>(l.fj)].count == 0; }),
               sweep_.end());
}

std::vector<std::vector<int>> ImplicitIntegrator::sweep_dependents() const {
  const DynamicsModel& model = *model_;
  std::vector<std::vector<int>> dependents(model.free_vertices.size());
  for (std::size_t k = 0; k < sweep_.size(); ++k) {
    const LimitedSpring& l = sweep_[k];
    if (l.fi >= 0) {
      dependents[static_cast<std::size_t>(l.fi)].push_back(static_cast<int>(k));
      dependents[static_cast<std::size_t>(l.fj)].push_back(static_cast<int>(k));
      continue;
    }
    const GeneralSpring& g = general_[static_cast<std::size_t>(l.fj)];
    for (int t = 0; t < g.count; ++t)
      dependents[static_cast<std::size_t>(general_terms_[static_cast<std::size_t>(g.first + t)].free)].push_back(static_cast<int>(k));
    if (g.sag_t >= 0)  // the row moves the T-node as the limiter reads it
      for (const int row : {g.sag_t == g.i ? g.j : g.i, g.sag_ca, g.sag_cb})  // the row's middle is the other end
        for (const StencilTerm& t : model.stencil[static_cast<std::size_t>(row)]) {
          std::vector<int>& list = dependents[static_cast<std::size_t>(t.free)];
          if (list.empty() || list.back() != static_cast<int>(k)) list.push_back(static_cast<int>(k));
        }
  }
  return dependents;
}

void ImplicitIntegrator::build_dependents() {
  dependent_start_.assign(1, 0);
  dependent_slots_.clear();
  for (const std::vector<int>& list : sweep_dependents()) {
    dependent_slots_.insert(dependent_slots_.end(), list.begin(), list.end());
    dependent_start_.push_back(static_cast<int>(dependent_slots_.size()));
  }
  due_.assign((sweep_.size() + 63) / 64, 0);
}

Eigen::Vector3d ImplicitIntegrator::position_of(int vertex, const Positions& q) const {
  Eigen::Vector3d x = pinned_part_.row(vertex).transpose();
  for (const StencilTerm& t : model_->stencil[vertex]) x += t.weight * q.row(t.free).transpose();
  return x;
}

bool ImplicitIntegrator::move_t_node(std::size_t h, const Eigen::Vector3d& delta, Positions& q,
                                     std::vector<char>* moved) const {
  const DynamicsModel& m = *model_;
  const auto& stencil = m.stencil[static_cast<std::size_t>(m.hanging_vertices[h])];
  double denominator = 0.0;
  for (const StencilTerm& t : stencil) denominator += t.weight * t.weight / m.free_mass[t.free];
  if (denominator <= 0.0) return false;
  // The smallest mass-weighted change of the free stencil that moves the
  // T-node by delta.
  for (const StencilTerm& t : stencil) {
    q.row(t.free) += (t.weight / m.free_mass[t.free] / denominator) * delta.transpose();
    if (moved) (*moved)[static_cast<std::size_t>(t.free)] = 1;
  }
  return true;
}

void ImplicitIntegrator::keep_t_nodes_in_front(Positions& q, std::vector<char>& moved) const {
  const DynamicsModel& m = *model_;
  const Eigen::Index free_count = static_cast<Eigen::Index>(m.free_vertices.size());
  for (int h : t_node_planes_) {
    const Eigen::Index row = free_count + h;
    const Eigen::Vector3d x = position_of(m.hanging_vertices[static_cast<std::size_t>(h)], q);
    const Eigen::Vector3d n = plane_normal_.row(row).transpose();
    const double behind = (x - plane_point_.row(row).transpose()).dot(n);
    if (behind < 0.0) move_t_node(static_cast<std::size_t>(h), -behind * n, q, &moved);
  }
}

// grad = M/h^2 (q - y) + S^T dE/dx at x = S q + P p.
void ImplicitIntegrator::gradient(const Positions& q, const Positions& y, Positions& grad) const {
  const DynamicsModel& m = *model_;
  full_.noalias() = m.S * q;
  full_ += pinned_part_;
  force_.setZero();
  const bool newton = options_.newton_cg > 0;
  if (newton) hessians_.resize(m.springs.size());
  for (std::size_t k = 0; k < m.springs.size(); ++k) {
    const Spring& s = m.springs[k];
    const Eigen::RowVector3d e = s.via < 0 ? Eigen::RowVector3d(full_.row(s.i) - full_.row(s.j))
                                           : Eigen::RowVector3d(full_.row(s.i) - 2.0 * full_.row(s.via) + full_.row(s.j));
    if (newton) hessians_[k] = projected_spring_hessian(e.transpose(), s.rest, s.stiffness);
    const double length = e.norm();
    if (length == 0.0) continue;
    const Eigen::RowVector3d g = (s.stiffness * (length - s.rest) / length) * e;
    force_.row(s.i) += g;  // energy gradient, not force
    if (s.via < 0) {
      force_.row(s.j) -= g;
    } else {  // e = xi - 2 xvia + xj
      force_.row(s.j) += g;
      force_.row(s.via) -= 2.0 * g;
    }
  }
  grad.noalias() = m.S.transpose() * force_;
  const double inv_h2 = 1.0 / (options_.time_step * options_.time_step);
  for (Eigen::Index f = 0; f < q.rows(); ++f) grad.row(f) += (m.free_mass[f] * inv_h2) * (q.row(f) - y.row(f));
}

void ImplicitIntegrator::hessian_product(const Positions& v, Positions& out) const {
  const DynamicsModel& m = *model_;
  full_.noalias() = m.S * v;  // pinned targets do not vary: no P part
  force_.setZero();
  for (std::size_t k = 0; k < m.springs.size(); ++k) {
    const Spring& s = m.springs[k];
    const ProjectedSpringHessian& h = hessians_[k];
    const Eigen::RowVector3d d = s.via < 0 ? Eigen::RowVector3d(full_.row(s.i) - full_.row(s.j))
                                           : Eigen::RowVector3d(full_.row(s.i) - 2.0 * full_.row(s.via) + full_.row(s.j));
    const Eigen::RowVector3d f = h.a * d + (h.b * d.dot(h.n.transpose())) * h.n.transpose();
    force_.row(s.i) += f;
    if (s.via < 0) {
      force_.row(s.j) -= f;
    } else {
      force_.row(s.j) += f;
      force_.row(s.via) -= 2.0 * f;
    }
  }
  out.noalias() = m.S.transpose() * force_;
  const double inv_h2 = 1.0 / (options_.time_step * options_.time_step);
  for (Eigen::Index f = 0; f < v.rows(); ++f) out.row(f) += (m.free_mass[f] * inv_h2) * v.row(f);
}

// Preconditioned conjugate gradients from delta = 0: the first iterate is
// Q^-1 grad scaled by the step that minimises the quadratic model along it.
void ImplicitIntegrator::newton_direction(const Positions& grad, Positions& delta) const {
  const auto dot = [](const Positions& a, const Positions& b) { return a.cwiseProduct(b).sum(); };
  delta = Positions::Zero(grad.rows(), 3);
  cg_residual_ = grad;
  cg_direction_ = grad;
  solver_.solve_in_place(cg_direction_);
  double rz = dot(cg_residual_, cg_direction_);
  // Converged once the preconditioned residual is a 1e-12th of the first:
  // iterating on round-off (newtonCg 1e9) divided 0 by 0 into NaN.
  const double converged = 1e-24 * rz;
  for (int it = 0; it < options_.newton_cg; ++it) {
    hessian_product(cg_direction_, cg_product_);
    const double curvature = dot(cg_direction_, cg_product_);
    if (!(curvature > 0.0) || !(rz > 0.0)) break;  // converged (or nothing to do)
    const double alpha = rz / curvature;
    delta += alpha * cg_direction_;
    if (it + 1 == options_.newton_cg) break;
    cg_residual_ -= alpha * cg_product_;
    Positions z = cg_residual_;
    solver_.solve_in_place(z);
    const double rz_next = dot(cg_residual_, z);
    if (!(rz_next > converged)) break;
    cg_direction_ = z + (rz_next / rz) * cg_direction_;
    rz = rz_next;
  }
}

// Moves free positions so no stretch spring exceeds (1 + limit) rest length,
// treating each spring as a constraint on its ends' free stencils (weights
// from S), each free vertex moving in proportion to its projection weight
// (mass^-limiter_mass_exponent), in spring order (deterministic).
double ImplicitIntegrator::limit_strain(Positions& q) const {
  const DynamicsModel& m = *model_;
  const double limit = 1.0 + m.material.stretch_limit;
  double largest = 0.0;        // the largest strain beyond the limit met
  double sweep_largest = 0.0;  // the same in the current sweep
  // Ends that are T-nodes or pinned: the constraint acts on their free
  // stencils, by their projection weights (general, slower path).
  // (The arithmetic is position_of's and the per-term update's, so a spring
  // without shared terms, a pinned end's, projects to the same bits as
  // before the terms were merged.)
  const auto limit_general = [&](const GeneralSpring& g) {
    // position_of(g.i, q) - position_of(g.j, q), from the spring's own copy
    // of its ends' stencils (the same arithmetic).
    Eigen::Vector3d xi = pinned_part_.row(g.i).transpose(), xj = pinned_part_.row(g.j).transpose();
    const StencilTerm* end = general_ends_.data() + g.ends_first;
    for (int t = 0; t < g.count_i; ++t) xi += end[t].weight * q.row(end[t].free).transpose();
    end += g.count_i;
    for (int t = 0; t < g.count_j; ++t) xj += end[t].weight * q.row(end[t].free).transpose();
    if (g.sag_t >= 0) {
      // The T-node as the fine cloth beside it would place its vertex: off
      // the chord by the fine row's bulge (at most 30 % of the spring's
      // rest length, so a row thrown about in a step cannot unlimit it).
      // The row's middle is the spring's other end, already read.
      Eigen::Vector3d& t_node = g.sag_t == g.i ? xi : xj;
      const Eigen::Vector3d& middle = g.sag_t == g.i ? xj : xi;
      t_node += fine_row_bulge(middle, position_of(g.sag_ca, q), position_of(g.sag_cb, q), 0.3 * g.rest);
    }
    const Eigen::Vector3d e = xi - xj;
    const double length = e.norm();
    const double excess = length - limit * g.rest;
    if (excess <= 0.0) return false;
    sweep_largest = std::max(sweep_largest, excess / g.rest);
    const Eigen::Vector3d n = e / length;
    const double lambda = excess / g.denominator;
    const GeneralTerm* terms = general_terms_.data() + g.first;
    for (int t = 0; t < g.count; ++t) {
      q.row(terms[t].free) -= (lambda * terms[t].weight * projection_weight_[terms[t].free]) * n.transpose();
      keep_in_front(terms[t].free, q);
    }
    return true;
  };
  // Both ends free vertices: plain weighted projection.
  const auto limit_direct = [&](const LimitedSpring& s) __attribute__((always_inline)) {  // inlined in both sweeps below
    const int fi = s.fi, fj = s.fj;
    double e[3], length2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      e[c] = q(fi, c) - q(fj, c);
      length2 += e[c] * e[c];
    }
    const double max_length = s.max_length;
    if (length2 <= max_length * max_length) return false;
    const double length = std::sqrt(length2);
    sweep_largest = std::max(sweep_largest, (length - max_length) / s.rest);
    const double wi = projection_weight_[fi], wj = projection_weight_[fj];
    const double lambda = (length - max_length) / ((wi + wj) * length);
    for (int c = 0; c < 3; ++c) {
      q(fi, c) -= lambda * wi * e[c];
      q(fj, c) += lambda * wj * e[c];
    }
    keep_in_front(fi, q);
    keep_in_front(fj, q);
    return true;
  };
  // Active set: a spring is evaluated only when a free vertex it depends on
  // moved since its last evaluation; the others would find themselves within
  // the limit again (their last evaluation did, and nothing they depend on
  // changed), so skipping them gives the same bits. `dirty` flags the free
  // vertices moved since, `moved` those moved in the current sweep.
  std::vector<char>& dirty = dirty_;
  std::vector<char>& moved = swept_;
  const std::size_t free_count = static_cast<std::size_t>(q.rows());
  moved.assign(free_count, 0);
  if (fresh_pass_ || !options_.active_set) {
    dirty.assign(free_count, 1);
    fresh_pass_ = false;
  } else {
    // Moved by the collisions since the last pass, or in its last sweep.
    for (std::size_t f = 0; f < free_count; ++f)
      if (q.row(static_cast<Eigen::Index>(f)) != limited_.row(static_cast<Eigen::Index>(f))) dirty[f] = 1;
  }
  // A sweep visits the springs that are due, those with a dirty vertex.
  // When few vertices are dirty it finds them through a bit per slot, set
  // for every dirty vertex's dependents as the sweep starts and as vertices
  // turn dirty during it, and skips the rest a word at a time; otherwise it
  // tests each spring's vertices in turn (setting bits then costs more than
  // the tests: the shared skirt refined twice, about half its vertices
  // dirty in a sweep, was slower with bits throughout, while its adaptive
  // d5 mesh's limiter was about 10 % faster). Either way the same springs
  // in the same order.
  std::uint64_t* due = due_.data();
  const auto set_due = [&](std::size_t f) {
    for (int k = dependent_start_[f]; k < dependent_start_[f + 1]; ++k) {
      const auto slot = static_cast<std::size_t>(dependent_slots_[static_cast<std::size_t>(k)]);
      due[slot >> 6] |= std::uint64_t{1} << (slot & 63);
    }
  };
  // A due spring (one whose vertices include a dirty one); by_bits: the
  // sweep finds due springs by their bits, which a vertex turning dirty sets.
  // (Inlined: called once per due spring, half a million times a step on
  // the twice-refined skirt.)
  const auto limit_spring = [&](const LimitedSpring& l, auto by_bits) __attribute__((always_inline)) {  // GCC, Clang
    const auto make_dirty = [&](std::size_t f) {
      if constexpr (decltype(by_bits)::value) {
        if (!dirty[f]) set_due(f);
      }
      dirty[f] = moved[f] = 1;
    };
    if (l.fi >= 0) {
      if (!limit_direct(l)) return false;
      make_dirty(static_cast<std::size_t>(l.fi));
      make_dirty(static_cast<std::size_t>(l.fj));
      return true;
    }
    const GeneralSpring& spring = general_[static_cast<std::size_t>(l.fj)];
    if (!limit_general(spring)) return false;
    const GeneralTerm* terms = general_terms_.data() + spring.first;
    for (int t = 0; t < spring.count; ++t) make_dirty(static_cast<std::size_t>(terms[t].free));
    return true;
  };
  const std::true_type by_bits;
  const std::false_type by_flags;
  // The due springs in sweep order (forward) or its reverse, each as it
  // comes: a spring turned due by one before it in the same sweep is seen.
  const std::size_t words = due_.size();
  const auto sweep_due = [&](bool forward) {
    std::size_t dirty_count = 0;
    for (std::size_t f = 0; f < free_count; ++f) dirty_count += dirty[f] != 0;
    bool any = false;
    if (dirty_count > free_count / 4) {  // many dirty: test each spring
      const auto is_due = [&](const LimitedSpring& l) {
        if (l.fi >= 0) return dirty[static_cast<std::size_t>(l.fi)] || dirty[static_cast<std::size_t>(l.fj)];
        const GeneralSpring& g = general_[static_cast<std::size_t>(l.fj)];
        // A sagging T-node spring also reads its fine row (the extra rows
        // among its dependents): tested every sweep, as every spring is
        // without the active set (testing only its terms left springs the
        // row had stretched unprojected, and the bits differed).
        if (g.sag_t >= 0) return true;
        const GeneralTerm* terms = general_terms_.data() + g.first;
        bool found = false;
        for (int t = 0; t < g.count && !found; ++t) found = dirty[static_cast<std::size_t>(terms[t].free)] != 0;
        return found;
      };
      const std::size_t count = sweep_.size();
      if (forward)
        for (std::size_t k = 0; k < count; ++k) any |= is_due(sweep_[k]) && limit_spring(sweep_[k], by_flags);
      else
        for (std::size_t k = count; k-- > 0;) any |= is_due(sweep_[k]) && limit_spring(sweep_[k], by_flags);
      return any;
    }
    std::fill(due_.begin(), due_.end(), 0);
    for (std::size_t f = 0; f < free_count; ++f)
      if (dirty[f]) set_due(f);
    if (forward) {
      for (std::size_t w = 0; w < words; ++w)
        for (std::uint64_t bits = due[w]; bits != 0;) {
          const int b = __builtin_ctzll(bits);
          any |= limit_spring(sweep_[(w << 6) + static_cast<std::size_t>(b)], by_bits);
          // Later slots of this word, as they are now.
          bits = b == 63 ? 0 : due[w] & (~std::uint64_t{0} << (b + 1));
        }
    } else {
      for (std::size_t w = words; w-- > 0;)
        for (std::uint64_t bits = due[w]; bits != 0;) {
          const int b = 63 - __builtin_clzll(bits);
          any |= limit_spring(sweep_[(w << 6) + static_cast<std::size_t>(b)], by_bits);
          bits = due[w] & ((std::uint64_t{1} << b) - 1);  // earlier slots of this word
        }
    }
    return any;
  };
  // Tethers: no free vertex farther from its nearest pinned vertex than the
  // cloth between them allows (long-range attachments): what a chain of
  // springs hanging from the pins would take a sweep per link to pass down.
  // Each sweep starts with them, and the springs have the last word. (Over
  // the walk table at three pre-rolls, 108 runs, tethers first tore 6 runs
  // against 11 with tethers last, which stretch springs to keep the reach
  // exact, and 9 without tethers.)
  const auto pull_tethers = [&] {
    bool any = false;
    for (const Tether& t : tethers_) {
      const auto f = static_cast<Eigen::Index>(t.free);
      double d[3], length2 = 0.0;
      for (int c = 0; c < 3; ++c) {
        d[c] = q(f, c) - pinned_part_(t.pinned, c);
        length2 += d[c] * d[c];
      }
      if (length2 <= t.max_length * t.max_length) continue;
      const double scale = t.max_length / std::sqrt(length2);
      for (int c = 0; c < 3; ++c) q(f, c) = pinned_part_(t.pinned, c) + scale * d[c];
      keep_in_front(f, q);
      dirty[static_cast<std::size_t>(t.free)] = moved[static_cast<std::size_t>(t.free)] = 1;  // the sweep's due bits are built after the tethers
      any = true;
    }
    return any;
  };
  // Chebyshev semi-iterative acceleration (Wang 2015, "A Chebyshev
  // semi-iterative approach for accelerating projective and position-based
  // dynamics"): after sweep k >= 1 of a round, q = older + w_k (q - older),
  // older the iterate two sweeps back. A correction then crosses a long
  // chain of springs (a trouser leg from waist to cuff) in far fewer sweeps
  // than plain Gauss-Seidel passes it, one link per sweep. The round's last
  // sweep is not extrapolated: the limiter's last word is a projection. A
  // round stops accelerating once a sweep meets no spring beyond the round
  // tolerance: over-relaxed sweeps overshoot one-sided constraints, and
  // cloth resting at its limit would shimmer. (The walk table at three
  // pre-rolls, 108 runs: with rho 0.97 4 tore and the median largest
  // stretch was 29-32 %, 38 % over the refined runs, against 5, 35-36 %
  // and 58 % plain; see README.)
  // The chain's estimate (acceleration_from_chain) only where the cloth is
  // far from its limit: a round whose first sweep finds no spring more than
  // 2 % beyond it is near rest, and sweeps with the options' estimate (with
  // the chain's, a 31 x 31 curtain hanging at its limit shimmered at 0.3 m/s).
  constexpr double kNearRest = 0.02;
  double rho = rho_;
  double weight = 1.0;
  bool accelerating = rho > 0.0;
  if (accelerating) previous_ = q;
  for (int sweep = 0; sweep < options_.strain_limit_sweeps; ++sweep) {
    bool any = options_.tethers && pull_tethers();
    sweep_largest = 0.0;
    // Symmetric Gauss-Seidel: alternating sweep directions carry a correction
    // across the whole cloth in a few sweeps instead of one row per sweep.
    any |= sweep_due(sweep % 2 == 0);
    largest = std::max(largest, sweep_largest);
    if (sweep == 0 && sweep_largest <= kNearRest) rho = std::min(rho, options_.limiter_acceleration);
    accelerating = accelerating && sweep_largest > options_.round_tolerance;
    if (accelerating && any && sweep + 1 < options_.strain_limit_sweeps) {
      weight = chebyshev_weight(sweep, rho, weight);
      if (sweep >= 1) extrapolate(q, weight, moved);
      older_.swap(previous_);
      previous_ = q;
    }
    keep_t_nodes_in_front(q, moved);
    if (options_.active_set) {
      dirty.swap(moved);  // the next sweep evaluates the springs of what moved in this one
      std::fill(moved.begin(), moved.end(), 0);
    }
    if (!any) break;
  }
  limited_ = q;
  return largest;
}

void ImplicitIntegrator::extrapolate(Positions& q, double weight, std::vector<char>& moved) const {
  for (Eigen::Index f = 0; f < q.rows(); ++f) {
    // Unmoved over the last two sweeps: the extrapolation leaves it (and
    // the active set's record of it) as it is.
    if (!moved[static_cast<std::size_t>(f)] && q.row(f) == older_.row(f)) continue;
    for (int c = 0; c < 3; ++c) q(f, c) = older_(f, c) + weight * (q(f, c) - older_(f, c));
    keep_in_front(f, q);
    moved[static_cast<std::size_t>(f)] = 1;
  }
}

void ImplicitIntegrator::set_plane(Eigen::Index row, const Eigen::Vector3d& before, const Eigen::Vector3d& after,
                                   const SurfaceNearby& nearby) const {
  const auto k = static_cast<std::size_t>(row);
  has_plane_[k] = 0;
  if (!options_.contact_planes) return;
  const Eigen::Vector3d push = after - before;
  const double length = push.norm();
  if (length > 0.0) {
    // Pushed: across the push (the surface's normal, tilted by at most the
    // friction angle in the step's first check). In front of it the point
    // is where the collider put it or farther out, and the limiter cannot
    // drag it on the way friction held it; sliding the other way along the
    // plane it may sink into the thickness by up to the slack times the
    // sine of the friction angle. (Over the walk table at three pre-rolls,
    // 108 runs: planes across the push tore 6 and left none inside; the
    // surface's tangent plane instead tore 9 and left 3 inside, both
    // together tore 9 and left 1.)
    plane_point_.row(row) = after.transpose();
    plane_normal_.row(row) = push.transpose() / length;
    has_plane_[k] = 1;
  } else if (nearby.has_plane) {
    // Near a surface: its thickened surface's tangent plane.
    plane_point_.row(row) = nearby.point.transpose();
    plane_normal_.row(row) = nearby.normal.transpose();
    has_plane_[k] = 1;
  }
}

double ImplicitIntegrator::slack_of(const SurfaceNearby& nearby, bool planed) const {
  // A point may move as far as it is clear of every thickened surface, and
  // on a plane at least contact_slack along it (the plane stands for the
  // surface there).
  return std::min(planed ? std::max(nearby.clearance, options_.contact_slack) : nearby.clearance, nearby.flip);
}

int ImplicitIntegrator::check_contacts(const Positions& q_previous, Positions& q, const CollisionScene& scene,
                                       bool first, double& largest) const {
  if (scene.empty()) return 0;
  const Eigen::Index free_count = q.rows();
  memos_.resize(static_cast<std::size_t>(free_count) + model_->hanging_vertices.size());
  ContactPass pass{q_previous, q, scene, first, largest};
  moved_.assign(static_cast<std::size_t>(free_count), 0);
  check_free_vertices(nullptr, pass);
  // A push moves parents that neighbouring T-nodes share, after those
  // T-nodes and the parents were checked: the moved parents are checked
  // again, then the T-nodes on them, a few times at most. (The shared
  // skirt's multi-resolution mesh on the skinned body, CMU 07_03: T-nodes
  // 45.9 -> 24.5 mm inside at worst, stretch 1676 -> 205 %.)
  bool pushed = check_t_nodes(nullptr, pass);
  for (int again = 0; pushed && again < 3; ++again) {
    check_.swap(moved_);
    moved_.assign(check_.size(), 0);
    check_free_vertices(&check_, pass);
    pushed = check_t_nodes(&check_, pass);
  }
  list_t_node_planes(free_count);
  return pass.checked;
}

bool ImplicitIntegrator::needs_check(Eigen::Index row, const Eigen::Vector3d& x, bool first) const {
  if (first) return true;
  const double slack = slack_[static_cast<std::size_t>(row)];
  return (x - anchor_.row(row).transpose()).squaredNorm() > slack * slack;
}

double ImplicitIntegrator::check_vertex(Eigen::Index f, bool forced, const ContactPass& pass) const {
  // Friction acts once, in the step's first check. Each vertex's resolve
  // reads and writes its own rows and memo.
  const Eigen::Vector3d before = pass.q.row(f).transpose();
  if (!forced && !needs_check(f, before, pass.first)) return -1.0;
  Eigen::Vector3d x = before;
  SurfaceNearby nearby;
  const double correction = pass.scene.resolve(pass.q_previous.row(f).transpose(), x, pass.first && !forced,
                                               &memos_[static_cast<std::size_t>(memo_slot_[static_cast<std::size_t>(f)])], &nearby);
  pass.q.row(f) = x.transpose();
  anchor_.row(f) = x.transpose();
  set_plane(f, before, x, nearby);
  slack_[static_cast<std::size_t>(f)] = slack_of(nearby, has_plane_[static_cast<std::size_t>(f)] != 0);
  return correction;
}

void ImplicitIntegrator::check_free_vertices(const std::vector<char>* only, ContactPass& pass) const {
  if (!pool_ || only) {
    for (const int ordered : check_order_) {
      const Eigen::Index f = ordered;
      if (only && !(*only)[static_cast<std::size_t>(f)]) continue;
      const double correction = check_vertex(f, only != nullptr, pass);
      if (correction < 0.0) continue;
      ++pass.checked;
      pass.largest = std::max(pass.largest, correction);
    }
    return;
  }
  // In parts: any split gives the same bits (each vertex is its own).
  pool_->run(static_cast<std::size_t>(pass.q.rows()), [&](int part, std::size_t begin, std::size_t end) {
    double& part_largest = part_largest_[static_cast<std::size_t>(part)];
    int& part_checked = part_checked_[static_cast<std::size_t>(part)];
    part_largest = 0.0;
    part_checked = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const auto f = static_cast<Eigen::Index>(check_order_[k]);
      const double correction = check_vertex(f, false, pass);
      if (correction < 0.0) continue;
      ++part_checked;
      part_largest = std::max(part_largest, correction);
    }
  });
  for (std::size_t part = 0; part < part_largest_.size(); ++part) {
    pass.largest = std::max(pass.largest, part_largest_[part]);
    pass.checked += part_checked_[part];
  }
}

bool ImplicitIntegrator::check_t_nodes(const std::vector<char>* only, ContactPass& pass) const {
  // A T-node can be inside while its parents are outside (the collider is
  // curved): its free stencil is pushed by the correction, mass-weighted.
  const DynamicsModel& m = *model_;
  const Eigen::Index free_count = pass.q.rows();
  bool pushed = false;
  for (std::size_t h = 0; h < m.hanging_vertices.size(); ++h) {
    const int v = m.hanging_vertices[h];
    if (only && std::none_of(m.stencil[v].begin(), m.stencil[v].end(), [&](const StencilTerm& t) {
          return (*only)[static_cast<std::size_t>(t.free)] != 0;
        }))
      continue;
    const Eigen::Index row = free_count + static_cast<Eigen::Index>(h);
    const Eigen::Vector3d x = position_of(v, pass.q);
    if (!only && !needs_check(row, x, pass.first)) continue;
    ++pass.checked;
    Eigen::Vector3d target = x;
    SurfaceNearby nearby;
    const double correction =
        pass.scene.resolve(position_of(v, pass.q_previous), target, false, &memos_[static_cast<std::size_t>(row)], &nearby);
    if (correction > 0.0 && move_t_node(h, target - x, pass.q, &moved_)) {
      pass.largest = std::max(pass.largest, correction);
      pushed = true;
    } else {
      target = x;  // not moved (no free stencil to move it by)
    }
    anchor_.row(row) = target.transpose();
    set_plane(row, x, target, nearby);
    slack_[static_cast<std::size_t>(row)] = slack_of(nearby, has_plane_[static_cast<std::size_t>(row)] != 0);
  }
  return pushed;
}

void ImplicitIntegrator::list_t_node_planes(Eigen::Index free_count) const {
  t_node_planes_.clear();
  for (std::size_t h = 0; h < model_->hanging_vertices.size(); ++h)
    if (has_plane_[static_cast<std::size_t>(free_count) + h]) t_node_planes_.push_back(static_cast<int>(h));
}

StepReport ImplicitIntegrator::step(ClothState& state, const Positions& pinned_next,
                                    const std::vector<Collider>& colliders) {
  return step(state, pinned_next, AnalyticScene(colliders));
}

void ImplicitIntegrator::solve_dynamics(const Positions& y, Positions& q) const {
  Positions delta(q.rows(), 3);
  Positions grad;
  for (int it = 0; it < options_.iterations; ++it) {
    if (options_.newton_cg > 0) {
      gradient(q, y, grad);
      newton_direction(grad, delta);
    } else {
      gradient(q, y, delta);
      solver_.solve_in_place(delta);
    }
    q -= delta;
  }
}

void ImplicitIntegrator::collide_and_limit(const Positions& q_previous, Positions& q, const CollisionScene& scene,
                                          StepReport& report) {
  // Collisions are found once per step, right after the solve: each point
  // is resolved against the scene (posed for the end of the step, so it
  // does not move within it), with friction on the step's motion, and
  // leaves a contact plane where it was pushed or lies within reach of a
  // surface: the surface linearised there, for the rest of the step. The
  // strain limiter then keeps every point in front of its plane (it can
  // pull cloth along the body, not into it), and a point it moved farther
  // than its slack (its clearance, or contact_slack along a plane) from
  // where its check left it is checked again: the planes stand for the
  // surface only that far. Rounds of (limiting, checking) repeat while
  // checks move points, cloth-cloth contact pushed any, or a spring the
  // limiter can move started the round more than the round tolerance beyond
  // the limit, at most collision_rounds; the last word is
  // the check's, or the limiter's where no point left its slack. (Checking
  // once per step and then only what left its slack, with tethers, against
  // every moved point in every round before: over the walk table's 108 runs
  // 5 tore instead of 15 and the median largest stretch fell from 48-56 %
  // to 35-36 %, at about the same cost.)
  {
    const auto check_start = Clock::now();
    for (std::size_t k = 0; k < has_plane_.size(); ++k) has_plane_[k] = 0;  // planes last one step
    report.max_correction = 0.0;
    check_contacts(q_previous, q, scene, /*first=*/true, report.max_correction);
    report.first_round_ms = ms_since(check_start);
    report.collision_ms += report.first_round_ms;
  }
  for (int round = 0; round < options_.collision_rounds; ++round) {
    const auto limit_start = Clock::now();
    const double excess = limit_strain(q);
    const double limit_ms = ms_since(limit_start);
    report.dynamics_ms += limit_ms;
    report.limiter_ms += limit_ms;
    const auto collide_start = Clock::now();
    const double self_pushed = self_contact_.enabled() ? self_contact_.project(q, pinned_part_) : 0.0;
    const int checked = check_contacts(q_previous, q, scene, /*first=*/false, report.max_correction);
    report.collision_ms += ms_since(collide_start);
    ++report.rounds;
    if (checked == 0 && excess <= options_.round_tolerance && self_pushed == 0.0) break;
  }
}

StepReport ImplicitIntegrator::step(ClothState& state, const Positions& pinned_next, const CollisionScene& scene) {
  if (!model_) throw Error("ImplicitIntegrator::step called before precompute");
  const DynamicsModel& m = *model_;
  if (pinned_next.rows() != static_cast<Eigen::Index>(m.pinned_vertices.size()))
    throw ArgumentError("pinned targets have " + std::to_string(pinned_next.rows()) + " rows; the model pins " +
                        std::to_string(m.pinned_vertices.size()) + " vertices");
  StepReport report;
  const double h = options_.time_step;
  if (m.P.cols() > 0) pinned_part_.noalias() = m.P * pinned_next;

  const Positions q_previous = state.positions;
  fresh_pass_ = true;  // the dynamics moved everything: the first limiter pass evaluates every spring
  // Gravity is integrated exactly (x += h v + h^2 g / 2, v += h g), so free
  // fall follows the true parabola and a hanging cloth carries its full weight.
  Positions y = state.positions + h * state.velocities;
  y.rowwise() += (0.5 * h * h) * options_.gravity.transpose();
  Positions q = y;  // the inertial prediction is the usual warm start
  const auto start = Clock::now();
  solve_dynamics(y, q);
  report.dynamics_ms = ms_since(start);
  if (self_contact_.enabled()) {
    const auto gather_start = Clock::now();
    full_.noalias() = m.S * q;
    full_ += pinned_part_;
    self_contact_.gather(full_positions(m, q_previous, state.pinned), full_);
    report.collision_ms = ms_since(gather_start);
  }

  collide_and_limit(q_previous, q, scene, report);

  const double keep = 1.0 / (1.0 + m.material.damping * h);
  state.velocities = (keep / h) * (q - q_previous);
  state.velocities.rowwise() += (0.5 * h) * options_.gravity.transpose();
  state.positions = std::move(q);
  state.pinned = pinned_next;
  state.time += h;
  report.finite = state.positions.allFinite() && state.velocities.allFinite();
  return report;
}

}  // namespace mrcloth
