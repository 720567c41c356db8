#include "pipeline/run.h"

#include <chrono>
#include <new>

#include "core/result_folder.h"
#include "io/model_files.h"
#include "pipeline/report.h"
#include "pipeline/resources.h"
#include "pipeline/run_steps.h"

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

Result<WrittenResult> writeResult(const Job& job, const OutputOptions& output,
                                  const RunSettings& settings, MessageSink& sink,
                                  const RunHooks& hooks) {
  const std::atomic<bool>& interrupted = hooks.interrupted ? *hooks.interrupted : kNeverStopped;
  CommandTimings timings;
  timings.start = Clock::now();
  const bool forward = job.mode == Job::Mode::Forward;
  const std::optional<GateLimits>& limits = settings.limits;
  // The output folder is locked and checked before anything is solved; the result is written
  // into a staging folder beside it and swapped in whole, or not at all.
  ResultFolder folder;
  if (Status s = folder.begin(output.outDir, resultFileNames()); !s.isOk()) return s;

  // Solve first: nothing is written for a run that fails.
  DForm model;
  Result<ForwardRun> forwardRun = Status(ErrorCode::Internal, "not run");
  Result<InverseRun> inverseRun = Status(ErrorCode::Internal, "not run");
  if (forward) {
    forwardRun = runForward(job.forward, sink, hooks);
    if (!forwardRun.isOk()) return namingFolder(forwardRun.status(), output.outDir);
    model = forwardRun.value().model;
  } else {
    inverseRun = runInverse(job.inverse, sink, hooks);
    if (!inverseRun.isOk()) return namingFolder(inverseRun.status(), output.outDir);
    model = inverseRun.value().model;
  }
  std::optional<GateReport> gate;
  if (limits) {
    const auto gateStart = Clock::now();
    // On the figures the run measured on this model (the exact body, the round trip): not twice.
    gate = forward ? runGate(model, *limits, forwardRun.value().metrics, nullptr, nullptr)
                   : runGate(model, *limits, inverseRun.value().metrics, &inverseRun.value().target,
                             &inverseRun.value().curveMatch);
    timings.gate = secondsSince(gateStart);
  }
  if (interrupted) return leftAsItWas(output.outDir, "interrupted");

  // The pattern's layout is the gate's last check, so it is laid out before the verdict; the
  // report is written whatever the export does, so that a failed export (a sheet too small)
  // still leaves the solved result complete and the export can be redone alone.
  const std::string name = jobName(job);
  Result<PreparedExport> prepared = Status(ErrorCode::Internal, "no export");
  const auto exportStart = Clock::now();
  if (output.exportFiles) {
    prepared = prepare(model, *settings.exporting, gate && !gate->passed(), name);
    if (interrupted) return leftAsItWas(output.outDir, "interrupted");
    if (prepared.isOk() && gate) {
      const bool passedBefore = gate->passed();
      gate->checks.push_back(layoutCheck(prepared.value().layout));
      // Failed on its layout alone: lay it out again with the FAILED GATE mark.
      if (passedBefore && !gate->passed()) prepared = prepare(model, *settings.exporting, true, name);
    } else if (!prepared.isOk()) {
      if (gate)
        gate->checks.push_back(
            notRunCheck("pattern_layout", 0, "the export failed: " + prepared.status().message()));
      sink.emit(Level::Error, "export: " + prepared.status().message() +
                                  " (the result is saved; run `dform export " + output.outDir +
                                  "` with another --sheet or --profile)");
    }
    if (prepared.isOk() && !gate && prepared.value().layout.problems() > 0)
      sink.warning("export: " + layoutCheck(prepared.value().layout).detail);
  } else if (gate) {
    gate->checks.push_back(notRunCheck("pattern_layout", 0, "no export (--no-export)"));
  }
  if (output.exportFiles) timings.exportFiles = secondsSince(exportStart);
  const bool gateFailed = gate && !gate->passed();

  // Everything is computed; a Ctrl-C that came meanwhile leaves the output folder as it was.
  if (interrupted) return leftAsItWas(output.outDir, "interrupted");
  const Status exported =
      prepared.isOk() || !output.exportFiles ? Status::ok() : prepared.status();
  // The whole result goes into the staging folder: meshes, report.json (the gate's verdict,
  // measured on the export prepared in memory), the cutting files, report.html. Any failure
  // drops it and leaves the output folder as it was.
  const std::string& staging = folder.staging();
  const auto writeStart = Clock::now();
  Status written = writeModel(staging, model);
  if (written.isOk() && !forward) written = writeTargetCurve(staging, inverseRun.value().target);
  if (!written.isOk()) return folder.named(written);
  timings.write = secondsSince(writeStart);
  const bool release = prepared.isOk() && (!gateFailed || output.exportAnyway);
  if (release) noteExport(prepared.value(), sink);
  const GateReport* gateReport = gate ? &*gate : nullptr;
  const Result<std::string> reported =
      forward ? writeForwardReport(staging, job, forwardRun.value(), sink.messages(), gateReport,
                                   timings)
              : writeInverseReport(staging, job, inverseRun.value(), sink.messages(), gateReport,
                                   timings);
  if (!reported.isOk()) return folder.named(reported.status());
  if (release)
    if (Status s = writeExport(prepared.value(), staging).status(); !s.isOk())
      return folder.named(s);
  if (Status html = writeReportPage(staging, reported.value(), output.outDir + "/report.json",
                                    release ? &prepared.value() : nullptr, model);
      !html.isOk())
    return folder.named(html);
  if (Status s = commitUnlessInterrupted(folder, output.outDir, interrupted); !s.isOk())
    return s;
  // A signal held back during the swap is delivered now: the new result is in place.
  if (interrupted)
    return Status(ErrorCode::Interrupted,
                  output.outDir + ": interrupted; the new result was written completely");
  WrittenResult result;
  result.gate = gate;
  result.exported = exported;
  if (forward) {
    result.metrics = forwardRun.value().metrics;
    result.timings = forwardRun.value().timings;
  } else {
    result.metrics = inverseRun.value().metrics;
    result.curve = inverseRun.value().curveMatch;
    result.timings = inverseRun.value().timings;
  }
  return result;
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
    return writeResult(job, output, settings, sink, hooks);
  } catch (const std::bad_alloc&) {
    // Past the solve (which says this itself, with its estimate): exporting, measuring, writing.
    const int resolution =
        job.mode == Job::Mode::Forward ? job.forward.resolution : job.inverse.resolution;
    return outOfMemory({}, resolution, output.outDir + ": the run");
  }
}

Result<std::vector<SweepRow>> sweepAndWrite(const Job& base, const SweepOptions& options,
                                            const OutputOptions& output,
                                            const RunSettings& settings,
                                            const SweepProgress& progress,
                                            const std::atomic<bool>& interrupted) {
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
  return runSweep(base, options, output.outDir, run, progress, interrupted);
}

Result<std::vector<BatchRow>> batchAndWrite(const std::vector<BatchJob>& jobs,
                                            const BatchOptions& options,
                                            const OutputOptions& output,
                                            const RunSettings& settings,
                                            const SweepProgress& progress,
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
