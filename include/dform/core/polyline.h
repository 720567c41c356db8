// SPDX-License-Identifier: GPL-3.0-or-later
// Elementary geometry of polylines: closed ones (outlines and seam curves), where the last point
// joins the first and is not repeated, and open ones (crease lines).
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "dform/core/constants.h"
#include "dform/core/types.h"

namespace dform {

/// Length of the closed polyline through the rows of P (#P by d).
double closedLength(const Eigen::MatrixXd& P);

/// Cumulative arc length at each vertex of the closed polyline: s[0] = 0, s[i] = length up to row
/// i.
Eigen::VectorXd cumulativeArcLength(const Eigen::MatrixXd& P);

/// Signed area of a closed planar polygon, positive when counter-clockwise.
double signedArea(const Points2& P);

/// n points spaced uniformly by arc length along the closed polyline P (#P by d), the first at
/// arc length `startFraction` * length from P's first point (fraction in [0, 1)).
Eigen::MatrixXd resampleClosed(const Eigen::MatrixXd& P, int n, double startFraction = 0.0);

/// The points of the closed polyline P (#P by d) at the given arc-length fractions from P's first
/// point (taken modulo 1), in the given order.
Eigen::MatrixXd resampleAtFractions(const Eigen::MatrixXd& P, const std::vector<double>& fractions);

/// Length of the open polyline through the rows of P (#P by d).
double openLength(const Eigen::MatrixXd& P);

/// segments + 1 points spaced uniformly by arc length along the open polyline P (#P by d, at
/// least 2 rows), from its first row to its last (both kept exactly).
Eigen::MatrixXd resampleOpen(const Eigen::MatrixXd& P, int segments);

/// A flattened smooth curve turns by a fraction of a degree per point; a drawn corner by much
/// more. 20 degrees separates the two for any outline a designer draws.
constexpr double kCornerTurnRadians = 20.0 * kDegree;

/// The turning angle (radians, in [0, pi]) of the closed polygon P (#P by d) at each vertex.
Eigen::VectorXd turningAngles(const Eigen::MatrixXd& P);

/// Which vertices of the closed polygon P (#P by d), sampled along a drawn line, are its corners:
/// a turn of kCornerTurnRadians or more that is at least twice each neighbour's. A coarse sampling
/// of a tight smooth bend turns as much at neighbouring vertices; a drawn corner stands alone.
std::vector<bool> sampledCorners(const Eigen::MatrixXd& P);

/// The closed polygon P (#P by d, sampled along a smooth curve with corners) with each vertex
/// moved away from its centre of curvature by kappa h^2 / 24, where kappa is the curvature of the
/// circle through it and its two neighbours and h the mean length of its two edges. A polygon
/// inscribed in a curve falls short of the curve's length by about kappa^2 h^3 / 24 per edge;
/// moved so, it straddles the curve and matches its length to O(h^4) (exactly, for a circle
/// sampled evenly). Corners (sampledCorners) stay where they are.
Eigen::MatrixXd compensateChordLoss(const Eigen::MatrixXd& P);

/// Arc-length fractions, ascending, of the vertices of the closed polygon P where it turns by at
/// least minTurnRadians (either way): its corners.
std::vector<double> cornerFractions(const Points2& P, double minTurnRadians);

/// Arc-length fraction in [0, 1) of the point of closed polyline P nearest to q.
double nearestArcFraction(const Points2& P, const Eigen::Vector2d& q);

/// The first pair of non-adjacent edges (i, j) of the polyline that touch or cross, if any. Edge
/// i joins row i to row i+1, modulo #P when `closed` (a polygon); an open polyline has #P - 1
/// edges. Runs in O(#P log #P) for typical outlines.
std::optional<std::pair<int, int>> findSelfIntersection(const Points2& P, bool closed = true);

/// The first pair of edges (i of P, j of Q) of two closed polygons that touch or cross, if any.
std::optional<std::pair<int, int>> findCrossing(const Points2& P, const Points2& Q);

/// Whether the 2D segments [a, b] and [c, d] touch or cross.
bool segmentsIntersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d);

/// Where segments [a, b] and [c, d], known to touch or cross, meet (an end point of one lying on
/// the other where they overlap or only touch).
Eigen::Vector2d segmentsMeetingPoint(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                     const Eigen::Vector2d& c, const Eigen::Vector2d& d);

/// Distance from q to the segment [a, b].
double distanceToSegment(const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b);

/// Whether q lies inside the closed polygon P (even-odd rule). Meant for points off P's edges;
/// for a point on an edge the answer is either.
bool insidePolygon(const Points2& P, const Eigen::Vector2d& q);

/// The same for the closed polygon through the points of P (a sheet polyline).
bool insidePolygon(const std::vector<Eigen::Vector2d>& P, const Eigen::Vector2d& q);

}  // namespace dform
