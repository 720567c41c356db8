// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the SVG part of readOutline. svgpp is confined to svg_outline.cpp because one
// translation unit that includes it costs ~17 s to compile.
#pragma once

#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/io/outline_reader.h"

namespace dform::io_detail {

/// One polyline found in a file, before shape assembly: mm in the y-up page frame. `label` names
/// it in messages ("path 2").
struct DrawnLine {
  Points2 points;
  std::string label;
};

/// What a file draws: closed outlines (either orientation, the closing point not repeated) and
/// open crease lines (marked as described in docs/io.md).
struct Drawing {
  std::vector<DrawnLine> loops;
  std::vector<DrawnLine> creases;
};

/// Every closed subpath and closed basic shape of the SVG document `text` (read from `path`),
/// and every crease line, flattened to options.flattenTolerance. Open subpaths that are not
/// creases, closed creases, malformed XML and out-of-range coordinates are Statuses naming `path`.
Result<Drawing> readSvgDrawing(const std::string& path, std::string text,
                               const OutlineReadOptions& options);

}  // namespace dform::io_detail
