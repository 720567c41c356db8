// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/saved_result.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "dform/core/input_file.h"
#include "dform/core/interrupt.h"
#include "dform/core/result_folder.h"
#include "dform/io/curve_reader.h"
#include "dform/io/model_files.h"
#include "dform/pipeline/report.h"
#include "reference_seams.h"
#include "run_steps.h"
#include "saved_gate.h"

namespace dform {

namespace {

namespace fs = std::filesystem;

Result<std::string> exportSavedOrThrow(const std::string& dir, const ExportSettings& settings,
                                       const SavedExport& how, MessageSink& sink,
                                       const std::atomic<bool>& interrupted) {
  if (Status s = checkExportSettings(settings); !s.isOk()) return s;
  const Result<ExportOptions> exporting = exportOptions(settings);
  if (!exporting.isOk()) return exporting.status();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))  // a name too long for the system is no folder either
    return Status(ErrorCode::InputUnreadable, dir + ": no such result folder");
  // Locked before it is read, so that no run replaces the result between reading and writing;
  // the export is staged with the result's other files and swapped in whole. Exported into
  // another folder (-o), the result is only read: held by a shared lock, written nowhere.
  ResultFolder folder;
  const Status locked =
      how.outDir.empty() ? folder.begin(dir, resultFileNames()) : folder.read(dir);
  if (!locked.isOk()) return locked;
  const Result<SavedModel> saved = readSaved(dir);
  if (!saved.isOk()) return saved.status();
  if (interrupted) return leftAsItWas(dir, "interrupted");
  const DForm& model = saved.value().model;
  // A result that failed its gate is exported only on purpose, and marked.
  const Result<SavedGate> judged = judgeSaved(dir, saved.value(), how.regate, sink);
  if (!judged.isOk()) return judged.status();
  if (interrupted) return leftAsItWas(dir, "interrupted");
  bool failedGate = judged.value().failed;
  if (failedGate && !settings.exportAnyway) return gateRefusal(dir, judged.value());
  // Laid out once: a layout that fails is stamped as it is (the stamp is an overlay).
  std::string modelName;
  const Result<LaidOutExport> laidOut =
      layOut(model, withFolds(exporting.value(), savedFolds(dir, modelName), modelName, sink),
             savedJobName(dir));
  if (interrupted) return leftAsItWas(dir, "interrupted");
  if (!laidOut.isOk()) return laidOut.status();
  const LayoutFindings& layout = laidOut.value().layout;
  if (layout.problems() > 0 && !settings.exportAnyway) {
    return Status(ErrorCode::GateFailed, dir + ": the pattern does not lay out cleanly (" +
                                             layoutCheck(layout).detail + "); nothing exported (" +
                                             mention(Setting::ExportAnyway) +
                                             " exports it marked FAILED GATE)");
  }
  failedGate = failedGate || layout.problems() > 0;
  const Result<PreparedExport> prepared = render(model, laidOut.value(), failedGate);
  if (interrupted) return leftAsItWas(dir, "interrupted");
  if (!prepared.isOk()) return prepared.status();
  noteExport(prepared.value(), sink);
  // -o: the pattern set goes into a folder of its own, as one transaction too, and the result
  // folder is left as it is (its lock is released unchanged).
  if (!how.outDir.empty()) {
    ResultFolder out;
    if (Status s = out.begin(how.outDir, resultFileNames()); !s.isOk()) return s;
    if (Status s = writeExport(prepared.value(), out.staging()).status(); !s.isOk())
      return out.named(s);
    if (Status s = commitUnlessInterrupted(out, how.outDir, interrupted, &sink); !s.isOk())
      return s;
    return how.outDir;
  }
  // The result's own files go into the new folder unchanged; earlier cutting files do not.
  for (const char* kept : {ModelFileNames::aFlat, ModelFileNames::a3d, ModelFileNames::bFlat,
                           ModelFileNames::b3d, ModelFileNames::targetCurve, "report.json"})
    if (fs::exists(fs::path(dir) / kept))
      if (Status s = folder.carryOver(kept); !s.isOk()) return s;
  if (Status s = writeExport(prepared.value(), folder.staging()).status(); !s.isOk())
    return folder.named(s);
  // The report page shows the pattern: redrawn with the new one.
  if (fs::exists(fs::path(dir) / "report.json")) {
    const std::string reportPath = (fs::path(dir) / "report.json").string();
    const Result<std::string> report = readInputFile(reportPath);
    if (!report.isOk()) return report.status();
    if (Status s =
            writeReportPage(folder.staging(), report.value(), reportPath, &prepared.value(), model);
        !s.isOk())
      return folder.named(s);
  }
  if (Status s = commitUnlessInterrupted(folder, dir, interrupted, &sink); !s.isOk()) return s;
  if (interrupted)
    return Status(ErrorCode::Interrupted,
                  dir + ": interrupted; the new export was written completely");
  return dir;
}

}  // namespace

Result<std::string> exportSavedResult(const std::string& dir, const ExportSettings& settings,
                                      const SavedExport& how, MessageSink& sink,
                                      const std::atomic<bool>& interrupted) {
  try {
    return exportSavedOrThrow(dir, settings, how, sink, interrupted);
  } catch (const Interrupted&) {  // inside the figures or the report page's pictures
    return leftAsItWas(dir, "interrupted");
  }
}

Result<SavedCheck> validateSavedResult(const std::string& dir, const std::string& gateName) {
  const bool judged = gateName != "none";
  // The option first, as for every command.
  Result<GateLimits> limits = loadGate(judged ? gateName : "default");
  if (!limits.isOk()) return limits.status();
  Result<DForm> model = readModel(dir);
  if (!model.isOk()) return model.status();
  // An inverse result carries its target curve; its seam is measured against it.
  Result<std::optional<Curve3>> target = readSavedTarget(dir, model.value());
  if (!target.isOk()) return target.status();
  SavedCheck check;
  check.gateName = judged ? limits.value().name : "none";
  check.judged = judged;
  check.gate =
      measureAndGate(model.value(), limits.value(), target.value() ? &*target.value() : nullptr);
  check.gate.checks.push_back(notRunCheck(
      "pattern_layout", 0, "validate re-checks the meshes; `dform export` checks the layout"));
  // The figures are recomputed from the meshes, never taken from the report.
  Result<std::vector<std::string>> differences = compareWithReport(
      dir, model.value(), check.gate.metrics, check.gate.curve ? &*check.gate.curve : nullptr);
  if (differences.isOk())
    check.differences = differences.value();
  else
    check.report = differences.status();
  return check;
}

}  // namespace dform
