// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/solver/solver.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "dform/solver/supernodal_cholesky.h"

namespace dform {

const char* terminationName(Termination t) {
  switch (t) {
    case Termination::Converged: return "converged";
    case Termination::NoConvergence: return "no_convergence";
    case Termination::Failure: return "failure";
    case Termination::UserAbort: return "user_abort";
  }
  return "unknown";
}

bool SolverOptions::isValid(std::string* why) const {
  auto fail = [&](const char* text) {
    if (why) *why = text;
    return false;
  };
  if (maxIterations < 0) return fail("maxIterations must be >= 0");
  if (!(functionTolerance >= 0) || !(gradientTolerance >= 0) || !(parameterTolerance >= 0) ||
      !(absoluteCostTolerance >= 0))
    return fail("tolerances must be >= 0");
  if (!(initialDampingRatio > 0)) return fail("initialDampingRatio must be > 0");
  if (maxCgIterations < 0) return fail("maxCgIterations must be >= 0");
  if (!(cgRelativeTolerance > 0 && cgRelativeTolerance < 1))
    return fail("cgRelativeTolerance must be in (0, 1)");
  if (!(maxAccelerationRatio > 0)) return fail("maxAccelerationRatio must be > 0");
  return true;
}

std::string SolverSummary::briefReport() const {
  char line[256];
  std::snprintf(line, sizeof line,
                "%s after %d iterations (%d factorisations): cost %.6g -> %.6g in %.3f s",
                terminationName(termination), int(iterations.size()), factorisations, initialCost,
                finalCost, totalSeconds);
  return line;
}

void SolverSummary::append(SolverSummary later) {
  const int offset = iterations.empty() ? 0 : iterations.back().iteration;
  for (IterationSummary& it : later.iterations) {
    it.iteration += offset;
    it.cumulativeSeconds += totalSeconds;
    iterations.push_back(std::move(it));
  }
  termination = later.termination;
  message = std::move(later.message);
  finalCost = later.finalCost;
  finalTermCosts = std::move(later.finalTermCosts);
  factorisations += later.factorisations;
  totalSeconds += later.totalSeconds;
}

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

using SparseLower = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The stacked, weighted residual vector and Jacobian of a problem, and its normal equations
// A = J^T J (lower triangle, fixed pattern) and g = J^T r.
class NormalEquations {
 public:
  explicit NormalEquations(const Problem& problem)
      : problem_(problem), constant_(problem.constantMask()) {
    const int n = problem.numVariables();
    // Stack the terms' patterns.
    for (int t = 0; t < problem.numTerms(); ++t) {
      const JacobianPattern p = problem.term(t).pattern();
      assert(int(p.rowStart.size()) == problem.term(t).numResiduals() + 1 &&
             "pattern rows must match numResiduals");
      Block b;
      b.firstRow = int(rowStart_.size()) - 1;
      b.rows = p.rows();
      b.firstValue = int(cols_.size());
      b.sqrtWeight = std::sqrt(problem.termWeight(t));
      b.linear = problem.term(t).isLinear();
      for (int i = 0; i < p.rows(); ++i) rowStart_.push_back(b.firstValue + p.rowStart[i + 1]);
      cols_.insert(cols_.end(), p.cols.begin(), p.cols.end());
      blocks_.push_back(b);
    }
    r_.setZero(int(rowStart_.size()) - 1);
    J_.assign(cols_.size(), 0.0);

    // Pattern of the lower triangle of J^T J: every variable's diagonal plus each row's pairs.
    std::vector<std::vector<int>> rowsOfColumn(n);
    for (int c = 0; c < n; ++c) rowsOfColumn[c].push_back(c);
    forEachPair([&](int hi, int lo) { rowsOfColumn[lo].push_back(hi); });
    std::vector<int> outer(n + 1, 0);
    for (int c = 0; c < n; ++c) {
      auto& rows = rowsOfColumn[c];
      std::sort(rows.begin(), rows.end());
      rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
      outer[c + 1] = outer[c] + int(rows.size());
    }
    A_.resize(n, n);
    A_.resizeNonZeros(outer[n]);
    std::copy(outer.begin(), outer.end(), A_.outerIndexPtr());
    for (int c = 0; c < n; ++c)
      std::copy(rowsOfColumn[c].begin(), rowsOfColumn[c].end(), A_.innerIndexPtr() + outer[c]);
    auto slot = [&](int hi, int lo) {
      const auto& rows = rowsOfColumn[lo];
      return outer[lo] + int(std::lower_bound(rows.begin(), rows.end(), hi) - rows.begin());
    };
    for (int c = 0; c < n; ++c) diagonalSlots_.push_back(slot(c, c));

    // Linear terms: their J^T J part is assembled once. Nonlinear rows keep their scatter slots.
    Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n);
    evaluate(x0, true);
    constantA_.assign(A_.nonZeros(), 0.0);
    for (const Block& b : blocks_) {
      for (int i = b.firstRow; i < b.firstRow + b.rows; ++i) {
        for (int p = rowStart_[i]; p < rowStart_[i + 1]; ++p) {
          for (int q = rowStart_[i]; q <= p; ++q) {
            assert((q == p || cols_[p] != cols_[q]) && "a Jacobian row repeats a column");
            const int hi = std::max(cols_[p], cols_[q]), lo = std::min(cols_[p], cols_[q]);
            const int s = slot(hi, lo);
            if (b.linear) {
              constantA_[s] += J_[p] * J_[q];
            } else {
              pairSlots_.push_back(s);
            }
          }
        }
      }
    }
  }

  int numRows() const { return int(r_.size()); }

  // Weighted residuals (and Jacobian values) at x; returns f = ||r||^2.
  double evaluate(const Eigen::VectorXd& x, bool withJacobian) {
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      const Block& b = blocks_[t];
      double* r = r_.data() + b.firstRow;
      const bool needJ = withJacobian && (!b.linear || !linearJacobianDone_);
      problem_.term(int(t)).evaluate(x, r, needJ ? J_.data() + b.firstValue : nullptr);
      for (int i = 0; i < b.rows; ++i) r[i] *= b.sqrtWeight;
      if (needJ) {
        const int end = rowStart_[b.firstRow + b.rows];
        for (int v = b.firstValue; v < end; ++v) J_[v] *= b.sqrtWeight;
        // A constant unknown has no column: A + mu I then keeps it where it is (dx = 0).
        if (!constant_.empty())
          for (int v = b.firstValue; v < end; ++v)
            if (constant_[std::size_t(cols_[v])]) J_[v] = 0.0;
      }
    }
    if (withJacobian) linearJacobianDone_ = true;
    return r_.squaredNorm();
  }

  // Per-term costs of the last evaluation.
  std::vector<double> termCosts() const {
    std::vector<double> costs;
    for (const Block& b : blocks_) costs.push_back(r_.segment(b.firstRow, b.rows).squaredNorm());
    return costs;
  }

  // A = J^T J and g = J^T r from the last evaluation with Jacobian.
  void assemble() {
    double* a = A_.valuePtr();
    std::copy(constantA_.begin(), constantA_.end(), a);
    std::size_t k = 0;
    for (const Block& b : blocks_) {
      if (b.linear) continue;
      for (int i = b.firstRow; i < b.firstRow + b.rows; ++i)
        for (int p = rowStart_[i]; p < rowStart_[i + 1]; ++p)
          for (int q = rowStart_[i]; q <= p; ++q) a[pairSlots_[k++]] += J_[p] * J_[q];
    }
    g_.setZero(A_.cols());
    for (int i = 0; i < numRows(); ++i)
      for (int p = rowStart_[i]; p < rowStart_[i + 1]; ++p) g_[cols_[p]] += J_[p] * r_[i];
  }

  // J^T r''[v, v] at the point of the last evaluation with Jacobian, x.
  Eigen::VectorXd curvatureGradient(const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
    rvv_.setZero(r_.size());
    for (std::size_t t = 0; t < blocks_.size(); ++t) {
      const Block& b = blocks_[t];
      if (b.linear) continue;
      double* rvv = rvv_.data() + b.firstRow;
      problem_.term(int(t)).secondDirectionalDerivative(x, v, rvv);
      for (int i = 0; i < b.rows; ++i) rvv[i] *= b.sqrtWeight;
    }
    Eigen::VectorXd out = Eigen::VectorXd::Zero(A_.cols());
    for (int i = 0; i < numRows(); ++i)
      for (int p = rowStart_[i]; p < rowStart_[i + 1]; ++p) out[cols_[p]] += J_[p] * rvv_[i];
    return out;
  }

  const SparseLower& A() const { return A_; }
  const Eigen::VectorXd& g() const { return g_; }
  double maxDiagonal() const {
    double m = 0;
    for (int s : diagonalSlots_) m = std::max(m, A_.valuePtr()[s]);
    return m;
  }

 private:
  struct Block {
    int firstRow, rows, firstValue;
    double sqrtWeight;
    bool linear;
  };

  template <typename F>
  void forEachPair(F f) const {
    for (int i = 0; i + 1 < int(rowStart_.size()); ++i)
      for (int p = rowStart_[i]; p < rowStart_[i + 1]; ++p)
        for (int q = rowStart_[i]; q <= p; ++q)
          f(std::max(cols_[p], cols_[q]), std::min(cols_[p], cols_[q]));
  }

  const Problem& problem_;
  const std::vector<bool>& constant_;
  std::vector<Block> blocks_;
  std::vector<int> rowStart_{0};
  std::vector<int> cols_;
  std::vector<double> J_;
  Eigen::VectorXd r_, g_, rvv_;
  SparseLower A_;
  std::vector<double> constantA_;
  std::vector<int> pairSlots_;
  std::vector<int> diagonalSlots_;
  bool linearJacobianDone_ = false;
};

// (A + mu I) y for the lower-stored symmetric A.
Eigen::VectorXd shiftedProduct(const SparseLower& A, double mu, const Eigen::VectorXd& y) {
  Eigen::VectorXd out = A.selfadjointView<Eigen::Lower>() * y;
  out += mu * y;
  return out;
}

// Solves (A + mu I) dx = -g, reusing `factor` as a preconditioner when it is good enough and
// refactorising otherwise.
class StepSolver {
 public:
  StepSolver(const SparseLower& pattern, int blockSize, const SolverOptions& options)
      : options_(options), factor_(pattern, blockSize) {
    // CHOLMOD's analysis counts the factorisation's flops and L's nonzeros. One CG iteration
    // costs two triangular solves with L (2 flops per nonzero each) and a product with A
    // (4 flops per stored lower nonzero). CG may spend a quarter of a factorisation: a stale
    // preconditioner that needs longer stays stale for the next steps too, and refactorising
    // serves them all. Counting flops rather than seconds keeps runs reproducible.
    const double factorFlops = factor_.factorFlops();
    const double cgFlops = 4.0 * factor_.factorNonZeros() + 4.0 * double(pattern.nonZeros());
    cgBudget_ = std::clamp(int(0.25 * factorFlops / std::max(cgFlops, 1.0)), 1,
                           std::max(1, options.maxCgIterations));
  }

  bool solve(const SparseLower& A, double mu, const Eigen::VectorXd& g, Eigen::VectorXd& dx,
             IterationSummary& it) {
    it.refactorised = false;
    it.cgIterations = 0;
    if (haveFactor_ && options_.maxCgIterations > 0 && preconditionedCg(A, mu, g, dx, it))
      return true;
    ++factorisations_;
    it.refactorised = true;
    if (!factor_.factorize(A, mu)) return haveFactor_ = false;
    haveFactor_ = true;
    dx = -factor_.solve(g);
    return dx.allFinite();
  }

  // Solves (A + mu I) y = -g again, for the same A and mu as the last solve(): a back-substitution
  // when that solve refactorised, else preconditioned CG within the same budget.
  bool solveAgain(const SparseLower& A, double mu, const Eigen::VectorXd& g, Eigen::VectorXd& y,
                  const IterationSummary& last) {
    if (!haveFactor_) return false;
    if (last.refactorised) {
      y = -factor_.solve(g);
      return y.allFinite();
    }
    IterationSummary scratch;
    return preconditionedCg(A, mu, g, y, scratch);
  }

  int factorisations() const { return factorisations_; }

 private:
  bool preconditionedCg(const SparseLower& A, double mu, const Eigen::VectorXd& g,
                        Eigen::VectorXd& dx, IterationSummary& it) {
    const Eigen::VectorXd b = -g;
    const double stop = options_.cgRelativeTolerance * b.norm();
    dx.setZero(b.size());
    Eigen::VectorXd res = b;
    Eigen::VectorXd z = factor_.solve(res);
    Eigen::VectorXd p = z;
    double rz = res.dot(z);
    for (int k = 1; k <= cgBudget_; ++k) {
      const Eigen::VectorXd Ap = shiftedProduct(A, mu, p);
      const double pAp = p.dot(Ap);
      if (!(pAp > 0)) return false;
      const double alpha = rz / pAp;
      dx += alpha * p;
      res -= alpha * Ap;
      it.cgIterations = k;
      if (res.norm() <= stop) return dx.allFinite();
      z = factor_.solve(res);
      const double rzNext = res.dot(z);
      p = z + (rzNext / rz) * p;
      rz = rzNext;
    }
    return false;
  }

  const SolverOptions& options_;
  // Not CHOLMOD's supernodal factor: it hands its dense blocks to whichever kernel OpenBLAS picks
  // for the CPU (AVX-512, Haswell, ...), and those round differently; a solve that ends on a flat
  // objective then took other steps per machine (the Squaricle sample folded with one kernel and
  // not with another, docs/solver-design.md "Same result on every machine").
  SupernodalCholesky factor_;
  bool haveFactor_ = false;
  int factorisations_ = 0;
  int cgBudget_ = 1;  ///< CG iterations allowed per step before refactorising
};

}  // namespace

struct LeastSquaresSolver::Impl {
  Impl(const Problem& p, SolverOptions o)
      : problem(p),
        options(std::move(o)),
        normal(p),
        stepSolver(normal.A(), p.blockSize(), options) {}
  const Problem& problem;
  const SolverOptions options;
  NormalEquations normal;
  StepSolver stepSolver;
  double setupSeconds = 0;
  double lastDamping = 0;  ///< mu at the end of the previous solve(); a later solve starts there
};

LeastSquaresSolver::LeastSquaresSolver(const Problem& problem, SolverOptions options) {
  const auto start = Clock::now();
  impl_ = std::make_unique<Impl>(problem, std::move(options));
  impl_->setupSeconds = secondsSince(start);
}

LeastSquaresSolver::~LeastSquaresSolver() = default;

SolverSummary summaryWithoutSteps(const Problem& problem, const Eigen::VectorXd& x) {
  SolverSummary summary;
  for (int t = 0; t < problem.numTerms(); ++t) summary.termNames.push_back(problem.termName(t));
  summary.numVariables = problem.numVariables();
  for (int t = 0; t < problem.numTerms(); ++t)
    summary.numResiduals += problem.term(t).numResiduals();
  summary.initialTermCosts = summary.finalTermCosts = problem.termCosts(x);
  summary.initialCost = summary.finalCost =
      std::accumulate(summary.finalTermCosts.begin(), summary.finalTermCosts.end(), 0.0);
  summary.termination =
      std::isfinite(summary.finalCost) ? Termination::NoConvergence : Termination::Failure;
  summary.message = std::isfinite(summary.finalCost)
                        ? "the iteration cap is 0: no step was taken"
                        : "the objective is not finite at the starting point";
  return summary;
}

SolverSummary solve(const Problem& problem, const SolverOptions& options, Eigen::VectorXd& x) {
  std::string why;
  if (!options.isValid(&why)) {
    SolverSummary summary;
    summary.message = why;
    return summary;
  }
  if (options.maxIterations == 0) return summaryWithoutSteps(problem, x);
  return LeastSquaresSolver(problem, options).solve(x);
}

SolverSummary LeastSquaresSolver::solve(Eigen::VectorXd& x) {
  const Problem& problem = impl_->problem;
  const SolverOptions& options = impl_->options;
  NormalEquations& normal = impl_->normal;
  StepSolver& stepSolver = impl_->stepSolver;
  const auto start = Clock::now();
  SolverSummary summary;
  for (int t = 0; t < problem.numTerms(); ++t) summary.termNames.push_back(problem.termName(t));
  summary.numVariables = problem.numVariables();
  if (!options.isValid(&summary.message)) return summary;
  assert(x.size() == problem.numVariables() && "x has the wrong size");
  summary.numResiduals = normal.numRows();
  summary.setupSeconds = impl_->setupSeconds;
  const int factorisationsBefore = stepSolver.factorisations();

  double cost = normal.evaluate(x, true);
  summary.initialCost = cost;
  summary.initialTermCosts = normal.termCosts();
  summary.finalTermCosts = summary.initialTermCosts;
  if (!std::isfinite(cost)) {
    summary.message = "the objective is not finite at the starting point";
    summary.finalCost = cost;
    summary.totalSeconds = secondsSince(start);
    return summary;
  }
  normal.assemble();
  double mu = impl_->lastDamping > 0
                  ? impl_->lastDamping
                  : options.initialDampingRatio * std::max(normal.maxDiagonal(), 1.0);
  const double muFloor = 1e-12 * std::max(normal.maxDiagonal(), 1.0);  // keeps A + mu I definite
  double nu = 2.0;
  summary.termination = Termination::NoConvergence;
  summary.message = "reached the iteration cap";

  // Times and keeps an iteration and reports it; false when the callback asks to stop.
  auto record = [&](IterationSummary& it, Clock::time_point iterationStart) {
    it.seconds = secondsSince(iterationStart);
    it.cumulativeSeconds = secondsSince(start);
    summary.iterations.push_back(it);
    if (!options.callback || options.callback(it)) return true;
    summary.termination = Termination::UserAbort;
    summary.message = "stopped by the callback";
    return false;
  };

  Eigen::VectorXd dx, acceleration;
  for (int iteration = 1; iteration <= options.maxIterations; ++iteration) {
    const auto iterationStart = Clock::now();
    IterationSummary it;
    it.iteration = iteration;
    it.gradientMaxNorm = normal.g().lpNorm<Eigen::Infinity>();
    if (it.gradientMaxNorm < options.gradientTolerance) {
      summary.termination = Termination::Converged;
      summary.message = "gradient below gradientTolerance";
      break;
    }
    it.damping = mu;
    if (!stepSolver.solve(normal.A(), mu, normal.g(), dx, it)) {
      // A failed factorisation at tiny damping: more damping makes A + mu I definite.
      mu *= 10.0;
      if (mu > 1e12 * std::max(normal.maxDiagonal(), 1.0)) {
        summary.termination = Termination::Failure;
        summary.message = "the linear system could not be solved";
        break;
      }
      continue;
    }
    it.stepNorm = dx.norm();
    // The fraction t of the step taken: 1, or less where the valley bends too much for it.
    double t = 1.0;
    Eigen::VectorXd step = dx;
    if (options.geodesicAcceleration &&
        stepSolver.solveAgain(normal.A(), mu, normal.curvatureGradient(x, dx), acceleration, it)) {
      it.acceleration = 2.0 * acceleration.norm() / std::max(it.stepNorm, 1e-300);
      if (it.acceleration > options.maxAccelerationRatio)
        t = options.maxAccelerationRatio / it.acceleration;
      step = t * dx + (0.5 * t * t) * acceleration;
    }
    // Predicted decrease of the model m(t dx) = f + 2 t g.dx + t^2 dx.A.dx.
    const double predicted = -(2.0 * t * normal.g().dot(dx) +
                               t * t * dx.dot(normal.A().selfadjointView<Eigen::Lower>() * dx));
    const Eigen::VectorXd xTrial = x + step;
    const double trialCost = normal.evaluate(xTrial, false);
    const double actual = cost - trialCost;
    const double rho = predicted > 0 ? actual / predicted : -1.0;
    if (std::isfinite(trialCost) && actual > 0 && rho > 0 &&
        (!options.acceptStep || options.acceptStep(x, xTrial))) {
      x = xTrial;
      normal.evaluate(x, true);
      normal.assemble();
      it.accepted = true;
      it.costChange = actual;
      const double previous = cost;
      cost = trialCost;
      mu = t < 1.0
               ? mu / t
               : std::max(muFloor, mu * std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3)));
      nu = 2.0;
      it.cost = cost;
      it.termCosts = normal.termCosts();
      const bool smallDecrease = actual < options.functionTolerance * previous;
      const bool smallStep =
          it.stepNorm < options.parameterTolerance * (x.norm() + options.parameterTolerance);
      const bool lowCost = cost < options.absoluteCostTolerance;
      if (!record(it, iterationStart)) break;
      if (smallDecrease || smallStep || lowCost) {
        summary.termination = Termination::Converged;
        summary.message = smallDecrease ? "relative decrease below functionTolerance"
                          : smallStep   ? "step below parameterTolerance"
                                        : "cost below absoluteCostTolerance";
        break;
      }
    } else {
      mu *= nu;
      nu *= 2.0;
      it.cost = cost;
      if (!record(it, iterationStart)) break;
      if (!std::isfinite(mu) || mu > 1e20) {
        summary.termination = Termination::Converged;
        summary.message = "no step lowers the cost further";
        break;
      }
    }
  }
  impl_->lastDamping = std::isfinite(mu) && mu < 1e10 ? mu : 0.0;
  normal.evaluate(x, false);
  summary.finalCost = cost;
  summary.finalTermCosts = normal.termCosts();
  summary.factorisations = stepSolver.factorisations() - factorisationsBefore;
  summary.totalSeconds = secondsSince(start);
  return summary;
}

int enforceByMultipliers(const std::function<bool(Eigen::VectorXd&)>& resolve,
                         const std::vector<Constraint>& constraints, int maxRounds,
                         Eigen::VectorXd& x) {
  std::vector<Eigen::VectorXd> targets;
  for (const Constraint& c : constraints) targets.push_back(c.term->target());
  auto met = [](const Constraint& c, const Eigen::VectorXd& r) {
    for (Eigen::Index k = 0; k + c.blockSize <= r.size(); k += c.blockSize)
      if (r.segment(k, c.blockSize).norm() > c.tolerance) return false;
    return true;
  };
  int rounds = 0;
  while (rounds < maxRounds) {
    bool allMet = true;
    for (std::size_t i = 0; i < constraints.size(); ++i) {
      LinearResidual& term = *constraints[i].term;
      const Eigen::VectorXd residual = term.matrix() * x - targets[i];
      if (met(constraints[i], residual)) continue;
      allMet = false;
      term.setTarget(term.target() - residual);
    }
    if (allMet) break;
    ++rounds;
    if (!resolve(x)) break;
  }
  return rounds;
}

int enforceByMultipliers(LeastSquaresSolver& solver, const std::vector<Constraint>& constraints,
                         int maxRounds, Eigen::VectorXd& x, SolverSummary& summary) {
  if (!summary.canContinue()) return 0;
  return enforceByMultipliers(
      [&](Eigen::VectorXd& y) {
        summary.append(solver.solve(y));
        return summary.canContinue();
      },
      constraints, maxRounds, x);
}

}  // namespace dform
