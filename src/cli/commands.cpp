#include "cli/commands.h"

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <nlohmann/json.hpp>
#include <set>

#include "cli/terminal.h"
#include "core/result_folder.h"
#include "export/exporter.h"
#include "io/curve_reader.h"
#include "io/model_files.h"
#include "pipeline/report.h"
#include "pipeline/resources.h"
#include "report/html_report.h"
#include "validate/gate.h"
#include "validate/metrics.h"

namespace dform::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Holds SIGINT and SIGTERM back for its lifetime; one that came meanwhile is delivered when it
// ends (a first one sets the run's flag, a second one ends the program: see main.cpp).
class StopSignalsHeld {
 public:
  StopSignalsHeld() {
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigprocmask(SIG_BLOCK, &stop, &previous_);
  }
  ~StopSignalsHeld() { sigprocmask(SIG_SETMASK, &previous_, nullptr); }
  StopSignalsHeld(const StopSignalsHeld&) = delete;
  StopSignalsHeld& operator=(const StopSignalsHeld&) = delete;

 private:
  sigset_t previous_;
};

int fail(const Status& status) {
  Terminal::error(status.message());
  return exitCode(status.code());
}

// "600x400", "600x400mm", "23.6x15.7in" -> millimetres.
Result<std::pair<double, double>> parseSheet(const std::string& text) {
  double w = 0, h = 0;
  char unit[8] = "";
  const int n = std::sscanf(text.c_str(), "%lfx%lf%7s", &w, &h, unit);
  const std::string u = unit;
  const double scale = u.empty() || u == "mm" ? 1.0 : u == "cm" ? 10.0 : u == "in" ? 25.4 : 0.0;
  if (n < 2 || scale == 0.0 || !(w > 0 && h > 0 && std::isfinite(w) && std::isfinite(h)))
    return Status(ErrorCode::Usage,
                  "--sheet must look like 600x400mm (units mm, cm or in), got '" + text + "'");
  return std::make_pair(w * scale, h * scale);
}

Result<GateLimits> loadGate(const std::string& nameOrPath) {
  const bool preset =
      nameOrPath.find('/') == std::string::npos && nameOrPath.find(".json") == std::string::npos;
  if (preset) {
    // A preset name that is not one is a usage mistake (2), as an unknown export profile is; a
    // gate file that cannot be read is unreadable input (3).
    const fs::path file = fs::path(templatesDir()) / "gates" / (nameOrPath + ".json");
    if (!fs::exists(file)) {
      std::set<std::string> names;
      for (const auto& entry : fs::directory_iterator(file.parent_path()))
        if (entry.path().extension() == ".json") names.insert(entry.path().stem().string());
      std::string known;
      for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
      return Status(ErrorCode::Usage, "--gate: unknown gate \"" + nameOrPath + "\" (known: " +
                                          known + ", or a gate .json file)");
    }
    return readGateFile(file.string());
  }
  // "gates/strict.json" as the docs write it: a path relative to templates/ when not one here.
  const std::string inTemplates = templatesDir() + "/" + nameOrPath;
  if (!fs::exists(nameOrPath) && fs::path(nameOrPath).is_relative() && fs::exists(inTemplates))
    return readGateFile(inTemplates);
  return readGateFile(nameOrPath);
}

// The export options the command line asks for, checked before anything is solved: Usage with a
// one-line message for a bad value.
Result<ExportOptions> exportOptions(const OutputOptions& output) {
  ExportOptions options;
  options.profile = output.profile;
  options.templatesDir = templatesDir();
  if (!output.sheet.empty()) {
    Result<std::pair<double, double>> sheet = parseSheet(output.sheet);
    if (!sheet.isOk()) return sheet.status();
    options.sheetWidthMm = sheet.value().first;
    options.sheetHeightMm = sheet.value().second;
    options.sheetGiven = true;
  }
  if (!output.page.empty() && !pageSizeMm(output.page))
    return Status(ErrorCode::Usage, "--page must be A4, Letter, A3, Tabloid or a size such as "
                                    "200x300mm, got '" + output.page + "'");
  options.page = output.page;
  if (output.scale == "fit") {
    options.scaleToFit = true;
  } else if (!output.scale.empty()) {
    double value = 0;
    char rest[4] = "";
    const int n = std::sscanf(output.scale.c_str(), "%lf%3s", &value, rest);
    const std::string unit = rest;
    if (n < 1 || !(unit.empty() || unit == "%"))
      return Status(ErrorCode::Usage,
                    "--scale must be a number (0.8), a percentage (80%) or fit, got '" +
                        output.scale + "'");
    options.scale = unit == "%" ? value / 100 : value;
  }
  if (output.tabWidthMm) options.tabWidthMm = *output.tabWidthMm;
  if (output.tickSpacingMm) options.tickSpacingMm = *output.tickSpacingMm;
  if (!output.tabs.empty()) {
    options.tabSide = tabSideNamed(output.tabs);
    if (!options.tabSide)
      return Status(ErrorCode::Usage,
                    "--tabs must be a, b, alternate or none, got '" + output.tabs + "'");
  }
  options.gltfBinary = !output.gltfText;
  options.title = output.title;
  if (Status s = checkExportOptions(options); !s.isOk()) return s;
  if (output.exportFiles) {  // the profile is read once, now, not after the solve
    Result<Profile> profile = loadProfile(options.profile, options.templatesDir);
    if (!profile.isOk()) return profile.status();
    options.profileOverride = profile.value();
    options.useProfileOverride = true;
  }
  return options;
}

// Lays out and renders the cutting patterns and previews of `model`, not yet written. The glTF
// preview carries the curvature map the report shows (COLOR_0).
Result<PreparedExport> prepare(const DForm& model, ExportOptions options, bool failedGate,
                               const std::string& jobName) {
  options.jobName = jobName;
  options.failedGateMark = failedGate;
  const Eigen::VectorXd curvature[2] = {curvatureMap(model.a), curvatureMap(model.b)};
  options.curvatureA.assign(curvature[0].data(), curvature[0].data() + curvature[0].size());
  options.curvatureB.assign(curvature[1].data(), curvature[1].data() + curvature[1].size());
  return prepareExport(model, options);
}

// A run's job name: its first input's file name.
std::string jobName(const Job& job) {
  return fs::path(job.mode == Job::Mode::Forward ? job.forward.pieceA : job.inverse.curve)
      .stem()
      .string();
}

// A saved result's job name, from the job its report.json records; the folder's name when there is
// no readable job.
std::string savedJobName(const std::string& dir) {
  const fs::path path = fs::path(dir) / "report.json";
  std::ifstream in(path);
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  if (report.is_object() && report.contains("job")) {
    Result<Job> job = parseJobJson(report["job"].dump(), path.string(), dir);
    if (job.isOk()) return jobName(job.value());
  }
  return fs::path(dir).filename().string();
}

// The gate's fabrication check: the laid-out pattern fits the sheet and nothing on it overlaps.
CheckResult layoutCheck(const LayoutFindings& f) {
  const std::string detail =
      f.problems() == 0 ? "every path on the sheet; tabs, pieces and labels clear of each other"
                        : std::to_string(f.outsideSheet) + " off the sheet, " +
                              std::to_string(f.overlappingTabs) + " overlapping tab pairs, " +
                              std::to_string(f.tabsOverPieces) + " tabs over a piece, " +
                              std::to_string(f.overlappingPieces) + " overlapping pieces, " +
                              std::to_string(f.labelsOutside) + " labels outside their piece, " +
                              std::to_string(f.overlappingLabels) + " overlapping label pairs, " +
                              std::to_string(f.titleOverlaps) +
                              " title lines over a piece or mark; first: " + f.example;
  return judgeCheck("pattern_layout", f.problems(), 0, detail);
}

// Says what a prepared export holds, before it is written (so that the report has it).
void noteExport(const PreparedExport& prepared, MessageSink& sink) {
  for (const std::string& note : prepared.summary.messages) sink.info("export: " + note);
  sink.info("export (" + prepared.summary.profile + "): " + std::to_string(prepared.files.size()) +
            " files");
}

// Every file a run or an export writes into a result folder: the only files a folder that is
// replaced as a whole may hold.
std::set<std::string> resultFileNames() {
  std::set<std::string> names = {ModelFileNames::aFlat, ModelFileNames::a3d,
                                 ModelFileNames::bFlat, ModelFileNames::b3d,
                                 ModelFileNames::targetCurve, "report.json", "report.html"};
  for (const std::string& name : exportFileNames()) names.insert(name);
  return names;
}

// An interrupt that stops a command before its result is in place, naming the folder.
Status leftAsItWas(const std::string& dir, const std::string& what) {
  return {ErrorCode::Interrupted, dir + ": " + what + "; the folder was left as it was"};
}

// A run's error; an interrupted solve, which names no file, names the folder it leaves as it was.
Status namingFolder(const Status& status, const std::string& dir) {
  const bool unnamed = status.message().rfind("interrupted", 0) == 0;
  return status.code() == ErrorCode::Interrupted && unnamed ? leftAsItWas(dir, status.message())
                                                            : status;
}

// Swaps the staged result in with SIGINT and SIGTERM held back, so that a signal cannot cut the
// swap short; one that came before it leaves the folder as it was.
Status commitUnlessInterrupted(ResultFolder& folder, const std::string& dir,
                               const std::atomic<bool>& interrupted) {
  const StopSignalsHeld held;
  if (interrupted) return leftAsItWas(dir, "interrupted");
  return folder.commit();
}

// An inverse result's target curve, when the folder holds one, checked against the seam.
Result<std::optional<Curve3>> readSavedTarget(const std::string& dir, const DForm& model) {
  const std::string curvePath = (fs::path(dir) / ModelFileNames::targetCurve).string();
  if (!fs::exists(curvePath)) return std::optional<Curve3>();
  Result<Curve3> curve = readCurve(curvePath);
  if (!curve.isOk()) return curve.status();
  if (std::size_t(curve.value().points.rows()) != model.a.seam.size())
    return Status(ErrorCode::InputInvalid,
                  curvePath + ": has a different number of points than the seam");
  return std::optional<Curve3>(curve.value());
}

void printFigures(const Metrics& m, const CurveMatch* curve, const Timings& t,
                  const std::string& dir) {
  std::fprintf(stdout, "L_error %.4f %%   L_max %.3f %%   ", 100 * m.L_error, 100 * m.L_max);
  if (curve)
    std::fprintf(stdout, "D_error %.2e   curve distance max %.2e mm\n", curve->D_error,
                 curve->curve_distance_max_mm);
  else
    std::fprintf(stdout, "B_error %.2e   seam gap %.2e mm\n", m.B_error, m.seam_gap_mm);
  std::fprintf(stdout,
               "gauss_max %.4f rad   flipped %d   degenerate %d   seam lengths %.3f / %.3f mm\n",
               m.gauss_max, m.flipped_2d + m.flipped_3d, m.degenerate_2d + m.degenerate_3d,
               m.seam_length_a_mm, m.seam_length_b_mm);
  std::fprintf(stdout, "solved in %.3f s (read %.3f, mesh %.3f, solve %.3f); results in %s\n",
               t.total, t.read, t.mesh, t.solve, dir.c_str());
}

void printGate(const GateReport& gate) {
  std::fprintf(stdout, "%-20s %12s %12s  %s\n", "check", "value", "limit", "verdict");
  for (const CheckResult& c : gate.checks)
    std::fprintf(stdout, "%-20s %12.4g %12.4g  %s%s%s\n", c.name.c_str(), c.value, c.limit,
                 verdictName(c.verdict), c.verdict == CheckResult::Verdict::Pass ? "" : ": ",
                 c.verdict == CheckResult::Verdict::Pass ? "" : c.detail.c_str());
  std::fprintf(stdout, "gate: %s (%s: %d failed, %d not run)\n",
               gate.passed() ? "PASSED" : "FAILED", gate.name.c_str(), gate.failed(),
               gate.notRun());
}

}  // namespace

int exitCode(ErrorCode code) {
  switch (code) {
    case ErrorCode::Ok: return 0;
    case ErrorCode::Internal: return 1;
    case ErrorCode::Usage: return 2;
    case ErrorCode::InputUnreadable: return 3;
    case ErrorCode::InputInvalid: return 4;
    case ErrorCode::SolveFailed: return 5;
    case ErrorCode::OutputFailed: return 6;
    case ErrorCode::GateFailed: return 7;
    case ErrorCode::Interrupted: return 130;
  }
  return 1;
}

std::string templatesDir() {
  const char* env = std::getenv("DFORM_TEMPLATES");
  return env && *env ? env : DFORM_TEMPLATES_DIR;
}

namespace {

// A run's settings, checked before anything is solved: the gate's limits (none: no gate) and the
// export options.
struct RunSettings {
  std::optional<GateLimits> limits;
  ExportOptions exporting;
};

// What a result written into its folder shows on the terminal afterwards. `exported` is the
// export's error when the result was saved without its cutting files.
struct WrittenResult {
  Metrics metrics;
  std::optional<CurveMatch> curve;
  Timings timings;
  std::optional<GateReport> gate;
  Status exported = Status::ok();
};

Result<RunSettings> runSettings(const OutputOptions& output) {
  RunSettings settings;
  if (output.gate != "none") {
    Result<GateLimits> loaded = loadGate(output.gate);
    if (!loaded.isOk()) return loaded.status();
    settings.limits = loaded.value();
  }
  Result<ExportOptions> exporting = exportOptions(output);
  if (!exporting.isOk()) return exporting.status();
  settings.exporting = exporting.value();
  return settings;
}

Result<WrittenResult> writeResult(const Job& job, const OutputOptions& output,
                                  const RunSettings& settings, const std::atomic<bool>& interrupted,
                                  MessageSink& sink, const RunHooks& hooks) {
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
    prepared = prepare(model, settings.exporting, gate && !gate->passed(), name);
    if (interrupted) return leftAsItWas(output.outDir, "interrupted");
    if (prepared.isOk() && gate) {
      const bool passedBefore = gate->passed();
      gate->checks.push_back(layoutCheck(prepared.value().layout));
      // Failed on its layout alone: lay it out again with the FAILED GATE mark.
      if (passedBefore && !gate->passed()) prepared = prepare(model, settings.exporting, true, name);
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
  const Status reported =
      forward ? writeForwardReport(staging, job, forwardRun.value(), sink.messages(), gateReport,
                                   timings)
              : writeInverseReport(staging, job, inverseRun.value(), sink.messages(), gateReport,
                                   timings);
  if (!reported.isOk()) return folder.named(reported);
  if (release)
    if (Status s = writeExport(prepared.value(), staging).status(); !s.isOk())
      return folder.named(s);
  if (Status html = writeReportHtml(staging, model, templatesDir()); !html.isOk())
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

int runJob(const Job& job, const OutputOptions& output, const std::atomic<bool>& interrupted) {
  Terminal terminal(output.quiet);
  MessageSink sink(terminal.listener());
  const bool forward = job.mode == Job::Mode::Forward;
  RunHooks hooks;
  hooks.interrupted = &interrupted;
  hooks.onIteration = [&](const char* stage, const IterationSummary& it) {
    terminal.progress(forward ? stage : std::string(stage) + " (inverse)", it);
  };
  const Result<RunSettings> settings = runSettings(output);
  if (!settings.isOk()) return fail(settings.status());
  Result<WrittenResult> result = Status();
  try {
    result = writeResult(job, output, settings.value(), interrupted, sink, hooks);
  } catch (const std::bad_alloc&) {
    // Past the solve (which says this itself, with its estimate): exporting, measuring, writing.
    const int resolution = forward ? job.forward.resolution : job.inverse.resolution;
    result = outOfMemory({}, resolution, output.outDir + ": the run");
  }
  terminal.clearProgress();
  if (!result.isOk()) return fail(result.status());
  const WrittenResult& written = result.value();
  if (!written.exported.isOk()) return exitCode(written.exported.code());
  printFigures(written.metrics, written.curve ? &*written.curve : nullptr, written.timings,
               output.outDir);
  const std::optional<GateReport>& gate = written.gate;
  const bool gateFailed = gate && !gate->passed();
  if (gate) {
    printGate(*gate);
    if (gateFailed) {
      Terminal::error(output.outDir + ": the result failed the quality gate '" +
                      settings.value().limits->name + "'" +
                      (output.exportAnyway ? " (exported anyway, marked FAILED GATE)"
                                           : "; no cutting files were written"));
      return exitCode(ErrorCode::GateFailed);
    }
  }
  return 0;
}

namespace {

// A progress line for many jobs: done of total, failed, and the time left at the pace so far.
SweepProgress progressLine(Terminal& terminal, const char* what) {
  return [&terminal, what](int done, int failed, int total, double seconds) {
    char line[160];
    std::snprintf(line, sizeof line, "%s: %d of %d done, %d failed, about %.0f s left", what, done,
                  total, failed, seconds / done * (total - done));
    terminal.status(line);
  };
}

void printBatchRows(const std::vector<BatchRow>& rows) {
  std::fprintf(stdout, "%-24s %-12s %4s %10s %12s %10s %8s\n", "job", "status", "exit",
               "height_mm", "volume_cm3", "max_curv", "seconds");
  for (const BatchRow& r : rows)
    std::fprintf(stdout, "%-24s %-12s %4d %10.2f %12.4g %10.4g %8.2f\n", r.job.name.c_str(),
                 r.status.c_str(), r.exitCode, r.figures.heightMm, r.figures.volumeMm3 / 1000,
                 r.figures.maxCurvature, r.seconds);
}

}  // namespace

int runSweepCommand(const Job& base, const SweepOptions& options, const OutputOptions& output,
                    const std::atomic<bool>& interrupted) {
  Terminal terminal(output.quiet);
  const Result<RunSettings> settings = runSettings(output);
  if (!settings.isOk()) return fail(settings.status());
  // Each start runs as `dform forward` would, into its own folder, its messages kept in its
  // report.json (its sink has no listener: many runs at once would interleave on the terminal).
  const SweepRunner run = [&](const Job& job, const std::string& dir, MessageSink& sink) {
    OutputOptions one = output;
    one.outDir = dir;
    RunHooks hooks;
    hooks.interrupted = &interrupted;
    const Result<WrittenResult> written =
        writeResult(job, one, settings.value(), interrupted, sink, hooks);
    return written.isOk() ? written.value().exported : written.status();
  };
  const Result<std::vector<SweepRow>> rows =
      runSweep(base, options, output.outDir, run, progressLine(terminal, "sweep"), interrupted);
  terminal.clearProgress();
  if (!rows.isOk()) return fail(rows.status());
  int passed = 0, solved = 0;
  std::fprintf(stdout, "%-16s %8s %10s %12s %10s %8s %8s\n", "start", "start_b", "height_mm",
               "volume_cm3", "max_curv", "gate", "seconds");
  for (const SweepRow& r : rows.value()) {
    solved += r.solved;
    passed += r.solved && r.passed;
    std::fprintf(stdout, "%-16s %8.4f %10.2f %12.4g %10.4g %8s %8.2f\n", r.subfolder.c_str(),
                 r.startB, r.heightMm, r.volumeMm3 / 1000, r.maxCurvature,
                 !r.solved ? "unsolved" : r.passed ? "passed" : "FAILED", r.seconds);
  }
  std::fprintf(stdout, "%d starts: %d passed the gate, %d failed; gallery in %s/gallery.html\n",
               int(rows.value().size()), passed, int(rows.value().size()) - passed,
               output.outDir.c_str());
  if (solved == 0) {
    Terminal::error(output.outDir + ": no start was solved (first: " + rows.value()[0].reason + ")");
    return exitCode(ErrorCode::SolveFailed);
  }
  return 0;
}

int runBatchCommand(const std::vector<BatchJob>& jobs, const BatchOptions& options,
                    const OutputOptions& output, const std::atomic<bool>& interrupted) {
  Terminal terminal(output.quiet);
  const Result<RunSettings> settings = runSettings(output);
  if (!settings.isOk()) return fail(settings.status());
  // Each job as `dform run` runs it; its messages are kept in its report.json.
  const BatchRunner run = [&](const std::string& path, const std::string& dir) -> JobOutcome {
    const Result<Job> job = readJobFile(path);
    if (!job.isOk()) return {exitCode(job.status().code()), job.status().message()};
    OutputOptions one = output;
    one.outDir = dir;
    MessageSink sink;
    RunHooks hooks;
    hooks.interrupted = &interrupted;
    const Result<WrittenResult> written =
        writeResult(job.value(), one, settings.value(), interrupted, sink, hooks);
    if (!written.isOk()) return {exitCode(written.status().code()), written.status().message()};
    if (!written.value().exported.isOk())
      return {exitCode(written.value().exported.code()), written.value().exported.message()};
    const bool gateFailed = written.value().gate && !written.value().gate->passed();
    return {gateFailed ? exitCode(ErrorCode::GateFailed) : 0, ""};
  };
  const Result<std::vector<BatchRow>> rows =
      runBatch(jobs, options, output.outDir, run, progressLine(terminal, "batch"), interrupted);
  terminal.clearProgress();
  if (!rows.isOk()) return fail(rows.status());
  printBatchRows(rows.value());
  int worst = 0, failed = 0;
  for (const BatchRow& r : rows.value()) {
    failed += r.exitCode != 0;
    if (r.exitCode != 0 && worst == 0) worst = r.exitCode;
  }
  std::fprintf(stdout, "%d jobs (shard %d of %d): %d done, %d failed; manifest %s/%s\n",
               int(rows.value().size()), options.shard, options.shards,
               int(rows.value().size()) - failed, failed, output.outDir.c_str(),
               manifestName(options).c_str());
  return worst;
}

int mergeBatchCommand(const std::string& dir) {
  const Result<std::vector<BatchRow>> rows = mergeBatch(dir);
  if (!rows.isOk()) return fail(rows.status());
  printBatchRows(rows.value());
  std::fprintf(stdout, "%d jobs merged into %s/batch.json and %s/gallery.html\n",
               int(rows.value().size()), dir.c_str(), dir.c_str());
  return 0;
}

int exportSaved(const std::string& dir, const OutputOptions& output,
                const std::atomic<bool>& interrupted) {
  Terminal terminal(output.quiet);
  MessageSink sink(terminal.listener());
  const Result<ExportOptions> exporting = exportOptions(output);
  if (!exporting.isOk()) return fail(exporting.status());
  if (!fs::is_directory(dir))
    return fail(Status(ErrorCode::InputUnreadable, dir + ": no such result folder"));
  // Locked before it is read, so that no run replaces the result between reading and writing;
  // the export is staged with the result's other files and swapped in whole.
  ResultFolder folder;
  if (Status s = folder.begin(dir, resultFileNames()); !s.isOk()) return fail(s);
  Result<DForm> model = readModel(dir);
  if (!model.isOk()) return fail(model.status());
  if (interrupted) return fail(leftAsItWas(dir, "interrupted"));
  Result<std::optional<Curve3>> target = readSavedTarget(dir, model.value());
  if (!target.isOk()) return fail(target.status());
  // A result that failed its gate is exported only on purpose, and marked. The gate is run
  // again on the meshes (report.json's verdicts could have been edited), with the limits of the
  // preset report.json names, else the default ones.
  const bool hasReport = fs::exists(fs::path(dir) / "report.json");
  bool failedGate = false;
  std::string gateName = "default";
  if (hasReport) {
    Result<std::optional<bool>> verdict = savedGateVerdict(dir);
    if (!verdict.isOk()) return fail(verdict.status());
    failedGate = verdict.value() == false;
    const Result<std::string> recorded = savedGateName(dir);
    if (recorded.isOk() && fs::exists(fs::path(templatesDir()) / "gates" / (recorded.value() + ".json")))
      gateName = recorded.value();
  }
  Result<GateLimits> limits = loadGate(gateName);
  if (!limits.isOk()) return fail(limits.status());
  const GateReport gate =
      runGate(model.value(), limits.value(), target.value() ? &*target.value() : nullptr);
  if (interrupted) return fail(leftAsItWas(dir, "interrupted"));
  std::string failing;
  for (const CheckResult& c : gate.checks)
    if (c.verdict == CheckResult::Verdict::Fail) failing += (failing.empty() ? "" : ", ") + c.name;
  failedGate = failedGate || !gate.passed();
  if (failedGate && !output.exportAnyway) {
    Terminal::error(dir + ": the result failed its quality gate '" + gateName +
                    "' (checked again on the meshes: " +
                    (failing.empty() ? "report.json records a failure" : failing + " fail") +
                    "); nothing exported (--export-anyway exports it marked FAILED GATE)");
    return exitCode(ErrorCode::GateFailed);
  }
  const std::string name = savedJobName(dir);
  Result<PreparedExport> prepared = prepare(model.value(), exporting.value(), failedGate, name);
  if (interrupted) return fail(leftAsItWas(dir, "interrupted"));
  if (!prepared.isOk()) return fail(prepared.status());
  const LayoutFindings& layout = prepared.value().layout;
  if (layout.problems() > 0) {
    if (!output.exportAnyway) {
      Terminal::error(dir + ": the pattern does not lay out cleanly (" +
                      layoutCheck(layout).detail +
                      "); nothing exported (--export-anyway exports it marked FAILED GATE)");
      return exitCode(ErrorCode::GateFailed);
    }
    if (!failedGate) prepared = prepare(model.value(), exporting.value(), true, name);
    if (!prepared.isOk()) return fail(prepared.status());
  }
  if (interrupted) return fail(leftAsItWas(dir, "interrupted"));
  noteExport(prepared.value(), sink);
  // -o: the pattern set goes into a folder of its own, as one transaction too, and the result
  // folder is left as it is (its lock is released unchanged).
  if (!output.outDir.empty()) {
    ResultFolder out;
    if (Status s = out.begin(output.outDir, resultFileNames()); !s.isOk()) return fail(s);
    if (Status s = writeExport(prepared.value(), out.staging()).status(); !s.isOk()) return fail(out.named(s));
    if (Status s = commitUnlessInterrupted(out, output.outDir, interrupted); !s.isOk()) return fail(s);
    std::fprintf(stdout, "exported %s into %s\n", output.profile.c_str(), output.outDir.c_str());
    return 0;
  }
  // The result's own files go into the new folder unchanged; earlier cutting files do not.
  for (const char* kept : {ModelFileNames::aFlat, ModelFileNames::a3d, ModelFileNames::bFlat,
                           ModelFileNames::b3d, ModelFileNames::targetCurve, "report.json"})
    if (fs::exists(fs::path(dir) / kept))
      if (Status s = folder.carryOver(kept); !s.isOk()) return fail(s);
  if (Status s = writeExport(prepared.value(), folder.staging()).status(); !s.isOk())
    return fail(folder.named(s));
  // The report page shows the pattern: redrawn with the new one.
  if (hasReport)
    if (Status s = writeReportHtml(folder.staging(), model.value(), templatesDir()); !s.isOk())
      return fail(folder.named(s));
  if (Status s = commitUnlessInterrupted(folder, dir, interrupted); !s.isOk()) return fail(s);
  if (interrupted)
    return fail(Status(ErrorCode::Interrupted,
                       dir + ": interrupted; the new export was written completely"));
  std::fprintf(stdout, "exported %s into %s\n", output.profile.c_str(), dir.c_str());
  return 0;
}

int validateSaved(const std::string& dir, const std::string& gateName) {
  Result<GateLimits> limits = loadGate(gateName);  // the option first, as for every command
  if (!limits.isOk()) return fail(limits.status());
  Result<DForm> model = readModel(dir);
  if (!model.isOk()) return fail(model.status());
  // An inverse result carries its target curve; its seam is measured against it.
  Result<std::optional<Curve3>> target = readSavedTarget(dir, model.value());
  if (!target.isOk()) return fail(target.status());
  GateReport gate =
      runGate(model.value(), limits.value(), target.value() ? &*target.value() : nullptr);
  gate.checks.push_back(notRunCheck(
      "pattern_layout", 0, "validate re-checks the meshes; `dform export` checks the layout"));
  printGate(gate);
  // The figures are recomputed from the meshes, never taken from the report; a report that is
  // missing or unreadable (3), or incomplete or disagreeing with its meshes (7), fails.
  Result<std::vector<std::string>> differences =
      compareWithReport(dir, model.value(), gate.metrics, gate.curve ? &*gate.curve : nullptr);
  if (!differences.isOk()) return fail(differences.status());
  if (!differences.value().empty()) {
    for (const std::string& line : differences.value())
      std::fprintf(stdout, "report.json differs: %s\n", line.c_str());
    Terminal::error(dir + "/report.json: " + std::to_string(differences.value().size()) +
                    " entries differ from the saved result (first: " + differences.value()[0] +
                    ")");
    return exitCode(ErrorCode::GateFailed);
  }
  std::fprintf(stdout, "report.json: its mode and mesh sizes agree, its figures match the meshes\n");
  if (!gate.passed())
    Terminal::error(dir + ": the result failed the quality gate '" + limits.value().name + "'");
  return gate.passed() ? 0 : exitCode(ErrorCode::GateFailed);
}

int listProfiles() {
  for (const std::string& name : dform::listProfiles(templatesDir()))
    std::fprintf(stdout, "%s\n", name.c_str());
  return 0;
}

}  // namespace dform::cli
