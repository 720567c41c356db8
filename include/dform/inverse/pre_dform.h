// SPDX-License-Identifier: GPL-3.0-or-later
// Initialisation of inverse modelling (paper 5.1): the pre-D-Form on the seam curve, cut into two
// discs, unfolded, remeshed and mapped back onto the discs. Design: docs/inverse.md.
#pragma once

#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

/// How the pre-D-Form (the start of an inverse solve) is built from the curve.
struct InverseInitOptions {
  /// Weight of a fold between a filled triangle and its neighbour, against the filled area
  /// measured in units of the hull's surface area (dimensionless): 1 makes a fold straight back
  /// cost as much as filling the whole hull. 0 gives the plain minimum-area filling.
  double foldWeight = 1.0;
  /// Interior edge length of the remeshed pieces as a multiple of the curve's mean edge length.
  double edgeLengthFactor = 1.0;
  /// Smallest triangle angle the remeshing aims for (degrees, boundary corners aside).
  double minAngleDegrees = 25.0;
  /// Accept a pre-D-Form whose triangles cross each other in 3D (a tangled initial shape) instead
  /// of failing with InputInvalid.
  bool allowSelfIntersection = false;
};

/// The pre-D-Form: two triangulations of the closed polygon C (#n by 3) that share only C.
/// Both use the rows of C as vertices and have no interior vertices (n - 2 triangles each).
struct PreDForm {
  /// Disc whose outward-facing triangles run the curve forwards (0, 1, ..., n-1) around their
  /// boundary: piece A. Outward means out of the closed surface discA + discB.
  Faces discA;
  /// The other disc, triangles outward-facing, so they run the curve backwards: piece B.
  Faces discB;
  bool onHull = false;              ///< every curve point is a vertex of the convex hull (paper)
  std::vector<int> insideVertices;  ///< curve points that are not hull vertices, ascending
  bool isHull = false;      ///< every triangle lies on the convex hull: the pre-D-Form is the hull
  int hullTriangles = 0;    ///< triangles of discA + discB that are hull faces
  int filledTriangles = 0;  ///< triangles of discA + discB that are not
  std::string summary;      ///< one line describing the case, for the run's messages
};

/// Builds the pre-D-Form of the closed curve C (#n by 3, n >= 4, any frame and scale): the
/// convex hull's faces on either side of C, with the parts where C leaves the hull filled by a
/// minimum-weight polygon triangulation (dynamic programming, O(n^3)). For an on-hull curve whose
/// consecutive points are hull edges this is exactly the hull cut along C. InputInvalid, with a
/// one-line cause and no file name, when the curve has fewer than 4 points, a non-finite
/// coordinate, a zero-length edge, two points that coincide, is planar, or when the two discs
/// would need a degenerate triangle or would cross each other (a knotted or tangled curve).
Result<PreDForm> buildPreDForm(const Points3& C, const InverseInitOptions& options = {});

/// Everything inverse modelling starts from.
struct InverseInit {
  /// Pieces A and B remeshed: `flat` is the unfolded piece (mm), `shape` the same vertices on the
  /// pre-D-Form (mm), F counter-clockwise flat and outward-facing in 3D. a.seam[i] and b.seam[i]
  /// are the vertices at curve point C.row(i); a's seam runs counter-clockwise around its flat
  /// outline, b's clockwise. The first n vertices of each piece are its seam vertices.
  DForm model;
  PreDForm pre;  ///< the pre-D-Form the pieces were unfolded from: its two discs on the curve
  /// The pre-D-Form pieces unfolded: V row i is curve point i laid flat, F = pre.discA or
  /// pre.discB (counter-clockwise flat), boundary counter-clockwise (B: 0, n-1, ..., 1).
  FlatMesh preFlatA;
  FlatMesh preFlatB;  ///< see preFlatA
  Faces preDFormF;    ///< pre.discA then pre.discB: the closed pre-D-Form on the rows of C
};

/// Paper 5.1 end to end: buildPreDForm, unfold both discs (edge lengths kept exactly), check each
/// flat outline is a simple polygon, remesh each flat domain with triangulateDomain (target edge
/// length = edgeLengthFactor times the curve's mean edge length) and map the new vertices onto
/// the discs by barycentric coordinates. C is the seam already resampled (uniformly, in mm).
/// InputInvalid as buildPreDForm, or when a piece unfolds onto itself ("piece B unfolds onto
/// itself near curve points ...: it cannot be cut from one sheet") or cannot be meshed.
Result<InverseInit> initialiseInverse(const Points3& C, const InverseInitOptions& options = {});

/// Same, with `curve.source` (the file) prefixed to every error message.
Result<InverseInit> initialiseInverse(const Curve3& curve, const InverseInitOptions& options = {});

}  // namespace dform
