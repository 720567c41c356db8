#include "solver/gram_matrix.h"

#include <algorithm>
#include <vector>

#include "core/interrupt.h"

namespace dform {

namespace {

// Columns per block: Eigen's product walks every column of M once per block, so blocks are wide;
// one block of a fine mesh's term (a million columns) is a fraction of a second.
constexpr Eigen::Index kBlockColumns = 1 << 17;

}  // namespace

Eigen::SparseMatrix<double> gramMatrix(const Eigen::SparseMatrix<double>& M) {
  const Eigen::Index n = M.cols();
  // Column j of M^T M is M^T times column j of M: a block of columns is a product of its own.
  std::vector<Eigen::SparseMatrix<double>> blocks;
  Eigen::Index nonZeros = 0;
  for (Eigen::Index first = 0; first < n; first += kBlockColumns) {
    throwIfInterrupted("the solve");
    blocks.emplace_back(M.transpose() * M.middleCols(first, std::min(kBlockColumns, n - first)));
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
    for (Eigen::Index j = 0; j < block.cols(); ++j) gram.outerIndexPtr()[column + j] = int(offset) + block.outerIndexPtr()[j];
    column += block.cols();
    offset += block.nonZeros();
  }
  gram.outerIndexPtr()[n] = int(offset);
  return gram;
}

}  // namespace dform
