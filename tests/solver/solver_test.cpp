// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/solver/solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "solver/gradient_check.h"

namespace dform {
namespace {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

RowSparse randomSparse(int rows, int cols, double density, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), p(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < rows; ++i) {
    entries.emplace_back(i, i % cols, 1.0 + p(rng));  // every row and column used
    for (int j = 0; j < cols; ++j)
      if (p(rng) < density) entries.emplace_back(i, j, u(rng));
  }
  RowSparse M(rows, cols);
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

// r_i(a, b) = a exp(b t_i) - y_i: fitting an exponential to exact data.
class ExponentialFit : public ResidualTerm {
 public:
  ExponentialFit(Eigen::VectorXd t, Eigen::VectorXd y) : t_(std::move(t)), y_(std::move(y)) {}
  int numResiduals() const override { return int(t_.size()); }
  JacobianPattern pattern() const override {
    JacobianPattern p;
    for (Eigen::Index i = 0; i < t_.size(); ++i) {
      p.cols.push_back(0);
      p.cols.push_back(1);
      p.rowStart.push_back(int(p.cols.size()));
    }
    return p;
  }
  void evaluate(const Eigen::VectorXd& x, double* r, double* J) const override {
    for (Eigen::Index i = 0; i < t_.size(); ++i) {
      const double e = std::exp(x[1] * t_[i]);
      r[i] = x[0] * e - y_[i];
      if (J) {
        J[2 * i] = e;
        J[2 * i + 1] = x[0] * t_[i] * e + (bug_ ? 0.1 : 0.0);
      }
    }
  }
  bool bug_ = false;

 private:
  Eigen::VectorXd t_, y_;
};

std::unique_ptr<ExponentialFit> exponentialData(double a, double b) {
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(20, 0.0, 2.0);
  Eigen::VectorXd y = (a * (b * t.array()).exp()).matrix();
  return std::make_unique<ExponentialFit>(t, y);
}

TEST(Solver, LinearLeastSquaresMatchesDenseSolution) {
  std::mt19937 rng(7);
  const int n = 30;
  RowSparse M1 = randomSparse(50, n, 0.1, rng), M2 = randomSparse(20, n, 0.2, rng);
  Eigen::VectorXd b1 = Eigen::VectorXd::Random(50), b2 = Eigen::VectorXd::Random(20);
  const double w1 = 1.0, w2 = 3.5;
  Problem problem(n);
  problem.addTerm("one", w1, std::make_unique<LinearResidual>(M1, b1));
  problem.addTerm("two", w2, std::make_unique<LinearResidual>(M2, b2));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  const SolverSummary summary = solve(problem, SolverOptions{}, x);
  ASSERT_TRUE(summary.usable()) << summary.message;
  // Normal equations of w1 |M1 x - b1|^2 + w2 |M2 x - b2|^2.
  const Eigen::MatrixXd D1 = Eigen::MatrixXd(M1), D2 = Eigen::MatrixXd(M2);
  const Eigen::MatrixXd A = w1 * D1.transpose() * D1 + w2 * D2.transpose() * D2;
  const Eigen::VectorXd rhs = w1 * D1.transpose() * b1 + w2 * D2.transpose() * b2;
  const Eigen::VectorXd exact = A.ldlt().solve(rhs);
  EXPECT_LT((x - exact).norm(), 1e-6 * exact.norm());
}

TEST(Solver, NonlinearFitFindsTheGeneratingParameters) {
  Problem problem(2);
  problem.addTerm("fit", 1.0, exponentialData(2.0, -0.7));
  Eigen::VectorXd x(2);
  x << 1.0, 0.0;
  SolverOptions options;
  options.functionTolerance = 1e-12;
  const SolverSummary summary = solve(problem, options, x);
  ASSERT_EQ(summary.termination, Termination::Converged) << summary.message;
  EXPECT_NEAR(x[0], 2.0, 1e-6);
  EXPECT_NEAR(x[1], -0.7, 1e-6);
  EXPECT_LT(summary.finalCost, 1e-12);
}

// Rosenbrock's banana valley as least squares: r = (k (y - x^2), 1 - x), minimum at (1, 1). The
// valley y = x^2 curves, so straight Gauss-Newton steps leave it; its curvature term uses the
// base class's central difference (exact here: r is quadratic).
class Rosenbrock : public ResidualTerm {
 public:
  explicit Rosenbrock(double k) : k_(k) {}
  int numResiduals() const override { return 2; }
  JacobianPattern pattern() const override {
    JacobianPattern p;
    p.cols = {0, 1, 0};
    p.rowStart = {0, 2, 3};
    return p;
  }
  void evaluate(const Eigen::VectorXd& x, double* r, double* J) const override {
    r[0] = k_ * (x[1] - x[0] * x[0]);
    r[1] = 1.0 - x[0];
    if (J) J[0] = -2.0 * k_ * x[0], J[1] = k_, J[2] = -1.0;
  }

 private:
  double k_;
};

// The valley of steepness k as a problem of its own.
Problem rosenbrockProblem(double k) {
  Problem problem(2);
  problem.addTerm("rosenbrock", 1.0, std::make_unique<Rosenbrock>(k));
  return problem;
}

// Options that stop on the gradient, the step or the cap, never on a small decrease.
SolverOptions withoutDecreaseStop(int maxIterations) {
  SolverOptions options;
  options.functionTolerance = 0.0;
  options.maxIterations = maxIterations;
  return options;
}

// The valley's classic start.
Eigen::VectorXd rosenbrockStart() {
  Eigen::VectorXd x(2);
  x << -1.2, 1.0;
  return x;
}

TEST(Solver, GeodesicAccelerationFollowsACurvedValley) {
  int iterations[2] = {0, 0};
  for (int accelerate = 0; accelerate < 2; ++accelerate) {
    const Problem problem = rosenbrockProblem(1000.0);
    Eigen::VectorXd x = rosenbrockStart();
    SolverOptions options = withoutDecreaseStop(1000);
    options.gradientTolerance = 1e-12;
    options.geodesicAcceleration = accelerate == 1;
    const SolverSummary summary = solve(problem, options, x);
    ASSERT_EQ(summary.termination, Termination::Converged) << summary.message;
    EXPECT_NEAR(x[0], 1.0, 1e-6);
    EXPECT_NEAR(x[1], 1.0, 1e-6);
    iterations[accelerate] = int(summary.iterations.size());
  }
  std::printf("  Rosenbrock (k = 1000): %d iterations plain, %d with geodesic acceleration\n",
              iterations[0], iterations[1]);
  EXPECT_LT(iterations[1], iterations[0]);
}

TEST(Solver, AStepTooLongForTheValleyIsShortenedAlongItNotRefused) {
  // From the classic start with almost no damping, the first Gauss-Newton steps leave Rosenbrock's
  // curved valley (2 |a| / |v| > maxAccelerationRatio). Such a step is taken shortened along the
  // geodesic, t v + t^2 a / 2 with t = maxAccelerationRatio / (2 |a| / |v|), rather than refused,
  // and the damping rises by 1 / t so that the next step starts at about the length that was
  // taken: refusing it instead multiplied the damping by 2, 4, 8, ... on the way in and cost the
  // anti D-Form's solve 54 iterations in place of 16.
  const Problem problem = rosenbrockProblem(1000.0);
  Eigen::VectorXd x = rosenbrockStart();
  SolverOptions options = withoutDecreaseStop(1000);
  options.initialDampingRatio = 1e-12;
  const SolverSummary summary = solve(problem, options, x);
  ASSERT_EQ(summary.termination, Termination::Converged) << summary.message;
  EXPECT_NEAR(x[0], 1.0, 1e-6);
  int shortened = 0;
  for (std::size_t i = 0; i + 1 < summary.iterations.size(); ++i) {
    const IterationSummary& it = summary.iterations[i];
    if (!(it.acceleration > options.maxAccelerationRatio) || !it.accepted) continue;
    ++shortened;
    EXPECT_GT(it.costChange, 0.0);
    EXPECT_NEAR(summary.iterations[i + 1].damping,
                it.damping * it.acceleration / options.maxAccelerationRatio,
                1e-12 * summary.iterations[i + 1].damping);
  }
  EXPECT_GT(shortened, 0);
}

TEST(Solver, ARefusedStepIsNeverTakenAndTheSolveStopsAtTheBoundary) {
  // Rosenbrock's minimum (1, 1) lies beyond x[0] = 0.5, which no step may cross: the solve goes
  // as far as it may, every point it stands on stays on the allowed side, and it still ends.
  const Problem problem = rosenbrockProblem(10.0);
  Eigen::VectorXd x = rosenbrockStart();
  SolverOptions options = withoutDecreaseStop(500);
  int asked = 0, fromOutside = 0;
  options.acceptStep = [&](const Eigen::VectorXd& from, const Eigen::VectorXd& to) {
    ++asked;
    if (from[0] > 0.5) ++fromOutside;
    return to[0] <= 0.5;
  };
  const SolverSummary summary = solve(problem, options, x);
  ASSERT_TRUE(summary.usable()) << summary.message;
  EXPECT_GT(asked, 0);
  EXPECT_EQ(fromOutside, 0);
  EXPECT_LE(x[0], 0.5);
  // It got close to the boundary: the cost at the constrained minimum (x[0] = 0.5, y = 0.25) is
  // 0.25.
  EXPECT_LT(summary.finalCost, 0.25 + 0.05);
  // Unconstrained, the same solve crosses the boundary to the minimum.
  Eigen::VectorXd free = rosenbrockStart();
  options.acceptStep = nullptr;
  ASSERT_TRUE(solve(problem, options, free).usable());
  EXPECT_NEAR(free[0], 1.0, 1e-4);
}

TEST(Solver, HeldUnknownsNeverMoveAndTheRestReachTheirConstrainedMinimum) {
  // |x - target|^2 with x[1] and x[3] held: those keep their start, the others reach the target.
  const int n = 5;
  RowSparse M(n, n);
  M.setIdentity();
  const Eigen::VectorXd target = Eigen::VectorXd::LinSpaced(n, 1.0, 5.0);
  Problem problem(n);
  problem.addTerm("fit", 1.0, std::make_unique<LinearResidual>(M, target));
  problem.addTerm("curve", 1.0, std::make_unique<Rosenbrock>(3.0));  // couples x[0] and x[1]
  problem.holdConstant({1, 3});
  Eigen::VectorXd x = Eigen::VectorXd::Constant(n, -2.0);
  SolverOptions options;
  options.functionTolerance = 1e-15;
  const SolverSummary summary = solve(problem, options, x);
  ASSERT_TRUE(summary.usable()) << summary.message;
  EXPECT_EQ(x[1], -2.0);
  EXPECT_EQ(x[3], -2.0);
  EXPECT_NEAR(x[2], 3.0, 1e-4);
  EXPECT_NEAR(x[4], 5.0, 1e-4);
  EXPECT_GT(std::abs(x[0] + 2.0), 0.1);  // x[0] moved, towards its own minimum with x[1] held
}

TEST(Solver, SummaryIsConsistent) {
  std::mt19937 rng(3);
  Problem problem(2);
  problem.addTerm("fit", 2.0, exponentialData(1.5, 0.4));
  problem.addTerm(
      "prior", 0.1,
      std::make_unique<LinearResidual>(randomSparse(2, 2, 1.0, rng), Eigen::Vector2d(1, 1)));
  Eigen::VectorXd x(2);
  x << 0.5, -0.5;
  const SolverSummary summary = solve(problem, SolverOptions{}, x);
  ASSERT_TRUE(summary.usable());
  ASSERT_EQ(summary.termNames.size(), 2u);
  // Per-term costs add up to the cost and equal Problem::termCosts at the result.
  const std::vector<double> costs = problem.termCosts(x);
  EXPECT_NEAR(summary.finalTermCosts[0] + summary.finalTermCosts[1], summary.finalCost, 1e-12);
  EXPECT_NEAR(summary.finalTermCosts[0], costs[0], 1e-12);
  EXPECT_NEAR(summary.finalTermCosts[1], costs[1], 1e-12);
  // Accepted steps never raise the cost; times only grow.
  double previous = summary.initialCost, time = 0.0;
  for (const IterationSummary& it : summary.iterations) {
    EXPECT_GE(it.cumulativeSeconds, time);
    time = it.cumulativeSeconds;
    if (!it.accepted) continue;
    EXPECT_LE(it.cost, previous);
    EXPECT_NEAR(previous - it.cost, it.costChange, 1e-12 * std::max(1.0, previous));
    previous = it.cost;
  }
  EXPECT_EQ(previous, summary.finalCost);
  EXPECT_FALSE(summary.briefReport().empty());
}

TEST(Solver, CallbackCanStopTheSolve) {
  Problem problem(2);
  problem.addTerm("fit", 1.0, exponentialData(2.0, -0.7));
  Eigen::VectorXd x(2);
  x << 1.0, 0.0;
  SolverOptions options;
  int calls = 0;
  options.callback = [&](const IterationSummary&) { return ++calls < 2; };
  const SolverSummary summary = solve(problem, options, x);
  EXPECT_EQ(summary.termination, Termination::UserAbort);
  EXPECT_EQ(calls, 2);
  EXPECT_TRUE(summary.usable());
  EXPECT_LE(problem.termCosts(x)[0], summary.initialCost);
}

TEST(Solver, InvalidOptionsAndNonFiniteStartAreReported) {
  Problem problem(2);
  problem.addTerm("fit", 1.0, exponentialData(2.0, -0.7));
  Eigen::VectorXd x(2);
  x << 1.0, 0.0;
  SolverOptions bad;
  bad.cgRelativeTolerance = 2.0;
  SolverSummary summary = solve(problem, bad, x);
  EXPECT_FALSE(summary.usable());
  EXPECT_NE(summary.message.find("cgRelativeTolerance"), std::string::npos);
  x << std::nan(""), 0.0;
  summary = solve(problem, SolverOptions{}, x);
  EXPECT_EQ(summary.termination, Termination::Failure);
  EXPECT_NE(summary.message.find("not finite"), std::string::npos);
}

TEST(Solver, PreconditionedStepsReachTheSameMinimumAsRefactorising) {
  Problem problem(2);
  problem.addTerm("fit", 1.0, exponentialData(3.0, 0.3));
  Eigen::VectorXd a(2), b(2);
  a << 1.0, 0.0;
  b = a;
  SolverOptions direct;
  direct.maxCgIterations = 0;
  direct.functionTolerance = 1e-14;
  SolverOptions reused = direct;
  reused.maxCgIterations = 50;
  solve(problem, direct, a);
  const SolverSummary summary = solve(problem, reused, b);
  EXPECT_LT((a - b).norm(), 1e-6);
  EXPECT_LE(summary.factorisations, int(summary.iterations.size()));
}

/// |x - (1, 2)|^2 + |x0 + x1 - 0|^2, with the second term's residual for constraint rounds.
struct PullWithSum {
  Problem problem{2};
  LinearResidual* sum = nullptr;
  PullWithSum() {
    RowSparse I(2, 2);
    I.setIdentity();
    RowSparse S(1, 2);
    S.insert(0, 0) = 1.0;
    S.insert(0, 1) = 1.0;
    problem.addTerm("pull", 1.0, std::make_unique<LinearResidual>(I, Eigen::Vector2d(1, 2)));
    auto term = std::make_unique<LinearResidual>(S, Eigen::VectorXd::Zero(1));
    sum = term.get();
    problem.addTerm("sum", 1.0, std::move(term));
  }
};

TEST(Solver, MultiplierRoundsMeetAConstraintWithoutRaisingItsWeight) {
  // The soft minimum misses x0 + x1 = 0, the constraint rounds meet it to the tolerance and land
  // on the constrained minimum (-0.5, 0.5).
  PullWithSum pull;
  LeastSquaresSolver solver(pull.problem, SolverOptions{});
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
  SolverSummary summary = solver.solve(x);
  EXPECT_NEAR(x[0] + x[1], 1.0, 1e-6);  // soft: (1 + 2) / 3
  const int rounds = enforceByMultipliers(solver, {{pull.sum, 1, 1e-7}}, 50, x, summary);
  EXPECT_GT(rounds, 0);
  EXPECT_GT(summary.iterations.size(), 1u);  // the rounds' solves are in the summary
  EXPECT_LT(std::abs(x[0] + x[1]), 1e-7);
  EXPECT_NEAR(x[0], -0.5, 1e-6);
  EXPECT_NEAR(x[1], 0.5, 1e-6);
}

TEST(Solver, AStopFromTheCallbackEndsTheMultiplierRounds) {
  // A Ctrl-C stops a solve through the callback: the constraint rounds must not go on with solves
  // of their own (each would take an iteration, seconds on a large mesh, before stopping).
  PullWithSum pull;
  SolverOptions options;
  bool stop = false;
  int calls = 0;
  options.callback = [&](const IterationSummary&) { return ++calls, !stop; };
  LeastSquaresSolver solver(pull.problem, options);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
  SolverSummary summary = solver.solve(x);
  ASSERT_TRUE(summary.canContinue());
  stop = true;  // the Ctrl-C comes during the first round's solve
  calls = 0;
  const int rounds = enforceByMultipliers(solver, {{pull.sum, 1, 1e-7}}, 50, x, summary);
  EXPECT_EQ(rounds, 1);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(summary.termination, Termination::UserAbort);
  EXPECT_FALSE(summary.canContinue());
  // Nor does a round start after the stop, though the constraint is still unmet.
  calls = 0;
  EXPECT_EQ(enforceByMultipliers(solver, {{pull.sum, 1, 1e-7}}, 50, x, summary), 0);
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace dform
