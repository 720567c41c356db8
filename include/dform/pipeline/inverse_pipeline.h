// SPDX-License-Identifier: GPL-3.0-or-later
// The inverse run end to end: a 3D seam curve in, the two flat pieces that make it out.
#pragma once

#include <string>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/inverse/pieces_from_curve.h"
#include "dform/validate/metrics.h"

namespace dform {

/// An inverse job: the settings and the curve's file.
struct InverseJob : InverseSettings {
  std::string curve;         ///< seam curve file (OBJ polyline, JSON points or Bezier)
  bool forceClosed = false;  ///< an open OBJ polyline is closed (`--closed`)
};

/// An inverse run's result: the solved pieces, their figures and how near the seam is to the curve.
struct InverseRun : SolvedPieces {
  Metrics metrics;        ///< the figures measured on the solved pieces (report.json's "metrics")
  CurveMatch curveMatch;  ///< D_error and the largest seam-to-curve distance
};

/// Reads the curve, then makes and measures its pieces as makePieces does. Errors name the file
/// and the problem.
Result<InverseRun> runInverse(const InverseJob& job, MessageSink& sink, const RunHooks& hooks = {});

/// The two flat pieces whose D-Form has `curve` (mm, closed, in memory) as its seam, checked as
/// a run from a file checks its job and file (the settings table's checkSettings, then io's
/// checkCurve: the same codes and messages, the curve named by its `source`, else "the curve"),
/// solved as inverse's solvePieces does, and measured.
Result<InverseRun> makePieces(Curve3 curve, const InverseSettings& settings, MessageSink& sink,
                              const RunHooks& hooks = {});

}  // namespace dform
