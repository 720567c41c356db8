// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/relax_then_solve.h"

#include <memory>

#include "dform/core/interrupt.h"

namespace dform {

SolveSequenceSummary relaxThenSolve(const LocalGlobalRelaxation& relaxation,
                                    const LocalGlobalOptions& relaxationOptions,
                                    const Problem& problem, const SolverOptions& solver,
                                    const FoldGuard& guard,
                                    const std::vector<Constraint>& constraints,
                                    int maxConstraintRounds, Eigen::VectorXd& x) {
  SolveSequenceSummary result;
  SolverOptions solverOptions = solver;
  refuseNewFolds(guard, solverOptions);
  // Levenberg-Marquardt's set-up (the normal equations' pattern, the symbolic analysis of their
  // factor) reads the problem's terms alone, never x: it is made beside the relaxation (0.11 s of
  // the 0.3 s relaxation of the non-convex sample's paper model at 100 seam points, where the
  // ruled engine's other start has left a core idle).
  Beside<std::unique_ptr<LeastSquaresSolver>> setUp(solverOptions.maxIterations > 0, [&] {
    return std::make_unique<LeastSquaresSolver>(problem, solverOptions);
  });
  result.relaxation = relaxation.relax(relaxationOptions, x);
  if (result.relaxation.stopped) {  // a Ctrl-C: no further solve
    result.summary = summaryWithoutSteps(problem, x);
    result.summary.termination = Termination::UserAbort;
  } else if (solverOptions.maxIterations == 0) {  // the relaxation is the result, its rounds too
    result.constraintRounds = enforceByMultipliers(
        [&](Eigen::VectorXd& y) {
          result.relaxation.append(relaxation.relax(relaxationOptions, y));
          return !result.relaxation.stopped;
        },
        constraints, maxConstraintRounds, x);
    result.summary = summaryWithoutSteps(problem, x);
  } else {
    const std::unique_ptr<LeastSquaresSolver> lm = setUp.get();
    result.summary = lm->solve(x);
    result.constraintRounds =
        enforceByMultipliers(*lm, constraints, maxConstraintRounds, x, result.summary);
  }
  return result;
}

}  // namespace dform
