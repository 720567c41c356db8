// Internal: fitting drawn crease lines to the piece they are drawn on (part of readShape).
#pragma once

#include <string>
#include <vector>

#include "core/status.h"
#include "io/outline_reader.h"
#include "io/svg_outline.h"

namespace dform::io_detail {

/// A crease end this close (mm) to the piece's boundary is taken to lie on it: a line drawn by
/// hand that stops short of the outline by less than a millimetre was meant to reach it (and a
/// fold cannot end inside an unstretched sheet).
constexpr double kCreaseEndSnapMm = 1.0;

/// Turns drawn crease lines into `shape.creases`: each line is clipped to the piece (a line drawn
/// across the outline, or across a hole, is cut where it crosses it and the parts inside are
/// kept), ends within kCreaseEndSnapMm of the boundary are moved onto it, and every kept part must
/// run from boundary to boundary. InputInvalid naming the file and the line when a line has a bad
/// coordinate, fewer than 2 distinct points, crosses itself, lies wholly outside the piece, ends
/// inside it, or crosses another crease away from the boundary.
Status fitCreases(const std::string& path, const std::vector<DrawnLine>& lines,
                  const OutlineReadOptions& options, Shape2& shape);

}  // namespace dform::io_detail
