// SPDX-License-Identifier: GPL-3.0-or-later
// The quality gate: every check of a solved D-Form against a limit read from a gate file
// (templates/gates/*.json). Definitions and limits: docs/validation.md.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/validate/metrics.h"

namespace dform {

/// Limits of the gate. The defaults are templates/gates/default.json (the paper's figures);
/// a gate file may leave any field out to keep its default.
struct GateLimits {
  std::string name = "default";   ///< the preset's name, for the report
  double lengthError = 0.005;     ///< max L_error (fraction): every Table 1 example is below 0.5%
  double lengthErrorMax = 0.03;   ///< max per-edge relative length error (fraction), paper: < 3%
  double seamError = 1e-6;        ///< max B_error (fraction of the 3D seam length), forward mode
  double curveError = 1e-6;       ///< max D_error (fraction of the curve length), inverse mode
  double seamGapMm = 0.1;         ///< max distance between seam partners (mm)
  double gaussMaxRad = 0.05;      ///< max |angle defect| away from the seam (radians)
  double seamLengthRel = 2e-3;    ///< max |flat seam A - flat seam B| / max of both (fraction)
  double hullDistanceRel = 0.01;  ///< max distance to the seam's hull / seam bbox diagonal
  /// max RMS seam distance from the exact D-Form of the same pieces / seam bbox diagonal: how far
  /// the shape shown is from the shape the cut pieces make
  double exactDistanceRel = 2e-3;
  /// inverse mode: max RMS distance of the zipped pieces' exact D-Form from the target curve /
  /// the curve's bbox diagonal
  double roundtripRel = 2e-3;
  int flipped = 0;     ///< max flipped triangles (flat and 3D together)
  int degenerate = 0;  ///< max degenerate triangles (flat and 3D together)
};

/// Reads a gate file: {"version": 1, "name": ..., "description": ..., "limits": {...}}.
/// InputUnreadable when the file is missing or not JSON; InputInvalid naming the field when a
/// field is unknown, of the wrong type, or a limit is negative.
Result<GateLimits> readGateFile(const std::string& path);

/// The same from the file's text; `source` names it in error messages.
Result<GateLimits> parseGateJson(const std::string& text, const std::string& source);

/// Every limit of `limits` as a gate file's "limits" object (JSON text, keys in a fixed order),
/// which parseGateJson reads back to the same limits: what a report records of the gate it judged.
std::string gateLimitsJson(const GateLimits& limits);

/// One check of a gate: the figure measured, the limit it was held to and the verdict.
struct CheckResult {
  /// Passed (value <= limit), failed, or could not be measured (never a pass).
  enum class Verdict { Pass, Fail, NotRun };
  std::string name;                   ///< the check's name, the gate file's field where it has one
  double value = 0;                   ///< the measured figure (NaN when not run)
  double limit = 0;                   ///< the limit it was held to
  Verdict verdict = Verdict::NotRun;  ///< the check's outcome
  std::string detail;  ///< one line: what was measured, where it failed, or why it did not run
};

/// "pass", "fail" or "not run", as report.json writes a verdict.
const char* verdictName(CheckResult::Verdict verdict);

/// A check judged like the gate's own: it passes when value <= limit, and NaN never passes. For
/// checks measured outside runGate too (the exporter's pattern layout).
CheckResult judgeCheck(std::string name, double value, double limit, std::string detail);

/// A check that could not run, with the reason; it is not a pass.
CheckResult notRunCheck(std::string name, double limit, std::string reason);

/// A gate's judgement of a result: its limits, every check, and the figures they came from.
struct GateReport {
  std::string name;                 ///< the gate's name (GateLimits::name)
  GateLimits limits;                ///< the limits it judged by
  std::vector<CheckResult> checks;  ///< every check of the gate, in the gate's order
  Metrics metrics;                  ///< the figures the checks were computed from
  std::optional<CurveMatch> curve;  ///< inverse mode: the seam-to-curve figures
  /// No check failed. A check that did not run is not a pass: it stays in `checks` with its
  /// reason for the report, and `notRun()` counts them.
  bool passed() const;
  int failed() const;  ///< the number of checks that failed
  int notRun() const;  ///< the number of checks that could not run
  /// The check of that name, or nullptr.
  const CheckResult* find(const std::string& name) const;
};

/// Runs every check on `model` with the figures the caller measured on it: `metrics` is
/// computeMetrics(model, ...) and `curve` computeCurveMatch(model, *target, ...) (nullptr without
/// a target). With a `target` curve (inverse mode, one point per seam pair) D_error is checked,
/// otherwise B_error. Pure: reads the meshes and the figures only (pipeline/reference_seams.h
/// measures a model read back from files, then calls this).
GateReport runGate(const DForm& model, const GateLimits& limits, const Metrics& metrics,
                   const Curve3* target, const CurveMatch* curve);

/// Where a failing check of a gate's report fails on the shape, for drawing it there: the edges of
/// L_max (|strain| over its limit) and of L_error (edges whose own |strain| is over that RMS
/// limit), the vertices of gauss_max_rad (those the check looks at with |angle defect| over its
/// limit), the seam points of seam_gap_mm (partners farther apart than its limit).
struct FailureSites {
  /// What `items` lists: mesh edges, mesh vertices, or seam points.
  enum class Kind { Edges, Vertices, SeamPoints };
  std::string check;        ///< the check's name
  Kind kind = Kind::Edges;  ///< what the check's sites are
  /// Per piece (A, B): vertex pairs (Edges: two entries an edge), vertex indices (Vertices); seam
  /// indices (SeamPoints), the same for both pieces.
  std::array<std::vector<int>, 2> items;
};

/// The sites of each check of `report` that failed on `model` and is one of the four above, in
/// the report's order; a failing check of another kind has none (it is not located on the shape).
std::vector<FailureSites> locateFailures(const DForm& model, const GateReport& report);

}  // namespace dform
