// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/run.h"

#include <chrono>
#include <new>

#include "dform/core/input_file.h"
#include "dform/core/interrupt.h"
#include "dform/core/result_folder.h"
#include "dform/io/model_files.h"
#include "dform/model/resources.h"
#include "dform/pipeline/report.h"
#include "run_steps.h"

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

// Each mode's job read and solved.
Result<ForwardRun> solveJob(const ForwardJob& job, MessageSink& sink, const RunHooks& hooks) {
  return runForward(job, sink, hooks);
}
Result<InverseRun> solveJob(const InverseJob& job, MessageSink& sink, const RunHooks& hooks) {
  return runInverse(job, sink, hooks);
}

// The gate on the figures the run measured on its model (the exact body, the round trip): not
// measured twice.
GateReport gateSolved(const SolvedRun& solved, const GateLimits& limits) {
  const InverseRun* inverse = std::get_if<InverseRun>(&solved);
  return runGate(solvedModel(solved), limits, solvedMetrics(solved),
                 inverse ? &inverse->target : nullptr, solvedCurveMatch(solved));
}

// The cutting files laid out once in memory and the layout judged as the gate's last check (so
// that it comes before the verdict), then rendered, stamped FAILED GATE when the gate failed for
// any reason: the stamp is an overlay, so the pattern judged is the pattern written. An export
// that fails leaves the rest of the result to be written (a sheet too small: the export can be
// redone alone). Nothing (nullopt) where no export was asked for.
std::optional<Result<PreparedExport>> prepareJudged(
    const SolvedRun& solved, const std::string& name, const OutputOptions& output,
    const RunSettings& settings, std::optional<GateReport>& gate, MessageSink& sink) {
  if (!settings.cuttingFiles) {
    if (gate)
      gate->checks.push_back(
          notRunCheck("pattern_layout", 0,
                      std::string("no export (") + settingKey(Setting::CuttingFiles) + " false)"));
    return std::nullopt;
  }
  const DForm& model = solvedModel(solved);
  const ModelUsed& used = solvedModelUsed(solved);
  const Result<LaidOutExport> laidOut = layOut(
      model, withFolds(*settings.exporting, foldsToScore(used, model), used.name, sink), name);
  Result<PreparedExport> prepared = laidOut.status();
  if (laidOut.isOk()) {
    if (gate) gate->checks.push_back(layoutCheck(laidOut.value().layout));
    prepared = render(model, laidOut.value(), gate && !gate->passed());
  } else if (gate) {
    gate->checks.push_back(
        notRunCheck("pattern_layout", 0, "the export failed: " + laidOut.status().message()));
  }
  if (!prepared.isOk()) {
    sink.emit(Level::Error, "export: " + prepared.status().text() +
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
Result<WrittenResult> gateAndWrite(const Job& job, const SolvedRun& solved, ResultFolder& folder,
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
  if (settings.cuttingFiles) timings.exportFiles = secondsSince(exportStart);
  const bool gateFailed = gate && !gate->passed();

  // Everything is computed; a Ctrl-C that came meanwhile leaves the output folder as it was.
  if (interrupted) return leftAsItWas(output.outDir, "interrupted");
  const std::string& staging = folder.staging();
  const auto writeStart = Clock::now();
  const InverseRun* inverse = std::get_if<InverseRun>(&solved);
  FileHashes resultFiles;
  Status written = writeModel(staging, solvedModel(solved), &resultFiles);
  if (written.isOk() && inverse) written = writeTargetCurve(staging, inverse->target, &resultFiles);
  if (!written.isOk()) return folder.named(written);
  timings.write = secondsSince(writeStart);
  const bool release = prepared && prepared->isOk() && (!gateFailed || settings.exportAnyway);
  if (release) noteExport(prepared->value(), sink);
  const GateReport* gateReport = gate ? &*gate : nullptr;
  const Result<std::string> reported =
      inverse ? writeInverseReport(staging, job, *inverse, sink.messages(), gateReport, timings,
                                   resultFiles)
              : writeForwardReport(staging, job, std::get<ForwardRun>(solved), sink.messages(),
                                   gateReport, timings, resultFiles);
  if (!reported.isOk()) return folder.named(reported.status());
  if (release)
    if (Status s = writeExport(prepared->value(), staging).status(); !s.isOk())
      return folder.named(s);
  if (Status html = writeReportPage(staging, reported.value(), output.outDir + "/report.json",
                                    release ? &prepared->value() : nullptr, solvedModel(solved));
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
  result.metrics = solvedMetrics(solved);
  result.timings = solvedTimings(solved);
  if (inverse) result.curve = inverse->curveMatch;
  return result;
}

// gateAndWrite, with a stop inside its figures, pictures or export (which poll the stop flag and
// throw) ending the run as a stop between its steps does.
Result<WrittenResult> writeSolved(const Job& job, const SolvedRun& solved, ResultFolder& folder,
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
  Result<SolvedRun> run = std::visit(
      [&](const auto& mode) -> Result<SolvedRun> {
        auto solved = solveJob(mode, sink, hooks);
        if (!solved.isOk()) return solved.status();
        return SolvedRun(std::move(solved).value());
      },
      job.run);
  if (!run.isOk()) return namingFolder(run.status(), output.outDir);
  return writeSolved(job, run.value(), folder, output, settings, sink, interrupted, timings);
}

}  // namespace

Result<RunSettings> checkOutput(const ExportSettings& exporting) {
  if (Status s = checkExportSettings(exporting); !s.isOk()) return s;
  RunSettings settings;
  if (exporting.gate != "none") {
    Result<GateLimits> loaded = loadGate(exporting.gate);
    if (!loaded.isOk()) return loaded.status();
    settings.limits = loaded.value();
  }
  Result<ExportOptions> options = exportOptions(exporting);
  if (!options.isOk()) return options.status();
  settings.exporting = std::make_shared<const ExportOptions>(options.value());
  settings.cuttingFiles = exporting.cuttingFiles;
  settings.exportAnyway = exporting.exportAnyway;
  return settings;
}

Result<WrittenResult> runAndWrite(const Job& job, const OutputOptions& output,
                                  const RunSettings& settings, MessageSink& sink,
                                  const RunHooks& hooks) {
  try {
    return solveAndWrite(job, output, settings, sink, hooks);
  } catch (const std::bad_alloc&) {
    // Past the solve (which says this itself, with its estimate): exporting, measuring, writing.
    return outOfMemory(nullptr, job.resolution(), output.outDir + ": the run");
  }
}

Result<WrittenResult> writeResult(const Job& job, const SolvedRun& run, const OutputOptions& output,
                                  const RunSettings& settings, MessageSink& sink) {
  CommandTimings timings;
  timings.start = Clock::now();
  ResultFolder folder;
  if (Status s = folder.begin(output.outDir, resultFileNames()); !s.isOk()) return s;
  return writeSolved(job, run, folder, output, settings, sink, kNeverStopped, timings);
}

Result<std::vector<SweepRow>> sweepAndWrite(const Job& base, const SweepOptions& options,
                                            const OutputOptions& output,
                                            const RunSettings& settings,
                                            const SweepProgress& progress,
                                            const std::atomic<bool>& interrupted,
                                            MessageSink* notes) {
  // A piece that cannot be read fails every start alike: said once, before the folder is made.
  for (const std::string& piece : base.inputs())
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
                                            const std::function<Status(Job&)>& adjust,
                                            const BatchProgress& progress,
                                            const std::atomic<bool>& interrupted) {
  // Each job as `dform run` runs it; its messages are kept in its report.json.
  const BatchRunner run = [&](const std::string& path, const std::string& dir) -> JobOutcome {
    Result<Job> job = readJobFile(path);
    if (!job.isOk()) return {exitCode(job.status().code()), job.status().message()};
    if (adjust)
      if (Status s = adjust(job.value()); !s.isOk()) return {exitCode(s.code()), s.message()};
    const Result<RunSettings> settings = checkOutput(job.value().exporting);
    if (!settings.isOk())
      return {exitCode(settings.status().code()), path + ": " + settings.status().message()};
    OutputOptions one = output;
    one.outDir = dir;
    MessageSink sink;
    RunHooks hooks;
    hooks.interrupted = &interrupted;
    const Result<WrittenResult> written =
        runAndWrite(job.value(), one, settings.value(), sink, hooks);
    if (!written.isOk()) return {exitCode(written.status().code()), written.status().message()};
    if (!written.value().exported.isOk())
      return {exitCode(written.value().exported.code()), written.value().exported.message()};
    const bool gateFailed = written.value().gate && !written.value().gate->passed();
    return {gateFailed ? exitCode(ErrorCode::GateFailed) : 0, ""};
  };
  return runBatch(jobs, options, output.outDir, run, progress, interrupted);
}

}  // namespace dform
