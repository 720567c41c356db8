// SPDX-License-Identifier: GPL-3.0-or-later
// Levenberg-Marquardt for sparse nonlinear least squares, in the spirit of Ceres' Solver::Options
// and Solver::Summary. Each step solves (J^T J + mu I) dx = -J^T r. J^T J is scattered into a
// pattern fixed at set-up (linear terms are assembled once), CHOLMOD's symbolic analysis is done
// once, and the last numeric factorisation is reused as the preconditioner of a conjugate-gradient
// solve on later steps, so that most steps cost a few back-substitutions instead of a
// refactorisation.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dform/solver/problem.h"

namespace dform {

/// One Levenberg-Marquardt iteration as it went: what the callback sees and the summary keeps.
struct IterationSummary {
  int iteration = 0;              ///< its number, from 0
  double cost = 0;                ///< f(x) after this iteration
  std::vector<double> termCosts;  ///< w_t ||r_t||^2 after this iteration, per term
  double costChange = 0;          ///< f before - f after (0 for a rejected step)
  double gradientMaxNorm = 0;     ///< max |J^T r| at the start of the iteration
  double stepNorm = 0;            ///< ||dx|| of the step tried
  double damping = 0;             ///< mu used for the step
  bool accepted = false;          ///< whether the step lowered f
  bool refactorised = false;      ///< whether a numeric factorisation was computed
  int cgIterations = 0;           ///< preconditioned CG iterations (0 for a direct solve)
  double acceleration = 0;        ///< 2 |a| / |v| of the geodesic acceleration (0 when off)
  double seconds = 0;             ///< wall time of this iteration
  double cumulativeSeconds = 0;   ///< wall time since the solve started
};

enum class Termination {
  Converged,      ///< a tolerance below was met
  NoConvergence,  ///< the iteration cap was reached; x holds the best point found
  Failure,        ///< numerical failure (non-finite values, factorisation failed)
  UserAbort,      ///< the callback asked to stop; x holds the best point found
};

/// The termination's name as reports write it ("converged", "no_convergence", "failure",
/// "user_abort").
const char* terminationName(Termination t);

/// How the least-squares solve runs and when it stops (in the spirit of Ceres' Solver::Options).
struct SolverOptions {
  int maxIterations = 100;  ///< the iteration cap (Termination::NoConvergence when reached)
  /// Converged when (f_old - f_new) < functionTolerance * f_old for an accepted step.
  double functionTolerance = 1e-6;
  /// Converged when max |J^T r| < gradientTolerance.
  double gradientTolerance = 1e-12;
  /// Converged when ||dx|| < parameterTolerance * (||x|| + parameterTolerance).
  double parameterTolerance = 1e-10;
  /// Converged when f < absoluteCostTolerance (the paper's f_min).
  double absoluteCostTolerance = 0.0;
  /// Initial mu as a multiple of the largest diagonal entry of J^T J.
  double initialDampingRatio = 1e-6;
  /// Reuse the last factorisation as a CG preconditioner while CG converges within this many
  /// iterations; 0 refactorises every step (plain Levenberg-Marquardt). Within the cap, CG also
  /// gives up once it has cost a quarter of a factorisation's flops (CHOLMOD's count).
  int maxCgIterations = 50;
  /// Inexact-Newton forcing term: CG stops when ||A dx + g|| <= cgRelativeTolerance * ||g||.
  double cgRelativeTolerance = 1e-3;
  /// Geodesic acceleration (Transtrum and Sethna, 2012): each step v gets the second-order
  /// correction a/2, a = -(J^T J + mu I)^-1 J^T r''[v, v], so that it follows a curved valley of
  /// the objective instead of leaving it (bending a sheet isometrically is such a valley). A step
  /// whose correction is large, 2 |a| / |v| > maxAccelerationRatio, is too long for the valley: it
  /// is taken shortened along it, t v + t^2 a / 2 with t = maxAccelerationRatio / (2 |a| / |v|),
  /// and the damping rises by 1 / t (refusing it instead raised the damping 64-fold in three
  /// refusals, and the anti D-Form's solve crawled).
  bool geodesicAcceleration = true;
  /// The largest 2 |a| / |v| a step is taken at full length with (see geodesicAcceleration).
  double maxAccelerationRatio = 0.75;
  /// Called after every iteration; return false to stop the solve (Termination::UserAbort).
  std::function<bool(const IterationSummary&)> callback;
  /// When set, a step from x to x' is taken only if acceptStep(x, x') is true (the forward solve
  /// refuses one that folds a triangle over); a refused step counts as one that did not lower the
  /// cost: more damping, a shorter step next.
  std::function<bool(const Eigen::VectorXd& from, const Eigen::VectorXd& to)> acceptStep;

  /// Whether every option is in its range; false with `why` (when not null) naming the first
  /// that is not.
  bool isValid(std::string* why) const;
};

/// How a solve went (in the spirit of Ceres' Solver::Summary). Costs are f = sum of w_t ||r_t||^2
/// in the problem's own unit; -1 where the solve never evaluated them.
struct SolverSummary {
  Termination termination = Termination::Failure;  ///< why it stopped
  /// The same in words, with the figure that decided.
  std::string message = "solve was not called";
  std::vector<std::string> termNames;        ///< the problem's terms, in order
  double initialCost = -1;                   ///< f at the start
  double finalCost = -1;                     ///< f at the answer
  std::vector<double> initialTermCosts;      ///< each term's w_t ||r_t||^2 at the start
  std::vector<double> finalTermCosts;        ///< each term's at the answer
  std::vector<IterationSummary> iterations;  ///< every iteration, in order
  int numVariables = 0;                      ///< the length of x
  int numResiduals = 0;                      ///< the number of residuals of all terms
  int factorisations = 0;                    ///< numeric Cholesky factorisations computed
  double setupSeconds = 0;                   ///< pattern analysis and symbolic factorisation
  double totalSeconds = 0;                   ///< wall time of set-up and every iteration

  /// Appends a later solve of the same problem (iterations renumbered, times and counts added).
  void append(SolverSummary later);

  /// Whether x holds a usable result (converged, or stopped early with finite values).
  bool usable() const { return termination != Termination::Failure; }
  /// Whether a further solve from x makes sense: usable, and not stopped by the callback (a
  /// Ctrl-C ends the run at once; another solve would take an iteration, seconds on a large mesh).
  bool canContinue() const { return usable() && termination != Termination::UserAbort; }
  /// One line: termination, iterations, cost change, time.
  std::string briefReport() const;
};

/// A solver bound to one problem. The Jacobian pattern, the normal-matrix pattern and CHOLMOD's
/// symbolic factorisation are built once, at construction; solve() may be called again, for
/// example after a LinearResidual's target moved, and reuses all of it.
class LeastSquaresSolver {
 public:
  /// A solver of `problem` (which must outlive it) with `options`; does the set-up.
  LeastSquaresSolver(const Problem& problem, SolverOptions options);
  ~LeastSquaresSolver();
  LeastSquaresSolver(const LeastSquaresSolver&) = delete;
  LeastSquaresSolver& operator=(const LeastSquaresSolver&) = delete;

  /// Minimises the objective starting from x (updated in place).
  SolverSummary solve(Eigen::VectorXd& x);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A LinearResidual term of a problem, r = M x - b0, to be driven to zero as a constraint: met
/// when every block of blockSize residuals (e.g. one 3D point) has norm <= tolerance.
struct Constraint {
  LinearResidual* term;  ///< the problem's term to drive to zero
  int blockSize;         ///< residuals per block (3 for a 3D point)
  double tolerance;      ///< the largest norm of a block that counts as met (problem's unit)
};

/// Augmented-Lagrangian rounds: while a constraint is not met, each unmet term's target moves by
/// its residual (b <- b - (M x - b0), a multiplier update) and `resolve` solves the problem again
/// from x (Levenberg-Marquardt, or any solver of the same objective); it returns false to stop the
/// rounds (a failed solve). The weights stay as the caller chose them. Returns the rounds used;
/// the terms' targets are left shifted.
int enforceByMultipliers(const std::function<bool(Eigen::VectorXd&)>& resolve,
                         const std::vector<Constraint>& constraints, int maxRounds,
                         Eigen::VectorXd& x);

/// The same rounds with `solver` re-solving its own problem: each solve is appended to `summary`,
/// and no round starts once `summary` cannot continue (a failed solve, or one the callback
/// stopped).
int enforceByMultipliers(LeastSquaresSolver& solver, const std::vector<Constraint>& constraints,
                         int maxRounds, Eigen::VectorXd& x, SolverSummary& summary);

/// The summary of a solve that takes no step (maxIterations = 0), made without setting up the
/// linear algebra, which a large problem would pay for in time and memory for nothing: the
/// objective and its terms at x, and Termination::NoConvergence with the reason.
SolverSummary summaryWithoutSteps(const Problem& problem, const Eigen::VectorXd& x);

/// Minimises problem's objective starting from x (updated in place): a one-off LeastSquaresSolver.
SolverSummary solve(const Problem& problem, const SolverOptions& options, Eigen::VectorXd& x);

}  // namespace dform
