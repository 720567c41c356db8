#include "model/local_global.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cassert>
#include <cmath>
#include <chrono>
#include <algorithm>
#include <deque>
#include <memory>

#include "core/interrupt.h"
#include "solver/gram_matrix.h"
#include "solver/supernodal_cholesky.h"

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
      : quadratic_(quadratic), edges_(edges), stride_(edges.stride), supernodalFrom_(supernodalFrom) {
    const int n = int(x0.size());
    // K = sum_t w_t M_t^T M_t + sum_e w_e D_e^T D_e + eps I. The eps I (with eps x_prev on the
    // right) is a proximal term: it fixes the free translation and vanishes at a fixed point.
    // Each step of the set-up takes up to a second on a fine mesh: a stop asked for meanwhile
    // throws Interrupted between them (and inside the products and factorisations).
    SparseMatrix K(n, n);
    for (const auto& [w, term] : quadratic) K += w * gramMatrix(term->matrix());
    throwIfInterrupted("the solve");
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t e = 0; e < edges.weight.size(); ++e) {
      const double w = edges.weight[e];
      auto addPair = [&](int a, int b, int dims) {
        for (int c = 0; c < dims; ++c) {
          entries.emplace_back(a + c, a + c, w);
          entries.emplace_back(b + c, b + c, w);
          entries.emplace_back(a + c, b + c, -w);
          entries.emplace_back(b + c, a + c, -w);
        }
      };
      addPair(edges.x[e][0], edges.x[e][1], 3);
      addPair(edges.u[e][0], edges.u[e][1], 2);
    }
    throwIfInterrupted("the solve");
    SparseMatrix edgePart(n, n);
    edgePart.setFromTriplets(entries.begin(), entries.end());
    K += edgePart;
    throwIfInterrupted("the solve");
    proximal_ = 1e-8 * K.diagonal().maxCoeff();
    SparseMatrix identity(n, n);
    identity.setIdentity();
    K += proximal_ * identity;
    // Held unknowns: their rows become x_i = x0_i and their couplings move to the right side.
    held_.assign(std::size_t(n), false);
    for (int i : held) held_[std::size_t(i)] = true;
    heldRhs_ = Eigen::VectorXd::Zero(n);
    heldValue_ = x0;
    if (!held.empty()) {
      for (int c = 0; c < K.outerSize(); ++c) {
        if (c % 65536 == 0) throwIfInterrupted("the solve");
        if (!held_[std::size_t(c)]) continue;
        for (SparseMatrix::InnerIterator it(K, c); it; ++it)
          if (!held_[std::size_t(it.row())]) heldRhs_[it.row()] -= it.value() * x0[c];
      }
      throwIfInterrupted("the solve");
      // The held rows and columns leave K but for their diagonal, which becomes 1 (the proximal
      // term put every diagonal entry in K's pattern).
      K.prune([&](Eigen::Index row, Eigen::Index col, double) {
        return row == col || (!held_[std::size_t(row)] && !held_[std::size_t(col)]);
      });
      for (int i : held) K.coeffRef(i, i) = 1.0;
    }
    splitByCoordinate(K);
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
    for (const auto& [w, term] : quadratic_) rhs += w * (term->matrix().transpose() * term->target());
    return rhs;
  }

  // The global step: the x minimising the energy for fixed projections (plus the proximal term);
  // `constant` is targetRhs().
  Eigen::VectorXd global(const Eigen::VectorXd& x, const Projections& proj, const Eigen::VectorXd& constant) const {
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

  // K restricted to coordinate c of every vertex (#vertices square).
  SparseMatrix coordinateBlock(const SparseMatrix& K, int c) const {
    std::vector<Eigen::Triplet<double>> entries;
    for (int j = c; j < K.outerSize(); j += stride_)
      for (SparseMatrix::InnerIterator it(K, j); it; ++it)
        if (it.row() % stride_ == c) entries.emplace_back(it.row() / stride_, j / stride_, it.value());
    SparseMatrix block(K.rows() / stride_, K.cols() / stride_);
    block.setFromTriplets(entries.begin(), entries.end());
    return block;
  }

  // The objective never couples different coordinates (x with y, or u with v), so K is block
  // diagonal by coordinate; x, y, z share one block and u, v another. Factorising each distinct
  // block once (#vertices square) is several times cheaper than factorising K.
  void splitByCoordinate(const SparseMatrix& K) {
    for (int j = 0; j < K.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(K, j); it; ++it)
        assert(it.row() % stride_ == j % stride_ && "the objective couples two coordinates");
    ok_ = true;
    for (int c = 0; c < stride_; ++c) {
      throwIfInterrupted("the solve");  // the factorisation polls between its supernodes too
      SparseMatrix block = coordinateBlock(K, c);
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
class Anderson {
 public:
  explicit Anderson(int depth) : depth_(depth) {}

  // Records G(x) = g with residual f and returns the accelerated next iterate.
  Eigen::VectorXd next(const Eigen::VectorXd& g, const Eigen::VectorXd& f) {
    if (havePrevious_) {
      dG_.push_back(g - previousG_);
      dF_.push_back(f - previousF_);
      if (int(dF_.size()) > depth_) dG_.pop_front(), dF_.pop_front();
    }
    previousG_ = g;
    previousF_ = f;
    havePrevious_ = true;
    if (dF_.empty()) return g;
    const int m = int(dF_.size());
    Eigen::MatrixXd F(f.size(), m), G(g.size(), m);
    for (int i = 0; i < m; ++i) F.col(i) = dF_[i], G.col(i) = dG_[i];
    const Eigen::VectorXd gamma = F.colPivHouseholderQr().solve(f);
    return g - G * gamma;
  }

 private:
  int depth_;
  std::deque<Eigen::VectorXd> dG_, dF_;
  Eigen::VectorXd previousG_, previousF_;
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

LocalGlobalRelaxation::LocalGlobalRelaxation(std::vector<std::pair<double, const LinearResidual*>> quadratic,
                                             const EdgeLengthPairs& edges, const Eigen::VectorXd& x0,
                                             const std::vector<int>& held, int supernodalFrom) {
  assert(edges.x.size() == edges.weight.size() && edges.u.size() == edges.weight.size());
  impl_ = std::make_unique<Impl>(std::move(quadratic), edges, x0, held, supernodalFrom);
}

LocalGlobalRelaxation::~LocalGlobalRelaxation() = default;

LocalGlobalSummary LocalGlobalRelaxation::relax(const LocalGlobalOptions& options, Eigen::VectorXd& x) const {
  const auto start = std::chrono::steady_clock::now();
  const LocalGlobal& lg = impl_->lg;
  LocalGlobalSummary summary;
  Projections proj;
  if (options.maxIterations <= 0) return summary;
  double energy = lg.energy(x, proj);
  summary.initialEnergy = summary.finalEnergy = energy;
  if (!lg.ok() || !std::isfinite(energy)) return summary;
  const Eigen::VectorXd constant = lg.targetRhs();

  Anderson anderson(options.andersonDepth);
  Projections candidateProj, longerProj;
  for (int k = 1; k <= options.maxIterations; ++k) {
    summary.iterations = k;
    const Eigen::VectorXd g = lg.global(x, proj, constant);
    const Eigen::VectorXd plainStep = g - x;
    const double plainGain = lg.globalStepDecrease(plainStep);
    Eigen::VectorXd candidate = options.andersonDepth > 0 ? anderson.next(g, plainStep) : g;
    double candidateEnergy = lg.energy(candidate, candidateProj);
    // Plain steps never raise the energy; an accelerated one that does is replaced by the plain
    // one, taken further while that keeps lowering the energy.
    if (!(candidateEnergy <= energy) && options.andersonDepth > 0) {
      ++summary.andersonRejected;
      candidate = g;
      candidateEnergy = lg.energy(candidate, candidateProj);
      for (int e = 1; e <= options.plainStepExtensions; ++e) {
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
      it.cumulativeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (!options.callback(it)) {
        summary.stopped = true;
        break;
      }
    }
    if (plainGain < options.relativeTolerance * energy) break;
  }
  summary.finalEnergy = energy;
  summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace dform
