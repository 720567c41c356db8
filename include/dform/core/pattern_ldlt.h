// SPDX-License-Identifier: GPL-3.0-or-later
// A sparse LDLT factorisation for a run of matrices of one pattern (a solve's steps): Eigen's
// SimplicialLDLT with its AMD ordering and symbolic analysis computed once per pattern.
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <vector>

namespace dform {

/// Factorises matrices as a fresh Eigen::SimplicialLDLT would, to the bit, but orders and
/// analyses a pattern only when it differs from the last one factorised (the same nonzero
/// places, explicit zeros included): a Newton or Levenberg-Marquardt run then pays the ordering
/// once instead of at every step.
class PatternLDLT {
 public:
  /// The matrices it factorises: Eigen's column-major sparse matrices of doubles.
  using Matrix = Eigen::SparseMatrix<double>;

  /// Factorises A (its lower triangle is read); false where that failed.
  bool factorize(Matrix A) {
    A.makeCompressed();
    if (!samePattern(A)) {
      solver_.analyzePattern(A);
      outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
      inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    }
    solver_.factorize(A);
    return solver_.info() == Eigen::Success;
  }
  /// The last factorisation (solve, vectorD).
  const Eigen::SimplicialLDLT<Matrix>& solver() const { return solver_; }

 private:
  bool samePattern(const Matrix& A) const {
    return outer_.size() == std::size_t(A.outerSize()) + 1 &&
           inner_.size() == std::size_t(A.nonZeros()) &&
           std::equal(outer_.begin(), outer_.end(), A.outerIndexPtr()) &&
           std::equal(inner_.begin(), inner_.end(), A.innerIndexPtr());
  }

  Eigen::SimplicialLDLT<Matrix> solver_;
  std::vector<int> outer_, inner_;
};

}  // namespace dform
