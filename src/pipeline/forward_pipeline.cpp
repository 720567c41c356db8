#include "pipeline/forward_pipeline.h"

#include <new>

#include "core/interrupt.h"
#include "io/outline_reader.h"
#include "model/resources.h"
#include "model/run_control.h"
#include "pipeline/reference_seams.h"

namespace dform {

using detail::Clock;
using detail::secondsSince;

Result<Metrics> measureDForm(const SolvedDForm& solved, const ForwardSettings& settings,
                             const std::string& pieces) {
  try {
    return measureModel(solved.model);
  } catch (const Interrupted& stop) {
    return Status(ErrorCode::Interrupted, std::string("interrupted during ") + stop.stage());
  } catch (const std::bad_alloc&) {
    return outOfMemory(nullptr, settings.resolution, pieces + ": measuring the run");
  }
}

Result<ForwardRun> makeDForm(Shape2 a, Shape2 b, const ForwardSettings& settings, MessageSink& sink,
                             const RunHooks& hooks) {
  const std::string pieces = (a.outer.source.empty() ? "piece A" : a.outer.source) + " and " +
                             (b.outer.source.empty() ? "piece B" : b.outer.source);
  Result<SolvedDForm> solved = solveDForm(std::move(a), std::move(b), settings, sink, hooks);
  if (!solved.isOk()) return solved.status();
  Result<Metrics> metrics = measureDForm(solved.value(), settings, pieces);
  if (!metrics.isOk()) return metrics.status();
  return ForwardRun{std::move(solved).value(), std::move(metrics).value()};
}

Result<ForwardRun> runForward(const ForwardJob& job, MessageSink& sink, const RunHooks& hooks) {
  // The job's numbers first: a bad one costs no reading.
  if (Status s = validateForwardJob(job); !s.isOk()) return s;
  const auto start = Clock::now();
  Result<Shape2> a = readShape(job.pieceA);
  if (!a.isOk()) return a.status();
  Result<Shape2> b = readShape(job.pieceB);
  if (!b.isOk()) return b.status();
  const double read = secondsSince(start);
  a.value().outer.source = job.pieceA;
  b.value().outer.source = job.pieceB;
  Result<ForwardRun> run = makeDForm(std::move(a).value(), std::move(b).value(), job, sink, hooks);
  if (!run.isOk()) return run;
  run.value().timings.read += read;
  run.value().timings.total = secondsSince(start);
  return run;
}

}  // namespace dform
