// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/solver/supernodal_cholesky.h"

#include <cholmod.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <memory>
#include <mutex>
#include <new>

#include "dform/core/interrupt.h"

namespace dform {

namespace {

using Matrix = Eigen::MatrixXd;
using Block = Eigen::Map<Matrix>;
using ConstBlock = Eigen::Map<const Matrix>;

// Eigen's dense product splits its sum over k into panels sized from the CPU's cache sizes, and
// another panel size sums in another order. These are fixed so that every machine sums alike;
// they are typical of an x86-64 core (32 KiB L1, 1 MiB L2, 8 MiB L3) and only set the panel
// sizes, not what is computed. Eigen keeps them in process-wide variables: they are set before
// main (one thread), and set again only if some code has changed them since, under a lock.
constexpr std::ptrdiff_t kL1 = 32 * 1024, kL2 = 1024 * 1024, kL3 = 8 * 1024 * 1024;
void pinProductBlocking() {
  if (Eigen::l1CacheSize() == kL1 && Eigen::l2CacheSize() == kL2 && Eigen::l3CacheSize() == kL3)
    return;
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  Eigen::setCpuCacheSizes(kL1, kL2, kL3);
}
[[maybe_unused]] const bool pinnedBeforeMain = (pinProductBlocking(), true);

// CHOLMOD's workspace for one analysis, released however the analysis ends.
struct CholmodSession {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  CholmodSession() { cholmod_start(&common); }
  ~CholmodSession() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
};

// CHOLMOD's view of the lower triangle of a symmetric pattern (no values).
cholmod_sparse patternView(int n, const int* outer, const int* inner) {
  cholmod_sparse view{};
  view.nrow = view.ncol = std::size_t(n);
  view.nzmax = std::size_t(outer[n]);
  view.p = const_cast<int*>(outer);
  view.i = const_cast<int*>(inner);
  view.stype = -1;  // the lower triangle of a symmetric matrix
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_PATTERN;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

// One CHOLMOD analysis of a symmetric pattern (its lower triangle), holding copies of all it reads.
struct PendingAnalysis {
  std::vector<int> outer, inner;
  std::vector<int> ordering;  ///< the ordering to analyse with; empty: CHOLMOD's methods choose one
  CholmodSession session;     ///< configured by the caller; holds the result

  PendingAnalysis(int n, const int* outerIndex, const int* innerIndex)
      : outer(outerIndex, outerIndex + n + 1), inner(innerIndex, innerIndex + outerIndex[n]) {}

  void run() {
    cholmod_sparse view = patternView(int(outer.size()) - 1, outer.data(), inner.data());
    if (!ordering.empty()) {
      session.factor = cholmod_analyze_p(&view, ordering.data(), nullptr, 0, &session.common);
    } else {
      const std::lock_guard<std::mutex> lock(cholmodAnalysisMutex());
      session.factor = cholmod_analyze(&view, &session.common);
    }
  }
};

// Runs the analysis. It takes seconds on a fine mesh (AMD, METIS, the symbolic factorisation) and
// cannot be stopped from outside, so it runs on a thread of its own while this one polls the stop
// flag (runWhilePolling): a stop throws Interrupted and leaves the thread to finish on its own
// copies, which it frees when it ends. Where it runs changes nothing in what it computes.
void analyzeWhilePolling(const std::shared_ptr<PendingAnalysis>& pending) {
  throwIfInterrupted("the solve");
  if (!runWhilePolling([pending] { pending->run(); })) throw Interrupted("the solve");
}

// A fill-reducing ordering of the symmetric pattern whose lower triangle is `pattern`, found by
// METIS on the graph of its blocks of `blockSize` unknowns (a vertex's x y z u v), each block
// ordered as one. That graph is blockSize times smaller, and METIS takes a small fraction of
// the time it took on the unknowns' graph (at 13k unknowns as long as a factorisation), for
// about the same fill.
std::vector<int> blockOrdering(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& pattern,
                               int blockSize) {
  const int n = int(pattern.rows()), blocks = (n + blockSize - 1) / blockSize;
  std::vector<std::vector<int>> below(blocks);  // lower triangle of the block graph
  for (int j = 0; j < n; ++j)
    for (int p = pattern.outerIndexPtr()[j]; p < pattern.outerIndexPtr()[j + 1]; ++p) {
      const int bi = pattern.innerIndexPtr()[p] / blockSize, bj = j / blockSize;
      below[std::min(bi, bj)].push_back(std::max(bi, bj));
    }
  std::vector<int> outer(blocks + 1, 0), inner;
  for (int b = 0; b < blocks; ++b) {
    below[b].push_back(b);
    std::sort(below[b].begin(), below[b].end());
    below[b].erase(std::unique(below[b].begin(), below[b].end()), below[b].end());
    inner.insert(inner.end(), below[b].begin(), below[b].end());
    outer[b + 1] = int(inner.size());
  }
  const auto pending = std::make_shared<PendingAnalysis>(blocks, outer.data(), inner.data());
  CholmodSession& session = pending->session;
  session.common.supernodal = CHOLMOD_SIMPLICIAL;  // only the ordering is wanted
  session.common.nmethods = 1;
  session.common.method[0].ordering = CHOLMOD_METIS;
  analyzeWhilePolling(pending);
  if (!session.factor || session.common.status < CHOLMOD_OK) throw std::bad_alloc();
  const int* blockOrder = static_cast<const int*>(session.factor->Perm);
  std::vector<int> order;
  order.reserve(n);
  for (int k = 0; k < blocks; ++k)
    for (int u = blockOrder[k] * blockSize; u < std::min(n, (blockOrder[k] + 1) * blockSize); ++u)
      order.push_back(u);
  return order;
}

// The dense work on a supernode comes in tiles of at most kTileRows x kPanel results, each one
// Eigen call: a stop is seen between two tiles (the last supernodes of a fine mesh have thousands
// of columns, and one call on a whole block of them runs for over a second), and every tile's
// shape, so its rounding, follows from the sizes alone.
constexpr int kPanel = 128, kTileRows = 512;

// Subtracts from a supernode's columns Lk (its first column is k1; `local` maps a row of L to
// Lk's) the update of a descendant whose columns are Ld and rows drows: the product of Ld's rows
// p1.. (all those that reach this supernode or a later one) with its rows p1 .. p1 + m - 1 (those
// among this supernode's columns), only the entries on or below the diagonal, in tiles computed
// in `tile` (room for kTileRows x kPanel).
void subtractUpdate(const ConstBlock& Ld, const int* drows, int p1, int m, const int* local, int k1,
                    Block& Lk, double* tile) {
  const int rest = int(Ld.rows()) - p1;
  for (int j0 = 0; j0 < m; j0 += kPanel) {
    const int q = std::min(kPanel, m - j0);
    for (int i0 = j0; i0 < rest; i0 += kTileRows) {
      throwIfInterrupted("the solve");
      const int p = std::min(kTileRows, rest - i0);
      Block update(tile, p, q);
      update.noalias() = Ld.middleRows(p1 + i0, p) * Ld.middleRows(p1 + j0, q).transpose();
      for (int j = 0; j < q; ++j) {
        const int col = drows[p1 + j0 + j] - k1;
        for (int i = std::max(0, j0 + j - i0); i < p; ++i)
          Lk(local[drows[p1 + i0 + i]], col) -= update(i, j);
      }
    }
  }
}

// Factorises a supernode whose updates are all in: its columns [L11; L21] become L11 (Cholesky
// factor of the top block, lower triangle) and L21 L11^-T, panel by panel, left-looking. The
// strict upper triangle of the top block is left holding no meaning. False when the top block is
// not numerically positive definite.
bool factorSupernode(Block& L) {
  const int nrows = int(L.rows()), cols = int(L.cols());
  for (int j0 = 0; j0 < cols; j0 += kPanel) {
    const int q = std::min(kPanel, cols - j0);
    if (j0 > 0)
      for (int i0 = j0; i0 < nrows; i0 += kTileRows) {
        throwIfInterrupted("the solve");
        const int p = std::min(kTileRows, nrows - i0);
        L.block(i0, j0, p, q).noalias() -=
            L.block(i0, 0, p, j0) * L.block(j0, 0, q, j0).transpose();
      }
    auto diagonal = L.block(j0, j0, q, q);
    Eigen::LLT<Eigen::Ref<Matrix>> llt(diagonal);
    if (llt.info() != Eigen::Success || !diagonal.diagonal().allFinite()) return false;
    for (int i0 = j0 + q; i0 < nrows; i0 += kTileRows) {
      throwIfInterrupted("the solve");
      auto below = L.block(i0, j0, std::min(kTileRows, nrows - i0), q);
      diagonal.transpose().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(below);
    }
  }
  return true;
}

}  // namespace

std::mutex& cholmodAnalysisMutex() {
  static std::mutex mutex;
  return mutex;
}

SupernodalCholesky::SupernodalCholesky(const SparseLower& pattern, int blockSize) {
  assert(pattern.rows() == pattern.cols() && pattern.isCompressed() &&
         "a compressed square pattern");
  n_ = int(pattern.rows());
  const auto pending =
      std::make_shared<PendingAnalysis>(n_, pattern.outerIndexPtr(), pattern.innerIndexPtr());
  CholmodSession& session = pending->session;
  cholmod_common& c = session.common;
  c.supernodal = CHOLMOD_SUPERNODAL;
  if (blockSize > 1) {
    pending->ordering = blockOrdering(pattern, blockSize);
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_GIVEN;
  }
  analyzeWhilePolling(pending);
  if (!session.factor || c.status < CHOLMOD_OK || !session.factor->is_super) throw std::bad_alloc();
  const cholmod_factor& L = *session.factor;
  factorFlops_ = c.fl;
  factorNonZeros_ = c.lnz;

  const int nsuper = int(L.nsuper);
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* px = static_cast<const int*>(L.px);
  const int* s = static_cast<const int*>(L.s);
  first_.assign(super, super + nsuper + 1);
  rowStart_.assign(pi, pi + nsuper + 1);
  valueStart_.assign(px, px + nsuper + 1);
  rows_.assign(s, s + L.ssize);
  perm_.assign(static_cast<const int*>(L.Perm), static_cast<const int*>(L.Perm) + n_);
  superOf_.assign(n_, 0);
  for (int k = 0; k < nsuper; ++k) {
    std::fill(superOf_.begin() + first_[k], superOf_.begin() + first_[k + 1], k);
    // The supernode's own columns come first; the rows below them are sorted here so that the
    // rows a descendant updates in one ancestor are contiguous (CHOLMOD lists them ascending).
    std::sort(rows_.begin() + rowStart_[k] + (first_[k + 1] - first_[k]),
              rows_.begin() + rowStart_[k + 1]);
  }
  values_.assign(std::size_t(valueStart_[nsuper]), 0.0);

  // Where each stored entry (i, j) of A lands: the entry (r, c) = (max, min) of P A P^T.
  std::vector<int> inverse(n_);
  for (int k = 0; k < n_; ++k) inverse[perm_[k]] = k;
  auto slot = [&](int r, int col) {
    const int k = superOf_[col];
    const auto begin = rows_.begin() + rowStart_[k], end = rows_.begin() + rowStart_[k + 1];
    const auto at = std::lower_bound(begin + (first_[k + 1] - first_[k]), end, r);
    const long position = r < first_[k + 1] ? r - first_[k] : long(at - begin);
    assert((r < first_[k + 1] || (at != end && *at == r)) &&
           "an entry outside the analysed pattern");
    return valueStart_[k] + long(col - first_[k]) * long(rowStart_[k + 1] - rowStart_[k]) +
           position;
  };
  scatter_.reserve(std::size_t(pattern.nonZeros()));
  for (int j = 0; j < n_; ++j) {
    if (j % 65536 == 0) throwIfInterrupted("the solve");
    for (int p = pattern.outerIndexPtr()[j]; p < pattern.outerIndexPtr()[j + 1]; ++p) {
      const int ri = inverse[pattern.innerIndexPtr()[p]], rj = inverse[j];
      scatter_.push_back(slot(std::max(ri, rj), std::min(ri, rj)));
    }
  }
  diagonal_.resize(n_);
  for (int k = 0; k < n_; ++k) diagonal_[k] = slot(k, k);
}

SupernodalCholesky::~SupernodalCholesky() = default;

bool SupernodalCholesky::factorize(const SparseLower& A, double shift) {
  assert(A.nonZeros() == long(scatter_.size()) && "A must have the analysed pattern");
  pinProductBlocking();
  factored_ = false;
  std::fill(values_.begin(), values_.end(), 0.0);
  const double* a = A.valuePtr();
  for (std::size_t p = 0; p < scatter_.size(); ++p) values_[scatter_[p]] += a[p];
  for (long d : diagonal_) values_[d] += shift;

  // Left-looking: supernode k gathers the updates of every earlier supernode d whose rows reach
  // its columns. d waits in the list of the next supernode its rows reach (head/next), with
  // `position` the first of its rows not yet used.
  const int nsuper = int(first_.size()) - 1;
  std::vector<int> head(nsuper, -1), next(nsuper, -1), position(nsuper, 0), local(n_, -1);
  std::vector<double> tile(std::size_t(kTileRows) * kPanel);
  for (int k = 0; k < nsuper; ++k) {
    throwIfInterrupted("the solve");
    const int k1 = first_[k], k2 = first_[k + 1], cols = k2 - k1;
    const int* rows = rows_.data() + rowStart_[k];
    const int nrows = rowStart_[k + 1] - rowStart_[k];
    for (int i = 0; i < nrows; ++i) local[rows[i]] = i;
    Block Lk(values_.data() + valueStart_[k], nrows, cols);
    for (int d = head[k]; d != -1;) {
      const int following = next[d];
      const int* drows = rows_.data() + rowStart_[d];
      const int dnrows = rowStart_[d + 1] - rowStart_[d];
      const ConstBlock Ld(values_.data() + valueStart_[d], dnrows, first_[d + 1] - first_[d]);
      const int p1 = position[d];
      int p2 = p1;
      while (p2 < dnrows && drows[p2] < k2) ++p2;
      subtractUpdate(Ld, drows, p1, p2 - p1, local.data(), k1, Lk, tile.data());
      position[d] = p2;
      if (p2 < dnrows) {
        const int t = superOf_[drows[p2]];
        next[d] = head[t];
        head[t] = d;
      }
      d = following;
    }
    if (!factorSupernode(Lk)) return false;
    if (nrows > cols) {
      const int t = superOf_[rows[cols]];
      position[k] = cols;
      next[k] = head[t];
      head[t] = k;
    }
  }
  factored_ = true;
  return true;
}

Eigen::MatrixXd SupernodalCholesky::solve(const Eigen::MatrixXd& b) const {
  assert(factored_ && b.rows() == n_ &&
         "solve needs a factorisation and right-hand sides of n rows");
  pinProductBlocking();  // several right-hand sides make its products matrix products
  Matrix x(n_, b.cols()), gathered;
  for (int k = 0; k < n_; ++k) x.row(k) = b.row(perm_[k]);
  const int nsuper = int(first_.size()) - 1;
  auto supernode = [&](int k) {
    const int cols = first_[k + 1] - first_[k], nrows = rowStart_[k + 1] - rowStart_[k];
    return ConstBlock(values_.data() + valueStart_[k], nrows, cols);
  };
  // A stop asked for meanwhile throws Interrupted every few thousand supernodes (a fine mesh's
  // solve takes a second on a loaded machine).
  constexpr int kPollSupernodes = 4096;
  for (int k = 0; k < nsuper; ++k) {  // L Z = P B
    if (k % kPollSupernodes == 0) throwIfInterrupted("the solve");
    const ConstBlock Lk = supernode(k);
    const int cols = int(Lk.cols()), below = int(Lk.rows()) - cols;
    auto xk = x.middleRows(first_[k], cols);
    Lk.topRows(cols).triangularView<Eigen::Lower>().solveInPlace(xk);
    if (below == 0) continue;
    gathered.noalias() = Lk.bottomRows(below) * xk;
    const int* rows = rows_.data() + rowStart_[k] + cols;
    for (int i = 0; i < below; ++i) x.row(rows[i]) -= gathered.row(i);
  }
  for (int k = nsuper - 1; k >= 0; --k) {  // L^T W = Z
    if (k % kPollSupernodes == 0) throwIfInterrupted("the solve");
    const ConstBlock Lk = supernode(k);
    const int cols = int(Lk.cols()), below = int(Lk.rows()) - cols;
    auto xk = x.middleRows(first_[k], cols);
    if (below > 0) {
      gathered.resize(below, x.cols());
      const int* rows = rows_.data() + rowStart_[k] + cols;
      for (int i = 0; i < below; ++i) gathered.row(i) = x.row(rows[i]);
      xk.noalias() -= Lk.bottomRows(below).transpose() * gathered;
    }
    Lk.topRows(cols).transpose().triangularView<Eigen::Upper>().solveInPlace(xk);
  }
  Matrix y(n_, b.cols());
  for (int k = 0; k < n_; ++k) y.row(perm_[k]) = x.row(k);
  return y;
}

}  // namespace dform
