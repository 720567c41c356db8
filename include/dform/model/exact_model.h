// SPDX-License-Identifier: GPL-3.0-or-later
// A D-Form made by the exact engine (src/exact), meshed as the paper model's pieces are: shared by
// forward runs and by inverse runs whose curve lies on its convex hull.
#pragma once

#include <string>

#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/exact/exact_gluing.h"
#include "dform/model/run_types.h"

namespace dform {

/// A smoothly curved surface of n seam points folds by up to about 3 x 360/n degrees between
/// neighbouring faces (measured on the exact body of ellipse pairs and an ellipse with a circle,
/// n = 100 to 400: 10.4, 5.2 and 2.6 degrees); a real crease keeps its angle as n grows (a
/// square's corners against a circle: 66 degrees). The angle, radians, above which a fold is a
/// found crease: twice that margin, and never below 20 degrees.
double foundCreaseRadians(long n);

/// Folds under this (radians) are not followed by a piece's mesh: a mesh edge across a fold of
/// angle theta is shorter than flat by at most theta^2 / 8 of its length, 1.25e-11 here, below
/// what the figures resolve; such folds are a flat face's triangulation and rounding.
constexpr double kFollowedFold = 1e-5;

/// The two seam polygons (row k of each glued to the other's) made equal-chorded, glued into
/// their convex body, both pieces meshed with interior edges about `targetEdge` mm (folds of
/// the body through a piece become mesh lines and the piece's creases) and every vertex placed on
/// the body. Piece A's seam is rows 0..n-1 of its mesh, B's the same polygon counter-clockwise.
/// `paths` name the pieces in errors; `used` gets what the engine did.
Result<DForm> exactDForm(exact::SeamPolygons polygons, double targetEdge,
                         const std::string paths[2], ModelUsed& used);

}  // namespace dform
