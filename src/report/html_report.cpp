// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/report/html_report.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <kainjow/mustache.hpp>
#include <nlohmann/json.hpp>

#include "convergence_plot.h"
#include "dform/core/input_file.h"
#include "dform/core/message_text.h"
#include "dform/report/views.h"
#include "dform/validate/metrics.h"
#include "viewer_model.h"

namespace dform {

namespace {

namespace fs = std::filesystem;
using kainjow::mustache::data;
using nlohmann::json;

std::string show(const json& v) {
  if (v.is_null()) return "\u2014";  // not a finite number, or a stage that did not run
  if (v.is_number_float()) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v.get<double>());
    return text;
  }
  return v.is_string() ? v.get<std::string>()
                       : v.dump(-1, ' ', false, json::error_handler_t::replace);
}

// {key, value} rows of a JSON object, for a two-column table.
data keyValueRows(const json& object) {
  data rows{data::type::list};
  for (const auto& [key, value] : object.items()) {
    data row;
    row.set("key", key);
    row.set("value", show(value));
    rows.push_back(row);
  }
  return rows;
}

// Objective per term and in total against the iteration, from report.json's solver history
// (iteration 0 is the total before the first step).
std::vector<PlotSeries> convergenceSeries(const json& solver) {
  std::vector<PlotSeries> series{{"total", {{0.0, solver.value("initial_cost", 0.0)}}}};
  for (const json& it : solver["iterations"]) {
    const double x = it["iteration"].get<double>();
    series[0].points.emplace_back(x, it["cost"].get<double>());
    for (const auto& item : it["term_costs"].items()) {
      // Not a structured binding: C++17 lambdas cannot capture those (clang refuses).
      const std::string& term = item.key();
      auto s = std::find_if(series.begin(), series.end(),
                            [&](const PlotSeries& p) { return p.name == term; });
      if (s == series.end()) s = series.insert(series.end(), PlotSeries{term, {}});
      s->points.emplace_back(x, item.value().get<double>());
    }
  }
  return series;
}

// One row per crease of either piece: its fold from the solved shape (validate's creaseFolds).
data creaseRows(const DForm& model) {
  auto fixed = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", v);
    return std::string(text);
  };
  data rows{data::type::list};
  for (const Piece* p : {&model.a, &model.b}) {
    const std::vector<CreaseFold> folds = creaseFolds(*p);
    for (size_t k = 0; k < folds.size(); ++k) {
      data row;
      row.set("piece", p->name);
      row.set("number", std::to_string(k + 1));
      row.set("direction", foldDirectionName(folds[k].direction));
      row.set("angle", fixed(folds[k].angleDeg));
      row.set("range", fixed(folds[k].minAngleDeg) + " to " + fixed(folds[k].maxAngleDeg));
      row.set("length", fixed(folds[k].lengthMm));
      rows.push_back(row);
    }
  }
  return rows;
}

// The shape's still pictures from four viewpoints, each {svg, caption}; the interactive view's
// first one is the first of them.
data stillViews(const DForm& model) {
  data views{data::type::list};
  for (const auto& [azimuth, elevation, caption] :
       std::vector<std::tuple<double, double, std::string>>{{30, 25, "from the front, above"},
                                                            {120, 10, "from the side"},
                                                            {-60, -30, "from below"},
                                                            {0, 89, "from the top"}}) {
    View view;
    view.azimuthDeg = azimuth;
    view.elevationDeg = elevation;
    view.widthPx = 280;
    data item;
    item.set("svg", shapeSvg(model, view));
    item.set("caption", caption);
    views.push_back(item);
  }
  return views;
}

// The pattern as inline SVG: the file minus its XML declaration.
// The exact body's folds from report.json (none for the paper model).
std::vector<FlatFold> flatFolds(const json& report) {
  std::vector<FlatFold> out;
  if (!report.contains("model") || !report["model"].contains("folds")) return out;
  for (const json& f : report["model"]["folds"]) {
    const json &from = f["from_mm"], &to = f["to_mm"];
    if (!from[0].is_number() || !from[1].is_number() || !to[0].is_number() || !to[1].is_number())
      continue;
    out.push_back({f["piece"] == "A" ? 0 : 1,
                   {from[0].get<double>(), from[1].get<double>()},
                   {to[0].get<double>(), to[1].get<double>()},
                   f["crease"].get<bool>()});
  }
  return out;
}

std::string inlineSvg(const std::string& svg) {
  const auto start = svg.find("<svg");
  return start == std::string::npos ? std::string() : svg.substr(start);
}

}  // namespace

Result<std::string> renderReportHtml(const ReportSources& sources, const DForm& model,
                                     const std::string& templatesDir) {
  const Result<std::string> templateText =
      readInputFile(templatesDir + "/report/report.html.mustache");
  if (!templateText.isOk()) return templateText.status();
  const Result<std::string> viewerScript = readInputFile(templatesDir + "/report/viewer.js");
  if (!viewerScript.isOk()) return viewerScript.status();
  json report;
  try {
    report = json::parse(sources.reportJson);
  } catch (const json::exception& e) {
    return Status(ErrorCode::InputUnreadable,
                  sources.reportPath + ": not valid JSON (" + parserReason(e.what()) + ")");
  }

  data page;
  const std::string mode = report.value("mode", "forward");
  const json& job = report["job"];
  page.set("title", mode == "forward"
                        ? fs::path(job.value("piece_a", "")).filename().string() + " + " +
                              fs::path(job.value("piece_b", "")).filename().string()
                        : fs::path(job.value("curve", "")).filename().string());
  page.set("mode", mode);
  page.set("version", show(report["tool"]["version"]));
  page.set("schema_version", show(report["schema_version"]));

  data checks{data::type::list};
  const json& gate = report["gate"];
  if (gate.is_object()) {
    const bool passed = gate["passed"].get<bool>();
    page.set("verdict", passed ? "PASSED" : "FAILED GATE");
    page.set("verdict_class", passed ? "passed" : "failed");
    page.set("verdict_note", "gate '" + show(gate["name"]) +
                                 "': " + std::to_string(gate["failed"].get<int>()) + " failed, " +
                                 std::to_string(gate["not_run"].get<int>()) + " not run");
    for (const json& c : gate["checks"]) {
      data row;
      row.set("name", show(c["name"]));
      row.set("value", show(c["value"]));
      row.set("limit", show(c["limit"]));
      row.set("verdict", show(c["verdict"]));
      row.set("detail", show(c["detail"]));
      row.set("row_class", c["verdict"] == "fail"      ? "fail"
                           : c["verdict"] == "not run" ? "notrun"
                                                       : "");
      checks.push_back(row);
    }
  } else {
    page.set("verdict", "NO GATE");
    page.set("verdict_class", "none");
    page.set("verdict_note", std::string("the run was made with ") + settingKey(Setting::Gate) +
                                 " none: no quality gate judged it");
  }
  page.set("checks", checks);

  page.set("metrics", keyValueRows(report["metrics"]));

  // Which model made the shape and how far it is from the one the cut pieces make.
  const json& model_ = report.contains("model") ? report["model"] : json();
  page.set("has_model",
           model_.is_object() ? data(data::type::bool_true) : data(data::type::bool_false));
  if (model_.is_object()) {
    page.set("model_name", show(model_["name"]));
    page.set("model_reason", show(model_["reason"]));
    const json& m = report["metrics"];
    const bool inverse = mode == "inverse";
    const json& rms = inverse ? m["roundtrip_rms_rel"] : m["exact_distance_rms_rel"];
    const json& max = inverse ? m["roundtrip_max_rel"] : m["exact_distance_max_rel"];
    page.set("object_figure",
             rms.is_number()
                 ? std::string(inverse ? "The pieces zipped again lie " : "The shape lies ") +
                       show(rms) + " (RMS, largest " + show(max) +
                       ") of the seam's bounding-box diagonal from " +
                       (inverse ? "the curve asked for." : "the exact D-Form the cut pieces make.")
                 : "No exact D-Form to compare with: " +
                       show(inverse ? m["roundtrip_note"] : m["exact_note"]) + ".");
    const std::size_t found = model_.contains("found_creases") ? model_["found_creases"].size() : 0;
    page.set("found_creases", found == 0 ? std::string()
                                         : std::to_string(found) +
                                               " crease(s) found by the exact model, drawn on the "
                                               "pattern like drawn ones.");
  }

  page.set("views", stillViews(model));
  View curvatureView;
  curvatureView.curvature = true;
  curvatureView.widthPx = 420;
  const CurvatureMaps maps = curvatureMaps(model);  // once for the two pictures and the scale
  page.set("curvature_3d", shapeSvg(model, curvatureView, &maps));
  const std::vector<FlatFold> folds = flatFolds(report);
  page.set("curvature_flat", flatCurvatureSvg(model, 520, &maps, folds));
  page.set("fold_legend", folds.empty() ? std::string()
                                        : ". Faint lines: the folds of the exact body (" +
                                              std::to_string(folds.size()) +
                                              "), darker where one is a found crease.");
  char scale[32];
  std::snprintf(scale, sizeof scale, "%.3g", maps.scale);
  page.set("curvature_scale", scale);
  page.set("viewer_model", viewerModelJson(model, maps, sources.seamTicks));
  page.set("viewer_js", viewerScript.value());
  page.set("has_ticks",
           sources.seamTicks.empty() ? data(data::type::bool_false) : data(data::type::bool_true));
  page.set("creases", creaseRows(model));
  page.set("has_creases", model.a.creases.empty() && model.b.creases.empty()
                              ? data(data::type::bool_false)
                              : data(data::type::bool_true));

  // The export's pictures, inline when the result has them: has_<key> and <key>_svg.
  for (const auto& [svg, key] :
       {std::pair{&sources.patternSvg, "pattern"}, {&sources.assemblySvg, "assembly"}}) {
    page.set(std::string("has_") + key,
             svg->empty() ? data(data::type::bool_false) : data(data::type::bool_true));
    page.set(std::string(key) + "_svg", inlineSvg(*svg));
  }

  const json& solver = report["solver"];
  page.set("termination", show(solver["termination"]));
  page.set("solver_message", show(solver["message"]));
  page.set("iterations", std::to_string(solver["iterations"].size()));
  page.set("factorisations", show(solver["factorisations"]));
  page.set("convergence_plot", convergencePlotSvg(convergenceSeries(solver), 640, 300));
  const json& relaxation = solver["local_global"];
  page.set("relaxation", std::to_string(relaxation["iterations"].get<int>()) +
                             " local-global iterations, energy " +
                             show(relaxation["initial_energy"]) + " to " +
                             show(relaxation["final_energy"]));
  page.set("timings", keyValueRows(report["timings"]));
  page.set("job", job.dump(2, ' ', false, json::error_handler_t::replace));
  data messages{data::type::list};
  for (const json& m : report["messages"]) {
    if (m["level"] == "debug") continue;
    data row;
    row.set("level", show(m["level"]));
    row.set("text", show(m["text"]));
    messages.push_back(row);
  }
  page.set("messages", messages);

  kainjow::mustache::mustache tmpl{templateText.value()};
  if (!tmpl.is_valid())
    return Status(ErrorCode::Internal,
                  templatesDir + "/report/report.html.mustache: " + tmpl.error_message());
  return tmpl.render(page);
}

}  // namespace dform
