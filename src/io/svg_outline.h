// Internal: the SVG part of readShape. svgpp is confined to svg_outline.cpp because one translation
// unit that includes it costs ~17 s to compile.
#pragma once

#include <string>
#include <vector>

#include "core/status.h"
#include "core/types.h"
#include "io/outline_reader.h"

namespace dform::io_detail {

/// One closed outline found in a file, before shape assembly: mm in the y-up page frame, either
/// orientation, the closing point not repeated. `label` names it in messages ("path 2").
struct ClosedLoop {
  Points2 points;
  std::string label;
};

/// Every closed subpath and closed basic shape of the SVG document `text` (read from `path`),
/// flattened to options.flattenTolerance. Open subpaths, malformed XML and out-of-range
/// coordinates are Statuses naming `path`.
Result<std::vector<ClosedLoop>> readSvgLoops(const std::string& path, std::string text,
                                             const OutlineReadOptions& options);

}  // namespace dform::io_detail
