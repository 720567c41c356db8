// SPDX-License-Identifier: GPL-3.0-or-later
// A sparse Cholesky factorisation L L^T = P (A + mu I) P^T whose rounding is the same on every
// x86-64 machine and thread count, at the speed of a supernodal factor.
//
// CHOLMOD's supernodal factor hands its dense blocks to the BLAS, and OpenBLAS picks a kernel per
// CPU (AVX-512, Haswell, Sandybridge, ...) that sums in another order; its simplicial factor is
// reproducible but does scalar work (about 1.8 GFlop/s, docs/solver-design.md). This class keeps
// CHOLMOD's symbolic analysis (ordering, supernodes, which involve no floating-point rounding) and
// does the numeric work itself, left-looking over the supernodes, with Eigen's dense kernels.
// Those are compiled into this binary (no run-time kernel choice) and their only machine-dependent
// choice, the product's blocking, which follows the CPU's cache sizes, is pinned.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <mutex>
#include <vector>

namespace dform {

/// Held by every CHOLMOD analysis in dform. METIS, which CHOLMOD's analysis calls for its
/// ordering, draws its random numbers from the C library's one rand() state, seeded at the start
/// of each call: two analyses on two threads at once interleave their draws, and an ordering (so
/// a factor's rounding, so a result) then depends on the timing. One at a time, every analysis
/// is the one it is in a process of its own, whatever else the process runs (a sweep's or a
/// batch's other jobs).
std::mutex& cholmodAnalysisMutex();

/// A sparse Cholesky factorisation by supernodes (dense blocks of columns), analysed once for a
/// pattern and factorised again for each matrix of that pattern and each shift.
class SupernodalCholesky {
 public:
  /// A symmetric matrix given by its lower triangle.
  using SparseLower = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /// Analyses the pattern of `pattern`'s lower triangle (fill-reducing ordering, supernodes).
  /// With blockSize > 1 the unknowns come in consecutive blocks of that many (the last may be
  /// shorter), and the ordering keeps each block together.
  explicit SupernodalCholesky(const SparseLower& pattern, int blockSize = 1);
  ~SupernodalCholesky();
  SupernodalCholesky(const SupernodalCholesky&) = delete;
  SupernodalCholesky& operator=(const SupernodalCholesky&) = delete;

  /// Factorises A + shift I, A given by its lower triangle with the analysed pattern (values
  /// outside it are an error). False when A + shift I is not numerically positive definite.
  /// Throws Interrupted (core/interrupt.h) between tiles of its dense work (see the .cpp) when a
  /// stop has been requested.
  bool factorize(const SparseLower& A, double shift = 0.0);

  /// The solution Y of (A + shift I) Y = B for the last successful factorisation (one column
  /// per right-hand side).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;

  /// Floating-point operations of one factorisation and nonzeros of L, as the analysis counts
  /// them (they set how many CG iterations a factorisation is worth).
  double factorFlops() const { return factorFlops_; }
  double factorNonZeros() const { return factorNonZeros_; }  ///< see factorFlops

 private:
  // The supernodes: columns first[s] .. first[s + 1] - 1 of L; their rows rows[rowStart[s] ..
  // rowStart[s + 1]) (ascending, the supernode's own columns first); their values, column-major,
  // at values[valueStart[s]].
  int n_ = 0;
  std::vector<int> first_, rowStart_, rows_, superOf_;
  std::vector<long> valueStart_;
  std::vector<int> perm_;       ///< row k of P A P^T is row perm_[k] of A
  std::vector<long> scatter_;   ///< where each stored entry of A lands in values_
  std::vector<long> diagonal_;  ///< where each diagonal entry of L lands (for the shift)
  std::vector<double> values_;
  double factorFlops_ = 0, factorNonZeros_ = 0;
  bool factored_ = false;
};

}  // namespace dform
