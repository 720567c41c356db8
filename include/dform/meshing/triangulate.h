// SPDX-License-Identifier: GPL-3.0-or-later
// Triangulating flat domains for the solver.
#pragma once

#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

/// How fine and how well-shaped triangulateDomain's triangles are.
struct TriangulateOptions {
  double targetEdgeLength = 1.0;  ///< interior edge length to aim for (same unit as the input)
  double minAngleDegrees = 25.0;  ///< smallest triangle angle to aim for (boundary corners aside)
};

/// An open constraint line inside the domain (a crease) from one fixed point to another: `from`
/// and `to` index the fixed points (the outline's rows first, then each hole's in turn) and
/// `interior` holds the line's points in between, in order (#I by 2, possibly none).
struct InteriorLine {
  int from = 0;      ///< the fixed point the line starts at
  int to = 0;        ///< the fixed point it ends at
  Points2 interior;  ///< its points in between, #I by 2
};

/// Constrained Delaunay triangulation with refinement of the polygon `boundary` (#B by 2,
/// counter-clockwise, simple), optional holes (each a simple polygon inside it) and optional
/// interior lines. The result's first #B vertices are exactly the boundary points in order (no
/// boundary edge is split), then each hole's points in order, then each line's interior points,
/// then the other interior vertices. FlatMesh::boundary = 0..#B-1; FlatMesh::lines lists each
/// line's vertices from `from` to `to`, every consecutive pair a mesh edge. Triangles are
/// counter-clockwise. Returns InputInvalid if the domain cannot be meshed (a line that crosses the
/// boundary, a hole or another line away from its ends, or leaves the domain).
Result<FlatMesh> triangulateDomain(const Points2& boundary, const std::vector<Points2>& holes,
                                   const TriangulateOptions& options,
                                   const std::vector<InteriorLine>& lines = {});

/// The constrained Delaunay triangulation of a domain using its boundary points only, no point
/// added: `points` (#P by 2) hold the loops' points, each loop a run of consecutive rows given as
/// (first row, count); the domain is inside an odd number of loops. Every loop edge and every pair
/// of `edges` (rows) is an edge of the result. Triangles counter-clockwise. InputInvalid when
/// points coincide or loops and edges cross.
Result<Faces> triangulateBoundaryPoints(const Points2& points,
                                        const std::vector<std::pair<int, int>>& loops,
                                        const std::vector<std::pair<int, int>>& edges = {});

}  // namespace dform
