#include "dform/pipeline/run.h"

#include <chrono>
#include <new>

#include "dform/core/input_file.h"
#include "dform/core/interrupt.h"
#include "dform/core/result_folder.h"
#include "dform/io/model_files.h"
#include "dform/model/resources.h"
#include "dform/pipeline/report.h"
#include "dform/pipeline/run_steps.h"

namespace dform {

namespace {

using Clock = std::chrono::steady_clock;

const std::atomic<bool> kNeverStopped{false};

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A run's error; an interrupted solve, which names no file, names the folder it leaves as it was.
Status namingFolder(const Status& status, const std::string& dir) {
  const bool unnamed = status.message().rfind("interrupted", 0) == 0;
  return status.code() == ErrorCode::Interrupted && unnamed ? leftAsItWas(dir, status.message())
                                                            : status;
}

// A run's solved result, of either mode (exactly one is set).
struct Solved {
  const ForwardRun* forward = nullptr;
  const InverseRun* inverse = nullptr;
  const DForm& model() const { return forward ? forward->model : inverse->model; }
};

// The gate on the figures the run measured on its model (the exact body, the round trip): not
// measured twice.
GateReport gateSolved(const Solved& solved, const GateLimits& limits) {
  return solved.forward ? runGate(solved.model(), limits, solved.forward->metrics, nullptr, nullptr)
                        : runGate(solved.model(), limits, solved.inverse->metrics,
                                  &solved.inverse->target, &solved.inverse->curveMatch);
}

// The cutting files laid out once in memory and the layout judged as the gate's last check (so
// that it comes before the verdict), then rendered, stamped FAILED GATE when the gate failed for
// any reason: the stamp is an overlay, so the pattern judged is the pattern written. An export
// that fails leaves the rest of the result to be written (a sheet too small: the export can be
// redone alone). Nothing (nullopt) where no export was asked for.
std::optional<Result<PreparedExport>> prepareJudged(const Solved& solved, const std::string& name,
                                                    const OutputOptions& output,
                                                    const RunSettings& settings,
                                                    std::optional<GateReport>& gate,
                                                    MessageSink& sink) {
  if (!output.exportFiles) {
    if (gate) gate->checks.push_back(notRunCheck("pattern_layout", 0, "no export (--no-export)"));
    return std::nullopt;
  }
  const ModelUsed& used = solved.forward ? solved.forward->modelUsed : solved.inverse->modelUsed;
  const Result<LaidOutExport> laidOut = layOut(
      solved.model(),
      withFolds(*settings.exporting, foldsToScore(used, solved.model()), used.name, sink), name);
  Result<PreparedExport> prepared = laidOut.status();
  if (laidOut.isOk()) {
    if (gate) gate->checks.push_back(layoutCheck(laidOut.value().layout));
    prepared = render(solved.model(), laidOut.value(), gate && !gate->passed());
  } else if (gate) {
    gate->checks.push_back(
        notRunCheck("pattern_layout", 0, "the export failed: " + laidOut.status().message()));
  }
  if (!prepared.isOk()) {
    sink.emit(Level::Error, "export: " + prepared.status().message() +
                                " (the result is saved: `dform export " + output.outDir +
                                "` exports it again with other options)");
  } else if (!gate && prepared.value().layout.problems() > 0) {
    sink.warning("export: " + layoutCheck(prepared.value().layout).detail);
  }
  return prepared;
}

// Gates, lays out and writes a solved run into `folder` (begun before the solve), then swaps it
// in: meshes, report.json (the gate's verdict, measured on the export prepared in memory), the
// cutting files when released, report.html. Any failure drops it and leaves the output folder
// as it was.
Result<WrittenResult> gateAndWrite(const Job& job, const Solved& solved, ResultFolder& folder,
                                   const OutputOptions& output, const RunSettings& settings,
                                   MessageSink& sink, const std::atomic<bool>& interrupted,
                                   CommandTimings timings) {
  std::optional<GateReport> gate;
  if (settings.limits) {
    const auto gateStart = Clock::now();
    gate = gateSolved(solved, *settings.limits);
    timings.gate = secondsSince(gateStart);
  }
  if (interrupted) return leftAsItWas(output.outDir, "interrupted");
  const auto exportStart = Clock::now();
  const std::optional<Result<PreparedExport>> prepared =
      prepareJudged(solved, jobName(job), output, settings, gate, sink);
  if (output.exportFiles) timings.exportFiles = secondsSince(exportStart);
  const bool gateFailed = gate && !gate->passed();

  // Everything is computed; a Ctrl-C that came meanwhile leaves the output folder as it was.
  if (interrupted) return leftAsItWas(output.outDir, "interrupted");
  const std::string& staging = folder.staging();
  const auto writeStart = Clock::now();
  FileHashes resultFiles;
  Status written = writeModel(staging, solved.model(), &resultFiles);
  if (written.isOk() && solved.inverse)
    written = writeTargetCurve(staging, solved.inverse->target, &resultFiles);
  if (!written.isOk()) return folder.named(written);
  timings.write = secondsSince(writeStart);
  const bool release = prepared && prepared->isOk() && (!gateFailed || output.exportAnyway);
  if (release) noteExport(prepared->value(), sink);
  const GateReport* gateReport = gate ? &*gate : nullptr;
  const Result<std::string> reported =
      solved.forward ? writeForwardReport(staging, job, *solved.forward, sink.messages(),
                                          gateReport, timings, resultFiles)
                     : writeInverseReport(staging, job, *solved.inverse, sink.messages(),
                                          gateReport, timings, resultFiles);
  if (!reported.isOk()) return folder.named(reported.status());
  if (release)
    if (Status s = writeExport(prepared->value(), staging).status(); !s.isOk())
      return folder.named(s);
  if (Status html = writeReportPage(staging, reported.value(), output.outDir + "/report.json",
                                    release ? &prepared->value() : nullptr, solved.model());
      !html.isOk())
    return folder.named(html);
  if (Status s = commitUnlessInterrupted(folder, output.outDir, interrupted, &sink); !s.isOk())
    return s;
  // A signal held back during the swap is delivered now: the new result is in place.
  if (interrupted)
    return Status(ErrorCode::Interrupted,
                  output.outDir + ": interrupted; the new result was written completely");
  WrittenResult result;
  result.gate = gate;
  result.exported = !prepared || prepared->isOk() ? Status::ok() : prepared->status();
  result.metrics = solved.forward ? solved.forward->metrics : solved.inverse->metrics;
  result.timings = solved.forward ? solved.forward->timings : solved.inverse->timings;
  if (solved.inverse) result.curve = solved.inverse->curveMatch;
  return result;
}

// gateAndWrite, with a stop inside its figures, pictures or export (which poll the stop flag and
// throw) ending the run as a stop between its steps does.
Result<WrittenResult> writeSolved(const Job& job, const Solved& solved, ResultFolder& folder,
                                  const OutputOptions& output, const RunSettings& settings,
                                  MessageSink& sink, const std::atomic<bool>& interrupted,
                                  CommandTimings timings) {
  try {
    return gateAndWrite(job, solved, folder, output, settings, sink, interrupted, timings);
  } catch (const Interrupted& stop) {
    return leftAsItWas(output.outDir, interruptedDuring(stop.stage()).message());
  }
}

// The output folder is locked and checked before anything is solved; nothing is written for a
// run that fails.
Result<WrittenResult> solveAndWrite(const Job& job, const OutputOptions& output,
                                    const RunSettings& settings, MessageSink& sink,
                                    const RunHooks& hooks) {
  const std::atomic<bool>& interrupted = hooks.interrupted ? *hooks.interrupted : kNeverStopped;
  CommandTimings timings;
  timings.start = Clock::now();
  ResultFolder folder;
  if (Status s = folder.begin(output.outDir, resultFileNames()); !s.isOk()) return s;
  if (job.mode == Job::Mode::Forward) {
    const Result<ForwardRun> run = runForward(job.forward, sink, hooks);
    if (!run.isOk()) return namingFolder(run.status(), output.outDir);
    return writeSolved(job, {&run.value(), nullptr}, folder, output, settings, sink, interrupted,
                       timings);
  }
  const Result<InverseRun> run = runInverse(job.inverse, sink, hooks);
  if (!run.isOk()) return namingFolder(run.status(), output.outDir);
  return writeSolved(job, {nullptr, &run.value()}, folder, output, settings, sink, interrupted,
                     timings);
}

// A result made in memory, written as a run writes its own.
Result<WrittenResult> writeMade(const Job& job, const Solved& solved, const OutputOptions& output,
                                const RunSettings& settings, MessageSink& sink) {
  CommandTimings timings;
  timings.start = Clock::now();
  ResultFolder folder;
  if (Status s = folder.begin(output.outDir, resultFileNames()); !s.isOk()) return s;
  return writeSolved(job, solved, folder, output, settings, sink, kNeverStopped, timings);
}

}  // namespace

Result<RunSettings> checkOutput(const OutputOptions& output) {
  RunSettings settings;
  if (output.gate != "none") {
    Result<GateLimits> loaded = loadGate(output.gate);
    if (!loaded.isOk()) return loaded.status();
    settings.limits = loaded.value();
  }
  Result<ExportOptions> exporting = exportOptions(output);
  if (!exporting.isOk()) return exporting.status();
  settings.exporting = std::make_shared<const ExportOptions>(exporting.value());
  return settings;
}

Result<WrittenResult> runAndWrite(const Job& job, const OutputOptions& output,
                                  const RunSettings& settings, MessageSink& sink,
                                  const RunHooks& hooks) {
  try {
    return solveAndWrite(job, output, settings, sink, hooks);
  } catch (const std::bad_alloc&) {
    // Past the solve (which says this itself, with its estimate): exporting, measuring, writing.
    const int resolution =
        job.mode == Job::Mode::Forward ? job.forward.resolution : job.inverse.resolution;
    return outOfMemory(nullptr, resolution, output.outDir + ": the run");
  }
}

Result<WrittenResult> writeResult(const ForwardJob& job, const ForwardRun& run,
                                  const OutputOptions& output, const RunSettings& settings,
                                  MessageSink& sink) {
  Job whole;
  whole.forward = job;
  return writeMade(whole, {&run, nullptr}, output, settings, sink);
}

Result<WrittenResult> writeResult(const InverseJob& job, const InverseRun& run,
                                  const OutputOptions& output, const RunSettings& settings,
                                  MessageSink& sink) {
  Job whole;
  whole.mode = Job::Mode::Inverse;
  whole.inverse = job;
  return writeMade(whole, {nullptr, &run}, output, settings, sink);
}

Result<std::vector<SweepRow>> sweepAndWrite(const Job& base, const SweepOptions& options,
                                            const OutputOptions& output,
                                            const RunSettings& settings,
                                            const SweepProgress& progress,
                                            const std::atomic<bool>& interrupted,
                                            MessageSink* notes) {
  // A piece that cannot be read fails every start alike: said once, before the folder is made.
  for (const std::string& piece : {base.forward.pieceA, base.forward.pieceB})
    if (const Result<std::string> read = readInputFile(piece); !read.isOk()) return read.status();
  // Each start runs as `dform forward` would, into its own folder, its messages kept in its
  // report.json (its sink has no listener: many runs at once would interleave on a terminal).
  const SweepRunner run = [&](const Job& job, const std::string& dir, MessageSink& sink) {
    OutputOptions one = output;
    one.outDir = dir;
    RunHooks hooks;
    hooks.interrupted = &interrupted;
    const Result<WrittenResult> written = runAndWrite(job, one, settings, sink, hooks);
    return written.isOk() ? written.value().exported : written.status();
  };
  return runSweep(base, options, output.outDir, run, progress, interrupted, notes);
}

Result<std::vector<BatchRow>> batchAndWrite(const std::vector<BatchJob>& jobs,
                                            const BatchOptions& options,
                                            const OutputOptions& output,
                                            const RunSettings& settings,
                                            const BatchProgress& progress,
                                            const std::atomic<bool>& interrupted) {
  // Each job as `dform run` runs it; its messages are kept in its report.json.
  const BatchRunner run = [&](const std::string& path, const std::string& dir) -> JobOutcome {
    const Result<Job> job = readJobFile(path);
    if (!job.isOk()) return {exitCode(job.status().code()), job.status().message()};
    OutputOptions one = output;
    one.outDir = dir;
    MessageSink sink;
    RunHooks hooks;
    hooks.interrupted = &interrupted;
    const Result<WrittenResult> written = runAndWrite(job.value(), one, settings, sink, hooks);
    if (!written.isOk()) return {exitCode(written.status().code()), written.status().message()};
    if (!written.value().exported.isOk())
      return {exitCode(written.value().exported.code()), written.value().exported.message()};
    const bool gateFailed = written.value().gate && !written.value().gate->passed();
    return {gateFailed ? exitCode(ErrorCode::GateFailed) : 0, ""};
  };
  return runBatch(jobs, options, output.outDir, run, progress, interrupted);
}

}  // namespace dform
