#include "sparse_ldlt3.h"

#include "mesh_ops/errors.h"

#include <Eigen/SparseCholesky>

namespace mrcloth {

bool SparseLdlt3::factorize(const Eigen::SparseMatrix<double>& matrix, const std::function<bool()>& keep_going) {
  // What compute() does, in its two halves (the same permutation and the
  // same permuted matrix, so the same factor).
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  ldlt.analyzePattern(matrix);
  if (keep_going && !keep_going()) return false;
  ldlt.factorize(matrix);
  if (ldlt.info() != Eigen::Success) throw Error("the solver's system matrix could not be factorised (not positive definite)");
  n_ = static_cast<int>(matrix.rows());
  const auto& L = ldlt.matrixL().nestedExpression();  // unit lower triangular, CSC
  col_start_.assign(n_ + 1, 0);
  row_.clear();
  values_.clear();
  for (int j = 0; j < n_; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it) {
      if (it.row() == j) continue;
      row_.push_back(static_cast<int>(it.row()));
      values_.push_back(it.value());
    }
    col_start_[j + 1] = static_cast<int>(row_.size());
  }
  const Eigen::VectorXd d = ldlt.vectorD();
  inverse_diagonal_.resize(n_);
  for (int i = 0; i < n_; ++i) inverse_diagonal_[i] = 1.0 / d[i];
  const auto& p = ldlt.permutationP().indices();
  perm_.assign(p.data(), p.data() + n_);
  work_.assign(3 * static_cast<std::size_t>(n_), 0.0);
  return true;
}

void SparseLdlt3::solve_in_place(Eigen::Ref<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> rhs) const {
  double* z = work_.data();
  for (int i = 0; i < n_; ++i)
    for (int c = 0; c < 3; ++c) z[3 * perm_[i] + c] = rhs(i, c);
  // L z' = z (forward), z'' = D^-1 z', L^T w = z'' (backward).
  for (int j = 0; j < n_; ++j) {
    const double z0 = z[3 * j], z1 = z[3 * j + 1], z2 = z[3 * j + 2];
    for (int k = col_start_[j]; k < col_start_[j + 1]; ++k) {
      double* zi = z + 3 * row_[k];
      const double v = values_[k];
      zi[0] -= v * z0;
      zi[1] -= v * z1;
      zi[2] -= v * z2;
    }
  }
  for (int j = 0; j < n_; ++j)
    for (int c = 0; c < 3; ++c) z[3 * j + c] *= inverse_diagonal_[j];
  for (int j = n_ - 1; j >= 0; --j) {
    double s0 = z[3 * j], s1 = z[3 * j + 1], s2 = z[3 * j + 2];
    for (int k = col_start_[j]; k < col_start_[j + 1]; ++k) {
      const double* zi = z + 3 * row_[k];
      const double v = values_[k];
      s0 -= v * zi[0];
      s1 -= v * zi[1];
      s2 -= v * zi[2];
    }
    z[3 * j] = s0;
    z[3 * j + 1] = s1;
    z[3 * j + 2] = s2;
  }
  for (int i = 0; i < n_; ++i)
    for (int c = 0; c < 3; ++c) rhs(i, c) = z[3 * perm_[i] + c];
}

}  // namespace mrcloth
