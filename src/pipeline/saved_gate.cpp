// SPDX-License-Identifier: GPL-3.0-or-later
#include "saved_gate.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dform/io/curve_reader.h"
#include "dform/pipeline/job_file.h"
#include "dform/pipeline/report.h"
#include "reference_seams.h"
#include "run_steps.h"

namespace dform {

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
    fold.crease = f.contains("crease") && f["crease"] == true;  // drawn as the crease line
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

Result<SavedModel> readSaved(const std::string& dir) {
  SavedModel saved;
  Result<DForm> model = readModel(dir, &saved.files);
  if (!model.isOk()) return model.status();
  saved.model = std::move(model.value());
  Result<std::optional<Curve3>> target = readSavedTarget(dir, saved.model);
  if (!target.isOk()) return target.status();
  saved.target = std::move(target.value());
  if (saved.target) saved.files[ModelFileNames::targetCurve] = saved.target->sha256;
  return saved;
}

Result<SavedGate> judgeSaved(const std::string& dir, const SavedModel& saved, bool regate,
                             MessageSink& sink) {
  // Its gate is the one report.json records where the meshes are the bytes the run wrote and
  // judged (their hashes there), by the same dform and the same limits; else (or when asked) it
  // is run again on the meshes (report.json's verdicts could have been edited), with the limits
  // of the preset report.json names, else the default ones.
  SavedGate judged;
  judged.gateName = "default";
  const bool hasReport = fs::exists(fs::path(dir) / "report.json");
  if (hasReport) {
    Result<std::optional<bool>> verdict = savedGateVerdict(dir);
    if (!verdict.isOk()) return verdict.status();
    judged.failed = verdict.value() == false;
    const Result<std::string> recorded = savedGateName(dir);
    const Result<std::string> templates = templatesDir();
    if (!templates.isOk()) return templates.status();
    if (recorded.isOk() &&
        fs::exists(fs::path(templates.value()) / "gates" / (recorded.value() + ".json")))
      judged.gateName = recorded.value();
  }
  Result<GateLimits> limits = loadGate(judged.gateName);
  if (!limits.isOk()) return limits.status();
  std::optional<GateReport> recorded;
  if (hasReport && !regate) {
    Result<std::optional<GateReport>> reused = reusableGate(dir, saved.files, limits.value());
    if (!reused.isOk()) return reused.status();
    recorded = reused.value();
  }
  judged.reused = recorded.has_value();
  if (judged.reused)
    sink.info(dir + ": the gate's verdict is report.json's: the meshes are as the run wrote them");
  judged.gate = recorded ? *recorded
                         : measureAndGate(saved.model, limits.value(),
                                          saved.target ? &*saved.target : nullptr);
  for (const CheckResult& c : judged.gate.checks)
    if (c.verdict == CheckResult::Verdict::Fail)
      judged.failing += (judged.failing.empty() ? "" : ", ") + c.name;
  judged.failed = judged.failed || !judged.gate.passed();
  return judged;
}

Status gateRefusal(const std::string& dir, const SavedGate& judged) {
  return Status(
      ErrorCode::GateFailed,
      dir + ": the result failed its quality gate '" + judged.gateName +
          "' (checked again on the meshes: " +
          (judged.failing.empty() ? "report.json records a failure" : judged.failing + " fail") +
          "); nothing exported (" + mention(Setting::ExportAnyway) +
          " exports it marked FAILED GATE)");
}

}  // namespace dform
