// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/solver/supernodal_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

namespace dform {
namespace {

using SparseLower = SupernodalCholesky::SparseLower;

// The normal-equation shape of a mesh: a side x side grid of vertices with `unknowns` coupled
// unknowns each, an edge between grid neighbours and one diagonal, random positive edge weights,
// plus `diagonal` on the diagonal. Positive definite for diagonal > 0. Returns the full matrix.
Eigen::SparseMatrix<double> gridMatrix(int side, int unknowns, double diagonal, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> weight(0.5, 1.5);
  std::vector<Eigen::Triplet<double>> entries;
  auto couple = [&](int a, int b) {
    const double w = weight(rng);
    for (int c = 0; c < unknowns; ++c)
      for (int d = 0; d < unknowns; ++d) {
        const double v = c == d ? w : 0.2 * w;  // each edge's block is positive definite
        entries.emplace_back(a * unknowns + c, a * unknowns + d, v);
        entries.emplace_back(b * unknowns + c, b * unknowns + d, v);
        entries.emplace_back(a * unknowns + c, b * unknowns + d, -v);
        entries.emplace_back(b * unknowns + c, a * unknowns + d, -v);
      }
  };
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const int v = i * side + j;
      if (i + 1 < side) couple(v, v + side);
      if (j + 1 < side) couple(v, v + 1);
      if (i + 1 < side && j + 1 < side) couple(v, v + side + 1);
    }
  const int n = side * side * unknowns;
  for (int k = 0; k < n; ++k) entries.emplace_back(k, k, diagonal);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// Two dense blocks of `block` unknowns, coupled to each other only through a dense border of
// `border` unknowns that is eliminated last: its supernode has several panels of columns and
// tiles of rows, and each block's update of it is larger than one tile both ways. Random,
// diagonally dominant, so positive definite.
Eigen::SparseMatrix<double> arrowMatrix(int block, int border, unsigned seed = 3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const int n = 2 * block + border;
  std::vector<Eigen::Triplet<double>> entries;
  auto couple = [&](int i, int j) {
    const double v = value(rng);
    entries.emplace_back(i, j, v);
    entries.emplace_back(j, i, v);
  };
  for (int b = 0; b < 2; ++b)
    for (int i = b * block; i < (b + 1) * block; ++i) {
      for (int j = b * block; j < i; ++j) couple(i, j);
      for (int j = 2 * block; j < n; ++j) couple(i, j);
    }
  for (int i = 2 * block; i < n; ++i)
    for (int j = 2 * block; j < i; ++j) couple(i, j);
  for (int k = 0; k < n; ++k) entries.emplace_back(k, k, double(n));
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

SparseLower lowerOf(const Eigen::SparseMatrix<double>& A) {
  SparseLower lower = A.triangularView<Eigen::Lower>();
  lower.makeCompressed();
  return lower;
}

double relativeResidual(const Eigen::SparseMatrix<double>& A, double shift,
                        const Eigen::MatrixXd& X, const Eigen::MatrixXd& B) {
  return (A * X + shift * X - B).norm() / B.norm();
}

TEST(SupernodalCholesky, SolvesAMeshShapedSystemToRounding) {
  // 24 x 24 vertices, 5 unknowns each (a forward solve's x y z u v): 2880 unknowns, supernodes
  // of tens of columns, so the dense blocks, the updates between supernodes and the triangular
  // solves all take part. Ordered unknown by unknown, by the vertices' blocks, and by blocks of 7
  // that straddle vertices and leave a short last block.
  const Eigen::SparseMatrix<double> A = gridMatrix(24, 5, 1e-3);
  const SparseLower lower = lowerOf(A);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 3);
  for (int blockSize : {1, 5, 7}) {
    SCOPED_TRACE(blockSize);
    SupernodalCholesky factor(lower, blockSize);
    ASSERT_TRUE(factor.factorize(lower));
    const Eigen::MatrixXd X = factor.solve(B);
    EXPECT_LT(relativeResidual(A, 0.0, X, B), 1e-10);
    // One column at a time gives the same answer as the three together.
    for (int c = 0; c < 3; ++c)
      EXPECT_LT((factor.solve(B.col(c)) - X.col(c)).norm(), 1e-12 * X.norm());
    EXPECT_GT(factor.factorFlops(), 0.0);
    EXPECT_GE(factor.factorNonZeros(), double(lower.nonZeros()));
  }
}

// The dense work on a large supernode is done in panels of columns and tiles of rows (so that a
// stop is seen between them); the factor is the one dense LLT gives, whichever way the border's
// columns fall into panels and its rows into tiles.
TEST(SupernodalCholesky, FactorisesSupernodesOfManyPanelsAndTiles) {
  for (const auto& [block, border] : {std::pair{600, 700}, std::pair{300, 1100}}) {
    SCOPED_TRACE(border);
    const Eigen::SparseMatrix<double> A = arrowMatrix(block, border);
    const SparseLower lower = lowerOf(A);
    SupernodalCholesky factor(lower);
    ASSERT_TRUE(factor.factorize(lower, 0.5));
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 2);
    const Eigen::MatrixXd X = factor.solve(B);
    EXPECT_LT(relativeResidual(A, 0.5, X, B), 1e-13);
    Eigen::MatrixXd dense = Eigen::MatrixXd(A);
    dense.diagonal().array() += 0.5;
    const Eigen::MatrixXd reference = dense.llt().solve(B);
    EXPECT_LT((X - reference).norm(), 1e-12 * reference.norm());
  }
}

TEST(SupernodalCholesky, FactorisesTheShiftedMatrix) {
  const Eigen::SparseMatrix<double> A = gridMatrix(10, 3, 1e-3);
  const SparseLower lower = lowerOf(A);
  SupernodalCholesky factor(lower);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 1);
  // A shift of 2 changes the answer by far more than rounding: a factor that ignored it, or
  // added it twice, fails the residual.
  ASSERT_TRUE(factor.factorize(lower, 2.0));
  EXPECT_LT(relativeResidual(A, 2.0, factor.solve(B), B), 1e-12);
  ASSERT_TRUE(factor.factorize(lower, 0.0));  // refactorising starts from A again
  EXPECT_LT(relativeResidual(A, 0.0, factor.solve(B), B), 1e-10);
}

TEST(SupernodalCholesky, RefusesAMatrixThatIsNotPositiveDefinite) {
  // The grid matrix with a negative diagonal shift of -0.5 has negative eigenvalues (its
  // smallest is near -0.5 + 1e-3); shifted back by +1 it is positive definite again.
  const Eigen::SparseMatrix<double> A = gridMatrix(8, 2, 1e-3);
  const SparseLower lower = lowerOf(A);
  SupernodalCholesky factor(lower);
  EXPECT_FALSE(factor.factorize(lower, -0.5));
  EXPECT_TRUE(factor.factorize(lower, 0.5));
  Eigen::SparseMatrix<double> nan = A;
  nan.coeffRef(3, 3) = std::numeric_limits<double>::quiet_NaN();
  const SparseLower nanLower = lowerOf(nan);
  EXPECT_FALSE(factor.factorize(nanLower)) << "a NaN on the diagonal must not pass as a pivot";
}

TEST(SupernodalCholesky, SolvesADiagonalAndAOneByOneSystem) {
  Eigen::SparseMatrix<double> D(4, 4);
  for (int k = 0; k < 4; ++k) D.insert(k, k) = double(k + 1);
  D.makeCompressed();
  SupernodalCholesky diagonal(lowerOf(D));
  ASSERT_TRUE(diagonal.factorize(lowerOf(D)));
  const Eigen::VectorXd x = diagonal.solve(Eigen::VectorXd::Ones(4));
  for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(x[k], 1.0 / double(k + 1));
  Eigen::SparseMatrix<double> one(1, 1);
  one.insert(0, 0) = 4.0;
  one.makeCompressed();
  SupernodalCholesky scalar(lowerOf(one));
  ASSERT_TRUE(scalar.factorize(lowerOf(one), 4.0));
  EXPECT_DOUBLE_EQ(scalar.solve(Eigen::VectorXd::Constant(1, 2.0))(0, 0), 0.25);
}

// Eigen sizes its product's panels from the CPU's caches, and other panels sum in another order.
// The factor pins them, so what Eigen believes about the caches beforehand changes no bit.
TEST(SupernodalCholesky, RoundsTheSameWhateverCachesTheMachineReports) {
  const std::ptrdiff_t caches[2][3] = {{4 * 1024, 16 * 1024, 64 * 1024},
                                       {512 * 1024, 32 * 1024 * 1024, 256 * 1024 * 1024}};
  for (const Eigen::SparseMatrix<double>& A : {gridMatrix(30, 5, 1e-3, 7), arrowMatrix(300, 700)}) {
    const SparseLower lower = lowerOf(A);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 2);
    Eigen::MatrixXd X[2];
    for (int run = 0; run < 2; ++run) {
      Eigen::setCpuCacheSizes(caches[run][0], caches[run][1], caches[run][2]);
      SupernodalCholesky factor(lower);
      ASSERT_TRUE(factor.factorize(lower, 1e-6));
      X[run] = factor.solve(B);
    }
    EXPECT_LT(relativeResidual(A, 1e-6, X[0], B), 1e-9);
    EXPECT_EQ(0, std::memcmp(X[0].data(), X[1].data(), sizeof(double) * std::size_t(X[0].size())))
        << "largest difference " << (X[0] - X[1]).cwiseAbs().maxCoeff();
  }
}

// METIS, which orders the blocks here, draws from the C library's one rand() state: analyses on
// four threads at once must order, and so round, exactly as one alone does, as a sweep's or a
// batch's jobs do (cholmodAnalysisMutex). Without the lock their draws interleave and the
// factors differ from the lone one in the last bits.
TEST(SupernodalCholesky, RoundsTheSameWhenFactorisedOnSeveralThreadsAtOnce) {
  const Eigen::SparseMatrix<double> A = gridMatrix(40, 5, 1e-3, 11);
  const SparseLower lower = lowerOf(A);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 1);
  const auto solveOnce = [&] {
    SupernodalCholesky factor(lower, 5);
    EXPECT_TRUE(factor.factorize(lower, 1e-6));
    return factor.solve(B);
  };
  const Eigen::MatrixXd alone = solveOnce();
  EXPECT_LT(relativeResidual(A, 1e-6, alone, B), 1e-9);
  for (int round = 0; round < 5; ++round) {
    std::vector<Eigen::MatrixXd> X(4);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < X.size(); ++t) threads.emplace_back([&, t] { X[t] = solveOnce(); });
    for (std::thread& t : threads) t.join();
    for (const Eigen::MatrixXd& x : X)
      EXPECT_EQ(0, std::memcmp(alone.data(), x.data(), sizeof(double) * std::size_t(x.size())))
          << "round " << round << ": largest difference " << (alone - x).cwiseAbs().maxCoeff();
  }
}

}  // namespace
}  // namespace dform
