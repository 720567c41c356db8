// SPDX-License-Identifier: GPL-3.0-or-later
// The convex pairs the project ships (samples/forward) or builds (the studio's parametric
// outlines), written as outline files rounded to a number of decimals, and the exact model's run
// of one (pair, start, flip, resolution, rounding) judged: solved by the exact model, passed by
// the default gate, no mesh edge shorter than 1e-6 of the pieces' size.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "dform/core/polyline.h"
#include "dform/io/outline_reader.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/validate/gate.h"
#include "studio/outlines.h"

namespace dform::convex {

/// An outline file's text and its name (the extension says SVG or JSON).
struct OutlineText {
  std::string name, text;
};

/// Decimals a file is rounded to; kExact keeps every digit (17 significant).
constexpr int kExact = -1;

/// `text` with every decimal number written with at most `decimals` decimals.
inline std::string roundNumbers(const std::string& text, int decimals) {
  if (decimals == kExact) return text;
  static const std::regex number(R"(-?[0-9]+\.[0-9]+(e-?[0-9]+)?)");
  std::string out;
  auto last = text.cbegin();
  for (std::sregex_iterator it(text.begin(), text.end(), number), end; it != end; ++it) {
    out.append(last, it->prefix().second);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, std::stod(it->str()));
    out += buffer;
    last = it->suffix().first;
  }
  out.append(last, text.cend());
  return out;
}

/// A shipped sample, rounded.
inline OutlineText shipped(const std::string& name, int decimals) {
  std::ifstream in(std::string(DFORM_SAMPLES_DIR) + "/forward/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return {name, roundNumbers(text.str(), decimals)};
}

/// A studio outline (studio::parametricOutline) scaled about its centroid to `perimeter` mm and
/// written as a JSON point list with `decimals` decimals.
inline OutlineText built(const std::string& kind, const std::map<std::string, double>& values,
                         double perimeter, int decimals) {
  const nlohmann::json points = nlohmann::json::parse(studio::parametricOutline(kind, values));
  Points2 P(Eigen::Index(points["points"].size()), 2);
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    P.row(i) << points["points"][std::size_t(i)][0].get<double>(),
        points["points"][std::size_t(i)][1].get<double>();
  const Eigen::RowVector2d centre = P.colwise().mean();
  P = ((P.rowwise() - centre) * (perimeter / closedLength(P))).rowwise() +
      Eigen::RowVector2d(200.0, 200.0);
  std::string text = "{\"units\": \"mm\", \"points\": [";
  char buffer[96];
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    if (decimals == kExact)
      std::snprintf(buffer, sizeof buffer, "%s[%.17g, %.17g]", i ? ", " : "", P(i, 0), P(i, 1));
    else
      std::snprintf(buffer, sizeof buffer, "%s[%.*f, %.*f]", i ? ", " : "", decimals, P(i, 0),
                    decimals, P(i, 1));
    text += buffer;
  }
  return {kind + ".json", text + "]}"};
}

/// A pair family: its two outlines at a rounding.
struct Family {
  std::string name;
  std::function<std::pair<OutlineText, OutlineText>(int decimals)> make;
};

/// Every convex pair family: ellipses of several ratios, circle + square, circle + circle,
/// rounded squares, regular polygons, superellipses, Reuleaux shapes.
inline std::vector<Family> families() {
  auto both = [](auto a, auto b) {
    return [a, b](int d) { return std::pair<OutlineText, OutlineText>{a(d), b(d)}; };
  };
  auto sample = [](std::string name) { return [name](int d) { return shipped(name, d); }; };
  auto make = [](std::string kind, std::map<std::string, double> values) {
    return [kind, values](int d) { return built(kind, values, 800.0, d); };
  };
  return {
      {"circle + square", both(sample("circle.svg"), sample("square.svg"))},
      {"ellipses 1.46:1 + 1.34:1", both(sample("ellipses-a.svg"), sample("ellipses-b.svg"))},
      {"ellipse 3:1 + circle",
       both(make("ellipse", {{"a", 150}, {"b", 50}}), make("ellipse", {{"a", 100}, {"b", 100}}))},
      {"ellipse 1.5:1 twins",
       both(make("ellipse", {{"a", 120}, {"b", 80}}), make("ellipse", {{"a", 120}, {"b", 80}}))},
      {"circle + circle",
       both(make("ellipse", {{"a", 100}, {"b", 100}}), make("ellipse", {{"a", 100}, {"b", 100}}))},
      {"rounded squares, congruent",
       both(make("rounded_rectangle", {{"width", 200}, {"height", 200}, {"radius", 30}}),
            make("rounded_rectangle", {{"width", 200}, {"height", 200}, {"radius", 30}}))},
      {"rounded squares, radii 40 and 8",
       both(make("rounded_rectangle", {{"width", 200}, {"height", 200}, {"radius", 40}}),
            make("rounded_rectangle", {{"width", 200}, {"height", 200}, {"radius", 8}}))},
      {"hexagon + square", both(make("polygon", {{"sides", 6}, {"radius", 100}}),
                                make("polygon", {{"sides", 4}, {"radius", 100}}))},
      {"superellipses 3 + 2.5:1.2",
       both(make("superellipse", {{"a", 100}, {"b", 100}, {"exponent", 3}}),
            make("superellipse", {{"a", 120}, {"b", 100}, {"exponent", 2.5}}))},
      {"Reuleaux triangle + pentagon", both(make("reuleaux", {{"sides", 3}, {"radius", 100}}),
                                            make("reuleaux", {{"sides", 5}, {"radius", 100}}))},
  };
}

/// One run of the sweep.
struct Case {
  std::size_t family = 0;
  int decimals = kExact;
  bool flip = false;
  int resolution = 100;
  double startA = 0.0, startB = 0.0;
};

inline std::string describe(const std::vector<Family>& all, const Case& c) {
  char buffer[160];
  std::snprintf(
      buffer, sizeof buffer, "%s, %s, %sn = %d, start A %.6f, start B %.6f",
      all[c.family].name.c_str(),
      c.decimals == kExact ? "unrounded" : (std::to_string(c.decimals) + " decimals").c_str(),
      c.flip ? "B flipped, " : "", c.resolution, c.startA, c.startB);
  return buffer;
}

/// The shortest mesh edge of either piece over the larger piece's bounding-box diagonal.
inline double shortestEdgeOverSize(const DForm& model) {
  double shortest = INFINITY, size = 0.0;
  for (const Piece* piece : {&model.a, &model.b}) {
    size = std::max(size,
                    (piece->flat.colwise().maxCoeff() - piece->flat.colwise().minCoeff()).norm());
    for (Eigen::Index f = 0; f < piece->F.rows(); ++f)
      for (int c = 0; c < 3; ++c)
        shortest = std::min(
            shortest,
            (piece->flat.row(piece->F(f, c)) - piece->flat.row(piece->F(f, (c + 1) % 3))).norm());
  }
  return shortest / size;
}

/// Why the case falls short of the exact model at every start, or nothing where it does not: a
/// refusal or failure of the exact model, a failed gate check, or a mesh edge shorter than 1e-6
/// of the size. The interior is meshed about 8 mm apart whatever the resolution (the seam and
/// the body's folds are followed all the same), so that the sweep times the engine.
inline std::optional<std::string> judge(const std::pair<Shape2, Shape2>& shapes, const Case& c) {
  ForwardSettings settings;
  settings.model = ModelChoice::Exact;
  settings.resolution = c.resolution;
  settings.flip = c.flip;
  settings.startA.fraction = c.startA;
  settings.startB.fraction = c.startB;
  settings.interiorEdgeFactor =
      std::clamp(8.0 * c.resolution / 800.0, kMinInteriorEdgeFactor, kMaxInteriorEdgeFactor);
  MessageSink sink;
  Result<ForwardRun> run = makeDForm(shapes.first, shapes.second, settings, sink);
  if (!run.isOk()) return "refused: " + run.status().message();
  if (run.value().modelUsed.name != "exact") return "made by " + run.value().modelUsed.name;
  const GateReport gate =
      runGate(run.value().model, GateLimits{}, run.value().metrics, nullptr, nullptr);
  std::string failed;
  for (const CheckResult& check : gate.checks)
    if (check.verdict == CheckResult::Verdict::Fail)
      failed += " " + check.name + " " + std::to_string(check.value) + " (" + check.detail + ")";
  if (!failed.empty()) return "gate failed:" + failed;
  if (const double shortest = shortestEdgeOverSize(run.value().model); !(shortest >= 1e-6))
    return "a mesh edge of " + std::to_string(shortest) + " of the size";
  return std::nullopt;
}

/// The cases judged on every core; each failure described, in the order of `cases`.
inline std::vector<std::string> sweep(const std::vector<Case>& cases) {
  const std::vector<Family> all = families();
  // The shapes of each (family, rounding), read once.
  std::map<std::pair<std::size_t, int>, std::pair<Shape2, Shape2>> shapes;
  for (const Case& c : cases) {
    const auto key = std::make_pair(c.family, c.decimals);
    if (shapes.count(key)) continue;
    const auto [a, b] = all[c.family].make(c.decimals);
    Result<Shape2> A = parseOutline(a.text, a.name), B = parseOutline(b.text, b.name);
    if (!A.isOk() || !B.isOk()) return {"unreadable: " + describe(all, c)};
    shapes[key] = {A.value(), B.value()};
  }
  std::vector<std::optional<std::string>> verdicts(cases.size());
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < std::max(1u, std::thread::hardware_concurrency()); ++t)
    workers.emplace_back([&] {
      for (std::size_t i; (i = next++) < cases.size();)
        verdicts[i] = judge(shapes.at({cases[i].family, cases[i].decimals}), cases[i]);
    });
  for (std::thread& worker : workers) worker.join();
  std::vector<std::string> failures;
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (verdicts[i]) failures.push_back(describe(all, cases[i]) + ": " + *verdicts[i]);
  return failures;
}

}  // namespace dform::convex
