// SPDX-License-Identifier: GPL-3.0-or-later
// Checks a residual term's analytic Jacobian against central finite differences (as Ceres'
// GradientChecker does), for tests and for debugging new terms.
#pragma once

#include <Eigen/Core>

#include "dform/solver/problem.h"

namespace dform {

struct JacobianCheck {
  double maxAbsoluteError = 0;  ///< max |J_analytic - J_numeric| over the pattern's entries
  double maxRelativeError = 0;  ///< the same, divided by max(1, |J_numeric|)
  int worstRow = -1;
  int worstColumn = -1;
  bool outsidePatternIsZero = true;  ///< numeric derivatives vanish outside the declared pattern
};

/// Compares term's Jacobian at x with central differences of step h * max(1, |x_j|).
JacobianCheck checkJacobian(const ResidualTerm& term, const Eigen::VectorXd& x, double h = 1e-6);

}  // namespace dform
