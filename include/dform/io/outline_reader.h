// SPDX-License-Identifier: GPL-3.0-or-later
// Reading flat outlines (SVG or a JSON list of 2D points) into millimetres.
#pragma once

#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

/// How readOutline reads an outline file: how curves are flattened and the limits that refuse a
/// file too large to be a piece.
struct OutlineReadOptions {
  /// mm; largest chord deviation when curves are flattened. Fine enough that the seam's samples
  /// never share a flattened chord up to the exact engine's 1000 (chords of 0.2 mm on a 40 mm
  /// radius): samples on one straight chord make the exact body's faces meet the seam at
  /// corners too thin to mesh (docs/exact.md).
  double flattenTolerance = 1e-4;
  /// mm; a subpath whose end is this close to its start is closed (a gap a designer cannot see).
  double closeTolerance = 0.01;
  double maxCoordinate = 1.0e6;  ///< mm; larger coordinates are rejected as unreasonable
  /// Points in all outlines of a file together, after flattening; a file with more is refused as
  /// soon as that is known. No drawn piece needs as many, and reading stays under a second and
  /// a few hundred MB (docs/io.md, "Limits").
  std::size_t maxPoints = 1'000'000;
};

/// Reads a shape from `path`: SVG (.svg) or a JSON list of points (.json); see docs/io.md.
///
/// SVG: the root width/height/viewBox give millimetres (mm, cm, in, pt, pc, px at 96 per inch;
/// unitless = px; no width/height means a user unit is a px). SVG's y axis points down; the
/// result is in the page frame with y up and the origin at the page's bottom-left corner
/// (y' = page height - y), so what the designer sees is not mirrored. Curves are flattened to
/// options.flattenTolerance. Every closed subpath or shape is an outline: exactly one must
/// enclose all others, which become holes. <defs> content and display:none are ignored. Lines
/// marked as creases (class "crease", or inside a layer or group labelled "crease"/"creases"; in
/// JSON a "creases" list) are clipped to the piece and must run from boundary to boundary.
///
/// Every problem is a Status naming the file: InputUnreadable (missing, unreadable, not SVG/JSON)
/// or InputInvalid (no closed outline, open path, self-intersecting outline, NaN or huge
/// coordinates, too few points, several separate outlines, a crease that does not run from
/// boundary to boundary or crosses another).
Result<Shape2> readOutline(const std::string& path, const OutlineReadOptions& options = {});

/// The same from the file's text: `source` names it in messages, and its extension (or else the
/// first character of `text`) says whether it is SVG or JSON.
Result<Shape2> parseOutline(std::string text, const std::string& source,
                            const OutlineReadOptions& options = {});

/// A shape made in memory, checked as readOutline checks a file's, with the same codes and
/// messages and `name` in the place of the file ("piece A: the outline has fewer than 3 distinct
/// points"): the outline and each hole ("hole 1", ...) go through the same cleaning and nesting;
/// creases must already run inside the piece from boundary to boundary (within 1 mm), as
/// readOutline leaves them, and are checked, not moved. Returns the shape as readOutline gives
/// one: repeated points dropped, loops counter-clockwise, the largest loop the outline and the
/// others its holes; its creases, `source` and `sha256` kept. A shape readOutline gave passes
/// unchanged.
Result<Shape2> checkOutline(const Shape2& shape, const std::string& name,
                            const OutlineReadOptions& options = {});

}  // namespace dform
