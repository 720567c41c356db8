// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: fitting drawn crease lines to the piece they are drawn on (part of readOutline), and
// checking creases given with their piece (part of checkOutline).
#pragma once

#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/io/outline_reader.h"
#include "svg_outline.h"

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

/// Checks creases given with their piece (a shape made in memory) as fitCreases leaves them,
/// without moving them: each has good coordinates and at least 2 distinct points, does not cross
/// itself, stays inside the piece, ends within kCreaseEndSnapMm of its boundary at both ends, and
/// crosses no other crease away from the boundary. The same messages as fitCreases, naming `path`.
Status checkFittedCreases(const std::string& path, const Shape2& shape,
                          const OutlineReadOptions& options);

}  // namespace dform::io_detail
