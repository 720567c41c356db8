// SPDX-License-Identifier: GPL-3.0-or-later
// The D-Form solve forward and inverse modelling share once each has set up its objective: the
// local-global relaxation from the start, then Levenberg-Marquardt on the exact objective, and the
// constraints met by augmented-Lagrangian rounds (enforceByMultipliers).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dform/model/injectivity.h"
#include "dform/model/local_global.h"
#include "dform/solver/problem.h"
#include "dform/solver/solver.h"

namespace dform {

/// How the sequence went.
struct SolveSequenceSummary {
  LocalGlobalSummary relaxation;  ///< the relaxation, with the rounds that re-ran it appended
  SolverSummary summary;          ///< Levenberg-Marquardt's solves (none: its summary at x)
  int constraintRounds = 0;       ///< multiplier updates used to meet the constraints
};

/// Relaxes x (the problem's unknowns, in its normalised unit) with `relaxation`, then:
/// - when the relaxation was stopped by the caller: nothing more, and the summary ends with
///   UserAbort;
/// - when solver.maxIterations is 0: the relaxation is the result; each multiplier round that
///   `constraints` need runs it again;
/// - otherwise Levenberg-Marquardt on `problem`, refusing any step that folds a triangle over that
///   `guard` saw upright, and each multiplier round solves again.
/// At most maxConstraintRounds rounds either way.
SolveSequenceSummary relaxThenSolve(const LocalGlobalRelaxation& relaxation,
                                    const LocalGlobalOptions& relaxationOptions,
                                    const Problem& problem, const SolverOptions& solver,
                                    const FoldGuard& guard,
                                    const std::vector<Constraint>& constraints,
                                    int maxConstraintRounds, Eigen::VectorXd& x);

}  // namespace dform
