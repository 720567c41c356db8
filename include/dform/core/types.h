// SPDX-License-Identifier: GPL-3.0-or-later
// Value types shared by every stage of dform. Points are rows; lengths are millimetres at every
// module boundary (the solver may normalise internally and scales back).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace dform {

using Points2 = Eigen::Matrix<double, Eigen::Dynamic, 2>;  ///< #P by 2
using Points3 = Eigen::Matrix<double, Eigen::Dynamic, 3>;  ///< #P by 3
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3>;       ///< #F by 3 vertex indices

/// A closed planar outline in mm: #P by 2, counter-clockwise, the first point not repeated at the
/// end. `source` names where it came from (a file path) for error messages.
struct Outline2 {
  /// The outline's points in mm, #P by 2, counter-clockwise.
  Points2 points;
  /// Where the outline came from (a file path), named in error messages.
  std::string source;
};

/// A crease line drawn inside a piece: an open polyline (#P by 2, mm) whose two ends lie on the
/// piece's boundary (its outline or a hole). `label` names it in messages ("path 3").
struct CreaseLine {
  /// The crease's points in mm, #P by 2, from one boundary to another.
  Points2 points;
  /// Its name in messages ("path 3"), as the input file calls it.
  std::string label;
};

/// A flat shape: its outer outline and any holes (each counter-clockwise, dense polylines in mm),
/// and the crease lines drawn on it.
struct Shape2 {
  /// The outer outline.
  Outline2 outer;
  /// The holes inside the outer outline, none for most pieces.
  std::vector<Outline2> holes;
  /// The fold lines drawn on the shape, each from boundary to boundary.
  std::vector<CreaseLine> creases;
  std::string sha256;  ///< of the file's bytes as read (readOutline); empty when not read from one
};

/// A closed space curve in mm: #P by 3, the first point not repeated at the end.
struct Curve3 {
  /// The curve's points in mm, #P by 3.
  Points3 points;
  /// Where the curve came from (a file path), named in error messages.
  std::string source;
  std::string sha256;  ///< of the file's bytes as read (readCurve); empty when not read from one
};

/// A triangulated flat domain. V is #V by 2 (mm), F is #F by 3 with counter-clockwise triangles,
/// `boundary` lists the outer boundary loop's vertex indices in counter-clockwise order, `lines`
/// the vertex indices of each interior constraint line (a crease), end to end along mesh edges.
struct FlatMesh {
  /// Vertex positions in mm, #V by 2.
  Points2 V;
  /// Triangles as vertex indices, #F by 3, counter-clockwise.
  Faces F;
  /// The outer boundary loop's vertex indices, counter-clockwise.
  std::vector<int> boundary;
  /// Each interior constraint line (a crease) as vertex indices end to end along mesh edges.
  std::vector<std::vector<int>> lines;
};

/// One piece of a D-Form: the flat shape as it is cut and the same triangles bent in 3D.
/// `flat` is #V by 2, `shape` is #V by 3, both in mm, sharing the faces F (counter-clockwise in
/// the flat layout, outward-facing in 3D). `seam` lists the joined boundary loop's vertices in
/// seam order: the outer outline of a classic D-Form piece, or a hole's loop for the anti and
/// demi variants (paper section 6.4).
struct Piece {
  /// The piece's name in messages and report.json ("piece A").
  std::string name;
  /// The flat layout as it is cut: #V by 2 in mm.
  Points2 flat;
  /// The same vertices bent in 3D: #V by 3 in mm.
  Points3 shape;
  /// Triangles shared by flat and shape, #F by 3 vertex indices.
  Faces F;
  /// The joined boundary loop's vertices in seam order.
  std::vector<int> seam;
  /// Boundary loops that are cut but not joined (the outer outline of an annulus-like piece whose
  /// hole is the seam, or a hole that is not joined), each with the piece on its left:
  /// counter-clockwise around an outer outline, clockwise around a hole.
  std::vector<std::vector<int>> freeBoundaries;
  /// Crease lines the designer drew: open polylines of vertex indices along mesh edges, each from
  /// boundary to boundary. The sheet may fold sharply along them.
  std::vector<std::vector<int>> creases;
};

/// A solved D-Form: a.seam[i] and b.seam[i] are the two sides of the same seam point. Piece A's
/// seam runs counter-clockwise around its flat outline, piece B's clockwise, so that both pieces'
/// faces are outward-facing on the closed 3D surface.
struct DForm {
  /// Piece A, whose seam runs counter-clockwise around its flat outline.
  Piece a;
  /// Piece B, whose seam runs clockwise; b.seam[i] is joined to a.seam[i].
  Piece b;
};

/// A numbered tick pair of the cut pattern at the 3D seam point where its two ticks meet: what
/// the assembly page and the report's 3D view label.
struct SeamTick {
  /// The tick pair's number along the seam, from 0 at the starting pair.
  int id = 0;
  std::string label;  ///< as printed on the pattern ("0", "1", ..., "6." for a turned-over 9)
  /// The 3D seam point, in mm, where the pair's two ticks meet.
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
};

}  // namespace dform
