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
#include "dform/pipeline/reference_seams.h"
#include "dform/pipeline/report.h"
#include "dform/pipeline/run_steps.h"

namespace dform {

namespace {

namespace fs = std::filesystem;

// A saved result's job name, from the job its report.json records; the folder's name when there is
// no readable job.
std::string savedJobName(const std::string& dir) {
  const fs::path path = fs::path(dir) / "report.json";
  std::ifstream in(path);
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  if (report.is_object() && report.contains("job")) {
    Result<Job> job =
        parseJobJson(report["job"].dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
                     path.string(), dir);
    if (job.isOk()) return jobName(job.value());
  }
  return fs::path(dir).filename().string();
}

// The body's folds report.json records (model.folds, flat mm), for --score-folds; entries that
// are not a piece, two points and an angle are passed over. `modelName` gets model.name.
std::vector<FoldToScore> savedFolds(const std::string& dir, std::string& modelName) {
  std::ifstream in(fs::path(dir) / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  std::vector<FoldToScore> out;
  if (!report.is_object() || !report.contains("model") || !report["model"].is_object()) return out;
  const nlohmann::json& model = report["model"];
  if (model.contains("name") && model["name"].is_string()) modelName = model["name"];
  if (!model.contains("folds") || !model["folds"].is_array()) return out;
  const auto point = [](const nlohmann::json& p, Eigen::Vector2d& q) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) return false;
    q = Eigen::Vector2d(p[0].get<double>(), p[1].get<double>());
    return true;
  };
  for (const nlohmann::json& f : model["folds"]) {
    FoldToScore fold;
    if (!f.is_object() || !f.contains("piece") || !f.contains("from_mm") || !f.contains("to_mm") ||
        !f.contains("angle_deg") || !f["angle_deg"].is_number() ||
        !point(f["from_mm"], fold.from) || !point(f["to_mm"], fold.to) ||
        !(f["piece"] == "A" || f["piece"] == "B"))
      continue;
    if (f.contains("crease") && f["crease"] == true) continue;  // drawn as the piece's crease line
    fold.piece = f["piece"] == "A" ? 0 : 1;
    fold.angleDeg = f["angle_deg"].get<double>();
    out.push_back(fold);
  }
  return out;
}

// An inverse result's target curve, when the folder holds one, checked against the seam.
Result<std::optional<Curve3>> readSavedTarget(const std::string& dir, const DForm& model) {
  const std::string curvePath = (fs::path(dir) / ModelFileNames::targetCurve).string();
  std::error_code ec;
  if (!fs::exists(curvePath, ec)) return std::optional<Curve3>();
  Result<Curve3> curve = readCurve(curvePath);
  if (!curve.isOk()) return curve.status();
  if (std::size_t(curve.value().points.rows()) != model.a.seam.size())
    return Status(ErrorCode::InputInvalid,
                  curvePath + ": has a different number of points than the seam");
  return std::optional<Curve3>(curve.value());
}

Result<std::string> exportSavedOrThrow(const std::string& dir, const OutputOptions& output,
                                       MessageSink& sink, const std::atomic<bool>& interrupted) {
  const Result<ExportOptions> exporting = exportOptions(output);
  if (!exporting.isOk()) return exporting.status();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))  // a name too long for the system is no folder either
    return Status(ErrorCode::InputUnreadable, dir + ": no such result folder");
  // Locked before it is read, so that no run replaces the result between reading and writing;
  // the export is staged with the result's other files and swapped in whole. Exported into
  // another folder (-o), the result is only read: held by a shared lock, written nowhere.
  ResultFolder folder;
  const Status locked =
      output.outDir.empty() ? folder.begin(dir, resultFileNames()) : folder.read(dir);
  if (!locked.isOk()) return locked;
  FileHashes files;
  Result<DForm> model = readModel(dir, &files);
  if (!model.isOk()) return model.status();
  if (interrupted) return leftAsItWas(dir, "interrupted");
  Result<std::optional<Curve3>> target = readSavedTarget(dir, model.value());
  if (!target.isOk()) return target.status();
  if (target.value()) files[ModelFileNames::targetCurve] = target.value()->sha256;
  // A result that failed its gate is exported only on purpose, and marked. Its gate is the one
  // report.json records where the meshes are the bytes the run wrote and judged (their hashes
  // there), by the same dform and the same limits; else (or when asked) it is run again on the
  // meshes, with the limits of the preset report.json names, else the default ones.
  const bool hasReport = fs::exists(fs::path(dir) / "report.json");
  bool failedGate = false;
  std::string gateName = "default";
  if (hasReport) {
    Result<std::optional<bool>> verdict = savedGateVerdict(dir);
    if (!verdict.isOk()) return verdict.status();
    failedGate = verdict.value() == false;
    const Result<std::string> recorded = savedGateName(dir);
    const Result<std::string> templates = templatesDir();
    if (!templates.isOk()) return templates.status();
    if (recorded.isOk() &&
        fs::exists(fs::path(templates.value()) / "gates" / (recorded.value() + ".json")))
      gateName = recorded.value();
  }
  Result<GateLimits> limits = loadGate(gateName);
  if (!limits.isOk()) return limits.status();
  std::optional<GateReport> recorded;
  if (hasReport && !output.regate) {
    Result<std::optional<GateReport>> reused = reusableGate(dir, files, limits.value());
    if (!reused.isOk()) return reused.status();
    recorded = reused.value();
  }
  if (recorded)
    sink.info("the gate's verdict is report.json's: the meshes are as the run wrote them");
  const GateReport gate = recorded ? *recorded
                                   : measureAndGate(model.value(), limits.value(),
                                                    target.value() ? &*target.value() : nullptr);
  if (interrupted) return leftAsItWas(dir, "interrupted");
  std::string failing;
  for (const CheckResult& c : gate.checks)
    if (c.verdict == CheckResult::Verdict::Fail) failing += (failing.empty() ? "" : ", ") + c.name;
  failedGate = failedGate || !gate.passed();
  if (failedGate && !output.exportAnyway) {
    return Status(ErrorCode::GateFailed,
                  dir + ": the result failed its quality gate '" + gateName +
                      "' (checked again on the meshes: " +
                      (failing.empty() ? "report.json records a failure" : failing + " fail") +
                      "); nothing exported (--export-anyway exports it marked FAILED GATE)");
  }
  // Laid out once: a layout that fails is stamped as it is (the stamp is an overlay).
  std::string modelName;
  const Result<LaidOutExport> laidOut = layOut(
      model.value(), withFolds(exporting.value(), savedFolds(dir, modelName), modelName, sink),
      savedJobName(dir));
  if (interrupted) return leftAsItWas(dir, "interrupted");
  if (!laidOut.isOk()) return laidOut.status();
  const LayoutFindings& layout = laidOut.value().layout;
  if (layout.problems() > 0 && !output.exportAnyway) {
    return Status(ErrorCode::GateFailed,
                  dir + ": the pattern does not lay out cleanly (" + layoutCheck(layout).detail +
                      "); nothing exported (--export-anyway exports it marked FAILED GATE)");
  }
  failedGate = failedGate || layout.problems() > 0;
  const Result<PreparedExport> prepared = render(model.value(), laidOut.value(), failedGate);
  if (interrupted) return leftAsItWas(dir, "interrupted");
  if (!prepared.isOk()) return prepared.status();
  noteExport(prepared.value(), sink);
  // -o: the pattern set goes into a folder of its own, as one transaction too, and the result
  // folder is left as it is (its lock is released unchanged).
  if (!output.outDir.empty()) {
    ResultFolder out;
    if (Status s = out.begin(output.outDir, resultFileNames()); !s.isOk()) return s;
    if (Status s = writeExport(prepared.value(), out.staging()).status(); !s.isOk())
      return out.named(s);
    if (Status s = commitUnlessInterrupted(out, output.outDir, interrupted, &sink); !s.isOk())
      return s;
    return output.outDir;
  }
  // The result's own files go into the new folder unchanged; earlier cutting files do not.
  for (const char* kept : {ModelFileNames::aFlat, ModelFileNames::a3d, ModelFileNames::bFlat,
                           ModelFileNames::b3d, ModelFileNames::targetCurve, "report.json"})
    if (fs::exists(fs::path(dir) / kept))
      if (Status s = folder.carryOver(kept); !s.isOk()) return s;
  if (Status s = writeExport(prepared.value(), folder.staging()).status(); !s.isOk())
    return folder.named(s);
  // The report page shows the pattern: redrawn with the new one.
  if (hasReport) {
    const std::string reportPath = (fs::path(dir) / "report.json").string();
    const Result<std::string> report = readInputFile(reportPath);
    if (!report.isOk()) return report.status();
    if (Status s = writeReportPage(folder.staging(), report.value(), reportPath, &prepared.value(),
                                   model.value());
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

Result<std::string> exportSavedResult(const std::string& dir, const OutputOptions& output,
                                      MessageSink& sink, const std::atomic<bool>& interrupted) {
  try {
    return exportSavedOrThrow(dir, output, sink, interrupted);
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
