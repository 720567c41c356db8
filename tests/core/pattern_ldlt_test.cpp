// SPDX-License-Identifier: GPL-3.0-or-later
// PatternLDLT: the factors of a fresh SimplicialLDLT to the bit while the pattern stays, and a new
// ordering when it changes.
#include "dform/core/pattern_ldlt.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <vector>

namespace dform {
namespace {

using Matrix = Eigen::SparseMatrix<double>;

// A symmetric positive definite matrix: a path graph's Laplacian plus `shift` on the diagonal,
// with extra couplings (i, i + span) when span > 0.
Matrix laplacian(int n, double shift, int span) {
  std::vector<Eigen::Triplet<double>> entries;
  auto couple = [&](int i, int j, double w) {
    entries.emplace_back(i, i, w);
    entries.emplace_back(j, j, w);
    entries.emplace_back(i, j, -w);
    entries.emplace_back(j, i, -w);
  };
  for (int i = 0; i + 1 < n; ++i) couple(i, i + 1, 1.0 + 0.1 * i);
  if (span > 0)
    for (int i = 0; i + span < n; i += 3) couple(i, i + span, 0.5);
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, shift);
  Matrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

Eigen::VectorXd freshSolve(const Matrix& A, const Eigen::VectorXd& b) {
  const Eigen::SimplicialLDLT<Matrix> fresh(A);
  return fresh.solve(b);
}

TEST(PatternLDLT, SolvesAsAFreshFactorisationToTheBit) {
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(40, -1.0, 2.0);
  PatternLDLT ldlt;
  // The same pattern with other values, then another pattern (and size), then the first again.
  for (const Matrix& A : {laplacian(40, 0.5, 7), laplacian(40, 3.0, 7), laplacian(40, 1e-3, 7)}) {
    ASSERT_TRUE(ldlt.factorize(A));
    const Eigen::VectorXd x = ldlt.solver().solve(b), expected = freshSolve(A, b);
    EXPECT_EQ(x, expected);
    EXPECT_LT((A * x - b).norm(), 1e-9 * b.norm());
  }
  const Matrix wider = laplacian(55, 0.5, 11);
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(55, 1.0, 3.0);
  ASSERT_TRUE(ldlt.factorize(wider));
  EXPECT_EQ(ldlt.solver().solve(c), freshSolve(wider, c));
  const Matrix otherCouplings = laplacian(40, 0.5, 5);
  ASSERT_TRUE(ldlt.factorize(otherCouplings));
  EXPECT_EQ(ldlt.solver().solve(b), freshSolve(otherCouplings, b));
  EXPECT_LT((otherCouplings * ldlt.solver().solve(b) - b).norm(), 1e-9 * b.norm());
}

TEST(PatternLDLT, ReportsAFailedFactorisation) {
  // A zero matrix with a full diagonal pattern: a zero pivot.
  Matrix zero(3, 3);
  std::vector<Eigen::Triplet<double>> entries{{0, 0, 0.0}, {1, 1, 0.0}, {2, 2, 0.0}};
  zero.setFromTriplets(entries.begin(), entries.end());
  PatternLDLT ldlt;
  EXPECT_FALSE(ldlt.factorize(zero));
}

}  // namespace
}  // namespace dform
