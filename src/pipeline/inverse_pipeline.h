// The inverse run end to end: a 3D seam curve in, the two flat pieces that make it out.
#pragma once

#include <string>

#include "core/messages.h"
#include "core/status.h"
#include "core/types.h"
#include "inverse/inverse_solve.h"
#include "inverse/pre_dform.h"
#include "pipeline/forward_pipeline.h"
#include "validate/metrics.h"

namespace dform {

/// Everything an inverse run needs besides the curve.
struct InverseSettings {
  int resolution = 100;     ///< seam vertices
  InverseInitOptions init;
  InverseOptions solve;
};

/// An inverse job: the settings and the curve's file.
struct InverseJob : InverseSettings {
  std::string curve;        ///< seam curve file (OBJ polyline, JSON points or Bezier)
  bool forceClosed = false; ///< an open OBJ polyline is closed (`--closed`)
};

struct InverseRun {
  DForm model;
  /// exact: the curve lies on its convex hull and the pieces are the hull's two sides unfolded,
  /// zipped by the exact engine; paper: the optimisation from the pre-D-Form.
  ModelUsed modelUsed;
  Curve3 target;           ///< the resampled curve the seam follows (mm)
  Metrics metrics;
  CurveMatch curveMatch;   ///< D_error and the largest seam-to-curve distance
  PreDForm pre;            ///< how the start was built (on-hull or not)
  LocalGlobalSummary relaxation;
  SolverSummary summary;
  double curveLength = 0;  ///< length of the curve as read (mm)
  Timings timings;
};

/// Checks a job's numbers before any work is done (Usage errors).
Status validateInverseJob(const InverseSettings& job);

/// Reads the curve, then makes and measures its pieces as makePieces does. Errors name the file
/// and the problem.
Result<InverseRun> runInverse(const InverseJob& job, MessageSink& sink, const RunHooks& hooks = {});

/// The two flat pieces whose D-Form has `curve` (mm, closed, in memory) as its seam: initialised
/// (pre-D-Form; the exact model where the curve lies on its convex hull), optimised and
/// measured. Messages and errors name the curve by its `source` (a file path), else "the curve".
/// A failed allocation is an error with the resolution that fits.
Result<InverseRun> makePieces(Curve3 curve, const InverseSettings& settings, MessageSink& sink,
                              const RunHooks& hooks = {});

}  // namespace dform
