// Triangulating flat domains for the solver.
#pragma once

#include <vector>

#include "core/status.h"
#include "core/types.h"

namespace dform {

struct TriangulateOptions {
  double targetEdgeLength = 1.0;  ///< interior edge length to aim for (same unit as the input)
  double minAngleDegrees = 25.0;  ///< smallest triangle angle to aim for (boundary corners aside)
};

/// Constrained Delaunay triangulation with refinement of the polygon `boundary` (#B by 2,
/// counter-clockwise, simple) and optional holes (each a simple polygon inside it). The result's
/// first #B vertices are exactly the boundary points in order (no boundary edge is split), then
/// each hole's points in order, then interior vertices. FlatMesh::boundary = 0..#B-1. Triangles
/// are counter-clockwise. Returns InputInvalid if the domain cannot be meshed.
Result<FlatMesh> triangulateDomain(const Points2& boundary, const std::vector<Points2>& holes,
                                   const TriangulateOptions& options);

}  // namespace dform
