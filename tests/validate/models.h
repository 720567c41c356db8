// SPDX-License-Identifier: GPL-3.0-or-later
// Test models with known answers: exact developments of polyhedral surfaces, so that every figure
// the tests expect is exact up to round-off.
#pragma once

#include <string>
#include <vector>

#include "dform/core/types.h"

namespace dform::test {

/// A piece whose flat layout is the exact development of `shape` (each face placed
/// counter-clockwise across an already placed edge) and whose seam is its boundary loop in face
/// orientation (counter-clockwise in the flat), starting at vertex `start`.
Piece developPiece(const Points3& shape, const Faces& F, const std::string& name, int start);

/// The disphenoid A=(-1,0,-h), B=(0,-1,h), C=(1,0,-h), D=(0,1,h) times `size` mm cut into two
/// pieces of two faces each (hinges AC and BD), every face split into k*k triangles. A closed,
/// convex, exactly developable D-Form whose surface is the convex hull of its seam. The hinge folds
/// by less than 90 degrees while h < 0.5.
DForm tetraDForm(int k, double size = 40.0, double h = 0.25);

/// A ribbon around the z axis from angle 0 to 2*pi*turns: outer edge at radius outerR rising
/// outerRise mm per radian, inner edge at innerR, lifted innerLift and rising innerRise. Piece A
/// and B are its two triangulations (the two diagonals of every quad), so together they close into
/// a chain of thin tetrahedra. All vertices are on the seam, so any such ribbon develops exactly.
struct Ribbon {
  int segments = 72;
  double turns = 1.2;
  double outerR = 30.0, innerR = 20.0;
  double outerRise = 1.5, innerRise = 1.5, innerLift = 0.0;
};
DForm ribbonDForm(const Ribbon& ribbon);

/// Two copies of a polar-grid disc of radius r: A as is, B mirrored; the shape is the disc in z=0.
DForm flatDoubleDisc(int rings, int sectors, double r);

/// A rectangle rolled exactly onto a prism inscribed in a cylinder of radius r (270 degrees,
/// `columns` facets, `rows` rows of height `height`/rows); B is a mirrored copy.
DForm rolledCylinder(int columns, int rows, double r, double height);

/// Piece B made from piece A: the same 3D shape, the flat mirrored, faces reversed, the same seam.
Piece mirroredCopy(const Piece& a, const std::string& name);

/// The vertices of `piece` whose 3D points lie on the segment from p to q (within 1e-9 mm), in
/// order from p: a crease along a straight fold of an exactly built model.
std::vector<int> verticesOnSegment(const Piece& piece, const Eigen::Vector3d& p,
                                   const Eigen::Vector3d& q);

/// tetraDForm with each piece's hinge (A-C on piece A, B-D on piece B) drawn as a crease. For h > 0
/// the hinges are mountains (the disphenoid is convex and its faces point out), for h < 0 valleys
/// (the faces point in); both fold by acos((1 - 4h^2) / (1 + 4h^2)).
DForm creasedTetraDForm(int k, double size = 40.0, double h = 0.25);

/// An anti D-Form: two annuli of outer radius R and hole radius r (each circle `sides`-gon),
/// meshed by triangulateDomain with edges of about `edge` mm, zipped along their holes. Piece A
/// rises as the cone (r + (rho - r) cos(slope), z = (rho - r) sin(slope)) over flat radius rho,
/// which is intrinsically flat (a cone's metric) though not isometric to the annulus; piece B is
/// its mirror image below z = 0 with its flat mirrored. The seam is the hole loop, the outer loops
/// are free boundaries (counter-clockwise in each flat layout).
DForm annulusDForm(double R = 50, double r = 20, int sides = 48, double edge = 6,
                   double slopeDeg = 5);

/// A demi D-Form: a disc A of radius r (a `sides`-gon) whose outline is zipped to the hole of an
/// annulus B (outer radius R), both meshed by triangulateDomain with edges of about `edge` mm.
/// A bulges up as the cap z = height (1 - rho^2 / r^2); B, not mirrored, falls away from the seam
/// as the cone of annulusDForm turned down. A's seam is its outline (counter-clockwise), B's the
/// hole loop at the same points; B's outer loop is a free boundary.
DForm demiDForm(double R = 45, double r = 25, int sides = 48, double edge = 6, double height = 12,
                double slopeDeg = 10);

/// A square of side `size` mm, a k by k grid whose cells are split along their (1, 1) diagonal,
/// folded exactly along straight creases. Crease c runs along mesh edges from grid point
/// (i0, j0) to (i1, j1), both on the boundary, in a direction (0, 1), (1, 0) or (1, 1); the part of
/// the square on its right is turned about it by angleDeg (positive: a mountain seen from the
/// faces' side, +z). Later creases must lie right of earlier ones. The seam is the outline.
struct GridCrease {
  int i0, j0, i1, j1;
  double angleDeg;
};
Piece foldedSquare(int k, double size, const std::vector<GridCrease>& creases,
                   const std::string& name = "A");

}  // namespace dform::test
