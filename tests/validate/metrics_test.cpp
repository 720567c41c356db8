// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/validate/metrics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <utility>
#include <vector>

#include "dform/core/interrupt.h"
#include "dform/core/polyline.h"
#include "dform/core/shape_projection.h"
#include "dform/validate/gate.h"
#include "models.h"
#include "validate/cgal_checks.h"
#include "validate/mesh_measures.h"

namespace dform {
namespace {

double seam3dLength(const DForm& model) {
  Points3 P(Eigen::Index(model.a.seam.size()), 3);
  for (size_t i = 0; i < model.a.seam.size(); ++i)
    P.row(Eigen::Index(i)) = model.a.shape.row(model.a.seam[i]);
  return closedLength(P);
}

TEST(Metrics, CylinderRolledExactlyFromARectangleHasNoError) {
  const DForm model = test::rolledCylinder(24, 6, 30.0, 50.0);
  const Metrics m = computeMetrics(model, {});
  EXPECT_LT(m.lengthError, 1e-12);
  EXPECT_LT(m.lengthErrorMax, 1e-12);
  EXPECT_LT(m.gaussMax, 1e-12);  // interior vertices lie on straight folds
  EXPECT_EQ(m.flipped2d, 0);
  EXPECT_EQ(m.flipped3d, 0);
  EXPECT_EQ(m.degenerate2d, 0);
  EXPECT_EQ(m.degenerate3d, 0);
  EXPECT_EQ(m.seamError, 0.0);
  EXPECT_EQ(m.seamGapMm, 0.0);
  // The flat seam is the rectangle's perimeter; the 3D seam has the same edges.
  const double chord = 2 * 30.0 * std::sin(1.5 * M_PI / 24 / 2);
  EXPECT_NEAR(m.seamLengthAMm, 2 * (24 * chord + 50.0), 1e-9);
  EXPECT_NEAR(m.seamLengthBMm, m.seamLengthAMm, 1e-9);
  EXPECT_NEAR(m.seamLength3dMm, m.seamLengthAMm, 1e-9);
}

TEST(Metrics, FlatDoubleDiscIsExactAndFlat) {
  const DForm model = test::flatDoubleDisc(5, 24, 50.0);
  const Metrics m = computeMetrics(model, {});
  EXPECT_EQ(m.lengthError, 0.0);
  EXPECT_EQ(m.lengthErrorMax, 0.0);
  EXPECT_LT(m.gaussMax, 1e-12);
  EXPECT_LT(m.gaussMean, 1e-12);
  EXPECT_EQ(m.seamError, 0.0);
  EXPECT_EQ(m.flipped2d, 0);
  EXPECT_EQ(m.flipped3d, 0);  // flat: every dihedral is 0
  EXPECT_EQ(m.degenerate2d + m.degenerate3d, 0);
  const double perimeter = 24 * 2 * 50.0 * std::sin(M_PI / 24);
  EXPECT_NEAR(m.seamLengthAMm, perimeter, 1e-9);
  EXPECT_NEAR(m.seamLengthBMm, perimeter, 1e-9);
  EXPECT_NEAR(m.seamLength3dMm, perimeter, 1e-9);
}

TEST(Metrics, TetraDFormIsExactlyDevelopable) {
  const DForm model = test::tetraDForm(6);
  const Metrics m = computeMetrics(model, {});
  EXPECT_LT(m.lengthError, 1e-12);
  EXPECT_LT(m.lengthErrorMax, 1e-12);
  EXPECT_LT(m.gaussMax, 1e-12);
  EXPECT_LT(m.seamError, 1e-15);
  EXPECT_EQ(m.flipped2d + m.flipped3d + m.degenerate2d + m.degenerate3d, 0);
  EXPECT_NEAR(m.seamLengthAMm, m.seamLength3dMm, 1e-9);
  EXPECT_NEAR(m.seamLengthBMm, m.seamLength3dMm, 1e-9);
}

TEST(Metrics, UniformStretchGivesItsFactor) {
  DForm model = test::tetraDForm(6);
  model.a.shape *= 1.01;
  model.b.shape *= 1.01;
  const Metrics m = computeMetrics(model, {});
  EXPECT_NEAR(m.lengthError, 0.01, 1e-12);
  EXPECT_NEAR(m.lengthErrorMax, 0.01, 1e-12);
  EXPECT_LT(m.gaussMax, 1e-12);  // scaling keeps every angle
}

// L_max is the largest single edge's error, not an average: on a stretch that differs from edge
// to edge it equals the worst edge's |L^ - L| / L (found here edge by edge) and exceeds L_error.
TEST(Metrics, LMaxIsTheWorstEdgeOfANonUniformStretch) {
  DForm model = test::tetraDForm(6);
  for (Piece* piece : {&model.a, &model.b}) {
    piece->shape.col(0) *= 1.004;  // each edge stretches by its own amount with its direction
    piece->shape.col(1) *= 1.0005;
  }
  double worst = 0;
  for (const Piece* piece : {&model.a, &model.b})
    for (Eigen::Index f = 0; f < piece->F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int u = piece->F(f, k), v = piece->F(f, (k + 1) % 3);
        const double flat = (piece->flat.row(u) - piece->flat.row(v)).norm();
        const double shape = (piece->shape.row(u) - piece->shape.row(v)).norm();
        worst = std::max(worst, std::abs(shape - flat) / flat);
      }
  const Metrics m = computeMetrics(model, {});
  EXPECT_NEAR(m.lengthErrorMax, worst, 1e-12);
  EXPECT_GT(m.lengthErrorMax, m.lengthError * (1 + 1e-3))
      << "a non-uniform stretch: the worst edge is above the norm";
}

// L_error is the relative root-sum-square over every edge of both pieces, each edge once:
// sqrt(sum (L^ - L)^2 / sum L^2), found here edge by edge. A mean of the relative errors, a
// root mean square of them, an edge counted once per triangle or a missing square root fails.
TEST(Metrics, LErrorIsTheRelativeRootSumSquareOverEveryEdgeOnce) {
  DForm model = test::tetraDForm(6);
  for (Piece* piece : {&model.a, &model.b}) {
    piece->shape.col(0) *= 1.004;
    piece->shape.col(1) *= 1.0005;
  }
  double sumSqDiff = 0, sumSqFlat = 0, sumRel = 0;
  int edges = 0;
  for (const Piece* piece : {&model.a, &model.b}) {
    std::set<std::pair<int, int>> seen;
    for (Eigen::Index f = 0; f < piece->F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int u = piece->F(f, k), v = piece->F(f, (k + 1) % 3);
        if (!seen.insert({std::min(u, v), std::max(u, v)}).second) continue;
        const double flat = (piece->flat.row(u) - piece->flat.row(v)).norm();
        const double shape = (piece->shape.row(u) - piece->shape.row(v)).norm();
        sumSqDiff += (shape - flat) * (shape - flat);
        sumSqFlat += flat * flat;
        sumRel += std::abs(shape - flat) / flat;
        ++edges;
      }
  }
  const Metrics m = computeMetrics(model, {});
  EXPECT_NEAR(m.lengthError, std::sqrt(sumSqDiff / sumSqFlat), 1e-14);
  EXPECT_GT(std::abs(m.lengthError - sumRel / edges), 1e-6) << "not the mean relative error";
}

// A pyramid of n faces and height H: the angle defect at its apex, 2 pi less its face angles.
Piece pyramid(int n, double r, double H, const std::string& name) {
  Piece a;
  a.name = name;
  a.shape.resize(n + 1, 3);
  a.flat.resize(n + 1, 2);
  a.shape.row(0) << 0, 0, H;
  a.flat.row(0) << 0, 0;
  a.F.resize(n, 3);
  for (int j = 0; j < n; ++j) {
    const double t = 2 * M_PI * j / n;
    a.shape.row(1 + j) << r * std::cos(t), r * std::sin(t), 0;
    a.flat.row(1 + j) << r * std::cos(t), r * std::sin(t);
    a.F.row(j) << 0, 1 + j, 1 + (j + 1) % n;
    a.seam.push_back(1 + j);
  }
  return a;
}
double apexDefect(int n, double r, double H) {
  return 2 * M_PI - n * std::acos((r * r * std::cos(2 * M_PI / n) + H * H) / (r * r + H * H));
}

TEST(Metrics, PyramidApexDefectIsTwoPiMinusItsFaceAngles) {
  const int n = 7;
  const double r = 20.0, H = 9.0;
  DForm model;
  model.a = pyramid(n, r, H, "A");
  model.b = test::mirroredCopy(model.a, "B");
  const Metrics m = computeMetrics(model, {});
  EXPECT_NEAR(m.gaussMax, apexDefect(n, r, H), 1e-12);
  EXPECT_NEAR(m.gaussMean, apexDefect(n, r, H), 1e-12);  // each piece's only interior vertex
}

TEST(Metrics, OpenSeamGivesGapAndBError) {
  DForm model = test::tetraDForm(6);
  model.b.shape.col(2).array() += 1.0;
  const Metrics m = computeMetrics(model, {});
  EXPECT_NEAR(m.seamGapMm, 1.0, 1e-12);
  EXPECT_NEAR(m.seamError, 1.0 / seam3dLength(model), 1e-15);
  EXPECT_NEAR(m.seamLength3dMm, seam3dLength(model), 1e-12);
}

TEST(Metrics, CurveMatchForAKnownShift) {
  DForm model = test::tetraDForm(6);
  const double delta = 0.25;
  Curve3 target;
  target.points.resize(Eigen::Index(model.a.seam.size()), 3);
  for (size_t i = 0; i < model.a.seam.size(); ++i)
    target.points.row(Eigen::Index(i)) =
        model.a.shape.row(model.a.seam[i]) + Eigen::RowVector3d(0, 0, delta);
  model.b.shape.col(2).array() += 2 * delta;  // B above the curve by delta, A below by delta
  const CurveMatch match = computeCurveMatch(model, target, {});
  EXPECT_NEAR(match.curveError, delta / closedLength(target.points), 1e-15);
  EXPECT_NEAR(match.curveDistanceMaxMm, delta, 1e-12);

  model.b.shape.col(2).array() += 2 * delta;  // now 3 delta from the curve: mean 2 delta
  const CurveMatch worse = computeCurveMatch(model, target, {});
  EXPECT_NEAR(worse.curveError, 2 * delta / closedLength(target.points), 1e-15);
  EXPECT_NEAR(worse.curveDistanceMaxMm, 3 * delta, 1e-12);
}

// validate compares with the seams it is given and solves none: the figures follow the reference
// handed in, whatever it is.
TEST(Metrics, ExactDistanceIsToTheGivenReferenceSeam) {
  const DForm model = test::tetraDForm(6);
  Points3 seam(Eigen::Index(model.a.seam.size()), 3);
  for (std::size_t k = 0; k < model.a.seam.size(); ++k)
    seam.row(Eigen::Index(k)) = model.a.shape.row(model.a.seam[k]);
  // The same seam turned and moved: rigid alignment takes it back.
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Points3 moved = ((seam * turn.transpose()).rowwise() + Eigen::RowVector3d(5, -3, 2)).eval();
  const Metrics same = computeMetrics(model, {moved, "turned"});
  EXPECT_LE(same.exactDistanceMaxRel, 1e-12);
  EXPECT_TRUE(same.exactNote.empty());
  // One seam point of the reference 10 % of the diagonal away: a largest distance above the RMS.
  Points3 bent = seam;
  const double diagonal = (seam.colwise().maxCoeff() - seam.colwise().minCoeff()).norm();
  bent(0, 2) += 0.1 * diagonal;
  const Metrics off = computeMetrics(model, {bent, "bent"});
  EXPECT_GT(off.exactDistanceRmsRel, 1e-3);
  EXPECT_GT(off.exactDistanceMaxRel, off.exactDistanceRmsRel);
  // None given: NaN, and the note says why.
  const Metrics none = computeMetrics(model, {Points3(), "no body for this"});
  EXPECT_TRUE(std::isnan(none.exactDistanceRmsRel));
  EXPECT_TRUE(std::isnan(none.exactDistanceMaxRel));
  EXPECT_EQ(none.exactNote, "no body for this");
  // The round trip likewise: the curve itself as the zipped seam is 0 away, none is NaN.
  Curve3 target;
  target.points = seam;
  const CurveMatch back = computeCurveMatch(model, target, {moved, "zipped by a test"});
  EXPECT_LE(back.roundtripMaxRel, 1e-12);
  EXPECT_EQ(back.roundtripNote, "zipped by a test");
  EXPECT_TRUE(std::isnan(computeCurveMatch(model, target, {Points3(), "none"}).roundtripRmsRel));
}

// A unit ring of n points and a copy whose points move e cos(2 theta) out of its plane: the
// move is orthogonal to every rigid motion (translations and tilts are frequencies 0 and 1; the
// ring's symmetries pin the best fit to the identity), so aligned, point i lies e |cos(2 theta_i)|
// from the ring: the largest e, the root mean square e / sqrt 2, the mean 2 e / pi. Over the
// ring's bounding-box diagonal 2 sqrt 2.
struct RingAndWave {
  Points3 ring, wave;
  double e = 1e-2, diagonal = 2 * std::sqrt(2.0);
};
RingAndWave ringAndWave(Eigen::Index n) {
  RingAndWave out;
  out.ring.resize(n, 3);
  out.wave.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double theta = 2 * M_PI * double(i) / double(n);
    out.ring.row(i) << std::cos(theta), std::sin(theta), 0;
    out.wave.row(i) << std::cos(theta), std::sin(theta), out.e * std::cos(2 * theta);
  }
  return out;
}

// exact_distance_max_rel is the seam point farthest from the exact body's, exact_distance_rms_rel
// the root mean square over the seam points, both over the body seam's diagonal: a max reported
// as the RMS (or the mean), or the RMS as the max or the mean, fails here.
TEST(Metrics, ExactDistanceMaxAndRmsAreTheWorstAndTheRootMeanSquareSeamPoint) {
  DForm model = test::tetraDForm(6);
  const RingAndWave r = ringAndWave(Eigen::Index(model.a.seam.size()));
  for (std::size_t k = 0; k < model.a.seam.size(); ++k)
    model.a.shape.row(model.a.seam[k]) = r.wave.row(Eigen::Index(k));  // A's 3D seam is the wave
  const Metrics m = computeMetrics(model, {r.ring, "the ring"});
  EXPECT_NEAR(m.exactDistanceMaxRel, r.e / r.diagonal, 1e-9 * r.e);
  EXPECT_NEAR(m.exactDistanceRmsRel, r.e / std::sqrt(2.0) / r.diagonal, 1e-9 * r.e);
}

// The round trip likewise, the target curve against the pieces zipped again: roundtrip_max_rel
// the largest distance, roundtrip_rms_rel the root mean square, over the curve's diagonal.
TEST(Metrics, RoundTripMaxAndRmsAreTheWorstAndTheRootMeanSquareCurvePoint) {
  const DForm model = test::tetraDForm(6);
  const RingAndWave r = ringAndWave(Eigen::Index(model.a.seam.size()));
  Curve3 target;
  target.points = r.ring;
  const CurveMatch match = computeCurveMatch(model, target, {r.wave, "zipped by a test"});
  EXPECT_NEAR(match.roundtripMaxRel, r.e / r.diagonal, 1e-9 * r.e);
  EXPECT_NEAR(match.roundtripRmsRel, r.e / std::sqrt(2.0) / r.diagonal, 1e-9 * r.e);
}

// seam_gap_mm is the largest distance between seam partners, B_error their mean over the 3D
// seam's length: with one partner 3 mm off and the others 1 mm, the two differ by a clear margin.
TEST(Metrics, SeamGapIsTheWorstPartnerAndBErrorTheMeanOverTheSeamLength) {
  DForm model = test::tetraDForm(6);
  const std::size_t n = model.b.seam.size();
  for (std::size_t k = 0; k < n; ++k) model.b.shape(model.b.seam[k], 2) += k == 2 ? 3.0 : 1.0;
  const Metrics m = computeMetrics(model, {});
  EXPECT_NEAR(m.seamGapMm, 3.0, 1e-12);
  const double meanGap = (3.0 + double(n - 1)) / double(n);
  EXPECT_NEAR(m.seamError, meanGap / seam3dLength(model), 1e-15);
}

// gaussMax is the largest |angle defect|, gaussMean the mean: two apexes of different heights.
TEST(Metrics, GaussMaxIsTheSharperApexAndGaussMeanTheMeanOfBoth) {
  const int n = 7;
  const double r = 20.0;
  DForm model{pyramid(n, r, 9.0, "A"), test::mirroredCopy(pyramid(n, r, 4.0, "A"), "B")};
  const double sharp = apexDefect(n, r, 9.0), blunt = apexDefect(n, r, 4.0);
  ASSERT_GT(sharp, 1.5 * blunt);
  const Metrics m = computeMetrics(model, {});
  EXPECT_NEAR(m.gaussMax, sharp, 1e-12);
  EXPECT_NEAR(m.gaussMean, 0.5 * (sharp + blunt), 1e-12);
}

TEST(Metrics, ReversedFlatTriangleIsFlipped) {
  DForm model = test::tetraDForm(6);
  model.a.F.row(10) = Eigen::RowVector3i(model.a.F(10, 0), model.a.F(10, 2), model.a.F(10, 1));
  const Metrics m = computeMetrics(model, {});
  EXPECT_EQ(m.flipped2d, 1);
  EXPECT_EQ(m.flipped3d, 0);  // its flat neighbourhood is folded, so the 3D rule does not apply
}

TEST(Metrics, HingeFoldedBeyondNinetyDegreesIsFoldedOver) {
  const int k = 5;
  // h = 0.7 folds each hinge by acos((1 - 4h^2)/(1 + 4h^2)) = 117 degrees.
  const Metrics m = computeMetrics(test::tetraDForm(k, 40.0, 0.7), {});
  EXPECT_EQ(m.flipped2d, 0);
  EXPECT_EQ(m.flipped3d, 2 * 2 * k);  // per piece, the k triangles on each side of the hinge
  EXPECT_LT(m.lengthError, 1e-12);
}

TEST(Metrics, CollapsedEdgeGivesDegenerateTriangles) {
  DForm model = test::tetraDForm(6);
  auto onSeam = [&](int i) {
    return std::find(model.a.seam.begin(), model.a.seam.end(), i) != model.a.seam.end();
  };
  int f = 0;
  while (onSeam(model.a.F(f, 0)) || onSeam(model.a.F(f, 1))) ++f;  // an interior edge
  const int v = model.a.F(f, 0), w = model.a.F(f, 1);
  model.a.flat.row(v) = model.a.flat.row(w);
  model.a.shape.row(v) = model.a.shape.row(w);
  const Metrics m = computeMetrics(model, {});
  EXPECT_EQ(m.degenerate2d, 2);  // the two triangles on edge v-w
  EXPECT_EQ(m.degenerate3d, 2);
}

// The fold angle of a tetraDForm hinge: the angle between the normals of its two faces.
double hingeFoldDeg(double h) {
  return std::acos((1 - 4 * h * h) / (1 + 4 * h * h)) * 180.0 / M_PI;
}

TEST(Metrics, ExactFoldsGiveTheirAngleAndDirection) {
  // Two parallel creases folding a step (30 degrees up, then 50 back down) and a diagonal one.
  const Piece step = test::foldedSquare(12, 60.0, {{4, 0, 4, 12, 30.0}, {8, 0, 8, 12, -50.0}});
  const std::vector<CreaseFold> folds = creaseFolds(step);
  ASSERT_EQ(folds.size(), 2u);
  EXPECT_EQ(folds[0].direction, FoldDirection::Mountain);
  EXPECT_NEAR(folds[0].angleDeg, 30.0, 1e-9);
  EXPECT_EQ(folds[1].direction, FoldDirection::Valley);
  EXPECT_NEAR(folds[1].angleDeg, 50.0, 1e-9);
  EXPECT_NEAR(folds[1].minAngleDeg, -50.0, 1e-9);  // a rigid fold: every edge folds alike
  EXPECT_NEAR(folds[1].maxAngleDeg, -50.0, 1e-9);
  EXPECT_NEAR(folds[0].lengthMm, 60.0, 1e-9);
  EXPECT_STREQ(foldDirectionName(folds[0].direction), "mountain");
  EXPECT_STREQ(foldDirectionName(folds[1].direction), "valley");

  for (double angle : {120.0, -75.0}) {
    const Piece diagonal = test::foldedSquare(10, 50.0, {{0, 0, 10, 10, angle}});
    const CreaseFold fold = creaseFolds(diagonal).at(0);
    EXPECT_EQ(fold.direction, angle > 0 ? FoldDirection::Mountain : FoldDirection::Valley) << angle;
    EXPECT_NEAR(fold.angleDeg, std::abs(angle), 1e-9) << angle;
    EXPECT_NEAR(fold.lengthMm, 50.0 * std::sqrt(2.0), 1e-9);
  }
}

TEST(Metrics, CreaseAnglesFollowTheOutsideOfTheDForm) {
  // A convex disphenoid with outward faces: both hinges are mountains seen from outside. With
  // h < 0 the faces point in, so the same hinges are valleys seen from the faces' side.
  for (double h : {0.25, -0.25}) {
    const DForm model = test::creasedTetraDForm(6, 40.0, h);
    for (const Piece* p : {&model.a, &model.b}) {
      ASSERT_EQ(p->creases.at(0).size(), 7u);  // the hinge runs along k + 1 vertices
      const CreaseFold fold = creaseFolds(*p).at(0);
      EXPECT_EQ(fold.direction, h > 0 ? FoldDirection::Mountain : FoldDirection::Valley) << h;
      EXPECT_NEAR(fold.angleDeg, hingeFoldDeg(h), 1e-9) << h;
      EXPECT_NEAR(fold.lengthMm, 80.0, 1e-9);
    }
  }
}

TEST(Metrics, ASharpCreaseIsNoFoldOver) {
  // The hinges fold by 117 degrees: folded over without creases, a drawn fold with them.
  const Metrics creased = computeMetrics(test::creasedTetraDForm(5, 40.0, 0.7), {});
  EXPECT_EQ(creased.flipped3d, 0);
  EXPECT_LT(creased.lengthError, 1e-12);

  Piece square = test::foldedSquare(8, 40.0, {{4, 0, 4, 8, 150.0}});
  DForm model{square, test::mirroredCopy(square, "B")};
  EXPECT_EQ(computeMetrics(model, {}).flipped3d, 0);
  model.a.creases.clear();  // the same fold, not drawn: k triangles on each side of it per piece
  EXPECT_EQ(computeMetrics(model, {}).flipped3d, 2 * 8);
}

TEST(Metrics, ACreaseThroughAVertexTakesItsDefectOutOfTheFigures) {
  // A pyramid's apex has the only defect; a crease drawn through it leaves no interior vertex.
  const int n = 8;
  const Piece a = pyramid(n, 20.0, 9.0, "A");
  DForm model{a, test::mirroredCopy(a, "B")};
  EXPECT_GT(computeMetrics(model, {}).gaussMax, 0.1);
  EXPECT_GT(curvatureMap(model.a)(0), 0.1);
  for (Piece* p : {&model.a, &model.b}) p->creases = {{1, 0, 1 + n / 2}};
  const Metrics m = computeMetrics(model, {});
  EXPECT_EQ(m.gaussMax, 0.0);
  EXPECT_EQ(m.gaussMean, 0.0);
  EXPECT_EQ(curvatureMap(model.a)(0), 0.0);
}

// A crease whose edges fold by different angles: along the y axis, edges of 10 and 30 mm, each
// the hinge of its own pair of triangles, the left one flat in z = 0 and the right one turned up
// about the axis by its edge's angle (20 and 60 degrees). Seen from the faces' side (+z) the
// folds are grooves: valleys. Its angle is the length-weighted mean, (10 * 20 + 30 * 60) / 40 = 50
// degrees (40 unweighted), its smallest and largest edges' -60 and -20: a mean taken unweighted,
// or the largest edge's angle reported as the crease's, fails here.
TEST(Metrics, ACreaseFoldIsTheLengthWeightedMeanOfItsEdgesWithTheirExtremes) {
  const double d = 15.0, y[3] = {0.0, 10.0, 40.0}, turn[2] = {20.0, 60.0};
  Piece p;
  p.name = "A";
  p.flat.resize(7, 2);
  p.shape.resize(7, 3);
  p.F.resize(4, 3);
  for (int k = 0; k < 3; ++k) {  // the crease's vertices 0, 1, 2
    p.flat.row(k) << 0, y[k];
    p.shape.row(k) << 0, y[k], 0;
  }
  for (int k = 0; k < 2; ++k) {
    const double middle = 0.5 * (y[k] + y[k + 1]), angle = turn[k] * M_PI / 180.0;
    const int left = 3 + k, right = 5 + k;
    p.flat.row(left) << -d, middle;
    p.shape.row(left) << -d, middle, 0;
    p.flat.row(right) << d, middle;
    p.shape.row(right) << d * std::cos(angle), middle, d * std::sin(angle);
    p.F.row(2 * k) << k, k + 1, left;  // counter-clockwise in the flat layout
    p.F.row(2 * k + 1) << k + 1, k, right;
  }
  p.creases = {{0, 1, 2}};
  const std::vector<CreaseFold> folds = creaseFolds(p);
  ASSERT_EQ(folds.size(), 1u);
  EXPECT_EQ(folds[0].direction, FoldDirection::Valley);
  EXPECT_NEAR(folds[0].angleDeg, 50.0, 1e-9);
  EXPECT_NEAR(folds[0].minAngleDeg, -60.0, 1e-9);
  EXPECT_NEAR(folds[0].maxAngleDeg, -20.0, 1e-9);
  EXPECT_NEAR(folds[0].lengthMm, 40.0, 1e-12);
}

TEST(Metrics, AntiDFormIsMeasuredOverEveryEdgeAndAlongItsHoles) {
  const DForm model = test::annulusDForm();
  const Metrics m = computeMetrics(model, {});
  // Piece A's cone keeps radial lengths and shortens circles by (rho - r)(1 - cos 5 deg) / rho,
  // at most 30 * 0.0038 / 50 at the outer edge.
  EXPECT_GT(m.lengthErrorMax, 1e-4);
  EXPECT_LT(m.lengthErrorMax, 30.0 * (1 - std::cos(5 * M_PI / 180)) / 50.0 + 1e-9);
  EXPECT_LT(m.seamGapMm, 1e-12);  // both sides of the hole at z = 0 up to round-off
  EXPECT_NEAR(m.seamLengthAMm, 48 * 2 * 20.0 * std::sin(M_PI / 48), 1e-9);  // the hole's polygon
  EXPECT_NEAR(m.seamLengthBMm, m.seamLengthAMm, 1e-9);
  EXPECT_EQ(m.flipped2d + m.flipped3d, 0);
}

// The figures of a fine mesh take seconds (11.7 s at 385k vertices): each of their long loops
// polls the stop flag, so that Ctrl-C after the solve is seen at once. With a stop requested,
// each throws Interrupted naming its stage, and the gate and the figures as a whole do too.
TEST(Metrics, EachLongLoopOfTheFiguresSeesAStop) {
  const DForm model = test::tetraDForm(6);
  struct StopRequested {
    StopRequested() { interruptFlag() = true; }
    ~StopRequested() { interruptFlag() = false; }
  };
  const auto stage = [](const std::function<void()>& figure) -> std::string {
    const StopRequested stop;
    try {
      figure();
    } catch (const Interrupted& stopped) {
      return stopped.stage();
    }
    return "no stop seen";
  };
  EXPECT_EQ(stage([&] { detail::countFlatOverlaps(model.a.flat, model.a.F, nullptr); }),
            "the figures");
  EXPECT_EQ(stage([&] { detail::findSelfIntersections(model.a.shape, model.a.F); }), "the figures");
  EXPECT_EQ(stage([&] { detail::angleDefects(model.a.shape, model.a.F); }), "the figures");
  EXPECT_EQ(stage([&] { detail::edgeTopology(model.a.F); }), "the figures");
  EXPECT_EQ(stage([&] { computeMetrics(model, {}); }), "the figures");
  const Metrics figures = computeMetrics(model, {});
  EXPECT_EQ(stage([&] { runGate(model, GateLimits{}, figures, nullptr, nullptr); }), "the figures");
  EXPECT_EQ(stage([&] { clusterPoints(model.a.shape, 1.0); }), "the pictures");
  EXPECT_NO_THROW(runGate(model, GateLimits{}, figures, nullptr, nullptr)) << "the stop is over";
}

}  // namespace
}  // namespace dform
