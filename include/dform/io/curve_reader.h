// SPDX-License-Identifier: GPL-3.0-or-later
// Reading closed 3D seam curves (OBJ polyline, JSON points or closed cubic Bezier) into mm.
#pragma once

#include <string>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

/// How readCurve reads a curve file: whether it is closed, how Beziers are flattened, and the
/// limits that refuse a file too large to be a seam.
struct CurveReadOptions {
  bool forceClosed = false;        ///< treat an open polyline as closed (`--closed`)
  double flattenTolerance = 0.01;  ///< mm; largest chord deviation when Beziers are flattened
  double maxCoordinate = 1.0e6;    ///< mm
  /// Points of the curve (after flattening a Bezier); a file with more is refused as soon as
  /// that is known. The seam is resampled to --resolution points anyway, and reading stays
  /// under a second and a few hundred MB (docs/io.md, "Limits").
  std::size_t maxPoints = 1'000'000;
};

/// Reads a closed space curve from `path` (.obj or .json), dense, in mm. Problems are Statuses
/// naming the file: open curve, fewer than 5 distinct points, NaN/infinite/huge coordinates,
/// repeated consecutive points, self-intersection, faces but no polyline, malformed file.
Result<Curve3> readCurve(const std::string& path, const CurveReadOptions& options = {});

/// The same from the file's text; `source` names it in messages and its extension (.obj or
/// .json) gives the format, or else a text that is a JSON object is read as JSON.
Result<Curve3> parseCurve(const std::string& text, const std::string& source,
                          const CurveReadOptions& options = {});

/// A curve made in memory (#P by 3, mm, closed: a repeated closing point is dropped), checked as
/// readCurve checks a file's, with the same codes and messages, `name` in the place of the file
/// ("curve: the curve has fewer than 5 distinct points"). Its `source` and `sha256` are kept.
Result<Curve3> checkCurve(const Curve3& curve, const std::string& name,
                          const CurveReadOptions& options = {});

}  // namespace dform
