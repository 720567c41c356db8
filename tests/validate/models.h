// Test models with known answers: exact developments of polyhedral surfaces, so that every figure
// the tests expect is exact up to round-off.
#pragma once

#include <string>

#include "core/types.h"

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
/// outerRise mm per radian, inner edge at innerR, lifted innerLift and rising innerRise. Piece A and
/// B are its two triangulations (the two diagonals of every quad), so together they close into a
/// chain of thin tetrahedra. All vertices are on the seam, so any such ribbon develops exactly.
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

}  // namespace dform::test
