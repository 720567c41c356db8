// SPDX-License-Identifier: GPL-3.0-or-later
// What the studio's API sends and receives, as JSON text (docs/studio.md, "API"): settings read
// from a request, results written compactly (vertex arrays as base64 of little-endian doubles,
// faces as base64 of 32-bit indices), outlines and curves summarised for drawing.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/pipeline/job.h"
#include "dform/validate/gate.h"

namespace dform::studio {

/// A request the API refuses: HTTP 400 with {"error": what()}.
struct RequestError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A request's text field `key`; RequestError where it is missing or not a string.
std::string requiredText(const nlohmann::json& request, const char* key);

/// A request's "piece": 0 for "a", 1 for "b"; RequestError otherwise.
int pieceIndex(const nlohmann::json& request);

/// A request's "seq", the page's number for the input it asks about (0 where it has none, unless
/// `required`); RequestError where it is not a whole number.
long sequence(const nlohmann::json& request, bool required = false);

/// Base64 (RFC 4648, with padding) of `size` bytes.
std::string base64(const void* data, std::size_t size);

/// `text` percent-encoded (RFC 3986: every byte but letters, digits and -._~), for a header the
/// page reads with decodeURIComponent.
std::string percentEncoded(const std::string& text);

/// The finest seam a live solve takes: a request for more is refused (a job file may ask for
/// more, and the command line runs it).
constexpr int kMaxLiveResolution = 1000;

/// The job a request describes: `base` (the session's starting design of the request's mode,
/// "mode" forward unless "inverse") with every setting the request holds, its keys shaped as a
/// job file's ("resolution", "weights": {...}, "export": {...}), read through the settings table
/// (pipeline/settings.h). RequestError naming the setting (its key: the page's field names are
/// the keys) on a bad value, a resolution over kMaxLiveResolution, or an export profile or gate
/// that is not one the server ships (a request names no file on the server).
Job jobFrom(const nlohmann::json& request, const Job& base);

/// A solved forward run's shape for the page: model and why, both pieces, the starts and scale
/// (its figures follow with the gate's verdict: verdictJson), and "states": the ruled engine's
/// states least ranking energy first ({start, bending_energy, largest_fold_deg, ranking_energy,
/// pieces}, pieces null for the first, which is the answer; none from another model).
nlohmann::json forwardResultJson(const SolvedDForm& run);

/// A solved inverse run: as forwardResultJson, plus its figures, the curve match and the on-hull
/// test.
nlohmann::json inverseResultJson(const InverseRun& run);

/// The warnings among `messages`, each setting they mention named by its key (the page's field
/// names are the keys).
std::vector<std::string> warnings(const std::vector<Message>& messages);

/// `status`'s message with each setting it mentions named as the page labels its control, in
/// quotes ("sheet", "match perimeters", "export even if the gate fails"); a setting the page has
/// no control for by its job-file key, as the saved job names it.
std::string studioWords(const Status& status);

/// The export dialog's fields when empty, as the settings table says: a page's and a sheet's
/// (what an unset one is) and the scale's (its default and range), keyed "page", "sheet", "scale".
nlohmann::json exportPlaceholders();

/// The export dialog's lists, as the settings table has them: the material's and the numbers'
/// choices and the hinge's (true, false), each with what leaving it unset means, keyed
/// "material", "numbers", "hinge".
nlohmann::json exportChoices();

/// The settings of `job` that shape its solve, as text: every setting but the starts and the
/// export's (a session reuses a solve whose design text is the same).
std::string designSettings(const Job& job);

/// A run's figures (as report.json's "metrics"), the gate's verdict on them and what the page
/// draws on `model` with them: {"figures", "gate" (the gate's name, passed, and every check),
/// "overlay" (overlayJson)}.
nlohmann::json verdictJson(const DForm& model, const Metrics& metrics, const GateReport& gate);

/// What the page draws on the shape beside the figures: per piece ("pieces": A, B) its edges
/// ("edges": base64 of 32-bit vertex pairs) with their strain ("strain": base64 of doubles, one
/// an edge, EdgeStrain) and its curvature ("curvature": base64 of doubles, one a vertex,
/// curvatureMap); "failing": where each failing check of `gate` fails (locateFailures: "check",
/// "kind" edges/vertices/seam_points, "items" per piece); "unlocated": the failing checks that
/// have no sites on the shape.
nlohmann::json overlayJson(const DForm& model, const GateReport& gate);

/// An outline as read, for drawing and the start handles: outer loop, holes, creases (flat
/// [x0, y0, x1, y1, ...] arrays, mm, at most `maxPoints` points a loop), perimeters, bounds, and
/// the corners a start snaps to ("corners", "hole_corners": the arc-length fractions of each
/// loop's vertices that turn by kCornerTurnRadians or more, cornerFractions) and where the outer
/// loop's mirror axes cross it ("axes", symmetryFractions).
nlohmann::json shapeJson(const Shape2& shape, int maxPoints = 4000);

/// A curve as read: its points (flat [x, y, z, ...], at most `maxPoints`) and length.
nlohmann::json curveJson(const Curve3& curve, int maxPoints = 4000);

}  // namespace dform::studio
