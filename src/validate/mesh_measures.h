// SPDX-License-Identifier: GPL-3.0-or-later
// Internal to dform_validate: elementary measures of one triangle mesh (topology, angles, angle
// defects, flipped and degenerate triangles, overlaps in the plane). Eigen and std only.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "dform/core/types.h"

namespace dform::detail {

/// Each undirected edge of F once: `edges[e]` = {i, j} with i < j, `faces[e]` = the faces on its
/// two sides ({f, -1} for a boundary edge; a non-manifold edge keeps its first two faces).
struct EdgeTopology {
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 2>> faces;
};
EdgeTopology edgeTopology(const Faces& F);

/// Index into topology.edges of the edge joining i and j, or -1 when there is none.
int edgeIndex(const EdgeTopology& topology, int i, int j);

/// Per vertex of the piece: on a boundary edge of its faces, on its seam or on one of its creases
/// (the places where the sheet may turn, so the angle defect there is not curvature).
std::vector<bool> boundaryOrCreaseVertices(const Piece& piece, const EdgeTopology& topology);

/// Per vertex of the piece: whether the gate's curvature check looks at it, i.e. it is a vertex of
/// some face and neither lies on the boundary, the seam or a crease nor shares an edge with one.
std::vector<bool> awayFromSeam(const Piece& piece, const EdgeTopology& topology);

/// Per edge of topology.edges: whether it lies along one of the piece's creases.
std::vector<bool> creaseEdges(const Piece& piece, const EdgeTopology& topology);

/// Angle at corner `a` of triangle (a, b, c), in [0, pi]; 0 when an edge at `a` has zero length.
double cornerAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Per vertex: 2*pi minus the sum of the 3D angles of the faces around it (radians).
Eigen::VectorXd angleDefects(const Points3& V, const Faces& F);

/// Flat rows lifted to 3D (z = 0), so that 2D and 3D share the angle code.
Points3 lift(const Points2& P);

/// Whether flat triangle f has signed area <= 0 (counter-clockwise is positive).
bool isFlippedFlat(const Points2& P, const Faces& F, int f);

/// Triangles of layout V with an angle below 1e-3 rad or an area below 1e-12 * (mean edge length
/// of V)^2 (see the reasons in mesh_measures.cpp).
int countDegenerate(const Points3& V, const Faces& F, const EdgeTopology& topology);

/// 3D triangles folded back over a neighbour (see the definition in mesh_measures.cpp). Edges
/// with `hinge[e]` set (creases) may fold sharply and are not looked at.
int countFolded(const Points2& flat, const Points3& shape, const Faces& F,
                const EdgeTopology& topology, const std::vector<bool>& hinge);

/// Pairs of flat triangles whose interiors overlap (touching along an edge or at a corner is no
/// overlap). `example` receives the first pair found as "f1 and f2" when any.
int countFlatOverlaps(const Points2& P, const Faces& F, std::string* example);

/// Closed polyline through rows `idx` of V.
double seamLength(const Eigen::Ref<const Eigen::MatrixXd>& V, const std::vector<int>& idx);

}  // namespace dform::detail
