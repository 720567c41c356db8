// A D-Form made by the exact engine (src/exact), meshed as the paper model's pieces are: shared by
// forward runs and by inverse runs whose curve lies on its convex hull.
#pragma once

#include <string>

#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/exact/exact_gluing.h"
#include "dform/model/run_types.h"

namespace dform {

/// The two seam polygons (row k of each glued to the other's) made equal-chorded, glued into
/// their convex body, both pieces meshed with interior edges about `targetEdge` mm (folds of
/// the body through a piece become mesh lines and the piece's creases) and every vertex placed on
/// the body. Piece A's seam is rows 0..n-1 of its mesh, B's the same polygon counter-clockwise.
/// `paths` name the pieces in errors; `used` gets what the engine did.
Result<DForm> exactDForm(exact::SeamPolygons polygons, double targetEdge,
                         const std::string paths[2], ModelUsed& used);

}  // namespace dform
