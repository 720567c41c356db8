// SPDX-License-Identifier: GPL-3.0-or-later
// The 3D convex hull of a point set (for the inverse pre-D-Form).
#pragma once

#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

/// The convex hull of a 3D point set, and how far each point lies from its surface.
struct ConvexHull3 {
  Faces F;                   ///< #H by 3 indices into the input points, outward-facing
  std::vector<bool> onHull;  ///< per input point: is it a vertex of the hull
  /// Per input point: distance to the hull's surface (input units). 0 for hull vertices; a point
  /// on a hull face but not a vertex has a distance near 0 and onHull false.
  std::vector<double> distanceToHull;
};

/// Convex hull of the rows of P. Coplanar hull facets come triangulated. Repeated points count
/// as one: every copy of a hull vertex is onHull, F uses the first. Returns InputInvalid when the
/// points are (nearly) coplanar, so that the hull has no inside: "nearly" means the hull's
/// thickness (2 · volume / area) is below 1e-9 times the bounding-box diagonal.
Result<ConvexHull3> convexHull3(const Points3& P);

}  // namespace dform
