#include "pipeline/inverse_pipeline.h"

#include <cmath>

#include "core/polyline.h"
#include "io/curve_reader.h"
#include "pipeline/resources.h"
#include "pipeline/run_util.h"

namespace dform {

using detail::Clock;
using detail::format;
using detail::secondsSince;

Status validateInverseJob(const InverseJob& job) {
  auto usage = [](const std::string& text) { return Status(ErrorCode::Usage, text); };
  // The pre-D-Form's search is cubic in the curve's points: 1000 took 25 s here, so 2000 take
  // about 4 minutes; beyond that a run would look hung.
  if (job.resolution < 8 || job.resolution > 2000)
    return usage("resolution must be between 8 and 2000 curve points, got " +
                 std::to_string(job.resolution));
  const InverseWeights& w = job.solve.weights;
  for (double weight : {w.isometry, w.closeness, w.smooth3d, w.smooth2d})
    if (!(weight >= 0.0 && std::isfinite(weight))) return usage("weights must be finite and >= 0");
  std::string why;
  if (!job.solve.solver.isValid(&why)) return usage("solver options: " + why);
  return Status::ok();
}

Result<InverseRun> runInverse(const InverseJob& job, MessageSink& sink, const RunHooks& hooks) {
  if (Status s = validateInverseJob(job); !s.isOk()) return s;
  const auto start = Clock::now();
  InverseRun run;

  CurveReadOptions readOptions;
  readOptions.forceClosed = job.forceClosed;
  Result<Curve3> curve = readCurve(job.curve, readOptions);
  if (!curve.isOk()) return curve.status();
  // Measured on the samples, a curve of n points gives pieces of 0.10 n^2 to 0.18 n^2 vertices
  // together; the pre-D-Form's tables (cost, apex, normal, side per pair of points) hold 37 n^2
  // bytes.
  const double n = job.resolution;
  if (Status fits = checkMemory(0.2 * n * n, 37.0 * n * n, job.resolution, job.curve + ": the run"); !fits.isOk())
    return fits;
  run.curveLength = closedLength(curve.value().points);
  // Compensated for chord loss (core/polyline.h) so that the seam, and the flat outlines isometric
  // to it, keep the curve's length: inscribed, 100 points fall short of a tennis-ball seam by 0.11 %.
  run.target.points = compensateChordLoss(resampleClosed(curve.value().points, job.resolution));
  run.target.source = job.curve;
  run.timings.read = secondsSince(start);
  sink.info(format("curve: %.0f points, length %.3f mm", double(curve.value().points.rows()),
                   run.curveLength));

  const auto initStart = Clock::now();
  Result<InverseInit> init = initialiseInverse(run.target, job.init);
  if (!init.isOk()) return init.status();
  run.pre = init.value().pre;
  run.timings.mesh = secondsSince(initStart);
  sink.info("pre-D-Form: " + run.pre.summary);
  sink.info("meshed piece A with " + std::to_string(init.value().model.a.flat.rows()) +
            " vertices, piece B with " + std::to_string(init.value().model.b.flat.rows()));

  const auto solveStart = Clock::now();
  InverseOptions options = job.solve;
  detail::relaxOnlyIfLarge(init.value().model.a.flat.rows() + init.value().model.b.flat.rows(), options.solver,
                           options.relaxation);
  bool interrupted = false;
  detail::connectHooks(options.solver, hooks, interrupted);
  InverseResult solved = solveInverse(init.value().model, run.target.points, options);
  run.timings.solve = secondsSince(solveStart);
  if (interrupted) return Status(ErrorCode::Interrupted, "interrupted during the solve");
  if (!solved.summary.usable())
    return Status(ErrorCode::SolveFailed, job.curve + ": the solver failed: " + solved.summary.message);
  sink.emit(Level::Debug, format("local-global start: %.0f iterations, energy %.4g -> %.4g",
                   solved.relaxation.iterations, solved.relaxation.initialEnergy,
                   solved.relaxation.finalEnergy));
  sink.info("solve: " + solved.summary.briefReport());
  run.model = std::move(solved.model);
  run.relaxation = solved.relaxation;
  run.summary = std::move(solved.summary);
  run.metrics = computeMetrics(run.model);
  run.curveMatch = computeCurveMatch(run.model, run.target);
  for (const Piece* p : {&run.model.a, &run.model.b}) {
    Points2 outline(p->seam.size(), 2);
    for (std::size_t k = 0; k < p->seam.size(); ++k) outline.row(k) = p->flat.row(p->seam[k]);
    if (findSelfIntersection(outline))
      sink.warning("piece " + p->name + "'s flat outline overlaps itself: it cannot be cut from one sheet");
  }
  run.timings.total = secondsSince(start);
  return run;
}

}  // namespace dform
