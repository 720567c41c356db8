// The 3D convex hull of a point set (for the inverse pre-D-Form).
#pragma once

#include <vector>

#include "core/status.h"
#include "core/types.h"

namespace dform {

struct ConvexHull3 {
  Faces F;                    ///< #H by 3 indices into the input points, outward-facing
  std::vector<bool> onHull;   ///< per input point: is it a vertex of the hull
};

/// Convex hull of the rows of P. Returns InputInvalid when the points are (nearly) coplanar, so
/// that the hull has no inside.
Result<ConvexHull3> convexHull3(const Points3& P);

}  // namespace dform
