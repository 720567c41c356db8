// SPDX-License-Identifier: GPL-3.0-or-later
// Solving a ruled surface for its 3D positions: every edge as long as it is flat, and where the
// lengths leave freedom (free brims), the least bending energy.
#pragma once

#include <string>
#include <vector>

#include "dform/ruled/ruled_surface.h"

namespace dform::ruled {

/// When the ruled engine's solve stops: its tolerances, its step budget and its first damping.
struct SolveOptions {
  /// Largest | |x_i - x_j| - length | accepted, relative to the mean edge length. Lengths are
  /// known to ~1e-16 of themselves; rounding of the solve's last step leaves ~1e-15.
  double lengthTolerance = 1e-13;
  /// Where the lengths leave freedom: the relative first-order residual of the bending energy
  /// (its gradient off the constraints' span, over the gradient's size) accepted.
  double stationarityTolerance = 1e-9;
  int maxIterations = 100;  ///< Levenberg-Marquardt or SQP steps
  /// Levenberg-Marquardt's first damping, relative to J J^T's diagonal (2): 1e-3 of it from an
  /// unknown start; near a solution (a continuation step) smaller, so that the first steps are
  /// Newton's along weakly determined directions too.
  double initialDamping = 2e-3;
};

/// How a solve of the ruled engine went.
struct SolveSummary {
  bool converged = false;     ///< both tolerances of SolveOptions met
  int iterations = 0;         ///< Levenberg-Marquardt or SQP steps taken
  double maxLengthError = 0;  ///< relative, as maxLengthError()
  double stationarity = 0;    ///< as SolveOptions::stationarityTolerance measures it
  double bendingEnergy = 0;   ///< sum over chords of 3 l^2 / (A1 + A2) theta^2 at the answer
  std::string message;        ///< why not converged
};

/// Levenberg-Marquardt on the edge lengths (steps -J^T (J J^T + mu I)^-1 r: least-norm Newton
/// steps as mu falls, so rigid motions and flat hinges are left alone) from where surface.X is.
/// Converges quadratically where the lengths can be met; ends at a least-squares state where
/// they cannot (converged false).
/// `lengths` (mm, one per surface.edges() in its order) replaces the flat lengths when given.
SolveSummary solveLengths(RuledSurface& surface, const SolveOptions& options = {},
                          const std::vector<double>* lengths = nullptr);

/// The least bending energy with every length met: SQP on the KKT system of the energy's
/// Gauss-Newton Hessian and the lengths, from a state that meets them (solveLengths first).
/// `lengths` (mm, one per surface.edges() in its order) replaces the flat lengths when given.
SolveSummary minimiseBending(RuledSurface& surface, const SolveOptions& options = {},
                             const std::vector<double>* lengths = nullptr);

}  // namespace dform::ruled
