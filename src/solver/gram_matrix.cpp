// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/solver/gram_matrix.h"

#include <algorithm>
#include <vector>

#include "dform/core/interrupt.h"

namespace dform {

namespace {

// Columns per block. M^T is stored once, so a block's product costs only its own columns' work;
// on a fine mesh's term (a million columns, 10 to 20 entries each) a block is a few milliseconds.
constexpr Eigen::Index kBlockColumns = 1 << 14;

}  // namespace

Eigen::SparseMatrix<double> gramMatrix(const Eigen::SparseMatrix<double>& M) {
  const Eigen::Index n = M.cols();
  // Column j of M^T M is M^T times column j of M: a block of columns is a product of its own.
  // Stored column-major, M^T multiplies each block as Eigen's expression does: entry (i, j) sums
  // M(r, i) M(r, j) over the rows r of column j in ascending order.
  const Eigen::SparseMatrix<double> transposed = M.transpose();
  throwIfInterrupted("the solve");
  std::vector<Eigen::SparseMatrix<double>> blocks;
  Eigen::Index nonZeros = 0;
  for (Eigen::Index first = 0; first < n; first += kBlockColumns) {
    throwIfInterrupted("the solve");
    blocks.emplace_back(transposed * M.middleCols(first, std::min(kBlockColumns, n - first)));
    nonZeros += blocks.back().nonZeros();
  }
  throwIfInterrupted("the solve");
  // The blocks side by side: their compressed columns copied one after the other.
  Eigen::SparseMatrix<double> gram(n, n);
  gram.resizeNonZeros(nonZeros);
  Eigen::Index column = 0, offset = 0;
  for (const Eigen::SparseMatrix<double>& block : blocks) {
    std::copy_n(block.innerIndexPtr(), block.nonZeros(), gram.innerIndexPtr() + offset);
    std::copy_n(block.valuePtr(), block.nonZeros(), gram.valuePtr() + offset);
    for (Eigen::Index j = 0; j < block.cols(); ++j)
      gram.outerIndexPtr()[column + j] = int(offset) + block.outerIndexPtr()[j];
    column += block.cols();
    offset += block.nonZeros();
  }
  gram.outerIndexPtr()[n] = int(offset);
  return gram;
}

}  // namespace dform
