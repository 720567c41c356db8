// SPDX-License-Identifier: GPL-3.0-or-later
// A D-Form from two flat shapes (forward modelling end to end, in memory): the seam laid out on
// both pieces, then the exact D-Form where it applies, else the paper's optimisation coarse to
// fine. Measuring the result is validate's (pipeline/forward_pipeline.h makeDForm does both).
#pragma once

#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/forward/forward.h"
#include "dform/forward/settings.h"
#include "dform/model/run_types.h"

namespace dform {

// The names job files, the CLI and Python use for forward/settings.h's choices.
const char* joinedBoundaryName(JoinedBoundary boundary);  ///< "outer" or "inner"

/// The term weights a job starts from: paper Table 1's for a classic D-Form; for anti and demi
/// D-Forms (a hole joined) the 3D smoothness weight is 0.001, Table 1's inverse-mode value. At
/// 0.01 their free brims stay stiff enough to strain the seam past the 3% bar (docs/variants.md).
ForwardWeights defaultWeights(JoinedBoundary a, JoinedBoundary b);

/// Reads "outer,inner" (A's joined boundary, then B's; "outer" or "inner" each) into the job;
/// false when the text is not of that form.
bool parseJoin(const std::string& text, JoinedBoundary& a, JoinedBoundary& b);

/// "auto", "exact", "ruled", "paper" or "general"
const char* modelChoiceName(ModelChoice model);
bool parseModelChoice(const std::string& text, ModelChoice& model);

/// A solved forward job: the model, which model made it and how the solve went.
struct SolvedDForm {
  DForm model;                    ///< the solved pieces, mm
  ModelUsed modelUsed;            ///< which model made the shape, and why that one
  LocalGlobalSummary relaxation;  ///< the local-global start of the solve
  SolverSummary summary;          ///< the Levenberg-Marquardt solve
  int constraintRounds = 0;       ///< multiplier rounds that closed the seam and fixed the outlines
  Timings timings;                ///< how long each stage took, seconds
  double perimeterA = 0;          ///< piece A's joined boundary's length as read, mm
  double perimeterB = 0;          ///< piece B's joined boundary's length as read, mm
  std::string sha256A;            ///< SHA-256 of piece A's input file's bytes as read
  std::string sha256B;            ///< SHA-256 of piece B's input file's bytes as read
  double scaleB = 1.0;            ///< the scale fitPerimeter applied to piece B (1 without it)
  /// The resolved starting pair: arc-length fractions along A's and B's joined boundaries.
  double startFractionA = 0;
  double startFractionB = 0;  ///< see startFractionA
  /// The ruled engine's other states (modelUsed.states after the first, in that order), each
  /// meshed as the answer is; a state that could not be meshed has no faces.
  std::vector<DForm> otherStates;
};

/// The D-Form of two shapes in memory (mm, counter-clockwise loops, as io's readOutline gives
/// them): checked (lengths, joins, the memory the run needs), meshed and solved by the exact model
/// or the paper's. `settings` are in their ranges (the pipeline's settings table checks them:
/// pipeline/settings.h checkSettings, which makeDForm runs first). Messages and errors name a piece
/// by its outline's `source` (a file path), else "piece A" / "piece B". A failed allocation is an
/// error with the resolution that fits.
Result<SolvedDForm> solveDForm(Shape2 a, Shape2 b, const ForwardSettings& settings,
                               MessageSink& sink, const RunHooks& hooks = {});

}  // namespace dform
