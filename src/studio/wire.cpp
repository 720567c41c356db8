// SPDX-License-Identifier: GPL-3.0-or-later
#include "wire.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

#include "dform/core/polyline.h"
#include "dform/pipeline/report.h"
#include "dform/pipeline/run.h"
#include "dform/pipeline/settings.h"
#include "symmetry.h"

namespace dform::studio {

using nlohmann::json;

std::string base64(const void* data, std::size_t size) {
  static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const std::uint32_t n = (std::uint32_t(bytes[i]) << 16) |
                            (i + 1 < size ? std::uint32_t(bytes[i + 1]) << 8 : 0) |
                            (i + 2 < size ? std::uint32_t(bytes[i + 2]) : 0);
    out += alphabet[(n >> 18) & 63];
    out += alphabet[(n >> 12) & 63];
    out += i + 1 < size ? alphabet[(n >> 6) & 63] : '=';
    out += i + 2 < size ? alphabet[n & 63] : '=';
  }
  return out;
}

std::string percentEncoded(const std::string& text) {
  static const char hex[] = "0123456789ABCDEF";
  std::string out;
  for (const unsigned char c : text) {
    if ((c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '-' ||
        c == '.' || c == '_' || c == '~') {
      out += char(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

namespace {

// Little-endian doubles, row after row (the page reads them as a Float64Array; x86 and ARM
// Linux are little-endian, which the static_assert below pins).
template <typename Matrix>
std::string rowsBase64(const Matrix& m) {
  std::vector<double> values(std::size_t(m.rows()) * m.cols());
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) values[std::size_t(r * m.cols() + c)] = m(r, c);
  return base64(values.data(), values.size() * sizeof(double));
}

std::string indicesBase64(const std::vector<std::uint32_t>& indices) {
  return base64(indices.data(), indices.size() * sizeof(std::uint32_t));
}

std::string facesBase64(const Faces& F) {
  std::vector<std::uint32_t> indices(std::size_t(F.rows()) * 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) indices[std::size_t(f * 3 + k)] = std::uint32_t(F(f, k));
  return indicesBase64(indices);
}

json loops(const std::vector<std::vector<int>>& lines) {
  json out = json::array();
  for (const auto& line : lines) out.push_back(line);
  return out;
}

json pieceJson(const Piece& piece) {
  return {{"flat", rowsBase64(piece.flat)},      {"shape", rowsBase64(piece.shape)},
          {"faces", facesBase64(piece.F)},       {"seam", piece.seam},
          {"free", loops(piece.freeBoundaries)}, {"creases", loops(piece.creases)}};
}

// A figure that may be NaN (no exact D-Form to compare with): null, as report.json writes it.
json numberOrNull(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json figuresJson(const Metrics& metrics) { return json::parse(metricsJsonText(metrics, nullptr)); }

json gateChecks(const GateReport& gate) {
  json checks = json::array();
  for (const CheckResult& c : gate.checks)
    checks.push_back({{"name", c.name},
                      {"value", numberOrNull(c.value)},
                      {"limit", numberOrNull(c.limit)},
                      {"verdict", verdictName(c.verdict)},
                      {"detail", c.detail}});
  return checks;
}

// The gate's verdict: its name, passed, and every check.
json gateJson(const GateReport& gate) {
  return {{"name", gate.name},
          {"passed", gate.passed()},
          {"failed", gate.failed()},
          {"checks", gateChecks(gate)}};
}

json modelJson(const ModelUsed& used) {
  json creases = json::array();
  for (const FoundCrease& c : used.creases)
    creases.push_back({{"piece", c.piece},
                       {"crease", c.crease},
                       {"angle_deg", c.angleDeg},
                       {"length_mm", c.lengthMm}});
  return {{"name", used.name},
          {"reason", used.reason},
          {"cone_points", used.conePoints},
          {"doubly_covered", used.doublyCovered},
          {"found_creases", creases}};
}

json timingsJson(const Timings& t) {
  return {{"read", t.read}, {"mesh", t.mesh}, {"solve", t.solve}, {"total", t.total}};
}

// Flattened loop points, every k-th point so that at most maxPoints remain.
template <typename Matrix>
std::vector<double> flatPoints(const Matrix& points, int maxPoints) {
  const Eigen::Index step = std::max<Eigen::Index>(1, (points.rows() + maxPoints - 1) / maxPoints);
  std::vector<double> out;
  for (Eigen::Index r = 0; r < points.rows(); r += step)
    for (Eigen::Index c = 0; c < points.cols(); ++c) out.push_back(points(r, c));
  return out;
}

double loopLength(const Points2& p) {
  double length = 0;
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    length += (p.row((i + 1) % p.rows()) - p.row(i)).norm();
  return length;
}

// The ruled engine's states, least bending first: each one's start, bending energy and largest
// fold, and the shape of each but the answer (null where it could not be meshed).
json statesJson(const SolvedDForm& run) {
  json states = json::array();
  const std::vector<RuledStateSummary>& found = run.modelUsed.states;
  for (std::size_t s = 0; s < found.size(); ++s) {
    const DForm* shape =
        s > 0 && s - 1 < run.otherStates.size() ? &run.otherStates[s - 1] : nullptr;
    states.push_back({{"start", found[s].start},
                      {"bending_energy", numberOrNull(found[s].bendingEnergy)},
                      {"largest_fold_deg", numberOrNull(found[s].largestFoldDeg)},
                      {"ranking_energy", numberOrNull(found[s].rankingEnergy)},
                      {"pieces", shape && shape->a.F.rows() > 0 && shape->b.F.rows() > 0
                                     ? json{pieceJson(shape->a), pieceJson(shape->b)}
                                     : json(nullptr)}});
  }
  return states;
}

}  // namespace

static_assert(sizeof(double) == 8, "the page reads vertices as 64-bit doubles");

std::string requiredText(const json& request, const char* key) {
  if (!request.contains(key) || !request.at(key).is_string())
    throw RequestError(std::string(key) + ": must be a string");
  return request.at(key).get<std::string>();
}

int pieceIndex(const json& request) {
  const std::string piece = requiredText(request, "piece");
  if (piece != "a" && piece != "b") throw RequestError("piece: must be \"a\" or \"b\"");
  return piece == "a" ? 0 : 1;
}

long sequence(const json& request, bool required) {
  if (!request.contains("seq") && !required) return 0;
  if (!request.contains("seq") || !request.at("seq").is_number_integer())
    throw RequestError("seq: must be a whole number");
  return request.at("seq").get<long>();
}

Job jobFrom(const json& request, const Job& base) {
  if (!request.is_object()) throw RequestError("the request must be a JSON object");
  Job job = base;
  if (Status read = readSettings(job, request.dump()); !read.isOk())
    throw RequestError(read.message());
  if (job.resolution() > kMaxLiveResolution)
    throw RequestError(std::string(settingKey(Setting::Resolution)) + " must be at most " +
                       std::to_string(kMaxLiveResolution) + " in the studio, got " +
                       std::to_string(job.resolution()));
  const std::vector<std::string> profiles = exportProfileNames();
  const std::string& profile = job.exporting.pattern.profile;
  if (std::find(profiles.begin(), profiles.end(), profile) == profiles.end())
    throw RequestError(std::string(settingKey(Setting::Profile)) +
                       ": not one of the shipped export profiles");
  const std::string& gate = job.exporting.gate;
  if (gate.find('/') != std::string::npos || gate.find(".json") != std::string::npos)
    throw RequestError(std::string(settingKey(Setting::Gate)) +
                       ": a gate preset's name (a request names no file)");
  return job;
}

std::vector<std::string> warnings(const std::vector<Message>& messages) {
  std::vector<std::string> out;
  for (const Message& m : messages)
    if (m.level == Level::Warning) out.push_back(plainSettings(m.text));
  return out;
}

std::string studioWords(const Status& status) {
  static const std::map<std::string, std::string> labels = {
      {settingKey(Setting::Flip), "flip B"},
      {settingKey(Setting::FitPerimeter), "match perimeters"},
      {settingKey(Setting::StartA), "A start"},
      {settingKey(Setting::StartB), "B start"},
      {settingKey(Setting::Profile), "profile"},
      {settingKey(Setting::Page), "page"},
      {settingKey(Setting::Sheet), "sheet"},
      {settingKey(Setting::Scale), "scale"},
      {settingKey(Setting::ExportAnyway), "export even if the gate fails"}};
  return status.message([](const std::string& key) {
    const auto label = labels.find(key);
    return "\"" + (label != labels.end() ? label->second : key) + "\"";
  });
}

json exportPlaceholders() {
  json out = json::object();
  for (Setting s : {Setting::Page, Setting::Sheet, Setting::Scale}) {
    const SettingRow* row = findSetting(settingKey(s), true);
    const std::string key = row->key.substr(row->key.find('.') + 1);
    out[key] = !row->unset.empty()
                   ? row->unset
                   : json::parse(settingDefault(*row)).dump() + ": " + row->rangeText();
  }
  return out;
}

json exportChoices() {
  json out = json::object();
  for (Setting s : {Setting::Material, Setting::Numbers, Setting::Hinge}) {
    const SettingRow* row = findSetting(settingKey(s), true);
    json choices = json::array();
    if (row->type == SettingType::Flag) choices = {true, false};
    for (const SettingChoice& c : row->choices) choices.push_back(c.name);
    out[row->key.substr(row->key.find('.') + 1)] = {{"unset", row->unset}, {"choices", choices}};
  }
  return out;
}

std::string designSettings(const Job& job) {
  json settings = json::parse(settingsJson(job));
  for (Setting s : {Setting::StartA, Setting::StartB, Setting::Gate}) settings.erase(settingKey(s));
  settings.erase("export");
  return settings.dump();
}

json verdictJson(const DForm& model, const Metrics& metrics, const GateReport& gate) {
  return {{"figures", figuresJson(metrics)},
          {"gate", gateJson(gate)},
          {"overlay", overlayJson(model, gate)}};
}

json overlayJson(const DForm& model, const GateReport& gate) {
  json pieces = json::array();
  for (const Piece* p : {&model.a, &model.b}) {
    std::vector<std::uint32_t> ends;
    std::vector<double> strain;
    for (const EdgeStrain& e : edgeStrains(*p)) {
      ends.insert(ends.end(), {std::uint32_t(e.from), std::uint32_t(e.to)});
      strain.push_back(e.strain);
    }
    const Eigen::VectorXd curvature = curvatureMap(*p);
    pieces.push_back(
        {{"edges", indicesBase64(ends)},
         {"strain", base64(strain.data(), strain.size() * sizeof(double))},
         {"curvature", base64(curvature.data(), std::size_t(curvature.size()) * sizeof(double))}});
  }
  static const char* kinds[] = {"edges", "vertices", "seam_points"};
  json failing = json::array(), unlocated = json::array();
  const std::vector<FailureSites> sites = locateFailures(model, gate);
  for (const FailureSites& f : sites)
    failing.push_back({{"check", f.check}, {"kind", kinds[int(f.kind)]}, {"items", f.items}});
  for (const CheckResult& c : gate.checks)
    if (c.verdict == CheckResult::Verdict::Fail &&
        std::none_of(sites.begin(), sites.end(),
                     [&](const FailureSites& f) { return f.check == c.name; }))
      unlocated.push_back(c.name);
  return {{"pieces", pieces}, {"failing", failing}, {"unlocated", unlocated}};
}

json forwardResultJson(const SolvedDForm& run) {
  return {{"mode", "forward"},
          {"model", modelJson(run.modelUsed)},
          {"states", statesJson(run)},
          {"pieces", {pieceJson(run.model.a), pieceJson(run.model.b)}},
          {"start_a", run.startFractionA},
          {"start_b", run.startFractionB},
          {"scale_b", run.scaleB},
          {"perimeter_a", run.perimeterA},
          {"perimeter_b", run.perimeterB},
          {"timings", timingsJson(run.timings)}};
}

json inverseResultJson(const InverseRun& run) {
  const CurveMatch& c = run.curveMatch;
  return {{"mode", "inverse"},
          {"model", modelJson(run.modelUsed)},
          {"figures", figuresJson(run.metrics)},
          {"pieces", {pieceJson(run.model.a), pieceJson(run.model.b)}},
          {"curve_match",
           {{"D_error", numberOrNull(c.curveError)},
            {"curve_distance_max_mm", numberOrNull(c.curveDistanceMaxMm)},
            {"roundtrip_rms_rel", numberOrNull(c.roundtripRmsRel)},
            {"roundtrip_max_rel", numberOrNull(c.roundtripMaxRel)},
            {"roundtrip_note", c.roundtripNote}}},
          {"on_hull",
           {{"on_hull", run.pre.onHull},
            {"is_hull", run.pre.isHull},
            {"inside_points", run.pre.insideVertices},
            {"summary", run.pre.summary}}},
          {"target", rowsBase64(run.target.points)},
          {"curve_length", run.curveLength},
          {"timings", timingsJson(run.timings)}};
}

json shapeJson(const Shape2& shape, int maxPoints) {
  json holes = json::array(), holeLengths = json::array(), creases = json::array();
  json holeCorners = json::array();
  for (const Outline2& h : shape.holes) {
    holes.push_back(flatPoints(h.points, maxPoints));
    holeLengths.push_back(loopLength(h.points));
    holeCorners.push_back(cornerFractions(h.points, kCornerTurnRadians));
  }
  for (const CreaseLine& c : shape.creases) creases.push_back(flatPoints(c.points, maxPoints));
  const Points2& p = shape.outer.points;
  return {{"outer", flatPoints(p, maxPoints)},
          {"perimeter", loopLength(p)},
          {"corners", cornerFractions(p, kCornerTurnRadians)},
          {"axes", symmetryFractions(p)},
          {"holes", holes},
          {"hole_corners", holeCorners},
          {"hole_perimeters", holeLengths},
          {"creases", creases},
          {"min", {p.col(0).minCoeff(), p.col(1).minCoeff()}},
          {"max", {p.col(0).maxCoeff(), p.col(1).maxCoeff()}}};
}

json curveJson(const Curve3& curve, int maxPoints) {
  double length = 0;
  const Points3& p = curve.points;
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    length += (p.row((i + 1) % p.rows()) - p.row(i)).norm();
  return {{"points", flatPoints(p, maxPoints)}, {"length", length}};
}

}  // namespace dform::studio
