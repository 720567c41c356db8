// SPDX-License-Identifier: GPL-3.0-or-later
// Plane geometry on sheet polylines shared by the pattern builder and its layout check: polygon
// overlap through Clipper (integer grid), point in a region, distance to an outline (the single
// polygon and segment tests are core's, core/polyline.h). A region is a set of closed polygons
// read by the even-odd rule: a piece's outline and its holes. Internal.
#pragma once

#include <polyclipping/clipper.hpp>
#include <unordered_map>

#include "internal.h"

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

/// Whether q is inside the region (core's insidePolygon on each loop).
bool insideRegion(const std::vector<Polyline>& loops, const Vec2& q);

/// The parts of the open polyline `line` inside the region `loops` (even-odd).
std::vector<Polyline> clipToRegion(const Polyline& line, const std::vector<Polyline>& loops);

/// Distance from q to the nearest edge of the polylines, closed (`closed`) or open.
double distanceToPolylines(const std::vector<Polyline>& lines, const Vec2& q, bool closed);

/// The point at arc length `s` along the open polyline (its end past its length), and the unit
/// direction of the segment it is on.
Vec2 pointAlong(const Polyline& line, double s, Vec2* tangent = nullptr);

/// Whether `shape` shares more than `tol` mm^2 with one of `others`; Clipper runs only for the
/// others whose box meets the shape's.
bool overlapsAny(const Polyline& shape, const std::vector<Polyline>& others, double tol);

/// Boxes filed on a uniform grid of square cells, so that the boxes that may meet a given one are
/// found among its neighbours rather than among all of them. Complete: boxes that share a point
/// share a cell (or one of them is too large for the grid and is always a candidate).
class BoxIndex {
 public:
  /// `cell` (mm): about the size of the boxes filed, so that each covers few cells.
  explicit BoxIndex(double cell) : cell_(cell) {}
  void insert(int id, const Box& box);
  /// The ids of the filed boxes that share a point with `box`, ascending, each once.
  std::vector<int> overlapping(const Box& box) const;

 private:
  // A box spanning more cells than this per axis is kept aside (a sheet-wide title line).
  static constexpr long kMaxCellsPerAxis = 64;
  struct Span {
    long x0, y0, x1, y1;
  };
  Span span(const Box& box) const;
  double cell_;
  std::vector<Box> boxes_;  // by id
  std::vector<int> large_;  // ids of boxes kept aside
  std::unordered_map<long long, std::vector<int>> cells_;
};

/// The convex hull of the points of `parts`, counter-clockwise (Andrew's monotone chain).
Polyline convexHull(const std::vector<Polyline>& parts);

}  // namespace dform::fab
