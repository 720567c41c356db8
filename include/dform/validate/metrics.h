// SPDX-License-Identifier: GPL-3.0-or-later
// Quality figures of a D-Form (paper section 6.3 and Table 2), computed from the meshes alone.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "dform/core/types.h"

namespace dform {

/// The figures of a solved D-Form that report.json records under "metrics" and the gate judges:
/// how isometric the pieces stay, how closed the seam is, how curved and how well-formed the
/// meshes are, and how near the exact D-Form the seam lies.
struct Metrics {
  double lengthError = 0;     ///< |L3 - L2| / |L2| over all edges of both pieces (fraction)
  double lengthErrorMax = 0;  ///< max_i |L3_i - L2_i| / L2_i (fraction)
  double seamError = 0;       ///< mean distance between seam partners / seam length (fraction)
  double seamGapMm = 0;       ///< largest distance between seam partners (mm)
  double gaussMax = 0;        ///< largest |angle defect| at interior vertices (radians)
  double gaussMean = 0;       ///< mean |angle defect| at interior vertices (radians)
  int flipped2d = 0;          ///< flat triangles with non-positive signed area
  int flipped3d = 0;          ///< 3D triangles whose normal opposes its neighbours' (see .cpp)
  int degenerate2d = 0;       ///< flat triangles with an angle below 1e-3 rad or zero area
  int degenerate3d = 0;       ///< 3D triangles with an angle below 1e-3 rad or zero area
  double seamLengthAMm = 0;   ///< flat seam length (perimeter) of piece A
  double seamLengthBMm = 0;   ///< flat seam length of piece B
  double seamLength3dMm = 0;  ///< length of the 3D seam (piece A's side)
  /// The 3D seam against the seam of the exact D-Form of the same flat pieces (the reference the
  /// caller gives) after rigid alignment: root mean square and largest distance over the seam's
  /// bounding-box diagonal. NaN when there is no exact D-Form to compare with; exactNote then
  /// says why.
  double exactDistanceRmsRel = std::numeric_limits<double>::quiet_NaN();
  /// The largest distance of the comparison above, over the same diagonal (fraction; NaN too).
  double exactDistanceMaxRel = std::numeric_limits<double>::quiet_NaN();
  std::string exactNote;  ///< what the seam was compared with, or why it was not
};

/// A 3D seam that a result's figures compare it with (row k for seam point k), made by the
/// caller (pipeline/reference_seams.h): none (no rows) where there is none, and `note` says why;
/// else `note` says what made it.
struct ReferenceSeam {
  /// Why a reference is missing, for a caller that chooses another way to make one.
  enum class Missing {
    None,          ///< `points` holds the reference
    HoleZipped,    ///< a piece is zipped along a hole (anti or demi D-Form): no sphere is glued
    SeamTooLong,   ///< more seam points than the exact engine glues for a figure
    NotConvex,     ///< the glued metric is not convex: no convex D-Form exists
    EngineFailed,  ///< the exact engine or the optimisation failed on it
  };
  Points3 points;                   ///< the reference seam, #n by 3, mm; no rows when there is none
  std::string note;                 ///< what made the reference, or why there is none
  Missing missing = Missing::None;  ///< why there is none, None when `points` holds it
};

/// Figures of `model`, its seam compared with `exactBody` (the exact D-Form of the same flat
/// pieces). Pure: reads the meshes, never a solver.
Metrics computeMetrics(const DForm& model, const ReferenceSeam& exactBody);

/// One undirected mesh edge of a piece (vertices `from` < `to`) and its strain (L3 - L2) / L2: its
/// 3D length L3 against its flat length L2, signed (positive where the 3D edge is longer; infinite
/// for a zero flat edge whose 3D edge is not). L_max is the largest |strain| over both pieces.
struct EdgeStrain {
  int from = 0;       ///< the edge's lower vertex index in the piece
  int to = 0;         ///< its higher vertex index
  double strain = 0;  ///< (L3 - L2) / L2, signed
};

/// Every edge of a piece's faces once, with its strain.
std::vector<EdgeStrain> edgeStrains(const Piece& piece);

/// The discrete Gaussian curvature of a piece's 3D shape: per vertex, its angle defect
/// (radians) at interior vertices and 0 on the seam, the boundary and the creases, where the sheet
/// may turn.
Eigen::VectorXd curvatureMap(const Piece& piece);

/// How a crease folds, seen from the side of the flat pattern that faces up on the sheet (faces
/// counter-clockwise), which becomes the outside of the D-Form (faces outward-facing in 3D).
enum class FoldDirection {
  Mountain,  ///< the crease is a ridge towards the viewer: a convex edge seen from outside
  Valley,    ///< a groove away from the viewer: a concave edge seen from outside
};

/// "mountain" or "valley".
const char* foldDirectionName(FoldDirection direction);

/// One crease's fold. The signed fold angle of a crease edge is the angle between the 3D normals
/// of its two triangles, positive for a mountain and negative for a valley.
struct CreaseFold {
  FoldDirection direction = FoldDirection::Mountain;  ///< the sign of the mean signed angle
  double angleDeg = 0;     ///< |length-weighted mean of the signed fold angle| (degrees; 0 = flat)
  double minAngleDeg = 0;  ///< smallest signed fold angle of its edges (degrees)
  double maxAngleDeg = 0;  ///< largest signed fold angle of its edges (degrees)
  double lengthMm = 0;     ///< flat length of the crease (mm)
};

/// The fold of each of piece.creases, in order, from the 3D shape. Edges of a crease that are not
/// interior mesh edges (which readModel and the mesher never produce) count for nothing.
std::vector<CreaseFold> creaseFolds(const Piece& piece);

/// Inverse mode: D_error (paper Eq. 7, fraction) and the largest seam-to-curve distance (mm),
/// where curve.points.row(i) is the target of a.seam[i] and b.seam[i].
struct CurveMatch {
  double curveError = 0;          ///< D_error: mean seam-to-curve distance / curve length
  double curveDistanceMaxMm = 0;  ///< the largest seam-to-curve distance, mm
  /// The round trip: the flat pieces zipped again (their exact D-Form, or the optimisation where
  /// their metric is not convex; the reference the caller gives) against the target curve after
  /// rigid alignment, over the curve's bounding-box diagonal; roundtripNote says which zipped
  /// them. NaN when neither could (the note says why).
  double roundtripRmsRel = std::numeric_limits<double>::quiet_NaN();
  /// The round trip's largest distance over the same diagonal (fraction; NaN too).
  double roundtripMaxRel = std::numeric_limits<double>::quiet_NaN();
  std::string roundtripNote;  ///< what zipped the pieces again, or why nothing could
};
CurveMatch computeCurveMatch(const DForm& model, const Curve3& target,
                             const ReferenceSeam& zippedAgain);

}  // namespace dform
