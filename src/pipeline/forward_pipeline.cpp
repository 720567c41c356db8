// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/forward_pipeline.h"

#include <new>

#include "dform/core/input_file.h"
#include "dform/core/interrupt.h"
#include "dform/io/outline_reader.h"
#include "dform/model/resources.h"
#include "dform/model/run_control.h"
#include "dform/pipeline/settings.h"
#include "reference_seams.h"

namespace dform {

using detail::Clock;
using detail::secondsSince;

Result<Metrics> measureDForm(const SolvedDForm& solved, const ForwardSettings& settings,
                             const std::string& pieces) {
  try {
    return measureModel(solved.model);
  } catch (const Interrupted& stop) {
    return interruptedDuring(stop.stage());
  } catch (const std::bad_alloc&) {
    return outOfMemory(nullptr, settings.resolution, pieces + ": measuring the run");
  }
}

namespace {

// What messages call a piece: its outline's source (a file), else its role.
std::string pieceName(const Shape2& shape, const char* role) {
  return shape.outer.source.empty() ? role : shape.outer.source;
}

// makeDForm's solve and figures, for shapes already checked (read from files, or checkOutline's).
Result<ForwardRun> solveAndMeasure(Shape2 a, Shape2 b, const ForwardSettings& settings,
                                   MessageSink& sink, const RunHooks& hooks) {
  const std::string pieces = pieceName(a, "piece A") + " and " + pieceName(b, "piece B");
  Result<SolvedDForm> solved = solveDForm(std::move(a), std::move(b), settings, sink, hooks);
  if (!solved.isOk()) return solved.status();
  Result<Metrics> metrics = measureDForm(solved.value(), settings, pieces);
  if (!metrics.isOk()) return metrics.status();
  return ForwardRun{std::move(solved).value(), std::move(metrics).value()};
}

}  // namespace

namespace {

// As a run from files checks its job and files: the numbers first, then each shape as its file
// would be read.
Status checkShapes(Shape2& a, Shape2& b, const ForwardSettings& settings) {
  if (Status s = checkSettings(settings); !s.isOk()) return s;
  Result<Shape2> checkedA = checkOutline(a, pieceName(a, "piece A"));
  if (!checkedA.isOk()) return checkedA.status();
  Result<Shape2> checkedB = checkOutline(b, pieceName(b, "piece B"));
  if (!checkedB.isOk()) return checkedB.status();
  a = std::move(checkedA).value();
  b = std::move(checkedB).value();
  return Status::ok();
}

}  // namespace

Result<ForwardRun> makeDForm(Shape2 a, Shape2 b, const ForwardSettings& settings, MessageSink& sink,
                             const RunHooks& hooks) {
  if (Status s = checkShapes(a, b, settings); !s.isOk()) return s;
  return solveAndMeasure(std::move(a), std::move(b), settings, sink, hooks);
}

Result<SolvedDForm> shapeDForm(Shape2 a, Shape2 b, const ForwardSettings& settings,
                               MessageSink& sink, const RunHooks& hooks) {
  if (Status s = checkShapes(a, b, settings); !s.isOk()) return s;
  return solveDForm(std::move(a), std::move(b), settings, sink, hooks);
}

Result<ForwardRun> runForward(const ForwardJob& job, MessageSink& sink, const RunHooks& hooks) {
  // The job's numbers first: a bad one costs no reading.
  if (Status s = checkSettings(job); !s.isOk()) return s;
  const auto start = Clock::now();
  Result<Shape2> a = readOutline(job.pieceA);
  if (!a.isOk()) return a.status();
  Result<Shape2> b = readOutline(job.pieceB);
  if (!b.isOk()) return b.status();
  const double read = secondsSince(start);
  a.value().outer.source = inputName(job.pieceA);
  b.value().outer.source = inputName(job.pieceB);
  Result<ForwardRun> run =
      solveAndMeasure(std::move(a).value(), std::move(b).value(), job, sink, hooks);
  if (!run.isOk()) return run;
  run.value().timings.read += read;
  run.value().timings.total = secondsSince(start);
  return run;
}

}  // namespace dform
