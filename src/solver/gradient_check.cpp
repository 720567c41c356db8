// SPDX-License-Identifier: GPL-3.0-or-later
#include "gradient_check.h"

#include <algorithm>
#include <cmath>

namespace dform {

JacobianCheck checkJacobian(const ResidualTerm& term, const Eigen::VectorXd& x, double h) {
  const JacobianPattern pattern = term.pattern();
  const int rows = pattern.rows();
  std::vector<double> analytic(pattern.cols.size());
  Eigen::VectorXd r(rows), rPlus(rows), rMinus(rows);
  term.evaluate(x, r.data(), analytic.data());

  // Dense numeric Jacobian column by column; fine for test-sized problems.
  Eigen::MatrixXd numeric(rows, x.size());
  Eigen::VectorXd probe = x;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double step = h * std::max(1.0, std::abs(x[j]));
    probe[j] = x[j] + step;
    term.evaluate(probe, rPlus.data(), nullptr);
    probe[j] = x[j] - step;
    term.evaluate(probe, rMinus.data(), nullptr);
    probe[j] = x[j];
    numeric.col(j) = (rPlus - rMinus) / (2.0 * step);
  }

  JacobianCheck check;
  Eigen::MatrixXd covered = Eigen::MatrixXd::Zero(rows, x.size());
  for (int i = 0; i < rows; ++i) {
    for (int p = pattern.rowStart[i]; p < pattern.rowStart[i + 1]; ++p) {
      const int j = pattern.cols[p];
      covered(i, j) = 1.0;
      const double err = std::abs(analytic[p] - numeric(i, j));
      const double rel = err / std::max(1.0, std::abs(numeric(i, j)));
      check.maxAbsoluteError = std::max(check.maxAbsoluteError, err);
      if (rel > check.maxRelativeError) {
        check.maxRelativeError = rel;
        check.worstRow = i;
        check.worstColumn = j;
      }
    }
  }
  // Central differences of a smooth term are O(h^2); anything this large outside the pattern
  // means the pattern misses a dependency.
  const double outsideTolerance = 1e-6 * std::max(1.0, numeric.cwiseAbs().maxCoeff());
  for (int i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < x.size(); ++j)
      if (covered(i, j) == 0.0 && std::abs(numeric(i, j)) > outsideTolerance)
        check.outsidePatternIsZero = false;
  return check;
}

}  // namespace dform
