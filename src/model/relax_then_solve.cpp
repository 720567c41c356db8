// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/relax_then_solve.h"

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
    LeastSquaresSolver lm(problem, solverOptions);
    result.summary = lm.solve(x);
    result.constraintRounds =
        enforceByMultipliers(lm, constraints, maxConstraintRounds, x, result.summary);
  }
  return result;
}

}  // namespace dform
