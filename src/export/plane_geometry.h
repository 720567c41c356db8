// Plane geometry on sheet polylines shared by the pattern builder and its layout check: polygon
// overlap through Clipper (integer grid), point in polygon, distance to an outline. Internal.
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

/// Area (mm^2) common to two closed polygons.
double overlapArea(const Polyline& a, const Polyline& b);

/// Whether q is inside the closed polygon (even-odd rule).
bool insidePolygon(const Polyline& poly, const Vec2& q);

/// Distance from q to the closed polygon's edges.
double distanceToClosed(const Polyline& poly, const Vec2& q);

}  // namespace dform::fab
