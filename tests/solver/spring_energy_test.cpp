#include "test_meshes.h"

#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/uniform_refine.h"
#include "solver/spring_energy.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
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

class ModelForces : public ::testing::TestWithParam<BendModel> {};

TEST_P(ModelForces, AreMinusTheEnergyGradient) {
  QuadMesh mesh = test::make_grid(3, 2, 0.1);
  set_modes(mesh, {0, 1, 4, 5}, 4);
  adaptive_refine(mesh, {8.0, 3, true});
  DynamicsOptions options;
  options.bend_model = GetParam();
  const DynamicsModel model = build_dynamics(mesh, options);
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

INSTANTIATE_TEST_SUITE_P(BendModels, ModelForces,
                         ::testing::Values(BendModel::distance, BendModel::second_difference));

// The second-difference bend springs: through their pair's middle, at rest
// at the rest shape (no force), and blind to rigid motions.
TEST(SpringEnergy, SecondDifferenceBendSpringsRestAtTheRestShapeAndIgnoreRigidMotion) {
  QuadMesh mesh = test::make_grid(4, 3, 0.1);
  for (auto v : mesh.vertices()) {  // a curved rest shape: part of a cylinder of radius 0.3 m
    auto p = mesh.point(v);
    const double angle = p[0] / 0.3;
    mesh.set_point(v, {0.3 * std::sin(angle), p[1], 0.3 * (1.0 - std::cos(angle))});
  }
  set_modes(mesh, {0, 1, 5}, 4);
  adaptive_refine(mesh, {8.0, 3, true});
  DynamicsOptions options;
  options.bend_model = BendModel::second_difference;
  const DynamicsModel model = build_dynamics(mesh, options);
  int bend = 0;
  for (const Spring& s : model.springs) {
    if (s.kind != SpringKind::bend) {
      EXPECT_EQ(s.via, -1);
      continue;
    }
    ++bend;
    ASSERT_GE(s.via, 0);
    EXPECT_NEAR(s.rest, spring_vector(s, model.rest).norm(), 1e-15);
    EXPECT_LT(s.rest, 0.2 * (model.rest.row(s.i) - model.rest.row(s.j)).norm());  // nearly straight
  }
  EXPECT_GT(bend, 50);
  EXPECT_LT(spring_energy(model, model.rest), 1e-30);
  EXPECT_LT(spring_forces(model, model.rest).cwiseAbs().maxCoeff(), 1e-15);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  Positions x = model.rest;
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    for (int c = 0; c < 3; ++c) x(v, c) += u(rng);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Positions moved = x * turn.transpose();
  moved.rowwise() += Eigen::RowVector3d(0.4, -1.0, 2.0);
  const double energy = spring_energy(model, x);
  EXPECT_GT(energy, 0.0);
  EXPECT_NEAR(spring_energy(model, moved), energy, 1e-12 * energy);
}

// A flat sheet bent onto a cylinder: the second-difference springs, scaled
// x4 per level (alpha_bend 2), store about the same energy at every level,
// as a quadratic bending energy must; the distance springs, quartic in the
// curvature, store a quarter as much per level, so refined cloth bends
// more easily than coarse cloth beside it.
TEST(SpringEnergy, SecondDifferenceBendingEnergyIsTheSameAtEveryLevel) {
  const auto bend_energy = [](BendModel model_kind, int levels) {
    QuadMesh mesh = test::make_grid(12, 12, 0.025);
    uniform_refine(mesh, levels);
    DynamicsOptions options;
    options.bend_model = model_kind;
    const DynamicsModel model = build_dynamics(mesh, options);
    Positions x = model.rest;
    for (Eigen::Index v = 0; v < x.rows(); ++v) {  // onto a cylinder of radius 0.2 m, lengths kept
      const double angle = model.rest(v, 0) / 0.2;
      x(v, 0) = 0.2 * std::sin(angle);
      x(v, 2) = 0.2 * (1.0 - std::cos(angle));
    }
    double energy = 0.0;
    for (const Spring& s : model.springs)
      if (s.kind == SpringKind::bend) {
        const double stretch = spring_vector(s, x).norm() - s.rest;
        energy += 0.5 * s.stiffness * stretch * stretch;
      }
    return energy;
  };
  const double sd1 = bend_energy(BendModel::second_difference, 0), sd3 = bend_energy(BendModel::second_difference, 2);
  const double d1 = bend_energy(BendModel::distance, 0), d3 = bend_energy(BendModel::distance, 2);
  EXPECT_GT(sd1, 0.0);
  // (Pairs need both records, so the coarse grid's edge rows bend less of
  // its width: 11 of 12 columns against 47 of 48, about 7 %.)
  EXPECT_NEAR(sd3 / sd1, 1.0, 0.1) << sd1 << " J coarse, " << sd3 << " J refined twice";
  EXPECT_NEAR(d3 / d1, 1.0 / 16.0, 0.015) << d1 << " J coarse, " << d3 << " J refined twice";
}

}  // namespace
}  // namespace mrcloth
