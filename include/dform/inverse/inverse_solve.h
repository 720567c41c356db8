// SPDX-License-Identifier: GPL-3.0-or-later
// Inverse modelling's optimisation (paper 5.2, Eq. 6): from the pre-D-Form start, find flat pieces
// and their 3D shapes whose seam runs along the target curve, with the flat boundaries free.
#pragma once

#include "dform/core/types.h"
#include "dform/inverse/settings.h"
#include "dform/model/local_global.h"
#include "dform/solver/solver.h"

namespace dform {

/// What solveInverse made: the solved pieces and how the relaxation and the solve went.
struct InverseResult {
  DForm model;                    ///< solved pieces in mm
  LocalGlobalSummary relaxation;  ///< the local-global start
  SolverSummary summary;          ///< the Levenberg-Marquardt solve (normalised unit)
  double unitMm = 1.0;            ///< the solver's length unit in mm (mean curve edge)
};

/// Optimises from `start` (pieces in mm whose seams a.seam[i], b.seam[i] sit at curve.row(i); for
/// example InverseInit::model) towards a D-Form on `curve` (#n by 3, mm). Reads the settings'
/// weights, relaxation and solver.
InverseResult solveInverse(const DForm& start, const Points3& curve,
                           const InverseSettings& settings);

}  // namespace dform
