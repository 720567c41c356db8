// Plane geometry on sheet polylines shared by the pattern builder and its layout check: polygon
// overlap through Clipper (integer grid), point in polygon, distance to an outline. A region is a
// set of closed polygons read by the even-odd rule: a piece's outline and its holes. Internal.
#pragma once

#include <polyclipping/clipper.hpp>

#include "export/internal.h"

namespace dform::fab {

// Clipper works on integers: 1e4 units per mm resolves 0.1 um, far below any tolerance here.
constexpr double kClipScale = 1e4;
// Overlap that counts as real: rounding to Clipper's grid (<= 0.05 um) along a 40 mm tab edge
// leaves slivers of ~2e-6 mm^2; 0.01 mm^2 (a 0.1 x 0.1 mm square) is invisible on any material.
constexpr double kOverlapTolMm2 = 0.01;

/// A closed polyline on Clipper's grid, counter-clockwise.
ClipperLib::Path toClip(const Polyline& p);
Polyline fromClip(const ClipperLib::Path& p);

/// Area (mm^2) common to two regions.
double overlapArea(const std::vector<Polyline>& a, const std::vector<Polyline>& b);

/// Area (mm^2) common to two closed polygons.
double overlapArea(const Polyline& a, const Polyline& b);

/// Whether q is inside the closed polygon (even-odd rule).
bool insidePolygon(const Polyline& poly, const Vec2& q);

/// Whether q is inside the region.
bool insideRegion(const std::vector<Polyline>& loops, const Vec2& q);

/// Distance from q to the nearest edge of the polylines, closed (`closed`) or open.
double distanceToPolylines(const std::vector<Polyline>& lines, const Vec2& q, bool closed);

/// The convex hull of the points of `parts`, counter-clockwise (Andrew's monotone chain).
Polyline convexHull(const std::vector<Polyline>& parts);

}  // namespace dform::fab
