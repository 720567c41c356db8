// SPDX-License-Identifier: GPL-3.0-or-later
// A D-Form made of rigid flat triangles: the unknowns are the 3D positions of the pieces'
// boundary points only (seam points, free brim points, crease ends), and every face is a
// triangle of a flat piece whose corners are such points. Each face is so an isometric copy of
// a triangle of the pattern, and the sheet cannot stretch: the only equations are the lengths of
// the triangles' edges (the chords of the pieces), the only freedom which chords are edges (the
// rulings) and how the sheet bends along them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

#include "dform/core/types.h"

namespace dform::ruled {

/// One flat piece triangulated with its boundary points only. Halfedge h = 3 f + c runs from
/// corner c of face f to corner c + 1; faces are counter-clockwise in the piece's plane.
class PieceTriangulation {
 public:
  PieceTriangulation() = default;
  /// `flat` #P by 2 (mm), `faces` #F by 3 counter-clockwise rows of `flat`, `fixed` edges (pairs of
  /// rows: drawn creases) that flips never remove.
  PieceTriangulation(Points2 flat, const Faces& faces,
                     const std::vector<std::pair<int, int>>& fixed = {});

  const Points2& flat() const { return flat_; }            ///< the piece's points, #P by 2, mm
  int faceCount() const { return int(tail_.size()) / 3; }  ///< the number of triangles
  int halfedgeCount() const { return int(tail_.size()); }  ///< three per triangle
  /// The halfedge after h in its face (counter-clockwise).
  static int next(int h) { return 3 * (h / 3) + (h % 3 + 1) % 3; }
  /// The halfedge before h in its face.
  static int prev(int h) { return 3 * (h / 3) + (h % 3 + 2) % 3; }
  int tail(int h) const { return tail_[std::size_t(h)]; }        ///< the row h starts at
  int head(int h) const { return tail_[std::size_t(next(h))]; }  ///< the row h ends at
  int twin(int h) const { return twin_[std::size_t(h)]; }        ///< -1 on the boundary
  /// Whether h's edge is a drawn crease, which flips never remove.
  bool fixed(int h) const { return fixed_[std::size_t(h)]; }
  /// The vertex facing h in its face.
  int opposite(int h) const { return tail_[std::size_t(prev(h))]; }
  /// Flat length of h's edge, mm.
  double length(int h) const;
  /// Flat area of face f, mm^2.
  double area(int f) const;
  /// The triangles as rows of flat(), #F by 3, counter-clockwise.
  Faces faces() const;

  /// Whether the interior edge of h can be replaced by the other diagonal of its two triangles:
  /// not fixed, and the quadrilateral strictly convex in the plane (the new chord inside the
  /// piece), each of its four corners turning by more than `minTurn` radians.
  bool flippable(int h, double minTurn = 1e-9) const;
  /// Flips the edge of h (flippable(h) must hold). The two faces keep their indices and the
  /// new edge is halfedge 3 f + 0 of each; returns the new halfedge of h's face.
  int flip(int h);

 private:
  Points2 flat_;
  std::vector<int> tail_, twin_;
  std::vector<bool> fixed_;
};

/// An undirected edge of a piece's triangulation and what it is on the surface.
enum class EdgeKind {
  Boundary,  ///< on the piece's boundary: a seam chord or a free brim edge (a free hinge)
  Crease,    ///< a drawn crease: an interior edge that folds freely
  Chord,     ///< an interior chord: a ruling, whose fold costs bending energy
  Tie,       ///< no edge of the sheet: a distance between two vertices held while zipping
};

/// A distance held between two surface vertices that no face joins (a seam pair being zipped).
struct Tie {
  int i = 0;          ///< one surface vertex
  int j = 0;          ///< the other
  double length = 0;  ///< mm
};

/// An edge of the glued surface: where it lies, its ends, its flat length, its kind, and for an
/// interior edge the two vertices facing it and its bending weight.
struct SurfaceEdge {
  int piece = 0;      ///< 0 for A, 1 for B (a seam chord: A)
  int halfedge = 0;   ///< one of its halfedges in the piece (the one with twin < it or -1)
  int i = 0;          ///< the surface vertex at its start
  int j = 0;          ///< the surface vertex at its end
  double length = 0;  ///< flat length, mm (a seam chord: the mean of its two sides)
  EdgeKind kind = EdgeKind::Chord;  ///< what it is on the surface
  int k = -1;         ///< interior edges: the vertex facing it on the left of i->j (-1 for others)
  int l = -1;         ///< interior edges: the vertex facing it on the right
  double weight = 0;  ///< bending weight 3 length^2 / (A_k + A_l), dimensionless
};

/// Both pieces glued: their triangulations, which surface vertex each row is, the 3D positions.
/// Seam point k is row seamRows[p][k] of piece p and the same surface vertex on both pieces.
struct RuledSurface {
  std::array<PieceTriangulation, 2> pieces;  ///< A's and B's triangulations
  std::array<std::vector<int>, 2> vertexOf;  ///< per piece: row -> surface vertex
  std::array<std::vector<int>, 2> seamRows;  ///< per piece: its rows along the seam, in order
  /// Per piece: the rows of its free outline, counter-clockwise (empty for a piece zipped along
  /// its outline).
  std::array<std::vector<int>, 2> freeRows;
  std::vector<Tie> ties;  ///< distances held while zipping; empty on a zipped surface
  Points3 X;              ///< #V by 3, mm

  int vertexCount() const { return int(X.rows()); }  ///< the number of surface vertices
  /// Every edge once: a seam chord (the boundary of both pieces between two shared vertices) is
  /// listed once, from piece A.
  std::vector<SurfaceEdge> edges() const;
  /// Whether two different edges join the same two surface vertices (a chord of both pieces, or
  /// a chord beside a seam chord): a surface must not have them.
  bool hasDoubleEdge() const;
};

/// The signed dihedral angle of an interior edge, radians: 0 where its two triangles lie in one
/// plane, positive where the surface is convex there seen from the side the faces' normals point
/// to (B is A turned over, so both pieces' faces point the same way on the glued surface).
/// Its gradient with respect to x_i, x_j, x_k, x_l (rows 0..3) when `gradient` is given.
double dihedral(const Eigen::Vector3d& xi, const Eigen::Vector3d& xj, const Eigen::Vector3d& xk,
                const Eigen::Vector3d& xl, Eigen::Matrix<double, 4, 3>* gradient = nullptr);

/// The bending energy sum over chords of weight * angle^2 (dimensionless).
double bendingEnergy(const RuledSurface& surface, const std::vector<SurfaceEdge>& edges);

/// The largest | |x_i - x_j| - length | / length over the edges.
double maxLengthError(const RuledSurface& surface, const std::vector<SurfaceEdge>& edges);

}  // namespace dform::ruled
