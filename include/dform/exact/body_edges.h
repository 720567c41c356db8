// SPDX-License-Identifier: GPL-3.0-or-later
// The edges of the exact body, drawn in the flat pieces. Each edge of the body's triangulation is a
// geodesic of the glued surface between two cone points: straight in a flat piece, and where it
// crosses the seam it goes on straight in the other piece (the two sides of a seam chord are
// glued by a rigid motion). Tracing it through the pieces gives the lines a piece's mesh must
// follow so that every triangle lies in one face of the body.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dform/core/status.h"
#include "dform/exact/exact_gluing.h"

namespace dform::exact {

/// A place on the seam: seam point `chord` when t = 0, else the point a fraction t (0 < t < 1)
/// along the chord from seam point `chord` to `chord` + 1 (the same place on both pieces: paired
/// chords are equally long).
struct SeamPlace {
  int chord = 0;  ///< the seam point the place is at or after
  double t = 0;   ///< the fraction along the chord to the next seam point, in [0, 1)
  /// Whether the place is seam point `chord` itself.
  bool isSeamPoint() const { return t == 0.0; }
};

/// One straight run of a body edge through the inside of a piece, from one place on its seam to
/// another.
struct EdgeRun {
  int piece = 0;          ///< 0 for A, 1 for B
  SeamPlace from;         ///< where the run enters the piece
  SeamPlace to;           ///< where it leaves
  double fromLength = 0;  ///< how far along the body edge the run's start is, mm
  double toLength = 0;    ///< how far along the body edge the run's end is, mm
};

/// An edge of the body with its fold and its course through the pieces.
struct BodyEdge {
  int from = 0;       ///< the seam point it starts at
  int to = 0;         ///< the seam point it ends at
  double fold = 0;    ///< the angle between its two faces' normals, radians (0: coplanar)
  double length = 0;  ///< its length, mm
  /// Its runs through the pieces' insides, in order from `from`. Empty when the edge runs along
  /// the seam (a chord, or several in line across flat seam points).
  std::vector<EdgeRun> runs;
};

/// Every edge of the body (not doubly covered), traced through the pieces. A run that meets the
/// seam within `snap` (a fraction of the chord) of a seam point goes through that point.
/// SolveFailed when an edge cannot be followed to its far end (it would leave the pieces or meet
/// a cone point on its way), which sound input never causes.
Result<std::vector<BodyEdge>> traceBodyEdges(const ExactGluing& gluing, double snap = 1e-9);

/// Moves the body's vertices (Gauss-Newton on the edges' lengths) so that every edge is as long in
/// 3D as it is in the pieces, drawn straight through them (`edges` as traced, in the order of
/// traceBodyEdges), and sets each edge's fold again. The embedding meets the lengths its flips
/// left, which the chained laws of cosines put off by up to ~1e-7 across a flat face triangulated
/// many times over; the body is rigid (Cauchy, Dehn), so the lengths fix it. Returns the largest
/// move, mm.
double fitBodyToEdges(ExactGluing& gluing, std::vector<BodyEdge>& edges);

/// Damping of fitBodyToEdges' normal equations (mm^0: the edges' rows are unit vectors).
constexpr double kRigidDamping = 1e-10;

/// The flat position in piece `piece` (0: A, 1: B) of a place on the seam.
Eigen::Vector2d seamPlacePoint(const ExactGluing& gluing, int piece, const SeamPlace& place);

}  // namespace dform::exact
