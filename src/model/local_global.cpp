// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/local_global.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <memory>

#include "dform/core/interrupt.h"
#include "dform/solver/gram_matrix.h"
#include "dform/solver/supernodal_cholesky.h"

namespace dform {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Projections of every edge onto a common length: target 3D and flat edge vectors.
struct Projections {
  std::vector<Eigen::Vector3d> p;
  std::vector<Eigen::Vector2d> q;
};

class LocalGlobal {
 public:
  LocalGlobal(const std::vector<std::pair<double, const LinearResidual*>>& quadratic,
              const EdgeLengthPairs& edges, const Eigen::VectorXd& x0, const std::vector<int>& held,
              int supernodalFrom)
      : quadratic_(quadratic),
        edges_(edges),
        stride_(edges.stride),
        supernodalFrom_(supernodalFrom) {
    const int n = int(x0.size());
    // K = sum_t w_t M_t^T M_t + sum_e w_e D_e^T D_e + eps I. The eps I (with eps x_prev on the
    // right) is a proximal term: it fixes the free translation and vanishes at a fixed point.
    // The objective never couples different coordinates (x with y, or u with v), so K is block
    // diagonal by coordinate, and each block (#vertices square) is assembled on its own: every
    // entry is the same sum, in the same order, as in K assembled whole, and a stop asked for
    // meanwhile throws Interrupted between the steps (each a fraction of a second on a fine mesh).
    std::vector<SparseMatrix> blocks;
    double largestDiagonal = 0.0;
    for (int c = 0; c < stride_; ++c) {
      blocks.push_back(coordinateBlock(c, n / stride_));
      largestDiagonal = std::max(largestDiagonal, blocks.back().diagonal().maxCoeff());
    }
    proximal_ = 1e-8 * largestDiagonal;
    // Held unknowns: their rows become x_i = x0_i and their couplings move to the right side.
    held_.assign(std::size_t(n), false);
    for (int i : held) held_[std::size_t(i)] = true;
    heldRhs_ = Eigen::VectorXd::Zero(n);
    heldValue_ = x0;
    for (int c = 0; c < stride_; ++c) {
      SparseMatrix identity(blocks[c].rows(), blocks[c].cols());
      identity.setIdentity();
      blocks[c] += proximal_ * identity;
      throwIfInterrupted("the solve");
      if (!held.empty()) holdUnknowns(blocks[c], c, x0);
    }
    factorizeBlocks(std::move(blocks));
  }

  bool ok() const { return ok_; }

  // What the global step d = g - x lowers the energy by with the projections held: the
  // quadratic's exact decrease d^T K d, K's proximal part included (it is 1e-8 of K's diagonal).
  // The local step that follows only lowers the energy further.
  double globalStepDecrease(const Eigen::VectorXd& d) const {
    Eigen::Map<const RowMatrix> D(d.data(), Eigen::Index(d.size()) / stride_, stride_);
    double decrease = 0.0;
    for (const Group& group : groups_)
      for (int c : group.coordinates) {
        const Eigen::VectorXd column = D.col(c);
        decrease += column.dot(group.matrix * column);
      }
    return decrease;
  }

  // Energy at x; fills the projections that minimise it for this x.
  double energy(const Eigen::VectorXd& x, Projections& proj) const {
    double total = 0.0;
    for (const auto& [w, term] : quadratic_)
      total += w * (term->matrix() * x - term->target()).squaredNorm();
    const std::size_t m = edges_.weight.size();
    proj.p.resize(m);
    proj.q.resize(m);
    for (std::size_t e = 0; e < m; ++e) {
      const Eigen::Vector3d d3 = x.segment<3>(edges_.x[e][0]) - x.segment<3>(edges_.x[e][1]);
      const Eigen::Vector2d d2 = x.segment<2>(edges_.u[e][0]) - x.segment<2>(edges_.u[e][1]);
      const double l3 = d3.norm(), l2 = d2.norm(), common = 0.5 * (l3 + l2);
      proj.p[e] = l3 > 0 ? Eigen::Vector3d(d3 * (common / l3)) : d3;
      proj.q[e] = l2 > 0 ? Eigen::Vector2d(d2 * (common / l2)) : d2;
      total += 0.5 * edges_.weight[e] * (l3 - l2) * (l3 - l2);
    }
    return total;
  }

  // sum_t w_t M_t^T b_t, read from the terms' current targets.
  Eigen::VectorXd targetRhs() const {
    Eigen::VectorXd rhs = heldRhs_;
    for (const auto& [w, term] : quadratic_)
      rhs += w * (term->matrix().transpose() * term->target());
    return rhs;
  }

  // The global step: the x minimising the energy for fixed projections (plus the proximal term);
  // `constant` is targetRhs().
  Eigen::VectorXd global(const Eigen::VectorXd& x, const Projections& proj,
                         const Eigen::VectorXd& constant) const {
    Eigen::VectorXd rhs = constant + proximal_ * x;
    for (std::size_t e = 0; e < edges_.weight.size(); ++e) {
      const double w = edges_.weight[e];
      rhs.segment<3>(edges_.x[e][0]) += w * proj.p[e];
      rhs.segment<3>(edges_.x[e][1]) -= w * proj.p[e];
      rhs.segment<2>(edges_.u[e][0]) += w * proj.q[e];
      rhs.segment<2>(edges_.u[e][1]) -= w * proj.q[e];
    }
    for (std::size_t i = 0; i < held_.size(); ++i)
      if (held_[i]) rhs[Eigen::Index(i)] = heldValue_[Eigen::Index(i)];
    // Each coordinate group is solved with its own factor, all its coordinates at once.
    const int vertices = int(rhs.size()) / stride_;
    Eigen::Map<const RowMatrix> B(rhs.data(), vertices, stride_);
    Eigen::VectorXd out(rhs.size());
    Eigen::Map<RowMatrix> X(out.data(), vertices, stride_);
    for (const Group& group : groups_) {
      throwIfInterrupted("the solve");
      Eigen::MatrixXd part(vertices, group.coordinates.size());
      for (std::size_t k = 0; k < group.coordinates.size(); ++k)
        part.col(k) = B.col(group.coordinates[k]);
      part = group.factor.solve(part);
      for (std::size_t k = 0; k < group.coordinates.size(); ++k)
        X.col(group.coordinates[k]) = part.col(k);
    }
    return out;
  }

 private:
  const std::vector<std::pair<double, const LinearResidual*>>& quadratic_;
  const EdgeLengthPairs& edges_;
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  // The factor of one coordinate block, by size (kSupernodalRelaxationVertices): CHOLMOD's
  // simplicial one (no BLAS, no threads) or dform's supernodal one; both round the same on every
  // machine.
  class BlockFactor {
   public:
    BlockFactor(const SparseMatrix& block, bool supernodal) {
      if (supernodal) {
        const SupernodalCholesky::SparseLower lower = block.triangularView<Eigen::Lower>();
        supernodal_ = std::make_unique<SupernodalCholesky>(lower);
        ok_ = supernodal_->factorize(lower);
      } else {
        simplicial_ = std::make_unique<Eigen::CholmodSimplicialLLT<SparseMatrix>>();
        {
          const std::lock_guard<std::mutex> lock(cholmodAnalysisMutex());  // METIS's rand()
          simplicial_->analyzePattern(block);
        }
        simplicial_->factorize(block);
        ok_ = simplicial_->info() == Eigen::Success;
      }
    }
    bool ok() const { return ok_; }
    Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const {
      return supernodal_ ? supernodal_->solve(b) : Eigen::MatrixXd(simplicial_->solve(b));
    }

   private:
    std::unique_ptr<Eigen::CholmodSimplicialLLT<SparseMatrix>> simplicial_;
    std::unique_ptr<SupernodalCholesky> supernodal_;
    bool ok_ = false;
  };

  // Coordinates (offsets within a vertex's block) whose rows of K are the same matrix.
  struct Group {
    std::vector<int> coordinates;
    SparseMatrix matrix;  ///< K restricted to one of the coordinates (#vertices square)
    BlockFactor factor;
  };

  // The vertex of unknown i, when i is coordinate c of its vertex.
  int vertexOf(int i, int c) const {
    assert(i % stride_ == c && "the objective couples two coordinates");
    (void)c;
    return i / stride_;
  }

  // Whether a row of M has entries in two coordinates (a check of the premise of the blocks).
  bool couplesCoordinates(const SparseMatrix& M) const {
    std::vector<int> coordinate(std::size_t(M.rows()), -1);
    for (int j = 0; j < M.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
        int& seen = coordinate[std::size_t(it.row())];
        if (seen >= 0 && seen != j % stride_) return true;
        seen = j % stride_;
      }
    return false;
  }

  // Columns c, c + stride, ... of M: the term's part acting on coordinate c of every vertex.
  SparseMatrix coordinateColumns(const SparseMatrix& M, int c) const {
    const int vertices = int(M.cols()) / stride_;
    std::vector<int> outer(std::size_t(vertices) + 1, 0), inner;
    std::vector<double> values;
    for (int v = 0; v < vertices; ++v) {
      if (v % 65536 == 0) throwIfInterrupted("the solve");
      for (SparseMatrix::InnerIterator it(M, v * stride_ + c); it; ++it) {
        inner.push_back(int(it.row()));
        values.push_back(it.value());
      }
      outer[std::size_t(v) + 1] = int(inner.size());
    }
    return Eigen::Map<const SparseMatrix>(M.rows(), vertices, Eigen::Index(inner.size()),
                                          outer.data(), inner.data(), values.data());
  }

  // K restricted to coordinate c of every vertex (#vertices square), but for the proximal term:
  // the terms' Gram matrices summed in their order, then the edges' part.
  SparseMatrix coordinateBlock(int c, int vertices) const {
    SparseMatrix block(vertices, vertices);
    for (const auto& [w, term] : quadratic_) {
      assert((c > 0 || !couplesCoordinates(term->matrix())) &&
             "the objective couples two coordinates");
      block += w * gramMatrix(coordinateColumns(term->matrix(), c));
      throwIfInterrupted("the solve");
    }
    // The edges' part from triplets in the order of K's whole assembly, so that repeated entries
    // sum in the same order.
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t e = 0; e < edges_.weight.size(); ++e) {
      if (e % 65536 == 0) throwIfInterrupted("the solve");
      const double w = edges_.weight[e];
      auto addPair = [&](int a, int b, int dims) {
        for (int k = 0; k < dims; ++k) {
          if ((a + k) % stride_ != c) continue;
          const int va = vertexOf(a + k, c), vb = vertexOf(b + k, c);
          entries.emplace_back(va, va, w);
          entries.emplace_back(vb, vb, w);
          entries.emplace_back(va, vb, -w);
          entries.emplace_back(vb, va, -w);
        }
      };
      addPair(edges_.x[e][0], edges_.x[e][1], 3);
      addPair(edges_.u[e][0], edges_.u[e][1], 2);
    }
    throwIfInterrupted("the solve");
    SparseMatrix edgePart(vertices, vertices);
    edgePart.setFromTriplets(entries.begin(), entries.end());
    throwIfInterrupted("the solve");
    block += edgePart;
    throwIfInterrupted("the solve");
    return block;
  }

  // Replaces the rows and columns of coordinate c's held unknowns in its block by the identity's,
  // their couplings moved to the right side (heldRhs_).
  void holdUnknowns(SparseMatrix& block, int c, const Eigen::VectorXd& x0) {
    auto isHeld = [&](Eigen::Index v) { return held_[std::size_t(v * stride_ + c)]; };
    for (int v = 0; v < block.outerSize(); ++v) {
      if (v % 65536 == 0) throwIfInterrupted("the solve");
      if (!isHeld(v)) continue;
      for (SparseMatrix::InnerIterator it(block, v); it; ++it)
        if (!isHeld(it.row())) heldRhs_[it.row() * stride_ + c] -= it.value() * x0[v * stride_ + c];
    }
    throwIfInterrupted("the solve");
    // The held rows and columns leave the block but for their diagonal, which becomes 1 (the
    // proximal term put every diagonal entry in the block's pattern).
    block.prune([&](Eigen::Index row, Eigen::Index col, double) {
      return row == col || (!isHeld(row) && !isHeld(col));
    });
    for (int v = 0; v < block.outerSize(); ++v)
      if (isHeld(v)) block.coeffRef(v, v) = 1.0;
  }

  // x, y, z share one block and u, v another: each distinct block is factorised once, several
  // times cheaper than factorising K.
  void factorizeBlocks(std::vector<SparseMatrix> blocks) {
    ok_ = true;
    for (int c = 0; c < stride_; ++c) {
      throwIfInterrupted("the solve");  // the factorisation polls between its supernodes too
      SparseMatrix& block = blocks[std::size_t(c)];
      auto same = std::find_if(groups_.begin(), groups_.end(), [&](const Group& other) {
        return (other.matrix - block).norm() == 0.0;
      });
      if (same != groups_.end()) {
        same->coordinates.push_back(c);
        continue;
      }
      BlockFactor factor(block, block.rows() >= supernodalFrom_);
      ok_ = ok_ && factor.ok();
      groups_.push_back(Group{{c}, std::move(block), std::move(factor)});
    }
  }

  const int stride_;
  const int supernodalFrom_;
  std::vector<bool> held_;
  Eigen::VectorXd heldRhs_, heldValue_;
  double proximal_ = 0;
  std::vector<Group> groups_;
  bool ok_ = false;
};

// Anderson acceleration of the fixed-point map x -> G(x) (type II, least squares on the last
// `depth` differences of residuals f = G(x) - x). A refused accelerated step leaves the history
// as it is (Peng et al. 2018): the next pair is recorded at the point actually taken. Clearing it
// instead left one secant after every refusal, whose extrapolation (100-200 times the residual
// on the Squaricle) was refused in turn: 79-93 % of the steps of the bench's 2.6k-vertex rows,
// against 26-42 % with the history kept.
// The differences are kept as the columns of two matrices, oldest first, and the QR works in one
// decomposition's storage: sized once, none of them is allocated again per step. (Allocated per
// step, the non-convex sample's 50-seam-point relaxation spent half its time in the kernel,
// mapping fresh pages.)
class Anderson {
 public:
  Anderson(int depth, Eigen::Index unknowns)
      : depth_(depth),
        dG_(unknowns, depth),
        dF_(unknowns, depth),
        previousG_(unknowns),
        previousF_(unknowns),
        qr_(unknowns, depth) {}

  // Records G(x) = g with residual f and returns the accelerated next iterate.
  Eigen::VectorXd next(const Eigen::VectorXd& g, const Eigen::VectorXd& f) {
    if (havePrevious_) {
      if (used_ == depth_) {
        for (int i = 0; i + 1 < depth_; ++i) {
          dG_.col(i) = dG_.col(i + 1);
          dF_.col(i) = dF_.col(i + 1);
        }
        --used_;
      }
      dG_.col(used_) = g - previousG_;
      dF_.col(used_) = f - previousF_;
      ++used_;
    }
    previousG_ = g;
    previousF_ = f;
    havePrevious_ = true;
    if (used_ == 0) return g;
    qr_.compute(dF_.leftCols(used_));
    const Eigen::VectorXd gamma = qr_.solve(f);
    return g - dG_.leftCols(used_) * gamma;
  }

 private:
  int depth_;
  int used_ = 0;  // the differences recorded: the first `used_` columns of dG_ and dF_
  Eigen::MatrixXd dG_, dF_;
  Eigen::VectorXd previousG_, previousF_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_;
  bool havePrevious_ = false;
};

}  // namespace

struct LocalGlobalRelaxation::Impl {
  std::vector<std::pair<double, const LinearResidual*>> quadratic;
  LocalGlobal lg;
  Impl(std::vector<std::pair<double, const LinearResidual*>> q, const EdgeLengthPairs& edges,
       const Eigen::VectorXd& x0, const std::vector<int>& held, int supernodalFrom)
      : quadratic(std::move(q)), lg(quadratic, edges, x0, held, supernodalFrom) {}
};

LocalGlobalRelaxation::LocalGlobalRelaxation(
    std::vector<std::pair<double, const LinearResidual*>> quadratic, const EdgeLengthPairs& edges,
    const Eigen::VectorXd& x0, const std::vector<int>& held, int supernodalFrom) {
  assert(edges.x.size() == edges.weight.size() && edges.u.size() == edges.weight.size());
  impl_ = std::make_unique<Impl>(std::move(quadratic), edges, x0, held, supernodalFrom);
}

LocalGlobalRelaxation::~LocalGlobalRelaxation() = default;

LocalGlobalSummary LocalGlobalRelaxation::relax(const LocalGlobalOptions& options,
                                                Eigen::VectorXd& x) const {
  const auto start = std::chrono::steady_clock::now();
  const LocalGlobal& lg = impl_->lg;
  LocalGlobalSummary summary;
  Projections proj;
  if (options.maxIterations <= 0) return summary;
  double energy = lg.energy(x, proj);
  summary.initialEnergy = summary.finalEnergy = energy;
  if (!lg.ok() || !std::isfinite(energy)) return summary;
  const Eigen::VectorXd constant = lg.targetRhs();
  throwIfInterrupted("the solve");

  Anderson anderson(options.andersonDepth, x.size());
  Projections candidateProj, longerProj;
  // On a fine mesh one iteration takes seconds (each solve, energy and extrapolation a fraction of
  // one): a stop asked for meanwhile throws Interrupted between them, besides the callback's stop.
  for (int k = 1; k <= options.maxIterations; ++k) {
    summary.iterations = k;
    const Eigen::VectorXd g = lg.global(x, proj, constant);
    throwIfInterrupted("the solve");
    const Eigen::VectorXd plainStep = g - x;
    const double plainGain = lg.globalStepDecrease(plainStep);
    Eigen::VectorXd candidate = options.andersonDepth > 0 ? anderson.next(g, plainStep) : g;
    throwIfInterrupted("the solve");
    double candidateEnergy = lg.energy(candidate, candidateProj);
    // Plain steps never raise the energy; an accelerated one that does is replaced by the plain
    // one, taken further while that keeps lowering the energy.
    if (!(candidateEnergy <= energy) && options.andersonDepth > 0) {
      ++summary.andersonRejected;
      throwIfInterrupted("the solve");
      candidate = g;
      candidateEnergy = lg.energy(candidate, candidateProj);
      for (int e = 1; e <= options.plainStepExtensions; ++e) {
        throwIfInterrupted("the solve");
        Eigen::VectorXd longer = x + std::ldexp(1.0, e) * plainStep;
        const double longerEnergy = lg.energy(longer, longerProj);
        if (!(longerEnergy < candidateEnergy)) break;
        candidate = std::move(longer);
        candidateEnergy = longerEnergy;
        std::swap(candidateProj, longerProj);
      }
    }
    const double decrease = energy - candidateEnergy;
    x = std::move(candidate);
    std::swap(proj, candidateProj);
    energy = candidateEnergy;
    if (options.callback) {
      IterationSummary it;
      it.iteration = k;
      it.cost = energy;
      it.costChange = decrease;
      it.accepted = true;
      it.cumulativeSeconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (!options.callback(it)) {
        summary.stopped = true;
        break;
      }
    }
    if (plainGain < options.relativeTolerance * energy) break;
  }
  summary.finalEnergy = energy;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace dform
