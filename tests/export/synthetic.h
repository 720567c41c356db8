// SPDX-License-Identifier: GPL-3.0-or-later
// A small synthetic D-Form for the export tests (the solver is written elsewhere): an ellipse (A)
// and a circle (B) of equal polygon perimeter, ring-meshed, bent into two caps meeting at a
// planar seam. Not isometric (the exporter does not care); seams, orientations and counts are
// exactly as a solved model has them.
#pragma once

#include <vector>

#include "dform/core/types.h"

namespace dform::test {

/// Piece A: the ellipse with semi-axes ax, by (mm), seam counter-clockwise; piece B: a circle
/// whose polygon has A's perimeter, seam clockwise, b.seam[i] at A's arc length of a.seam[i].
/// Vertex 0 is the centre, then `rings` rings of `sectors` vertices, the last ring the seam.
/// 3D: A is the cap z = height (1 - rho^2) over the ellipse, B the mirror cap below; both share
/// the seam positions, faces are counter-clockwise in the flat and outward in 3D.
/// Triangles per piece: sectors * (2 rings - 1).
DForm ellipseCircleDForm(int sectors = 64, int rings = 8, double ax = 80, double by = 50,
                         double height = 30);

/// A plausible per-vertex curvature for colour tests: z / height of each vertex (unitless).
std::vector<double> fakeCurvature(const Piece& piece);

}  // namespace dform::test
