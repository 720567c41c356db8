// SPDX-License-Identifier: GPL-3.0-or-later
// The studio's built-in parametric outlines (docs/studio.md, "Outlines"): each is written as a
// JSON point list (docs/io.md) and then read like an uploaded file, so a saved job holds the very
// text the studio solved.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace dform::studio {

/// One slider of a parametric outline.
struct Parameter {
  std::string name;         ///< as the request and the page name it
  double min, max, value;   ///< range and default (mm, or a count, or a ratio)
  double step = 0;          ///< a count's whole step from min (2: odd counts only); 0: any value
  std::string unit = "mm";  ///< as the page shows it beside the value
};

/// A kind of outline and its sliders.
struct OutlineKind {
  std::string
      name;  ///< "ellipse", "superellipse", "rounded_rectangle", "polygon", "reuleaux", "lobed"
  std::string label;  ///< shown on the page
  std::vector<Parameter> parameters;
};

/// Every kind, in the page's order.
const std::vector<OutlineKind>& outlineKinds();

/// Every kind as /api/session sends it: name, label, and each parameter's name, min, max, value
/// (its default), step and unit.
nlohmann::json outlineKindsJson();

/// The JSON points text of `kind` with `values` (missing ones: their defaults; each is clamped
/// to its range, counts rounded). Empty when `kind` is unknown.
std::string parametricOutline(const std::string& kind, const std::map<std::string, double>& values);

}  // namespace dform::studio
