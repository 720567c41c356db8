// Internal to dform_validate: elementary measures of one triangle mesh (topology, angles, angle
// defects, flipped and degenerate triangles, overlaps in the plane). Eigen and std only.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/types.h"

namespace dform::detail {

/// Each undirected edge of F once: `edges[e]` = {i, j} with i < j, `faces[e]` = the faces on its
/// two sides ({f, -1} for a boundary edge; a non-manifold edge keeps its first two faces).
struct EdgeTopology {
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 2>> faces;
};
EdgeTopology edgeTopology(const Faces& F);

/// Per vertex: on a boundary edge of F or listed in `seam`.
std::vector<bool> boundaryVertices(int vertexCount, const std::vector<int>& seam,
                                   const EdgeTopology& topology);

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

/// 3D triangles folded back over a neighbour (see the definition in mesh_measures.cpp).
int countFolded(const Points2& flat, const Points3& shape, const Faces& F,
                const EdgeTopology& topology);

/// Pairs of flat triangles whose interiors overlap (touching along an edge or at a corner is no
/// overlap). `example` receives the first pair found as "f1 and f2" when any.
int countFlatOverlaps(const Points2& P, const Faces& F, std::string* example);

/// Closed polyline through rows `idx` of V.
double seamLength(const Eigen::Ref<const Eigen::MatrixXd>& V, const std::vector<int>& idx);

}  // namespace dform::detail
