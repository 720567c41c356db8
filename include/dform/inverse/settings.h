// SPDX-License-Identifier: GPL-3.0-or-later
// An inverse run's settings: one flat struct of the knobs a user sets (CLI flags, job files,
// Python keywords, the studio), each with its default. The optimisation (solveInverse) reads its
// fields from the same struct.
#pragma once

#include "dform/core/constants.h"
#include "dform/inverse/pre_dform.h"
#include "dform/model/local_global.h"
#include "dform/model/weights.h"
#include "dform/solver/solver.h"

namespace dform {

/// Everything an inverse run needs besides the curve.
struct InverseSettings {
  int resolution = kDefaultResolution;  ///< seam vertices
  InverseInitOptions init;              ///< the pre-D-Form start and the remeshing of its pieces
  InverseWeights weights;               ///< the terms of Eq. 6 (dimensionless)
  /// The pre-D-Form start is isometric already (its pieces are unfolded exactly): the relaxation
  /// (at most 300 steps) only smooths it, and stops once a plain step would lower the energy by
  /// less than 2e-5 of it (relative, dimensionless). That gain is the global step's, a lower
  /// bound on the step's.
  LocalGlobalOptions relaxation = [] {
    LocalGlobalOptions o;
    o.maxIterations = 300;
    o.relativeTolerance = 2e-5;
    return o;
  }();
  /// Levenberg-Marquardt after the relaxation, on Eq. 6 with its exact quartic isometry term. Off
  /// by default (maxIterations = 0): from the pre-D-Form start the relaxation meets every figure,
  /// and LM's steps cost far more than they give (its first steps trade edge lengths for the
  /// quartic objective).
  SolverOptions solver = [] {
    SolverOptions o;
    o.maxIterations = 0;
    return o;
  }();
};

}  // namespace dform
