// SPDX-License-Identifier: GPL-3.0-or-later
// A triangulation of a closed flat-cone surface known only by its edge lengths (an intrinsic
// triangulation), with edge flips, removal of flat vertices and geodesic tracing. Directions at a
// vertex are "signposts": angles in [0, cone angle) measured counter-clockwise in the input
// surface, so that a point given on the input (a flat piece) can be found in any triangulation the
// flips lead to (Sharp, Soliman and Crane, "Navigating intrinsic triangulations", 2019).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace dform::exact {

/// A point of the surface: a triangle and barycentric coordinates of its three corners.
struct SurfacePoint {
  /// The triangle the point lies in (-1: none).
  int face = -1;
  /// Barycentric coordinates of its three corners, summing to 1.
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
};

/// Halfedge h = 3 f + c runs from corner c of face f to corner c + 1; faces are counter-clockwise
/// in the surface's orientation.
class IntrinsicTriangulation {
 public:
  IntrinsicTriangulation() = default;
  /// `faces` #F by 3 vertex indices; `lengths` #F by 3, the length of the edge from corner c to
  /// corner c + 1; `signposts` #F by 3, the direction of that edge at corner c; `coneAngles` the
  /// total angle at each vertex. Faces sharing an edge list it in opposite directions. Two
  /// vertices may be joined by several edges (one through each piece of a glued surface): an edge
  /// is then matched within the faces of its `groups` entry (one per face) first.
  IntrinsicTriangulation(const Eigen::MatrixX3i& faces, const Eigen::MatrixX3d& lengths,
                         const Eigen::MatrixX3d& signposts, std::vector<double> coneAngles,
                         const std::vector<int>& groups = {});

  /// The number of vertices, removed ones included.
  int vertexCount() const { return int(coneAngle_.size()); }
  /// The number of face slots (faceAlive says which are in use).
  int faceCount() const { return int(tail_.size()) / 3; }
  /// Three per face slot.
  int halfedgeCount() const { return int(tail_.size()); }

  /// The halfedge after h in its face (counter-clockwise).
  static int next(int h) { return 3 * (h / 3) + (h % 3 + 1) % 3; }
  /// The halfedge before h in its face.
  static int prev(int h) { return 3 * (h / 3) + (h % 3 + 2) % 3; }
  /// The halfedge of the same edge in the neighbouring face, running the other way.
  int twin(int h) const { return twin_[h]; }
  /// The vertex h starts at.
  int tail(int h) const { return tail_[h]; }
  /// The vertex h ends at.
  int head(int h) const { return tail_[next(h)]; }
  /// The length of h's edge, in the surface's unit (mm).
  double length(int h) const { return length_[h]; }
  /// h's direction at its tail: an angle in [0, coneAngle) counter-clockwise in the input surface,
  /// radians.
  double signpost(int h) const { return signpost_[h]; }
  /// The total angle around v, radians (2 pi where the surface is flat).
  double coneAngle(int v) const { return coneAngle_[v]; }
  /// Whether face slot f is in use (a merge in removeFlatVertex frees slots).
  bool faceAlive(int f) const { return tail_[3 * f] >= 0; }

  /// The interior angle of h's face at h's tail.
  double cornerAngle(int h) const;
  /// Outgoing halfedges of v in counter-clockwise order.
  std::vector<int> outgoing(int v) const;

  /// The length the edge of h would have after a flip, and whether the flip is possible: the two
  /// triangles form a strictly convex quadrilateral and the edge joins two distinct faces.
  bool flippable(int h, double* newLength = nullptr) const;
  /// Flips the edge of h (flippable(h) must hold); its two faces keep their indices.
  void flip(int h);

  /// Removes vertex v, whose cone angle must be 2 pi, by flipping its edges until it has three,
  /// then merging its three triangles. False when no flip can lower its degree.
  bool removeFlatVertex(int v);
  /// Drops removed vertices and faces; returns each old vertex's new index (-1 if removed).
  std::vector<int> compact();

  /// Flips until every edge is Delaunay (opposite angles sum to at most pi). Returns the flips.
  int makeDelaunay();

  /// The point at distance `distance` from vertex v along the geodesic leaving it in direction
  /// `direction` (a signpost angle). Fails (face -1) when the trace does not end within a bound of
  /// steps, which only a bad input can cause.
  SurfacePoint trace(int v, double direction, double distance) const;

 private:
  std::vector<int> tail_, twin_;
  std::vector<double> length_, signpost_;
  std::vector<double> coneAngle_;
  std::vector<int> vertexHalfedge_;
};

/// Interior angle at a of the triangle with sides a-b = ab, b-c = bc, c-a = ca (law of cosines,
/// clamped so that rounding never yields NaN).
double triangleAngle(double ab, double bc, double ca);

}  // namespace dform::exact
