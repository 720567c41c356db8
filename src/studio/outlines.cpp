// SPDX-License-Identifier: GPL-3.0-or-later
#include "outlines.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "dform/core/constants.h"

namespace dform::studio {

namespace {

// Points along a smooth outline: the seam is resampled from them (at most a few hundred seam
// vertices), and 1440 keep the chord error of a 150 mm circle under 3 micrometres.
constexpr int kSmoothPoints = 1440;

using Loop = std::vector<std::array<double, 2>>;

Loop ellipse(double a, double b, double exponent) {
  Loop loop;
  for (int i = 0; i < kSmoothPoints; ++i) {
    const double t = 2 * kPi * i / kSmoothPoints, c = std::cos(t), s = std::sin(t);
    // |x/a|^n + |y/b|^n = 1 (n = 2: an ellipse)
    loop.push_back({a * std::copysign(std::pow(std::abs(c), 2 / exponent), c),
                    b * std::copysign(std::pow(std::abs(s), 2 / exponent), s)});
  }
  return loop;
}

Loop roundedRectangle(double w, double h, double r) {
  r = std::min(r, 0.5 * std::min(w, h) - 0.5);
  const int arc = kSmoothPoints / 8;
  const double cx[] = {w / 2 - r, -w / 2 + r, -w / 2 + r, w / 2 - r};
  const double cy[] = {h / 2 - r, h / 2 - r, -h / 2 + r, -h / 2 + r};
  Loop loop;
  for (int corner = 0; corner < 4; ++corner)
    for (int i = 0; i <= arc; ++i) {
      const double t = kPi / 2 * (corner + double(i) / arc);
      loop.push_back({cx[corner] + r * std::cos(t), cy[corner] + r * std::sin(t)});
    }
  return loop;
}

Loop polygon(int n, double radius) {
  Loop loop;
  for (int i = 0; i < n; ++i) {
    const double t = kPi / 2 + 2 * kPi * i / n;
    loop.push_back({radius * std::cos(t), radius * std::sin(t)});
  }
  return loop;
}

// A Reuleaux polygon (n odd): each side an arc centred on the opposite vertex.
Loop reuleaux(int n, double radius) {
  const Loop corners = polygon(n, radius);
  const double width =
      std::hypot(corners[0][0] - corners[n / 2][0], corners[0][1] - corners[n / 2][1]);
  const int arc = kSmoothPoints / n;
  Loop loop;
  for (int i = 0; i < n; ++i) {
    const auto& from = corners[i];
    const auto& centre = corners[(i + (n + 1) / 2) % n];
    const double t0 = std::atan2(from[1] - centre[1], from[0] - centre[0]);
    const double sweep = kPi / n;  // the arc's angle seen from its centre
    for (int k = 0; k < arc; ++k) {
      const double t = t0 + sweep * k / arc;
      loop.push_back({centre[0] + width * std::cos(t), centre[1] + width * std::sin(t)});
    }
  }
  return loop;
}

Loop lobed(double radius, int lobes, double amplitude) {
  Loop loop;
  for (int i = 0; i < kSmoothPoints; ++i) {
    const double t = 2 * kPi * i / kSmoothPoints;
    const double r = radius * (1 + amplitude * std::cos(lobes * t));
    loop.push_back({r * std::cos(t), r * std::sin(t)});
  }
  return loop;
}

}  // namespace

const std::vector<OutlineKind>& outlineKinds() {
  static const std::vector<OutlineKind> kinds = {
      {"ellipse", "Ellipse", {{"a", 10, 300, 120}, {"b", 10, 300, 70}}},
      {"superellipse",
       "Superellipse",
       {{"a", 10, 300, 100}, {"b", 10, 300, 80}, {"exponent", 1.2, 8, 3, 0, "power"}}},
      {"rounded_rectangle",
       "Rounded rectangle",
       {{"width", 20, 500, 200}, {"height", 20, 500, 140}, {"radius", 1, 150, 30}}},
      {"polygon", "Regular polygon", {{"sides", 3, 12, 6, 1, "sides"}, {"radius", 10, 300, 100}}},
      {"reuleaux", "Reuleaux polygon", {{"sides", 3, 11, 3, 2, "sides"}, {"radius", 10, 300, 100}}},
      {"lobed",
       "Lobed circle",
       {{"radius", 10, 300, 90},
        {"lobes", 2, 12, 4, 1, "lobes"},
        {"amplitude", 0, 0.3, 0.12, 0, "× radius"}}},
  };
  return kinds;
}

nlohmann::json outlineKindsJson() {
  nlohmann::json kinds = nlohmann::json::array();
  for (const OutlineKind& k : outlineKinds()) {
    nlohmann::json parameters = nlohmann::json::array();
    for (const Parameter& p : k.parameters)
      parameters.push_back({{"name", p.name},
                            {"min", p.min},
                            {"max", p.max},
                            {"value", p.value},
                            {"step", p.step},
                            {"unit", p.unit}});
    kinds.push_back({{"name", k.name}, {"label", k.label}, {"parameters", parameters}});
  }
  return kinds;
}

std::string parametricOutline(const std::string& kind,
                              const std::map<std::string, double>& values) {
  const auto found = std::find_if(outlineKinds().begin(), outlineKinds().end(),
                                  [&](const OutlineKind& k) { return k.name == kind; });
  if (found == outlineKinds().end()) return "";
  std::map<std::string, double> v;
  for (const Parameter& p : found->parameters) {
    const auto given = values.find(p.name);
    const double x =
        given != values.end() && std::isfinite(given->second) ? given->second : p.value;
    v[p.name] = std::clamp(x, p.min, p.max);
  }
  auto count = [&](const char* name) { return int(std::lround(v[name])); };
  Loop loop;
  if (kind == "ellipse") loop = ellipse(v["a"], v["b"], 2);
  if (kind == "superellipse") loop = ellipse(v["a"], v["b"], v["exponent"]);
  if (kind == "rounded_rectangle") loop = roundedRectangle(v["width"], v["height"], v["radius"]);
  if (kind == "polygon") loop = polygon(count("sides"), v["radius"]);
  if (kind == "reuleaux") loop = reuleaux(count("sides") | 1, v["radius"]);
  if (kind == "lobed") loop = lobed(v["radius"], count("lobes"), v["amplitude"]);
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : loop) points.push_back({p[0], p[1]});
  return nlohmann::json{{"points", points}, {"units", "mm"}}.dump();
}

}  // namespace dform::studio
