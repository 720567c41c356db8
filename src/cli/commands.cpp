// SPDX-License-Identifier: GPL-3.0-or-later
#include "commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "browser.h"
#include "dform/core/message_text.h"
#include "dform/pipeline/nested_export.h"
#include "dform/pipeline/saved_result.h"
#include "json_summary.h"
#include "terminal.h"

namespace dform::cli {

namespace {

int fail(const Status& status) {
  Terminal::error(status);
  return exitCode(status.code());
}

// One figure of the summary, named and measured as the gate file and report.json name it
// (fractions unless the name ends in _mm or _rad).
struct Figure {
  std::string name;
  double value;
};

// The figures a result is judged on, in the gate's units. gauss_max_rad is the gate's own
// (vertices away from the seam; report.json's metrics.angle_defect_max_rad takes every interior
// vertex), so it is listed only when a gate ran.
std::vector<Figure> summaryFigures(const Metrics& m, const CurveMatch* curve,
                                   const GateReport* gate) {
  std::vector<Figure> figures = {{"L_error", m.lengthError}, {"L_max", m.lengthErrorMax}};
  if (curve) {
    figures.push_back({"D_error", curve->curveError});
    figures.push_back({"curve_distance_max_mm", curve->curveDistanceMaxMm});
  } else {
    figures.push_back({"B_error", m.seamError});
    figures.push_back({"seam_gap_mm", m.seamGapMm});
  }
  if (gate)
    for (const CheckResult& c : gate->checks)
      if (c.name == "gauss_max_rad") figures.push_back({c.name, c.value});
  figures.push_back({"flipped", double(m.flipped2d + m.flipped3d)});
  figures.push_back({"degenerate", double(m.degenerate2d + m.degenerate3d)});
  figures.push_back({"seam_length_a_mm", m.seamLengthAMm});
  figures.push_back({"seam_length_b_mm", m.seamLengthBMm});
  return figures;
}

std::vector<Figure> summaryFigures(const WrittenResult& written) {
  return summaryFigures(written.metrics, written.curve ? &*written.curve : nullptr,
                        written.gate ? &*written.gate : nullptr);
}

void printFigures(const std::vector<Figure>& figures, const Timings& t, const std::string& dir) {
  std::string line;
  for (const Figure& f : figures) {
    char text[96];
    std::snprintf(text, sizeof text, "%s %.4g", f.name.c_str(), f.value);
    line += (line.empty() ? "" : "   ") + std::string(text);
  }
  std::fprintf(stdout, "%s\n", line.c_str());
  std::fprintf(stdout, "solved in %.3f s (read %.3f, mesh %.3f, solve %.3f); results in %s\n",
               t.total, t.read, t.mesh, t.solve, dir.c_str());
}

// The gate's table; `judged` false (--gate none): the figures only, no limits and no verdict.
void printGate(const GateReport& gate, bool judged = true) {
  if (!judged) {
    std::fprintf(stdout, "%-20s %12s\n", "check", "value");
    for (const CheckResult& c : gate.checks)
      std::fprintf(stdout, "%-20s %12.4g\n", c.name.c_str(), c.value);
    std::fprintf(stdout, "gate: none (figures measured, not judged)\n");
    return;
  }
  std::fprintf(stdout, "%-20s %12s %12s  %s\n", "check", "value", "limit", "verdict");
  for (const CheckResult& c : gate.checks)
    std::fprintf(stdout, "%-20s %12.4g %12.4g  %s%s%s\n", c.name.c_str(), c.value, c.limit,
                 verdictName(c.verdict), c.verdict == CheckResult::Verdict::Pass ? "" : ": ",
                 c.verdict == CheckResult::Verdict::Pass ? "" : c.detail.c_str());
  std::fprintf(stdout, "gate: %s (%s: %d failed, %d not run)\n",
               gate.passed() ? "PASSED" : "FAILED", gate.name.c_str(), gate.failed(),
               gate.notRun());
}

// A number, or null where it is not one (a check not run), as report.json writes them.
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

nlohmann::json gateJson(const GateReport& gate, bool judged) {
  nlohmann::json checks = nlohmann::json::array();
  for (const CheckResult& c : gate.checks) {
    nlohmann::json check = {{"name", c.name}, {"value", number(c.value)}};
    if (judged) {
      check["limit"] = number(c.limit);
      check["verdict"] = verdictName(c.verdict);
      check["detail"] = c.detail;
    }
    checks.push_back(check);
  }
  nlohmann::json out = {{"name", judged ? gate.name : "none"}, {"checks", checks}};
  out["passed"] = judged ? nlohmann::json(gate.passed()) : nlohmann::json();
  return out;
}

// The files of a result folder, by name.
nlohmann::json folderFiles(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error))
    if (entry.is_regular_file(error)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The model a result folder's run used, as its report.json names it (the one record of that
// choice); null when the report is missing or says none.
nlohmann::json modelName(const std::string& dir) {
  std::ifstream reportFile(std::filesystem::path(dir) / "report.json");
  const nlohmann::json report = nlohmann::json::parse(reportFile, nullptr, false);
  return report.is_object() && report.contains("model") && report["model"].is_object()
             ? report["model"].value("name", nlohmann::json())
             : nlohmann::json();
}

nlohmann::json figuresJson(const std::vector<Figure>& figures) {
  nlohmann::json out = nlohmann::json::object();
  for (const Figure& f : figures) out[f.name] = number(f.value);
  return out;
}

// --json: the run's summary as one object on stdout (docs/cli.md "Machine-readable summary").
void addRunJson(const Job& job, const WrittenResult& written, const OutputOptions& output) {
  nlohmann::json summary;
  summary["mode"] = job.modeName();
  summary["model"] = modelName(output.outDir);
  summary["figures"] = figuresJson(summaryFigures(written));
  summary["gate"] = written.gate ? gateJson(*written.gate, true) : nlohmann::json();
  summary["output"] = output.outDir;
  summary["files"] = folderFiles(output.outDir);
  json_summary::add(summary);
}

}  // namespace

int runJob(const Job& job, const OutputOptions& output, const Printing& printing,
           const std::atomic<bool>& interrupted) {
  Terminal terminal(printing.quiet);
  MessageSink sink(terminal.listener());
  const bool forward = job.isForward();
  RunHooks hooks;
  hooks.interrupted = &interrupted;
  hooks.onIteration = [&](const char* stage, const IterationSummary& it) {
    terminal.progress(forward ? stage : std::string(stage) + " (inverse)", it);
  };
  hooks.onLevel = [&](const LevelStart& start) { terminal.level(start); };
  const Result<RunSettings> settings = checkOutput(job.exporting);
  if (!settings.isOk()) return fail(settings.status());
  const Result<WrittenResult> result = runAndWrite(job, output, settings.value(), sink, hooks);
  terminal.clearProgress();
  if (!result.isOk()) return fail(result.status());
  const WrittenResult& written = result.value();
  if (!written.exported.isOk()) return exitCode(written.exported.code());
  const std::optional<GateReport>& gate = written.gate;
  const bool gateFailed = gate && !gate->passed();
  const int code = gateFailed ? exitCode(ErrorCode::GateFailed) : 0;
  if (printing.json) {
    addRunJson(job, written, output);
  } else if (!printing.quiet) {
    printFigures(summaryFigures(written), written.timings, output.outDir);
    if (gate) printGate(*gate);
  }
  if (gateFailed)
    Terminal::error(output.outDir + ": the result failed the quality gate '" +
                    settings.value().limits->name + "'" +
                    (job.exporting.exportAnyway ? " (exported anyway, marked FAILED GATE)"
                                                : "; no cutting files were written"));
  return code;
}

namespace {

// A progress line for many jobs: done of total, failed, and the time left (NaN: not known yet).
BatchProgress progressLine(Terminal& terminal, const char* what) {
  return [&terminal, what](int done, int failed, int total, double secondsLeft) {
    char line[160];
    if (std::isfinite(secondsLeft))
      std::snprintf(line, sizeof line, "%s: %d of %d done, %d failed, about %.0f s left", what,
                    done, total, failed, secondsLeft);
    else
      std::snprintf(line, sizeof line, "%s: %d of %d done, %d failed", what, done, total, failed);
    terminal.status(line);
  };
}

// `value` printed with `format` in `width` columns, or "-" there when it is not a number (a job
// that failed has no figures).
std::string figure(const char* format, int width, double value) {
  char text[64];
  if (std::isfinite(value))
    std::snprintf(text, sizeof text, format, width, value);
  else
    std::snprintf(text, sizeof text, "%*s", width, "-");
  return text;
}

void printBatchRows(const std::vector<BatchRow>& rows) {
  std::fprintf(stdout, "%-24s %-12s %4s %10s %12s %10s %8s\n", "job", "status", "exit", "height_mm",
               "volume_cm3", "max_curv", "seconds");
  for (const BatchRow& r : rows) {
    const SweepRow& f = r.figures;
    const double none = NAN;
    std::fprintf(stdout, "%-24s %-12s %4d %s %s %s %s\n", printable(r.job.name, 40).c_str(),
                 r.status.c_str(), r.exitCode,
                 figure("%*.2f", 10, f.solved ? f.heightMm : none).c_str(),
                 figure("%*.4g", 12, f.solved ? f.volumeMm3 / 1000 : none).c_str(),
                 figure("%*.4g", 10, f.solved ? f.maxCurvature : none).c_str(),
                 figure("%*.2f", 8, r.seconds).c_str());
  }
}

nlohmann::json batchRowsJson(const std::vector<BatchRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const BatchRow& r : rows) {
    const SweepRow& f = r.figures;
    out.push_back({{"job", r.job.name},
                   {"status", r.status},
                   {"exit_code", r.exitCode},
                   {"height_mm", f.solved ? number(f.heightMm) : nlohmann::json()},
                   {"volume_cm3", f.solved ? number(f.volumeMm3 / 1000) : nlohmann::json()},
                   {"max_curvature", f.solved ? number(f.maxCurvature) : nlohmann::json()},
                   {"seconds", number(r.seconds)}});
  }
  return out;
}

}  // namespace

int runSweepCommand(const Job& base, const SweepOptions& options, const OutputOptions& output,
                    const Printing& printing, const std::atomic<bool>& interrupted) {
  Terminal terminal(printing.quiet);
  const Result<RunSettings> settings = checkOutput(base.exporting);
  if (!settings.isOk()) return fail(settings.status());
  MessageSink notes(terminal.listener());
  const Result<std::vector<SweepRow>> rows = sweepAndWrite(
      base, options, output, settings.value(),
      [line = progressLine(terminal, "sweep")](int done, int failed, int total, double seconds) {
        line(done, failed, total, estimateSecondsLeft(seconds, done, total - done));
      },
      interrupted, &notes);
  terminal.clearProgress();
  if (!rows.isOk()) return fail(rows.status());
  const Status unwritten = unwrittenStarts(output.outDir, rows.value());
  if (printing.json) {
    nlohmann::json starts = nlohmann::json::array();
    for (const SweepRow& r : rows.value())
      starts.push_back({{"folder", r.subfolder},
                        {"start_b", r.startB},
                        {"solved", r.solved},
                        {"gate_passed", r.solved ? nlohmann::json(r.passed) : nlohmann::json()},
                        {"height_mm", r.solved ? number(r.heightMm) : nlohmann::json()},
                        {"volume_cm3", r.solved ? number(r.volumeMm3 / 1000) : nlohmann::json()},
                        {"max_curvature", r.solved ? number(r.maxCurvature) : nlohmann::json()},
                        {"seconds", number(r.seconds)}});
    json_summary::add({{"output", output.outDir}, {"starts", starts}});
  }
  if (printing.quiet || printing.json) return unwritten.isOk() ? 0 : fail(unwritten);
  int passed = 0;
  std::fprintf(stdout, "%-16s %8s %10s %12s %10s %8s %8s\n", "start", "start_b", "height_mm",
               "volume_cm3", "max_curv", "gate", "seconds");
  for (const SweepRow& r : rows.value()) {
    passed += r.solved && r.passed;
    std::fprintf(stdout, "%-16s %8.4f %10.2f %12.4g %10.4g %8s %8.2f\n", r.subfolder.c_str(),
                 r.startB, r.heightMm, r.volumeMm3 / 1000, r.maxCurvature,
                 !r.solved  ? "unsolved"
                 : r.passed ? "passed"
                            : "FAILED",
                 r.seconds);
  }
  std::fprintf(stdout, "%d starts: %d passed the gate, %d failed; gallery in %s/gallery.html\n",
               int(rows.value().size()), passed, int(rows.value().size()) - passed,
               output.outDir.c_str());
  return unwritten.isOk() ? 0 : fail(unwritten);
}

int runBatchCommand(const std::vector<BatchJob>& jobs, const BatchOptions& options,
                    const OutputOptions& output, const Printing& printing,
                    const std::function<Status(Job&)>& adjust,
                    const std::atomic<bool>& interrupted) {
  Terminal terminal(printing.quiet);
  const Result<std::vector<BatchRow>> rows =
      batchAndWrite(jobs, options, output, adjust, progressLine(terminal, "batch"), interrupted);
  terminal.clearProgress();
  if (!rows.isOk()) {
    // A batch cut short is finished by running it again with --resume.
    if (rows.status().code() == ErrorCode::Interrupted)
      Terminal::error(rows.status().text() + "; --resume runs the rest");
    else
      Terminal::error(rows.status());
    return exitCode(rows.status().code());
  }
  if (printing.json)
    json_summary::add({{"output", output.outDir},
                       {"manifest", manifestName(options)},
                       {"jobs", batchRowsJson(rows.value())}});
  else if (!printing.quiet)
    printBatchRows(rows.value());
  int worst = 0, failed = 0;
  const BatchRow* first = nullptr;
  for (const BatchRow& r : rows.value()) {
    failed += r.exitCode != 0;
    if (r.exitCode != 0 && worst == 0) {
      worst = r.exitCode;
      first = &r;
    }
  }
  if (!printing.quiet && !printing.json)
    std::fprintf(stdout, "%d jobs (shard %d of %d): %d done, %d failed; manifest %s/%s\n",
                 int(rows.value().size()), options.shard, options.shards,
                 int(rows.value().size()) - failed, failed, printable(output.outDir, 300).c_str(),
                 manifestName(options).c_str());
  // A failed batch says so on stderr, once: a scheduler's log shows why the job array failed.
  if (first)
    Terminal::error(output.outDir + "/" + manifestName(options) + ": " + std::to_string(failed) +
                    " of " + std::to_string(rows.value().size()) + " jobs failed (first: " +
                    first->job.name + ": " + printable(first->message, 200) + ")");
  return worst;
}

int mergeBatchCommand(const std::string& dir, bool allowPartial, bool quiet) {
  const Result<MergedBatch> merged = mergeBatch(dir, allowPartial);
  // A merge refused for jobs that have not finished is made all the same by --allow-partial.
  if (!merged.isOk() && merged.status().code() == ErrorCode::SolveFailed) {
    Terminal::error(merged.status().text() + "; --allow-partial merges what is there");
    return exitCode(merged.status().code());
  }
  if (!merged.isOk()) return fail(merged.status());
  const MergedBatch& m = merged.value();
  if (json_summary::enabled())
    json_summary::add(
        {{"output", dir},
         {"jobs", batchRowsJson(m.rows)},
         {"missing", m.missingCount > 0 ? nlohmann::json(missingText(m)) : nlohmann::json()}});
  if (quiet || json_summary::enabled()) return 0;
  printBatchRows(m.rows);
  const std::string into = printable(dir, 300);
  if (m.jobCount < 0)
    std::fprintf(stdout,
                 "%d jobs merged into %s/batch.json and %s/gallery.html (the manifests do not "
                 "record how many the list has)\n",
                 int(m.rows.size()), into.c_str(), into.c_str());
  else if (m.missingCount > 0)
    std::fprintf(stdout,
                 "%d of %d jobs merged into %s/batch.json and %s/gallery.html; %d have not "
                 "finished: %s\n",
                 m.jobCount - m.missingCount, m.jobCount, into.c_str(), into.c_str(),
                 m.missingCount, missingText(m).c_str());
  else
    std::fprintf(stdout, "%d of %d jobs merged into %s/batch.json and %s/gallery.html\n",
                 m.jobCount, m.jobCount, into.c_str(), into.c_str());
  return 0;
}

namespace {

// An export's outcome: the folder it wrote, as the JSON summary or one line ("<done> <profile>
// into <folder>"), or its failure.
int exportDone(const Result<std::string>& into, const char* done, const ExportSettings& settings,
               bool quiet) {
  if (!into.isOk()) return fail(into.status());
  if (json_summary::enabled())
    json_summary::add({{"profile", settings.pattern.profile},
                       {"output", into.value()},
                       {"files", folderFiles(into.value())}});
  else if (!quiet)
    std::fprintf(stdout, "%s %s into %s\n", done, settings.pattern.profile.c_str(),
                 into.value().c_str());
  return 0;
}

}  // namespace

int exportSaved(const std::string& dir, const ExportSettings& settings, const SavedExport& how,
                bool quiet, const std::atomic<bool>& interrupted) {
  Terminal terminal(quiet);
  MessageSink sink(terminal.listener());
  return exportDone(exportSavedResult(dir, settings, how, sink, interrupted), "exported", settings,
                    quiet);
}

int exportNested(const std::vector<std::string>& dirs, int copies, const ExportSettings& settings,
                 const SavedExport& how, bool quiet, const std::atomic<bool>& interrupted) {
  Terminal terminal(quiet);
  MessageSink sink(terminal.listener());
  return exportDone(exportNest(dirs, copies, settings, how, sink, interrupted), "nested", settings,
                    quiet);
}

int validateSaved(const std::string& dir, const std::string& gateName, const Printing& printing) {
  const Result<SavedCheck> checked = validateSavedResult(dir, gateName);
  if (!checked.isOk()) return fail(checked.status());
  const SavedCheck& check = checked.value();
  // A report that is missing or unreadable (3), or incomplete or disagreeing with its meshes
  // (7), fails; so does the gate, when one judged.
  const int code = !check.report.isOk()                   ? exitCode(check.report.code())
                   : !check.differences.empty()           ? exitCode(ErrorCode::GateFailed)
                   : check.judged && !check.gate.passed() ? exitCode(ErrorCode::GateFailed)
                                                          : 0;
  if (printing.json) {
    // The figures as the meshes give them (never report.json's), with the gate's gauss_max_rad.
    const GateReport& gate = check.gate;
    json_summary::add({{"model", modelName(dir)},
                       {"figures", figuresJson(summaryFigures(
                                       gate.metrics, gate.curve ? &*gate.curve : nullptr, &gate))},
                       {"gate", gateJson(gate, check.judged)},
                       {"report_differences", check.differences},
                       {"output", dir},
                       {"files", folderFiles(dir)}});
  } else if (!printing.quiet) {
    printGate(check.gate, check.judged);
    for (const std::string& line : check.differences)
      std::fprintf(stdout, "report.json differs: %s\n", line.c_str());
    if (check.report.isOk() && check.differences.empty())
      std::fprintf(stdout,
                   "report.json: its mode and mesh sizes agree, its figures match the meshes\n");
  }
  if (!check.report.isOk()) return fail(check.report);
  if (!check.differences.empty())
    Terminal::error(dir + "/report.json: " + std::to_string(check.differences.size()) +
                    " entries differ from the saved result (first: " + check.differences[0] + ")");
  else if (code != 0)
    Terminal::error(dir + ": the result failed the quality gate '" + check.gateName + "'");
  return code;
}

int listProfiles() {
  if (const Result<std::string> templates = templatesDir(); !templates.isOk()) {
    Terminal::error(templates.status().message());
    return exitCode(templates.status().code());
  }
  if (json_summary::enabled())
    json_summary::add({{"profiles", exportProfileNames()}});
  else
    for (const std::string& name : exportProfileNames()) std::fprintf(stdout, "%s\n", name.c_str());
  return 0;
}

int runStudio(const StudioOptions& options, bool openBrowser,
              const std::atomic<bool>& interrupted) {
  // A browser that closes a connection mid-answer must not end the server.
  std::signal(SIGPIPE, SIG_IGN);
  Result<std::unique_ptr<Studio>> studio = Studio::start(options);
  if (!studio.isOk()) {
    Terminal::error(studio.status());
    return exitCode(studio.status().code());
  }
  const std::string url = studio.value()->url();
  if (json_summary::enabled()) {
    json_summary::add({{"url", url}});
    json_summary::printNow(0);
  } else {
    std::printf("dform studio: open %s\n(Ctrl-C stops it)\n", url.c_str());
  }
  std::fflush(stdout);
  // Through a file only this user can read: the token never appears on a command line. Without
  // xdg-open (or a desktop) the printed address is all there is.
  PrivateOpener opener;
  if (openBrowser) opener.open(url);
  while (!interrupted.load()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  studio.value()->stop();
  return exitCode(ErrorCode::Interrupted);
}

}  // namespace dform::cli
