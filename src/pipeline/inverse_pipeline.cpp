// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/inverse_pipeline.h"

#include <new>

#include "dform/core/input_file.h"
#include "dform/core/interrupt.h"
#include "dform/core/polyline.h"
#include "dform/io/curve_reader.h"
#include "dform/model/resources.h"
#include "dform/model/run_control.h"
#include "dform/pipeline/settings.h"
#include "reference_seams.h"

namespace dform {

using detail::Clock;
using detail::secondsSince;

namespace {

// The figures of solved pieces, and what they say a designer should know.
InverseRun measure(SolvedPieces solved, MessageSink& sink) {
  InverseRun run{std::move(solved), {}, {}};
  measureInverse(run.model, run.target, run.metrics, run.curveMatch);
  const std::string name = curveLabel(run.target);
  // A sheet folded over is what the gate rejects; where the curve leaves its hull, say why.
  if (run.metrics.flipped3d > 0 && !run.pre.onHull)
    sink.warning(
        name + ": the shape folds over itself (" + std::to_string(run.metrics.flipped3d) +
        " triangles): the stretch of the curve inside its convex hull (" + run.pre.summary +
        ") is too deep to bend into a D-Form from the filled pre-D-Form; a shallower dent, or one "
        "spread along more of the curve, can be made (docs/inverse.md, Limits)");
  for (const Piece* p : {&run.model.a, &run.model.b}) {
    Points2 outline(p->seam.size(), 2);
    for (std::size_t k = 0; k < p->seam.size(); ++k) outline.row(k) = p->flat.row(p->seam[k]);
    if (findSelfIntersection(outline))
      sink.warning("piece " + p->name +
                   "'s flat outline overlaps itself: it cannot be cut from one sheet");
  }
  return run;
}

// makePieces' solve and figures, for a curve already checked (read from a file, or checkCurve's).
Result<InverseRun> solveAndMeasure(Curve3 curve, const InverseSettings& settings, MessageSink& sink,
                                   const RunHooks& hooks) {
  Result<SolvedPieces> solved = solvePieces(curve, settings, sink, hooks);
  if (!solved.isOk()) return solved.status();
  try {
    return measure(std::move(solved).value(), sink);
  } catch (const Interrupted& stop) {
    return interruptedDuring(stop.stage());
  } catch (const std::bad_alloc&) {
    return outOfMemory(nullptr, settings.resolution, curveLabel(curve) + ": measuring the run");
  }
}

}  // namespace

Result<InverseRun> makePieces(Curve3 curve, const InverseSettings& settings, MessageSink& sink,
                              const RunHooks& hooks) {
  // As a run from a file: the numbers first, then the curve as its file would be read.
  if (Status s = checkSettings(settings); !s.isOk()) return s;
  Result<Curve3> checked = checkCurve(curve, curveLabel(curve));
  if (!checked.isOk()) return checked.status();
  return solveAndMeasure(std::move(checked).value(), settings, sink, hooks);
}

Result<InverseRun> runInverse(const InverseJob& job, MessageSink& sink, const RunHooks& hooks) {
  // The job's numbers first: a bad one costs no reading.
  if (Status s = checkSettings(job); !s.isOk()) return s;
  const auto start = Clock::now();
  CurveReadOptions readOptions;
  readOptions.forceClosed = job.forceClosed;
  Result<Curve3> curve = readCurve(job.curve, readOptions);
  if (!curve.isOk()) return curve.status();
  curve.value().source = inputName(job.curve);
  const double read = secondsSince(start);
  Result<InverseRun> run = solveAndMeasure(std::move(curve).value(), job, sink, hooks);
  if (!run.isOk()) return run;
  run.value().timings.read += read;
  run.value().timings.total = secondsSince(start);
  return run;
}

}  // namespace dform
