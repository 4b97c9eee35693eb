#include "spring_energy.h"

#include <algorithm>

namespace mrcloth {

SpringEvaluation evaluate_spring(const Eigen::Vector3d& xi, const Eigen::Vector3d& xj, double rest, double stiffness) {
  const Eigen::Vector3d e = xi - xj;
  const double length = e.norm();
  SpringEvaluation out;
  const double stretch = length - rest;
  out.energy = 0.5 * stiffness * stretch * stretch;
  if (length == 0.0) {  // direction undefined: no force, isotropic stiffness
    out.gradient_i.setZero();
    out.hessian = stiffness * Eigen::Matrix3d::Identity();
    return out;
  }
  const Eigen::Vector3d n = e / length;
  out.gradient_i = stiffness * stretch * n;
  out.hessian = stiffness * (n * n.transpose() + (stretch / length) * (Eigen::Matrix3d::Identity() - n * n.transpose()));
  return out;
}

ProjectedSpringHessian projected_spring_hessian(const Eigen::Vector3d& e, double rest, double stiffness) {
  ProjectedSpringHessian h;
  const double length = e.norm();
  if (length == 0.0) {  // direction undefined: isotropic, as evaluate_spring
    h.a = stiffness;
    return h;
  }
  h.n = e / length;
  h.a = stiffness * std::max(0.0, 1.0 - rest / length);
  h.b = stiffness - h.a;
  return h;
}

Eigen::Vector3d spring_vector(const Spring& s, const Positions& x) {
  if (s.via < 0) return (x.row(s.i) - x.row(s.j)).transpose();
  return (x.row(s.i) - 2.0 * x.row(s.via) + x.row(s.j)).transpose();
}

double spring_energy(const DynamicsModel& model, const Positions& x) {
  double energy = 0.0;
  for (const Spring& s : model.springs) {
    const double stretch = spring_vector(s, x).norm() - s.rest;
    energy += 0.5 * s.stiffness * stretch * stretch;
  }
  return energy;
}

Positions spring_forces(const DynamicsModel& model, const Positions& x) {
  Positions f = Positions::Zero(x.rows(), 3);
  for (const Spring& s : model.springs) {
    const Eigen::Vector3d e = spring_vector(s, x);
    const double length = e.norm();
    if (length == 0.0) continue;
    const Eigen::Vector3d g = s.stiffness * (length - s.rest) / length * e;
    f.row(s.i) -= g.transpose();
    if (s.via < 0) {
      f.row(s.j) += g.transpose();
    } else {  // e = xi - 2 xvia + xj
      f.row(s.j) -= g.transpose();
      f.row(s.via) += 2.0 * g.transpose();
    }
  }
  return f;
}

}  // namespace mrcloth
