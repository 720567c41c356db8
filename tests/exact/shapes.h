// SPDX-License-Identifier: GPL-3.0-or-later
// Test shapes for the exact engine: sampled polygons and ellipses, in mm.
#pragma once

#include <cmath>
#include <vector>

#include "dform/core/polyline.h"
#include "dform/exact/exact_gluing.h"

namespace dform::exact::testshapes {

/// The polygon through `corners` (counter-clockwise) with every side split into `perSide` equal
/// segments.
inline Points2 polygonSampled(const std::vector<Eigen::Vector2d>& corners, int perSide) {
  const int m = int(corners.size());
  Points2 P(m * perSide, 2);
  for (int c = 0; c < m; ++c)
    for (int s = 0; s < perSide; ++s)
      P.row(c * perSide + s) =
          (corners[c] + (corners[(c + 1) % m] - corners[c]) * double(s) / perSide).transpose();
  return P;
}

/// n points evenly spaced by arc length on the ellipse with semi-axes rx, ry, counter-clockwise
/// from (rx, 0).
inline Points2 ellipse(double rx, double ry, int n) {
  const int dense = 20000;
  Points2 P(dense, 2);
  for (int i = 0; i < dense; ++i) {
    const double t = 2.0 * 3.14159265358979323846 * i / dense;
    P.row(i) << rx * std::cos(t), ry * std::sin(t);
  }
  return resampleClosed(P, n);
}

/// An ellipse of aspect `aspect` scaled to a 400 mm perimeter, n points.
inline Points2 ellipseOfPerimeter400(double aspect, int n) {
  const Points2 unit = ellipse(aspect, 1.0, 20000);
  const double s = 400.0 / closedLength(unit);
  return ellipse(aspect * s, s, n);
}

/// The held-out pair of the exact-gluing notes: ellipses 2:1 and 1.3:1 of perimeter 400 mm with
/// their major-axis ends paired and B turned over (B listed clockwise).
inline SeamPolygons ellipsePair(int n) {
  SeamPolygons s;
  s.a = ellipseOfPerimeter400(2.0, n);
  const Points2 b = ellipseOfPerimeter400(1.3, n);
  s.b.resize(n, 2);
  for (int k = 0; k < n; ++k) s.b.row(k) = b.row((n - k) % n);
  return s;
}

}  // namespace dform::exact::testshapes
