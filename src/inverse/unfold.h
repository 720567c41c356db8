// SPDX-License-Identifier: GPL-3.0-or-later
// Laying a pre-D-Form piece flat and mapping flat points back onto it (paper 5.1).
#pragma once

#include <string>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

/// Unfolds a triangulated disc without interior vertices isometrically into the plane.
/// V is #V by 3; F is #F by 3, consistently oriented, every vertex on the boundary, so
/// #F = #V - 2 and the dual graph is a tree. Returns #V by 2 flat positions (rows as V): every
/// edge keeps its 3D length up to rounding and every face comes out counter-clockwise. The faces
/// are laid out breadth-first over the dual tree, each new vertex placed from its two edge
/// lengths on the far side of the shared edge. InputInvalid when F is not such a disc (wrong face
/// count, an edge in more than two faces or twice the same way, disconnected faces, an unused
/// vertex). The layout can overlap itself: check it with checkSheet.
Result<Points2> unfoldDisc(const Points3& V, const Faces& F);

/// Checks that the closed outline through the rows of `outline` (#n by 2, row i = curve point i,
/// either orientation) is a simple polygon, i.e. the piece can be cut from one sheet. InputInvalid
/// otherwise: "piece <name> unfolds onto itself near curve points i-j and k-l: it cannot be cut
/// from one sheet".
Status checkSheet(const Points2& outline, const std::string& pieceName);

/// Maps each row of `query` (#Q by 2) to 3D by its barycentric coordinates in the triangle of
/// (flat, F) that contains it, applied to the same triangle of `shape` (flat #V by 2 and shape
/// #V by 3 share F). A query on an edge or vertex may use any triangle there; the map is exact
/// (bit for bit) for a query that coincides with a vertex of `flat`. A query outside every
/// triangle (beyond rounding) uses the triangle it is nearest to in barycentric terms and is
/// extrapolated affinely; the caller keeps queries inside the domain. Triangles are found through
/// a uniform grid over their bounding boxes, O(#F + #Q) for even meshes.
Points3 mapBarycentric(const Points2& flat, const Points3& shape, const Faces& F,
                       const Points2& query);

}  // namespace dform
