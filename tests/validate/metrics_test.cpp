#include "validate/metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/polyline.h"
#include "models.h"

namespace dform {
namespace {

double seam3dLength(const DForm& model) {
  Points3 P(Eigen::Index(model.a.seam.size()), 3);
  for (size_t i = 0; i < model.a.seam.size(); ++i) P.row(Eigen::Index(i)) = model.a.shape.row(model.a.seam[i]);
  return closedLength(P);
}

TEST(Metrics, CylinderRolledExactlyFromARectangleHasNoError) {
  const DForm model = test::rolledCylinder(24, 6, 30.0, 50.0);
  const Metrics m = computeMetrics(model);
  EXPECT_LT(m.L_error, 1e-12);
  EXPECT_LT(m.L_max, 1e-12);
  EXPECT_LT(m.gauss_max, 1e-12);  // interior vertices lie on straight folds
  EXPECT_EQ(m.flipped_2d, 0);
  EXPECT_EQ(m.flipped_3d, 0);
  EXPECT_EQ(m.degenerate_2d, 0);
  EXPECT_EQ(m.degenerate_3d, 0);
  EXPECT_EQ(m.B_error, 0.0);
  EXPECT_EQ(m.seam_gap_mm, 0.0);
  // The flat seam is the rectangle's perimeter; the 3D seam has the same edges.
  const double chord = 2 * 30.0 * std::sin(1.5 * M_PI / 24 / 2);
  EXPECT_NEAR(m.seam_length_a_mm, 2 * (24 * chord + 50.0), 1e-9);
  EXPECT_NEAR(m.seam_length_b_mm, m.seam_length_a_mm, 1e-9);
  EXPECT_NEAR(m.seam_length_3d_mm, m.seam_length_a_mm, 1e-9);
}

TEST(Metrics, FlatDoubleDiscIsExactAndFlat) {
  const DForm model = test::flatDoubleDisc(5, 24, 50.0);
  const Metrics m = computeMetrics(model);
  EXPECT_EQ(m.L_error, 0.0);
  EXPECT_EQ(m.L_max, 0.0);
  EXPECT_LT(m.gauss_max, 1e-12);
  EXPECT_LT(m.gauss_mean, 1e-12);
  EXPECT_EQ(m.B_error, 0.0);
  EXPECT_EQ(m.flipped_2d, 0);
  EXPECT_EQ(m.flipped_3d, 0);  // flat: every dihedral is 0
  EXPECT_EQ(m.degenerate_2d + m.degenerate_3d, 0);
  const double perimeter = 24 * 2 * 50.0 * std::sin(M_PI / 24);
  EXPECT_NEAR(m.seam_length_a_mm, perimeter, 1e-9);
  EXPECT_NEAR(m.seam_length_b_mm, perimeter, 1e-9);
  EXPECT_NEAR(m.seam_length_3d_mm, perimeter, 1e-9);
}

TEST(Metrics, TetraDFormIsExactlyDevelopable) {
  const DForm model = test::tetraDForm(6);
  const Metrics m = computeMetrics(model);
  EXPECT_LT(m.L_error, 1e-12);
  EXPECT_LT(m.L_max, 1e-12);
  EXPECT_LT(m.gauss_max, 1e-12);
  EXPECT_LT(m.B_error, 1e-15);
  EXPECT_EQ(m.flipped_2d + m.flipped_3d + m.degenerate_2d + m.degenerate_3d, 0);
  EXPECT_NEAR(m.seam_length_a_mm, m.seam_length_3d_mm, 1e-9);
  EXPECT_NEAR(m.seam_length_b_mm, m.seam_length_3d_mm, 1e-9);
}

TEST(Metrics, UniformStretchGivesItsFactor) {
  DForm model = test::tetraDForm(6);
  model.a.shape *= 1.01;
  model.b.shape *= 1.01;
  const Metrics m = computeMetrics(model);
  EXPECT_NEAR(m.L_error, 0.01, 1e-12);
  EXPECT_NEAR(m.L_max, 0.01, 1e-12);
  EXPECT_LT(m.gauss_max, 1e-12);  // scaling keeps every angle
}

TEST(Metrics, PyramidApexDefectIsTwoPiMinusItsFaceAngles) {
  const int n = 7;
  const double r = 20.0, H = 9.0;
  DForm model;
  Piece& a = model.a;
  a.name = "A";
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
  model.b = test::mirroredCopy(a, "B");
  // Each face angle at the apex from the dot product of two slant edges.
  const double faceAngle = std::acos((r * r * std::cos(2 * M_PI / n) + H * H) / (r * r + H * H));
  const double defect = 2 * M_PI - n * faceAngle;
  const Metrics m = computeMetrics(model);
  EXPECT_NEAR(m.gauss_max, defect, 1e-12);
  EXPECT_NEAR(m.gauss_mean, defect, 1e-12);  // the apex is each piece's only interior vertex
}

TEST(Metrics, OpenSeamGivesGapAndBError) {
  DForm model = test::tetraDForm(6);
  model.b.shape.col(2).array() += 1.0;
  const Metrics m = computeMetrics(model);
  EXPECT_NEAR(m.seam_gap_mm, 1.0, 1e-12);
  EXPECT_NEAR(m.B_error, 1.0 / seam3dLength(model), 1e-15);
  EXPECT_NEAR(m.seam_length_3d_mm, seam3dLength(model), 1e-12);
}

TEST(Metrics, CurveMatchForAKnownShift) {
  DForm model = test::tetraDForm(6);
  const double delta = 0.25;
  Curve3 target;
  target.points.resize(Eigen::Index(model.a.seam.size()), 3);
  for (size_t i = 0; i < model.a.seam.size(); ++i)
    target.points.row(Eigen::Index(i)) = model.a.shape.row(model.a.seam[i]) + Eigen::RowVector3d(0, 0, delta);
  model.b.shape.col(2).array() += 2 * delta;  // B above the curve by delta, A below by delta
  const CurveMatch match = computeCurveMatch(model, target);
  EXPECT_NEAR(match.D_error, delta / closedLength(target.points), 1e-15);
  EXPECT_NEAR(match.curve_distance_max_mm, delta, 1e-12);

  model.b.shape.col(2).array() += 2 * delta;  // now 3 delta from the curve: mean 2 delta
  const CurveMatch worse = computeCurveMatch(model, target);
  EXPECT_NEAR(worse.D_error, 2 * delta / closedLength(target.points), 1e-15);
  EXPECT_NEAR(worse.curve_distance_max_mm, 3 * delta, 1e-12);
}

TEST(Metrics, ReversedFlatTriangleIsFlipped) {
  DForm model = test::tetraDForm(6);
  model.a.F.row(10) = Eigen::RowVector3i(model.a.F(10, 0), model.a.F(10, 2), model.a.F(10, 1));
  const Metrics m = computeMetrics(model);
  EXPECT_EQ(m.flipped_2d, 1);
  EXPECT_EQ(m.flipped_3d, 0);  // its flat neighbourhood is folded, so the 3D rule does not apply
}

TEST(Metrics, HingeFoldedBeyondNinetyDegreesIsFoldedOver) {
  const int k = 5;
  // h = 0.7 folds each hinge by acos((1 - 4h^2)/(1 + 4h^2)) = 117 degrees.
  const Metrics m = computeMetrics(test::tetraDForm(k, 40.0, 0.7));
  EXPECT_EQ(m.flipped_2d, 0);
  EXPECT_EQ(m.flipped_3d, 2 * 2 * k);  // per piece, the k triangles on each side of the hinge
  EXPECT_LT(m.L_error, 1e-12);
}

TEST(Metrics, CollapsedEdgeGivesDegenerateTriangles) {
  DForm model = test::tetraDForm(6);
  auto onSeam = [&](int i) { return std::find(model.a.seam.begin(), model.a.seam.end(), i) != model.a.seam.end(); };
  int f = 0;
  while (onSeam(model.a.F(f, 0)) || onSeam(model.a.F(f, 1))) ++f;  // an interior edge
  const int v = model.a.F(f, 0), w = model.a.F(f, 1);
  model.a.flat.row(v) = model.a.flat.row(w);
  model.a.shape.row(v) = model.a.shape.row(w);
  const Metrics m = computeMetrics(model);
  EXPECT_EQ(m.degenerate_2d, 2);  // the two triangles on edge v-w
  EXPECT_EQ(m.degenerate_3d, 2);
}

}  // namespace
}  // namespace dform
