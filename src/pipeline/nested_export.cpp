// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/nested_export.h"

#include <filesystem>

#include "dform/core/interrupt.h"
#include "dform/core/result_folder.h"
#include "dform/io/model_files.h"
#include "dform/pipeline/settings.h"
#include "run_steps.h"
#include "saved_gate.h"

namespace dform {

namespace {

namespace fs = std::filesystem;

// A result of the nest, read and judged.
struct NestResult {
  DForm model;
  std::string jobName;
  std::vector<FoldToScore> folds;
  bool failed = false;
};

Result<NestResult> readJudged(const std::string& dir, const ExportSettings& settings, bool regate,
                              const ExportOptions& options, MessageSink& sink) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    return Status(ErrorCode::InputUnreadable, dir + ": no such result folder");
  ResultFolder held;  // a shared lock while it is read, as `dform export DIR -o OUT` holds it
  if (Status s = held.read(dir); !s.isOk()) return s;
  const Result<SavedModel> saved = readSaved(dir);
  if (!saved.isOk()) return saved.status();
  const Result<SavedGate> judged = judgeSaved(dir, saved.value(), regate, sink);
  if (!judged.isOk()) return judged.status();
  if (judged.value().failed && !settings.exportAnyway) return gateRefusal(dir, judged.value());
  NestResult result{saved.value().model, savedJobName(dir), {}, judged.value().failed};
  std::string modelName;
  result.folds = withFolds(options, savedFolds(dir, modelName), modelName, sink).folds;
  return result;
}

// The files a nest's folder may hold: a result's and every sheet's.
std::set<std::string> nestFileNames() {
  std::set<std::string> names = resultFileNames();
  for (int k = 1; k <= kMaxNestSheets; ++k)
    for (const char* extension : {"svg", "dxf"}) {
      names.insert(sheetFileName(k, extension));
      names.insert(printSheetFileName(k, extension == std::string("svg") ? "svg" : "png"));
    }
  return names;
}

Result<std::string> exportNestOrThrow(const std::vector<std::string>& dirs, int copies,
                                      const ExportSettings& settings, const SavedExport& how,
                                      MessageSink& sink, const std::atomic<bool>& interrupted) {
  if (dirs.empty()) return Status(ErrorCode::Usage, "a nest needs at least one result folder");
  if (how.outDir.empty())
    return Status(ErrorCode::Usage, "a nest is written into an output folder of its own");
  if (copies < 1 || copies > 1000)
    return Status(ErrorCode::Usage, "the copies of a nest must be from 1 to 1000");
  if (Status s = checkExportSettings(settings); !s.isOk()) return s;
  Result<ExportOptions> exporting = exportOptions(settings);
  if (!exporting.isOk()) return exporting.status();
  ExportOptions options = exporting.value();
  options.jobName = fs::path(how.outDir).lexically_normal().filename().string();
  if (options.jobName.empty() || options.jobName == ".") options.jobName = "nest";
  std::vector<NestResult> results;
  bool failed = false;
  for (const std::string& dir : dirs) {
    Result<NestResult> read = readJudged(dir, settings, how.regate, options, sink);
    if (!read.isOk()) return read.status();
    if (interrupted) return leftAsItWas(how.outDir, "interrupted");
    failed = failed || read.value().failed;
    results.push_back(std::move(read.value()));
  }
  std::vector<NestItem> items;
  for (const NestResult& r : results) items.push_back({&r.model, r.jobName, copies, r.folds});
  Result<LaidOutExport> laidOut = layOutNest(items, options);
  if (!laidOut.isOk()) return laidOut.status();
  if (interrupted) return leftAsItWas(how.outDir, "interrupted");
  const LayoutFindings& layout = laidOut.value().layout;
  if (layout.problems() > 0 && !settings.exportAnyway)
    return Status(ErrorCode::GateFailed, how.outDir + ": the nest does not lay out cleanly (" +
                                             layoutCheck(layout).detail + "); nothing exported");
  const LaidOutExport stamped =
      failed || layout.problems() > 0 ? markFailedGate(laidOut.value()) : laidOut.value();
  const Result<PreparedExport> prepared = renderNest(stamped);
  if (!prepared.isOk()) return prepared.status();
  if (interrupted) return leftAsItWas(how.outDir, "interrupted");
  const ExportSummary& summary = prepared.value().summary;
  if (summary.sheets > kMaxNestSheets)
    return Status(ErrorCode::Usage, "the nest takes " + std::to_string(summary.sheets) +
                                        " sheets, more than " + std::to_string(kMaxNestSheets));
  sink.info("nest: " + std::to_string(summary.pieces) + " pieces of " +
            std::to_string(dirs.size()) + " result(s) on " + std::to_string(summary.sheets) +
            " sheet(s)");
  for (const std::string& m : summary.messages) sink.info("nest: " + m);
  for (const std::string& w : summary.warnings) sink.warning("nest: " + w);
  ResultFolder out;
  if (Status s = out.begin(how.outDir, nestFileNames()); !s.isOk()) return s;
  if (Status s = writeExport(prepared.value(), out.staging()).status(); !s.isOk())
    return out.named(s);
  if (Status s = commitUnlessInterrupted(out, how.outDir, interrupted, &sink); !s.isOk()) return s;
  return how.outDir;
}

}  // namespace

Result<std::string> exportNest(const std::vector<std::string>& dirs, int copies,
                               const ExportSettings& settings, const SavedExport& how,
                               MessageSink& sink, const std::atomic<bool>& interrupted) {
  try {
    return exportNestOrThrow(dirs, copies, settings, how, sink, interrupted);
  } catch (const Interrupted&) {
    return leftAsItWas(how.outDir, "interrupted");
  }
}

}  // namespace dform
