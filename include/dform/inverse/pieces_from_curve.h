// SPDX-License-Identifier: GPL-3.0-or-later
// The two flat pieces whose D-Form has a given 3D seam (inverse modelling end to end, in memory):
// the pre-D-Form start, the exact pieces where the curve lies on its convex hull, else the
// optimisation coarse to fine. Measuring the result is validate's (pipeline/inverse_pipeline.h
// makePieces does both).
#pragma once

#include <string>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/inverse/inverse_solve.h"
#include "dform/inverse/pre_dform.h"
#include "dform/inverse/settings.h"
#include "dform/model/run_types.h"

namespace dform {

/// A solved inverse job: the pieces, which model made them and how the solve went.
struct SolvedPieces {
  DForm model;  ///< the solved pieces, mm
  /// exact: the curve lies on its convex hull and the pieces are the hull's two sides unfolded,
  /// zipped by the exact engine; paper: the optimisation from the pre-D-Form.
  ModelUsed modelUsed;
  Curve3 target;                  ///< the resampled curve the seam follows (mm)
  PreDForm pre;                   ///< how the start was built (on-hull or not)
  LocalGlobalSummary relaxation;  ///< paper: the local-global start of the solve
  SolverSummary summary;          ///< paper: the Levenberg-Marquardt solve
  double curveLength = 0;         ///< length of the curve as read (mm)
  Timings timings;                ///< how long each stage took, seconds
};

/// The pieces for `curve` (mm, closed, in memory): initialised (pre-D-Form; the exact model where
/// the curve lies on its convex hull) and optimised. Messages and errors name the curve by its
/// `source` (a file path), else "the curve". A failed allocation is an error with the resolution
/// that fits. `settings` are in their ranges (the pipeline's settings table checks them:
/// pipeline/settings.h checkSettings, which makePieces runs first).
Result<SolvedPieces> solvePieces(const Curve3& curve, const InverseSettings& settings,
                                 MessageSink& sink, const RunHooks& hooks = {});

/// What messages and errors call the curve: its file, else "the curve".
std::string curveLabel(const Curve3& curve);

}  // namespace dform
