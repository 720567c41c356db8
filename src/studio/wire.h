// What the studio's API sends and receives, as JSON text (docs/studio.md, "API"): settings read
// from a request, results written compactly (vertex arrays as base64 of little-endian doubles,
// faces as base64 of 32-bit indices), outlines and curves summarised for drawing.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/inverse_pipeline.h"
#include "dform/validate/gate.h"

namespace dform::studio {

/// A request the API refuses: HTTP 400 with {"error": what()}.
struct RequestError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Base64 (RFC 4648, with padding) of `size` bytes.
std::string base64(const void* data, std::size_t size);

/// The settings of a forward solve from the page's request ("start_a", "start_b", "flip",
/// "join", "model", "resolution", "fit_perimeter"; missing keys keep their defaults, the
/// weights are the join's defaults as the command line's). RequestError on a bad value.
ForwardSettings forwardSettingsFrom(const nlohmann::json& request);

/// A seam curve's settings ("resolution", "closed").
InverseSettings inverseSettingsFrom(const nlohmann::json& request, bool& forceClosed);

/// A solved forward run's shape for the page: model and why, both pieces, the starts and scale
/// (its figures follow with the gate's verdict: verdictJson).
nlohmann::json forwardResultJson(const SolvedDForm& run);

/// A solved inverse run: as forwardResultJson, plus its figures, the curve match and the on-hull
/// test.
nlohmann::json inverseResultJson(const InverseRun& run);

/// A run's figures (as report.json's "metrics") and the gate's verdict on them: {"figures",
/// "gate"}, the gate's name, passed, and every check.
nlohmann::json verdictJson(const Metrics& metrics, const GateReport& gate);

/// An outline as read, for drawing and the start handles: outer loop, holes, creases (flat
/// [x0, y0, x1, y1, ...] arrays, mm, at most `maxPoints` points a loop), perimeters, bounds.
nlohmann::json shapeJson(const Shape2& shape, int maxPoints = 4000);

/// A curve as read: its points (flat [x, y, z, ...], at most `maxPoints`) and length.
nlohmann::json curveJson(const Curve3& curve, int maxPoints = 4000);

}  // namespace dform::studio
