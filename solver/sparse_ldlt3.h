#pragma once
// A sparse LDL^T factorisation (Eigen's SimplicialLDLT with AMD ordering)
// whose solve handles the x, y and z columns in one pass over the factor:
// the factor is read once instead of three times, which is what a per-step
// solve of cloth positions is bound by.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <functional>
#include <vector>

namespace mrcloth {

class SparseLdlt3 {
 public:
  /// Factorises a symmetric positive definite matrix (lower triangle used).
  /// Throws Error if the factorisation fails (not positive definite).
  /// `keep_going`, if given, is consulted between the ordering (AMD and the
  /// symbolic analysis) and the numeric factorisation; false stops there and
  /// returns false, leaving this unusable. It changes no bit of the factor.
  bool factorize(const Eigen::SparseMatrix<double>& matrix, const std::function<bool()>& keep_going = {});

  /// Solves A X = B in place for B with 3 columns (row-major, n x 3).
  void solve_in_place(Eigen::Ref<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> rhs) const;

  int size() const { return n_; }
  std::size_t factor_nonzeros() const { return values_.size(); }

 private:
  int n_ = 0;
  std::vector<int> col_start_, row_;   // strictly lower part of L, CSC
  std::vector<double> values_;
  std::vector<double> inverse_diagonal_;
  std::vector<int> perm_;              // perm_[i] = position of row i in the factor
  mutable std::vector<double> work_;
};

}  // namespace mrcloth
