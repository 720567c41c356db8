// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/report.h"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "dform/core/atomic_file.h"
#include "dform/core/constants.h"
#include "dform/core/input_file.h"
#include "dform/core/message_text.h"
#include "json_values.h"

namespace dform {

namespace {

using nlohmann::json;

// The inverse figures measured against the target curve.
void addCurveMatch(json& metrics, const CurveMatch& c) {
  metrics["D_error"] = numberOrNull(c.curveError);
  metrics["curve_distance_max_mm"] = numberOrNull(c.curveDistanceMaxMm);
  metrics["roundtrip_rms_rel"] = numberOrNull(c.roundtripRmsRel);
  metrics["roundtrip_max_rel"] = numberOrNull(c.roundtripMaxRel);
  metrics["roundtrip_note"] = c.roundtripNote;
}

// A seam point's index, or null where a fold crosses a chord between seam points.
json seamPointOrNull(int k) { return k < 0 ? json(nullptr) : json(k); }

// The exact body's folds through the pieces, each with its ends in its piece's flat coordinates.
json foldsJson(const ModelUsed& used, const DForm& model) {
  json out = json::array();
  for (const BodyFold& f : used.folds) {
    const Points2& flat = f.piece == 0 ? model.a.flat : model.b.flat;
    const auto at = [&](int v) {
      return json::array({numberOrNull(flat(v, 0)), numberOrNull(flat(v, 1))});
    };
    json fold = {{"piece", f.piece == 0 ? "A" : "B"},
                 {"from_mm", at(f.from)},
                 {"to_mm", at(f.to)},
                 {"from_seam_point", seamPointOrNull(f.fromSeamPoint)},
                 {"to_seam_point", seamPointOrNull(f.toSeamPoint)},
                 {"body_edge", json::array({f.edgeFrom, f.edgeTo})},
                 {"length_mm", numberOrNull((flat.row(f.from) - flat.row(f.to)).norm())},
                 {"angle_deg", numberOrNull(f.radians / kDegree)},
                 {"angle_rad", numberOrNull(f.radians)},
                 {"crease", f.crease >= 0}};
    if (f.crease >= 0) fold["crease_index"] = f.crease + 1;
    out.push_back(std::move(fold));
  }
  return out;
}

// Which model made the shape, why, and what the exact engine found.
json modelJson(const ModelUsed& used, const DForm& model) {
  json creases = json::array();
  for (const FoundCrease& c : used.creases)
    creases.push_back({{"piece", c.piece == 0 ? "A" : "B"},
                       {"crease", c.crease + 1},
                       {"angle_deg", numberOrNull(c.angleDeg)},
                       {"length_mm", numberOrNull(c.lengthMm)}});
  json out = {{"name", used.name}, {"reason", used.reason}};
  if (used.name == "exact")
    out.update(
        {{"cone_points", used.conePoints},
         {"newton_steps", used.newtonSteps},
         {"max_curvature_rad", numberOrNull(used.maxCurvature)},
         {"chord_move_mm", numberOrNull(used.chordMoveMm)},
         {"doubly_covered", used.doublyCovered},
         {"precision_mm", numberOrNull(used.precisionMm)},
         {"pouch", used.pouch.empty()
                       ? json(nullptr)
                       : json{{"case", used.pouch},
                              {"deviation_mm", numberOrNull(used.flatDeviationMm)},
                              {"thickness_mm", used.pouch == "thin" ? numberOrNull(used.thicknessMm)
                                                                    : json(nullptr)}}},
         {"found_creases", creases},
         {"folds", foldsJson(used, model)}});
  if (used.name == "ruled") {
    json states = json::array();
    for (const RuledStateSummary& state : used.states)
      states.push_back({{"start", state.start},
                        {"bending_energy", numberOrNull(state.bendingEnergy)},
                        {"largest_fold_deg", numberOrNull(state.largestFoldDeg)},
                        {"ranking_energy", numberOrNull(state.rankingEnergy)}});
    out.update({{"bending_energy", numberOrNull(used.bendingEnergy)},
                {"length_error", numberOrNull(used.lengthError)},
                {"stationarity", numberOrNull(used.stationarity)},
                {"flips", used.flips},
                {"flips_stationary", used.flipsStationary},
                {"interior_vertices", used.interiorVertices},
                {"states", states},
                {"found_creases", creases},
                {"folds", foldsJson(used, model)}});
  }
  if (used.name == "general")
    out.update({{"newton_steps", used.newtonSteps},
                {"stationarity", numberOrNull(used.stationarity)},
                {"stiffness", numberOrNull(used.stiffness)}});
  return out;
}

// An input file: its path, the SHA-256 of the bytes the run read (hashed as they were read, not
// by opening the file again) and one measured size.
json inputJson(const std::string& path, const std::string& sha256, const char* sizeKey,
               double size) {
  return {{"path", utf8Text(path)},
          {"sha256", sha256.empty() ? json(nullptr) : json(sha256)},
          {sizeKey, numberOrNull(size)}};
}

json solverJson(const LocalGlobalSummary& relaxation, const SolverSummary& s) {
  json iterations = json::array();
  for (const IterationSummary& it : s.iterations) {
    json terms = json::object();
    for (std::size_t t = 0; t < it.termCosts.size() && t < s.termNames.size(); ++t)
      terms[s.termNames[t]] = numberOrNull(it.termCosts[t]);
    iterations.push_back({{"iteration", it.iteration},
                          {"cost", numberOrNull(it.cost)},
                          {"term_costs", terms},
                          {"step_norm", numberOrNull(it.stepNorm)},
                          {"damping", numberOrNull(it.damping)},
                          {"accepted", it.accepted},
                          {"refactorised", it.refactorised},
                          {"cg_iterations", it.cgIterations},
                          {"seconds", numberOrNull(it.seconds)}});
  }
  json finalTerms = json::object();
  for (std::size_t t = 0; t < s.finalTermCosts.size() && t < s.termNames.size(); ++t)
    finalTerms[s.termNames[t]] = numberOrNull(s.finalTermCosts[t]);
  return {{"local_global",
           {{"iterations", relaxation.iterations},
            {"initial_energy", numberOrNull(relaxation.initialEnergy)},
            {"final_energy", numberOrNull(relaxation.finalEnergy)},
            {"seconds", numberOrNull(relaxation.seconds)}}},
          {"termination", terminationName(s.termination)},
          {"message", s.message},
          {"initial_cost", numberOrNull(s.initialCost)},
          {"final_cost", numberOrNull(s.finalCost)},
          {"final_term_costs", finalTerms},
          {"factorisations", s.factorisations},
          {"variables", s.numVariables},
          {"residuals", s.numResiduals},
          {"setup_seconds", numberOrNull(s.setupSeconds)},
          {"solve_seconds", numberOrNull(s.totalSeconds)},
          {"iterations", iterations}};
}

json meshJson(const DForm& model) {
  return {{"vertices_a", model.a.flat.rows()},
          {"triangles_a", model.a.F.rows()},
          {"vertices_b", model.b.flat.rows()},
          {"triangles_b", model.b.F.rows()},
          {"seam_vertices", model.a.seam.size()}};
}

// The pipeline's stages, the run as a whole (read to measured model), the command's stages
// around it, and the making of the report; `report` and `total` are taken when the rest of the
// report is made, so that only serialising and writing it come after.
json timingsJson(const Timings& t, const CommandTimings& command,
                 std::chrono::steady_clock::time_point reportStart) {
  const auto now = std::chrono::steady_clock::now();
  const auto seconds = [](auto duration) {
    return std::chrono::duration<double>(duration).count();
  };
  return {{"read", numberOrNull(t.read)},
          {"mesh", numberOrNull(t.mesh)},
          {"solve", numberOrNull(t.solve)},
          {"run", numberOrNull(t.total)},
          {"gate", numberOrNull(command.gate)},
          {"write", numberOrNull(command.write)},
          {"export", numberOrNull(command.exportFiles)},
          {"report", numberOrNull(seconds(now - reportStart))},
          {"total", numberOrNull(seconds(now - command.start))}};
}

json messagesJson(const std::vector<Message>& messages) {
  json out = json::array();
  for (const Message& m : messages)
    out.push_back({{"level", levelName(m.level)}, {"text", plainSettings(m.text)}});
  return out;
}

json gateJson(const GateReport* gate) {
  if (!gate) return nullptr;
  json checks = json::array();
  for (const CheckResult& c : gate->checks)
    checks.push_back({{"name", c.name},
                      {"value", numberOrNull(c.value)},
                      {"limit", numberOrNull(c.limit)},
                      {"verdict", verdictName(c.verdict)},
                      {"detail", c.detail}});
  return {{"name", gate->name},        {"limits", json::parse(gateLimitsJson(gate->limits))},
          {"passed", gate->passed()},  {"failed", gate->failed()},
          {"not_run", gate->notRun()}, {"checks", checks}};
}

// Each crease's fold as solved: the piece, its number there (from 1), mountain or valley as seen
// from the pattern's printed side (the D-Form's outside), angles in degrees, flat length in mm.
json creasesJson(const DForm& model) {
  json out = json::array();
  for (const Piece* piece : {&model.a, &model.b}) {
    const std::vector<CreaseFold> folds = creaseFolds(*piece);
    for (std::size_t k = 0; k < folds.size(); ++k)
      out.push_back({{"piece", piece->name},
                     {"crease", k + 1},
                     {"fold", foldDirectionName(folds[k].direction)},
                     {"angle_deg", numberOrNull(folds[k].angleDeg)},
                     {"min_angle_deg", numberOrNull(folds[k].minAngleDeg)},
                     {"max_angle_deg", numberOrNull(folds[k].maxAngleDeg)},
                     {"length_mm", numberOrNull(folds[k].lengthMm)}});
  }
  return out;
}

json header(const Job& job, const char* mode) {
  return {{"schema", kReportSchema},
          {"schema_version", kReportSchemaVersion},
          {"tool", {{"name", "dform"}, {"version", DFORM_VERSION}}},
          {"mode", mode},
          {"job", json::parse(jobToJson(job))}};
}

Result<std::string> write(const std::string& dir, const json& report) {
  std::string text = report.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
  if (Status s = writeFileAtomically((std::filesystem::path(dir) / "report.json").string(), text);
      !s.isOk())
    return s;
  return text;
}

}  // namespace

json metricsJson(const Metrics& m) {
  return {{"L_error", numberOrNull(m.lengthError)},
          {"L_max", numberOrNull(m.lengthErrorMax)},
          {"B_error", numberOrNull(m.seamError)},
          {"seam_gap_mm", numberOrNull(m.seamGapMm)},
          {"angle_defect_max_rad", numberOrNull(m.gaussMax)},
          {"angle_defect_mean_rad", numberOrNull(m.gaussMean)},
          {"flipped_2d", m.flipped2d},
          {"flipped_3d", m.flipped3d},
          {"degenerate_2d", m.degenerate2d},
          {"degenerate_3d", m.degenerate3d},
          {"seam_length_a_mm", numberOrNull(m.seamLengthAMm)},
          {"seam_length_b_mm", numberOrNull(m.seamLengthBMm)},
          {"seam_length_3d_mm", numberOrNull(m.seamLength3dMm)},
          {"exact_distance_rms_rel", numberOrNull(m.exactDistanceRmsRel)},
          {"exact_distance_max_rel", numberOrNull(m.exactDistanceMaxRel)},
          {"exact_note", m.exactNote}};
}

std::string metricsJsonText(const Metrics& metrics, const CurveMatch* curve) {
  json figures = metricsJson(metrics);
  if (curve) addCurveMatch(figures, *curve);
  return figures.dump(-1, ' ', false, json::error_handler_t::replace);
}

Result<std::string> writeForwardReport(const std::string& dir, const Job& job,
                                       const ForwardRun& run, const std::vector<Message>& messages,
                                       const GateReport* gate, const CommandTimings& command,
                                       const FileHashes& resultFiles) {
  const auto reportStart = std::chrono::steady_clock::now();
  json report = header(job, "forward");
  report["inputs"] = {{"piece_a", inputJson(std::get<ForwardJob>(job.run).pieceA, run.sha256A,
                                            "perimeter_mm", run.perimeterA)},
                      {"piece_b", inputJson(std::get<ForwardJob>(job.run).pieceB, run.sha256B,
                                            "perimeter_mm", run.perimeterB)}};
  report["fit_perimeter_scale"] = numberOrNull(run.scaleB);
  report["start_fraction_a"] = numberOrNull(run.startFractionA);
  report["start_fraction_b"] = numberOrNull(run.startFractionB);
  report["model"] = modelJson(run.modelUsed, run.model);
  report["mesh"] = meshJson(run.model);
  report["solver"] = solverJson(run.relaxation, run.summary);
  report["solver"]["constraint_rounds"] = run.constraintRounds;
  report["metrics"] = metricsJson(run.metrics);
  report["creases"] = creasesJson(run.model);
  report["gate"] = gateJson(gate);
  report["result_files"] = resultFiles;
  report["messages"] = messagesJson(messages);
  report["timings"] = timingsJson(run.timings, command, reportStart);
  return write(dir, report);
}

Result<std::string> writeInverseReport(const std::string& dir, const Job& job,
                                       const InverseRun& run, const std::vector<Message>& messages,
                                       const GateReport* gate, const CommandTimings& command,
                                       const FileHashes& resultFiles) {
  const auto reportStart = std::chrono::steady_clock::now();
  json report = header(job, "inverse");
  report["inputs"] = {{"curve", inputJson(std::get<InverseJob>(job.run).curve, run.target.sha256,
                                          "length_mm", run.curveLength)}};
  report["model"] = modelJson(run.modelUsed, run.model);
  report["pre_dform"] = {{"on_hull", run.pre.onHull},
                         {"is_hull", run.pre.isHull},
                         {"inside_vertices", run.pre.insideVertices.size()},
                         {"summary", run.pre.summary}};
  report["mesh"] = meshJson(run.model);
  report["solver"] = solverJson(run.relaxation, run.summary);
  report["metrics"] = metricsJson(run.metrics);
  addCurveMatch(report["metrics"], run.curveMatch);
  report["metrics"]["curve_length_mm"] = numberOrNull(run.curveLength);
  report["gate"] = gateJson(gate);
  report["result_files"] = resultFiles;
  report["messages"] = messagesJson(messages);
  report["timings"] = timingsJson(run.timings, command, reportStart);
  return write(dir, report);
}

namespace {

Result<json> readReport(const std::string& dir) {
  const std::string path = (std::filesystem::path(dir) / "report.json").string();
  const Result<std::string> text = readInputFile(path);
  if (!text.isOk()) return text.status();
  try {
    return json::parse(text.value());
  } catch (const json::exception& e) {
    return Status(ErrorCode::InputUnreadable,
                  path + ": not valid JSON (" + parserReason(e.what()) + ")");
  }
}

}  // namespace

Result<std::optional<GateReport>> reusableGate(const std::string& dir, const FileHashes& files,
                                               const GateLimits& limits) {
  Result<json> read = readReport(dir);
  if (!read.isOk()) return read.status();
  const json& report = read.value();
  const std::optional<GateReport> none;
  const json* version = report.is_object() && report.contains("tool") && report["tool"].is_object()
                            ? &report["tool"]
                            : nullptr;
  if (!version || version->value("version", json()) != DFORM_VERSION) return none;
  if (!report.contains("result_files") || report["result_files"] != json(files)) return none;
  const json& gate = report.contains("gate") ? report["gate"] : json(nullptr);
  if (!gate.is_object() || gate.value("name", json()) != limits.name || !gate.contains("limits") ||
      gate["limits"] != json::parse(gateLimitsJson(limits)) || !gate.contains("checks") ||
      !gate["checks"].is_array())
    return none;
  GateReport out;
  out.name = limits.name;
  out.limits = limits;
  for (const json& c : gate["checks"]) {
    if (!c.is_object() || !c.contains("name") || !c["name"].is_string() || !c.contains("verdict") ||
        !c["verdict"].is_string())
      return none;
    if (c["name"] == "pattern_layout") continue;  // the export lays its own pattern out
    CheckResult check;
    check.name = c["name"].get<std::string>();
    check.value = c.contains("value") && c["value"].is_number() ? c["value"].get<double>() : NAN;
    check.limit = c.contains("limit") && c["limit"].is_number() ? c["limit"].get<double>() : NAN;
    check.detail = c.value("detail", std::string());
    const std::string verdict = c["verdict"].get<std::string>();
    bool known = false;
    for (CheckResult::Verdict v :
         {CheckResult::Verdict::Pass, CheckResult::Verdict::Fail, CheckResult::Verdict::NotRun})
      if (verdict == verdictName(v)) {
        check.verdict = v;
        known = true;
      }
    if (!known) return none;
    out.checks.push_back(check);
  }
  return std::optional<GateReport>(std::move(out));
}

Result<std::optional<bool>> savedGateVerdict(const std::string& dir) {
  Result<json> report = readReport(dir);
  if (!report.isOk()) return report.status();
  const json& gate = report.value().contains("gate") ? report.value()["gate"] : json(nullptr);
  if (gate.is_null()) return std::optional<bool>();
  if (!gate.is_object() || !gate.contains("passed") || !gate["passed"].is_boolean())
    return Status(ErrorCode::InputInvalid, dir + "/report.json: its gate has no verdict");
  return std::optional<bool>(gate["passed"].get<bool>());
}

Result<std::string> savedGateName(const std::string& dir) {
  Result<json> report = readReport(dir);
  if (!report.isOk()) return report.status();
  const json& saved = report.value();
  if (!saved.is_object() || !saved.contains("gate") || !saved["gate"].is_object() ||
      !saved["gate"].contains("name") || !saved["gate"]["name"].is_string())
    return Status(ErrorCode::InputInvalid, dir + "/report.json: records no gate");
  return saved["gate"]["name"].get<std::string>();
}

namespace {

// The model's entry in report.json holds the entries dform writes for the model it names, no
// more and no fewer: an exact result relabelled paper keeps the exact engine's cone points and
// folds, a paper one relabelled general lacks the sheet's stiffness.
void compareModelEntries(const json& saved, const std::string& name,
                         std::vector<std::string>& differences) {
  ModelUsed named;
  named.name = name;
  const json written = modelJson(named, DForm{});
  for (const auto& [key, value] : written.items())
    if (!saved.contains(key))
      differences.push_back("model." + key + ": report.json has none, which the " + name +
                            " model writes");
  for (const auto& [key, value] : saved.items())
    if (!written.contains(key))
      differences.push_back("model." + key + ": report.json says " + describeJsonValue(value) +
                            ", which the " + name + " model does not write");
}

// What report.json says of how the result was made, against the result: its schema, the model
// it names (an exact result lies on the exact shape: its seam within 1e-6 of the diagonal of
// it, or of its curve zipped again), the inputs it records and the job's resolution.
void compareSavedJob(const json& report, const Metrics& metrics, const CurveMatch* curve,
                     std::vector<std::string>& differences) {
  const auto differ = [&differences](const std::string& what) { differences.push_back(what); };
  const auto at = [](const json& object, const char* key) {
    return object.is_object() && object.contains(key) ? object[key] : json(nullptr);
  };
  if (at(report, "schema") != kReportSchema || at(report, "schema_version") != kReportSchemaVersion)
    differ("schema: report.json says " + describeJsonValue(at(report, "schema")) + " version " +
           describeJsonValue(at(report, "schema_version")) + ", dform writes \"" + kReportSchema +
           "\" version " + std::to_string(kReportSchemaVersion));
  const json model = at(at(report, "model"), "name");
  const double exactDistance = curve ? curve->roundtripMaxRel : metrics.exactDistanceMaxRel;
  if (model != "exact" && model != "ruled" && model != "paper" && model != "general")
    differ("model.name: report.json says " + describeJsonValue(model) +
           ", not exact, ruled, paper or general");
  else if (model == "exact" && !(exactDistance <= 1e-6))
    differ("model.name: report.json says exact, but the saved shape is " +
           describeJsonValue(json(exactDistance)) + " of its size from the exact one");
  else
    compareModelEntries(at(report, "model"), model.get<std::string>(), differences);
  const json job = at(report, "job"), inputs = at(report, "inputs");
  const std::vector<std::string> names =
      curve ? std::vector<std::string>{"curve"} : std::vector<std::string>{"piece_a", "piece_b"};
  for (const std::string& name : names) {
    const json input = at(inputs, name.c_str()), path = at(input, "path"),
               hash = at(input, "sha256");
    const json named = at(job, name.c_str());
    // A shape or curve given in memory (the Python module, the studio) has no bytes to hash.
    const bool hashed = hash.is_string() && hash.get<std::string>().size() == 64;
    if (!path.is_string() || !(hashed || hash.is_null()))
      differ("inputs." + name + ": report.json records no path and SHA-256 of it");
    else if (!named.is_string() || std::filesystem::path(named.get<std::string>()).filename() !=
                                       std::filesystem::path(path.get<std::string>()).filename())
      differ("job." + name + ": report.json says " + describeJsonValue(named) +
             ", its inputs record " + describeJsonValue(path));
  }
  const json resolution = at(job, "resolution"), seam = at(at(report, "mesh"), "seam_vertices");
  if (!resolution.is_number_integer() || !seam.is_number_integer() ||
      seam.get<long long>() < resolution.get<long long>())
    differ("job.resolution: report.json says " + describeJsonValue(resolution) + ", the seam has " +
           describeJsonValue(seam) + " vertices");
}

}  // namespace

Result<std::vector<std::string>> compareWithReport(const std::string& dir, const DForm& model,
                                                   const Metrics& metrics,
                                                   const CurveMatch* curve) {
  Result<json> read = readReport(dir);
  if (!read.isOk()) return read.status();
  const json& report = read.value();
  if (!report.is_object()) return std::vector<std::string>{"report.json is not a JSON object"};
  std::vector<std::string> differences;
  // An entry of report.json next to the value the saved result gives.
  const auto compare = [&differences](const std::string& name, const json& saved, const json& now) {
    const bool bothNumbers = saved.is_number() && now.is_number();
    const bool same = bothNumbers ? std::abs(saved.get<double>() - now.get<double>()) <=
                                        1e-9 * std::max(1.0, std::abs(now.get<double>()))
                                  : saved == now;
    if (!same)
      differences.push_back(
          name + ": report.json says " +
          (saved.is_discarded() ? std::string("nothing") : describeJsonValue(saved)) +
          ", the saved result gives " + describeJsonValue(now));
  };
  const auto entry = [](const json& object, const std::string& key) {
    return object.is_object() && object.contains(key) ? object[key]
                                                      : json(json::value_t::discarded);
  };
  compare("mode (inverse when the folder holds target-curve.obj)", entry(report, "mode"),
          curve ? "inverse" : "forward");
  const json mesh = entry(report, "mesh"), meshNow = meshJson(model);
  for (const auto& [key, value] : meshNow.items()) compare("mesh." + key, entry(mesh, key), value);
  json now = metricsJson(metrics);
  if (curve) addCurveMatch(now, *curve);
  const json saved = entry(report, "metrics");
  for (const auto& [key, value] : now.items()) compare("metrics." + key, entry(saved, key), value);
  // A figure the saved result does not give is one report.json may not claim either; an inverse
  // report's curve_length_mm (the curve as read, before resampling) is the one it adds.
  if (saved.is_object())
    for (const auto& [key, value] : saved.items())
      if (!now.contains(key) && !(curve && key == "curve_length_mm"))
        differences.push_back("metrics." + key + ": report.json says " + describeJsonValue(value) +
                              ", a figure dform does not write");
  compareSavedJob(report, metrics, curve, differences);
  return differences;
}

}  // namespace dform
