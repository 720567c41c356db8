// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: flattening curves into polylines with a guaranteed chord deviation. Shared by the SVG
// outline reader (2D) and the Bezier seam-curve reader (3D).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace dform::io_detail {

/// A curve may not be split into more pieces than this; beyond it the tolerance is unreasonably
/// small for the drawing and the reader reports it instead of exhausting memory.
constexpr double kMaxStepsPerCurve = 1.0e6;

/// Number of equal parameter steps over a range of length `paramRange` that keeps the chord
/// deviation of a C2 curve within `tolerance`, given `secondDerivativeBound` >= max |C''|: linear
/// interpolation over a step h deviates by at most h^2/8 * max |C''|. Returns 0 when more than
/// kMaxStepsPerCurve steps would be needed.
inline long stepsForDeviation(double secondDerivativeBound, double paramRange, double tolerance) {
  const double steps = std::ceil(paramRange * std::sqrt(secondDerivativeBound / (8.0 * tolerance)));
  if (!(steps <= kMaxStepsPerCurve)) return 0;
  return std::max(1L, long(steps));
}

/// Appends the flattened quadratic (3 control points) or cubic (4) Bezier curve to `out`: the
/// interior sample points and the end point, not the start point (the previous end). Chord
/// deviation <= tolerance (Wang's bound on the second derivative). Returns false, appending
/// nothing, when the tolerance would need more than kMaxStepsPerCurve steps.
template <typename Vec>
bool appendBezier(const std::vector<Vec>& ctrl, double tolerance, std::vector<Vec>& out) {
  const std::size_t degree = ctrl.size() - 1;
  double maxSecondDifference = 0.0;
  for (std::size_t i = 0; i + 2 < ctrl.size(); ++i)
    maxSecondDifference =
        std::max(maxSecondDifference, (ctrl[i] - 2.0 * ctrl[i + 1] + ctrl[i + 2]).norm());
  const double bound = double(degree * (degree - 1)) * maxSecondDifference;
  const long steps = stepsForDeviation(bound, 1.0, tolerance);
  if (steps == 0) return false;
  for (long k = 1; k <= steps; ++k) {
    const double t = double(k) / double(steps), s = 1.0 - t;
    if (degree == 2)
      out.push_back(s * s * ctrl[0] + 2.0 * s * t * ctrl[1] + t * t * ctrl[2]);
    else
      out.push_back(s * s * s * ctrl[0] + 3.0 * s * s * t * ctrl[1] + 3.0 * s * t * t * ctrl[2] +
                    t * t * t * ctrl[3]);
  }
  return true;
}

}  // namespace dform::io_detail
