// SPDX-License-Identifier: GPL-3.0-or-later
// The exact D-Form of two flat pieces: the unique convex body whose surface is the two pieces
// glued along their seam (Alexandrov; for convex pieces, Demaine and Price: the convex hull of the
// seam). Only the seam points are cone points of the glued metric; interior points are flat and
// are placed on the body afterwards by tracing geodesics from the seam.
#pragma once

#include <string>
#include <vector>

#include "dform/core/constants.h"
#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/exact/alexandrov.h"
#include "dform/exact/intrinsic_triangulation.h"

namespace dform::exact {

/// The two sides of a seam: row k of `a` (counter-clockwise round piece A) is glued to row k of
/// `b` (clockwise round piece B, in B's own plane), and the chord from k to k + 1 of one to that
/// of the other. Both in mm.
struct SeamPolygons {
  Points2 a;  ///< piece A's side, counter-clockwise
  Points2 b;  ///< piece B's side, clockwise, in B's own plane
};

/// Moves both polygons as little as possible (least-norm Gauss-Newton) so that chord k of each
/// has the mean of the two lengths, to rounding: the metric glues exactly only when the two sides
/// of every chord are equally long. Each polygon stays convex where it is: a point on a straight
/// line through its neighbours (to within kFlatCurvature) stays on one, and a point that turns
/// forwards does not come to turn backwards (it is kept straight instead), so that a metric
/// convex as drawn stays convex. A stretch of seam points where both pieces are straight to
/// within kSamplingExcess and whose angle sums exceed 2 pi while the points around it turn
/// forwards by more is made straight on both sides (a sampling artefact, exact_gluing.cpp).
/// Returns the largest move, mm.
double equalizeChords(SeamPolygons& seam);

/// How far from straight (each piece's turn, radians: 0.5 degrees) a seam point may be for
/// equalizeChords to take its angle sum over 2 pi for a sampling artefact.
constexpr double kSamplingExcess = 0.5 * kDegree;

/// The glued metric's angles at the seam points.
struct SeamAngles {
  Eigen::VectorXd a;  ///< piece A's interior angle at each seam point, radians
  Eigen::VectorXd b;  ///< piece B's interior angle at each seam point, radians
  /// 2 pi - (a + b): the cone point's curvature; negative where the metric is not convex.
  Eigen::VectorXd curvature;
  int firstNonConvex = -1;  ///< the first seam point whose angle sum exceeds 2 pi + tolerance
};

/// A cone point whose curvature is within this of 0 is flat. Angles of a polygon computed from
/// coordinates carry rounding of ~1e-15 rad per point; points sampled along two straight sides
/// are flat to that, and a smooth curve sampled at n points turns by ~2 pi / n >> 1e-9.
constexpr double kFlatCurvature = 1e-9;

SeamAngles seamAngles(const SeamPolygons& seam);

/// mm: the precision the outlines are known to, as the readers state it (io's flattenTolerance:
/// curves are flattened to within 1e-4 mm).
constexpr double kOutlinePrecision = 1e-4;

/// mm: the precision a seam is glued to: kOutlinePrecision, or a millionth of the pieces' size
/// (the larger bounding-box diagonal) where that is coarser. Pieces congruent to within it are
/// congruent, and no feature of the body smaller than it is drawn.
double seamPrecision(const SeamPolygons& seam);

/// Seams longer than this are not glued exactly (neither as a run's model nor for a figure): the
/// engine's time grows about as n^1.5 (1000 seam points take ~0.3 s), and such seams come from the
/// relaxation-only runs.
constexpr int kMaxExactSeam = 1000;

/// The glued surface embedded in 3D.
struct ExactGluing {
  SeamPolygons seam;  ///< the polygons glued (after equalizeChords)
  SeamAngles angles;  ///< the glued metric's angles and curvatures at the seam points
  /// The pieces are congruent and zipped point to point: the body is piece A doubly covered, and
  /// flatRotation * b + flatShift maps piece B's plane onto A's.
  bool doublyCovered = false;
  /// Why the body is the doubly covered piece: the pieces are congruent to within seamPrecision,
  /// or the body glued came out thinner than sqrt(precision x size / 2) (pressed flat, no length
  /// of it changes by more than the precision).
  enum class Pouch { None, Congruent, Thin };
  Pouch pouch = Pouch::None;  ///< None where the body is not doubly covered
  /// mm: the largest distance between a point of A and its partner of B laid onto A by the best
  /// flatRotation and flatShift (infinite where no reflection fits).
  double flatDeviation = 0;
  double thickness = 0;  ///< mm: the glued body's thickness, where it came out thin
  /// The rotation (or reflection) of the best fit of piece B's plane onto A's.
  Eigen::Matrix2d flatRotation = Eigen::Matrix2d::Identity();
  Eigen::Vector2d flatShift = Eigen::Vector2d::Zero();  ///< that fit's translation, mm
  IntrinsicTriangulation triangulation;                 ///< of the cone points: the body's faces
  std::vector<int> vertexOfSeam;  ///< seam point -> triangulation vertex, -1 if flat
  std::vector<int> seamOfVertex;  ///< triangulation vertex -> seam point
  Eigen::MatrixX3d vertices;      ///< 3D position of each triangulation vertex, mm
  AlexandrovResult embedding;     ///< how the 3D embedding converged (radii, curvature, edge error)
};

/// How glueExact embeds the glued metric.
struct ExactOptions {
  AlexandrovOptions embedding;  ///< the embedding's tolerances and step budget
};

/// Glues the two polygons (equal chords, as left by equalizeChords) and embeds the result.
/// InputInvalid when the metric is not convex (the message names the seam point and its angle
/// sum); SolveFailed when the embedding does not converge.
Result<ExactGluing> glue(const SeamPolygons& seam, const ExactOptions& options = {});

/// The 3D position on the glued body of each row of P, points of piece 0 (A) or 1 (B) given in
/// that piece's plane, inside or on its polygon. Rows that cannot be placed come back NaN.
Points3 placeOnBody(const ExactGluing& gluing, int piece, const Points2& P);

}  // namespace dform::exact
