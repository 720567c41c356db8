// Inverse modelling's optimisation (paper 5.2, Eq. 6): from the pre-D-Form start, find flat pieces
// and their 3D shapes whose seam runs along the target curve, with the flat boundaries free.
#pragma once

#include "core/types.h"
#include "model/local_global.h"
#include "model/weights.h"
#include "solver/solver.h"

namespace dform {

struct InverseOptions {
  InverseWeights weights;
  /// The pre-D-Form start is isometric already (its pieces are unfolded exactly): the relaxation
  /// only smooths it, and stops once a plain step would lower the energy by less than 2e-5 of it
  /// (at 1e-6 a tennis-ball seam at 300 points ran 712 steps to lower it by a tenth). That gain
  /// is the global step's, a lower bound on the step's: at 1e-4 the pushed-in curve stopped after
  /// 87 steps with L_max 0.56 %, at 2e-5 after 161 with 0.39 % (0.36 % when the test read the
  /// decrease of the step taken, at 1e-4).
  LocalGlobalOptions relaxation = [] {
    LocalGlobalOptions o;
    o.maxIterations = 300;
    o.relativeTolerance = 2e-5;
    return o;
  }();
  /// Levenberg-Marquardt after the relaxation, on Eq. 6 with its exact quartic isometry term. Off
  /// by default (maxIterations = 0): from the pre-D-Form start the relaxation meets every figure,
  /// and LM's steps cost far more than they give. Measured on the pushed-in curve: relaxation
  /// alone 0.19 s, L_error 0.038 %; with up to 100 LM iterations 7 s, 0.037 %; with 3, 0.64 s and
  /// 0.042 % (LM's first steps trade edge lengths for the quartic objective).
  SolverOptions solver = [] {
    SolverOptions o;
    o.maxIterations = 0;
    return o;
  }();
};

struct InverseResult {
  DForm model;                    ///< solved pieces in mm
  LocalGlobalSummary relaxation;  ///< the local-global start
  SolverSummary summary;          ///< the Levenberg-Marquardt solve (normalised unit)
  double unitMm = 1.0;            ///< the solver's length unit in mm (mean curve edge)
};

/// Optimises from `start` (pieces in mm whose seams a.seam[i], b.seam[i] sit at curve.row(i); for
/// example InverseInit::model) towards a D-Form on `curve` (#n by 3, mm).
InverseResult solveInverse(const DForm& start, const Points3& curve, const InverseOptions& options);

}  // namespace dform
