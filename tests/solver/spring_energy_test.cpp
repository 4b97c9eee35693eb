#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/mode_layer.h"
#include "solver/spring_energy.h"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <random>

namespace mrcloth {
namespace {

TEST(SpringEnergy, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d xi(u(rng), u(rng), u(rng)), xj(u(rng), u(rng), u(rng));
    const double rest = 0.5 + 0.5 * std::abs(u(rng)), k = 10.0 + 100.0 * std::abs(u(rng));
    const SpringEvaluation e = evaluate_spring(xi, xj, rest, k);
    const double h = 1e-6;
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d[c] = h;
      const double fd = (evaluate_spring(xi + d, xj, rest, k).energy - evaluate_spring(xi - d, xj, rest, k).energy) / (2 * h);
      EXPECT_NEAR(e.gradient_i[c], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "trial " << trial;
      const Eigen::Vector3d fd_grad =
          (evaluate_spring(xi + d, xj, rest, k).gradient_i - evaluate_spring(xi - d, xj, rest, k).gradient_i) / (2 * h);
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(e.hessian(r, c), fd_grad[r], 1e-5 * std::max(1.0, k)) << "trial " << trial;
      // d/dxj of the energy is the negative of d/dxi.
      const double fd_j =
          (evaluate_spring(xi, xj + d, rest, k).energy - evaluate_spring(xi, xj - d, rest, k).energy) / (2 * h);
      EXPECT_NEAR(-e.gradient_i[c], fd_j, 1e-6 * std::max(1.0, std::abs(fd_j)));
    }
  }
}

// The Newton steps' spring Hessian: the exact one while the spring is at
// least its rest length, and the exact one with its negative (sideways)
// eigenvalue set to 0 when it is compressed.
TEST(SpringEnergy, ProjectedHessianIsTheExactOneWithoutItsNegativePart) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compressed = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d xi(u(rng), u(rng), u(rng)), xj(u(rng), u(rng), u(rng));
    const double rest = 1.5 * std::abs(u(rng)), k = 10.0 + 100.0 * std::abs(u(rng));
    const Eigen::Matrix3d exact = evaluate_spring(xi, xj, rest, k).hessian;
    const ProjectedSpringHessian p = projected_spring_hessian(xi - xj, rest, k);
    const Eigen::Matrix3d projected = p.a * Eigen::Matrix3d::Identity() + p.b * p.n * p.n.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(exact);
    const Eigen::Matrix3d clamped =
        eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
    EXPECT_LT((projected - clamped).cwiseAbs().maxCoeff(), 1e-12 * k) << "trial " << trial;
    if ((xi - xj).norm() >= rest) EXPECT_LT((projected - exact).cwiseAbs().maxCoeff(), 1e-12 * k) << "trial " << trial;
    else ++compressed;
    EXPECT_GE(p.a, 0.0);
    EXPECT_NEAR(p.a + p.b, k, 1e-12 * k);
  }
  EXPECT_GT(compressed, 20);  // both cases were met
  // A spring of zero length: isotropic, as evaluate_spring.
  const ProjectedSpringHessian zero = projected_spring_hessian(Eigen::Vector3d::Zero(), 0.3, 7.0);
  EXPECT_EQ(zero.a, 7.0);
  EXPECT_EQ(zero.b, 0.0);
}

TEST(SpringEnergy, ModelForcesAreMinusTheEnergyGradient) {
  QuadMesh mesh = test::make_grid(3, 2, 0.1);
  set_modes(mesh, {0, 1, 4, 5}, 4);
  adaptive_refine(mesh, {8.0, 3, true});
  const DynamicsModel model = build_dynamics(mesh, {});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  Positions x = model.rest;
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    for (int c = 0; c < 3; ++c) x(v, c) += u(rng);
  const Positions f = spring_forces(model, x);
  const double h = 1e-7;
  for (Eigen::Index v = 0; v < x.rows(); v += 3)
    for (int c = 0; c < 3; ++c) {
      Positions a = x, b = x;
      a(v, c) += h;
      b(v, c) -= h;
      const double fd = (spring_energy(model, a) - spring_energy(model, b)) / (2 * h);
      EXPECT_NEAR(f(v, c), -fd, 1e-5 * std::max(1.0, std::abs(fd))) << "vertex " << v << " axis " << c;
    }
}

}  // namespace
}  // namespace mrcloth
