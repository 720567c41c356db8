// SPDX-License-Identifier: GPL-3.0-or-later
// Internal to dform_validate: the checks that need CGAL (exact predicates), behind Eigen/std
// types. cgal_checks.cpp is the module's only CGAL translation unit.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "dform/core/types.h"

namespace dform::detail {

struct SelfIntersections {
  int pairs = 0;              ///< pairs of triangles that intersect beyond their shared vertices
  int faceToFace = 0;         ///< nearby pairs (bounding boxes overlapping) that lie face to face
  int skippedDegenerate = 0;  ///< triangles left out because their corners are collinear
  std::string example;        ///< the first pair found, "triangles i and j", when any
};

/// Two triangles lie face to face when each one's corners are within this fraction of the soup's
/// bounding-box diagonal of the other's plane and their normals point opposite ways.
constexpr double kFaceToFaceTolerance = 1e-9;

/// Intersecting pairs of triangles of the soup (V, F), whose faces are oriented consistently (a
/// shared edge runs opposite ways in its two faces). Triangles that lie face to face (see
/// kFaceToFaceTolerance) touch and never count: a sheet folded flat onto another (a 180-degree
/// fold, a doubly covered body) is the limit of sheets that do not meet, while coplanar sheets
/// facing the same way, or sheets meeting at any angle, cross. Triangles that share vertex indices
/// are adjacent: they count only when they overlap beyond what they share (two triangles on one
/// edge folded onto each other the same way up; two on one corner whose opposite edge pierces the
/// other). Works on non-manifold soups. Exact predicates.
SelfIntersections findSelfIntersections(const Points3& V, const Faces& F);

/// Convex hull of the rows of P as a triangle mesh, outward-facing; nullopt when the points are
/// coplanar (the hull has no inside).
struct HullMesh {
  Points3 V;
  Faces F;
};
std::optional<HullMesh> convexHull(const Points3& P);

/// Indices of the rows of P that are corners of their convex hull, counter-clockwise (points on a
/// hull edge between two corners are not corners). Exact predicates.
std::vector<int> convexHull2(const Points2& P);

}  // namespace dform::detail
