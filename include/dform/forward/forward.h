// SPDX-License-Identifier: GPL-3.0-or-later
// Forward modelling (paper section 4): two triangulated flat pieces in, the D-Form they make out.
#pragma once

#include "dform/core/types.h"
#include "dform/forward/settings.h"
#include "dform/model/local_global.h"
#include "dform/solver/solver.h"

namespace dform {

/// What solveDForm made: the solved pieces and how the relaxation and the solve went.
struct ForwardResult {
  DForm model;                    ///< solved pieces in mm
  LocalGlobalSummary relaxation;  ///< the local-global start
  SolverSummary summary;          ///< how the LM solve went; costs are in the normalised unit
  int constraintRounds = 0;       ///< multiplier updates used to meet the constraints
  double unitMm = 1.0;            ///< the solver's length unit in mm (mean seam edge length)
};

/// The 3D smoothing weight the relaxation runs at for a solve at `smooth3d` (see
/// ForwardSettings::smoothingContinuation).
double relaxationSmoothing(double smooth3d, const ForwardSettings& settings);

/// Pillow-shaped starting shape: both pieces mapped harmonically onto the average of their seam
/// outlines (A as drawn, B turned over) and inflated, A up and B down, by the heights that best
/// preserve their edge lengths. The seam starts planar and closed. Inputs and output in mm.
DForm pillowInitialGuess(const Piece& a, const Piece& b);

/// Solves the forward problem. `a` and `b` carry the flat meshes (flat, F) in mm and their seams
/// (a.seam counter-clockwise, b.seam clockwise, a.seam[i] meeting b.seam[i]). When both carry a
/// shape (one 3D row per flat vertex, for example a coarser solution transferred), the solve starts
/// from it; otherwise from pillowInitialGuess. Reads the solve's settings: weights, relaxation,
/// solver, the continuation, constraintRounds and outlineTolerance.
ForwardResult solveForward(const Piece& a, const Piece& b, const ForwardSettings& settings);

}  // namespace dform
