// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/solver/gram_matrix.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "dform/core/interrupt.h"

namespace dform {
namespace {

// A random sparse matrix wide enough for several of gramMatrix's column blocks.
Eigen::SparseMatrix<double> randomGramSparse(int rows, int cols, int perRow, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k < perRow; ++k)
      entries.emplace_back(r, int(rng() % unsigned(cols)), value(rng));
  Eigen::SparseMatrix<double> M(rows, cols);
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

TEST(GramMatrix, IsEigensProductBitForBit) {
  // The relaxation's results (and the samples' digests) may not change by a bit: each entry must
  // be the same sum in the same order, the pattern the same, whatever the number of blocks.
  for (const int cols : {7, 131072, 300001}) {
    SCOPED_TRACE(cols);
    const Eigen::SparseMatrix<double> M = randomGramSparse(120000, cols, 4, unsigned(cols));
    Eigen::SparseMatrix<double> expected(M.transpose() * M);
    expected.makeCompressed();
    const Eigen::SparseMatrix<double> gram = gramMatrix(M);
    ASSERT_TRUE(gram.isCompressed());
    ASSERT_EQ(gram.rows(), cols);
    ASSERT_EQ(gram.nonZeros(), expected.nonZeros());
    EXPECT_EQ(0, std::memcmp(gram.outerIndexPtr(), expected.outerIndexPtr(),
                             sizeof(int) * std::size_t(cols + 1)));
    EXPECT_EQ(0, std::memcmp(gram.innerIndexPtr(), expected.innerIndexPtr(),
                             sizeof(int) * std::size_t(gram.nonZeros())));
    EXPECT_EQ(0, std::memcmp(gram.valuePtr(), expected.valuePtr(),
                             sizeof(double) * std::size_t(gram.nonZeros())));
  }
}

TEST(GramMatrix, AStopRequestedThrowsInterrupted) {
  const Eigen::SparseMatrix<double> M = randomGramSparse(1000, 300001, 2, 1);
  interruptFlag() = true;
  EXPECT_THROW(gramMatrix(M), Interrupted);
  interruptFlag() = false;
  EXPECT_NO_THROW(gramMatrix(M));
}

}  // namespace
}  // namespace dform
