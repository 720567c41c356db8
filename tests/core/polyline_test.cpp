// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/polyline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace dform {
namespace {

Points2 circle(int n, double r) {
  Points2 P(n, 2);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    P.row(i) << r * std::cos(t), r * std::sin(t);
  }
  return P;
}

TEST(Polyline, LengthAndAreaOfSquare) {
  Points2 sq(4, 2);
  sq << 0, 0, 10, 0, 10, 10, 0, 10;
  EXPECT_DOUBLE_EQ(closedLength(sq), 40.0);
  EXPECT_DOUBLE_EQ(signedArea(sq), 100.0);
  EXPECT_DOUBLE_EQ(signedArea(sq.colwise().reverse()), -100.0);
}

TEST(Polyline, ResampleIsUniformAndKeepsLength) {
  Points2 sq(4, 2);
  sq << 0, 0, 10, 0, 10, 10, 0, 10;
  const Eigen::MatrixXd R = resampleClosed(sq, 40, 0.0);
  ASSERT_EQ(R.rows(), 40);
  for (int i = 0; i < 40; ++i) EXPECT_NEAR((R.row((i + 1) % 40) - R.row(i)).norm(), 1.0, 1e-12);
  EXPECT_NEAR(closedLength(R), 40.0, 1e-12);
  EXPECT_NEAR(R(0, 0), 0.0, 1e-12);
}

TEST(Polyline, ResampleStartsAtFraction) {
  Points2 sq(4, 2);
  sq << 0, 0, 10, 0, 10, 10, 0, 10;
  const Eigen::MatrixXd R = resampleClosed(sq, 8, 0.375);  // 15 mm along: (10, 5)
  EXPECT_NEAR(R(0, 0), 10.0, 1e-12);
  EXPECT_NEAR(R(0, 1), 5.0, 1e-12);
  EXPECT_NEAR(R(1, 0), 10.0, 1e-12);  // 20 mm along: the corner (10, 10)
  EXPECT_NEAR(R(1, 1), 10.0, 1e-12);
}

TEST(Polyline, ResampleOpenIsUniformAndKeepsBothEnds) {
  Points2 bend(3, 2);
  bend << 0, 0, 6, 0, 6, 4;  // an L of length 10
  EXPECT_DOUBLE_EQ(openLength(bend), 10.0);
  const Eigen::MatrixXd R = resampleOpen(bend, 5);
  ASSERT_EQ(R.rows(), 6);
  EXPECT_EQ(Eigen::RowVector2d(R.row(0)), Eigen::RowVector2d(0, 0));
  EXPECT_EQ(Eigen::RowVector2d(R.row(5)), Eigen::RowVector2d(6, 4));
  // Points at arc length 2, 4, 6 (the corner), 8 lie on the L.
  EXPECT_NEAR((R.row(1) - Eigen::RowVector2d(2, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((R.row(3) - Eigen::RowVector2d(6, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((R.row(4) - Eigen::RowVector2d(6, 2)).norm(), 0.0, 1e-12);
  const Eigen::MatrixXd one = resampleOpen(bend, 1);
  EXPECT_EQ(one.rows(), 2);
  EXPECT_NEAR(openLength(one), std::sqrt(52.0), 1e-12);
}

TEST(Polyline, ChordLossCompensationKeepsACurvesLengthAndItsCorners) {
  // An evenly sampled circle straddled by the compensated polygon has exactly its length to
  // O(h^4): 2 pi R (1 + (pi/n)^2 / 6) sin(pi/n) / (pi/n) - 2 pi R.
  for (int n : {24, 100}) {
    const Eigen::MatrixXd R = resampleClosed(circle(20000, 50.0), n);
    const double inscribed = closedLength(R), compensated = closedLength(compensateChordLoss(R));
    const double exact = 2 * M_PI * 50.0;
    EXPECT_GT(exact - inscribed, 1e-4 * exact * 100.0 / n / n * 10);  // the loss is real ...
    EXPECT_LT(std::abs(compensated - exact), 0.03 * (exact - inscribed)) << n;  // ... and gone
  }
  // A square's corners are corners: they stay, and its straight sides need nothing.
  Points2 sq(4, 2);
  sq << 0, 0, 10, 0, 10, 10, 0, 10;
  const Eigen::MatrixXd dense = resampleClosed(sq, 40);
  EXPECT_TRUE(compensateChordLoss(dense).isApprox(dense, 1e-15));
  // The same in 3D: a tilted circle keeps its length.
  Eigen::MatrixXd tilted(60, 3);
  for (int i = 0; i < 60; ++i) {
    const double t = 2 * M_PI * i / 60;
    tilted.row(i) << 30 * std::cos(t), 30 * std::sin(t) * 0.6, 30 * std::sin(t) * 0.8;
  }
  EXPECT_NEAR(closedLength(compensateChordLoss(tilted)), 2 * M_PI * 30, 2e-3);
}

TEST(Polyline, SampledCornersAreIsolatedTurnsNotTightBends) {
  Points2 sq(4, 2);
  sq << 0, 0, 10, 0, 10, 10, 0, 10;
  const std::vector<bool> corners = sampledCorners(resampleClosed(sq, 40));
  for (int i = 0; i < 40; ++i) EXPECT_EQ(corners[std::size_t(i)], i % 10 == 0) << i;
  // A 12-gon turns 30 degrees at every vertex: a coarse circle, not twelve corners.
  const std::vector<bool> coarse = sampledCorners(resampleClosed(circle(20000, 50.0), 12));
  EXPECT_EQ(std::count(coarse.begin(), coarse.end(), true), 0);
}

TEST(Polyline, ResampledCircleLengthConverges) {
  const Points2 dense = circle(20000, 50.0);
  const Eigen::MatrixXd R = resampleClosed(dense, 100);
  // A regular 100-gon inscribed in radius 50 has perimeter 100 * 2 * 50 * sin(pi / 100).
  EXPECT_NEAR(closedLength(R), 100 * 100 * std::sin(M_PI / 100), 1e-3);
}

TEST(Polyline, ResampleAtFractionsFollowsArcLengthInAnyOrder) {
  Points2 sq(4, 2);
  sq << 0, 0, 4, 0, 4, 4, 0, 4;  // perimeter 16
  const Eigen::MatrixXd Q = resampleAtFractions(sq, {0.5, 0.125, 1.25, -0.0625});
  EXPECT_NEAR((Q.row(0) - Eigen::RowVector2d(4, 4)).norm(), 0.0, 1e-12);  // arc 8
  EXPECT_NEAR((Q.row(1) - Eigen::RowVector2d(2, 0)).norm(), 0.0, 1e-12);  // arc 2
  EXPECT_NEAR((Q.row(2) - Eigen::RowVector2d(4, 0)).norm(), 0.0, 1e-12);  // 1.25 = arc 4
  EXPECT_NEAR((Q.row(3) - Eigen::RowVector2d(0, 1)).norm(), 0.0, 1e-12);  // arc 15
}

TEST(Polyline, CornersOfASquareButNotOfACircle) {
  // A square with extra points along its sides: only the four corners turn.
  Points2 sq(8, 2);
  sq << 0, 0, 2, 0, 4, 0, 4, 2, 4, 4, 2, 4, 0, 4, 0, 2;
  const std::vector<double> corners = cornerFractions(sq, 20.0 * M_PI / 180.0);
  ASSERT_EQ(corners.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(corners[k], 0.25 * k, 1e-12);
  EXPECT_TRUE(cornerFractions(circle(360, 10.0), 20.0 * M_PI / 180.0).empty());
  // A 12-gon turns by 30 degrees at every vertex: all are corners at a 20 degree threshold.
  EXPECT_EQ(cornerFractions(circle(12, 10.0), 20.0 * M_PI / 180.0).size(), 12u);
}

TEST(Polyline, NearestArcFraction) {
  Points2 sq(4, 2);
  sq << 0, 0, 10, 0, 10, 10, 0, 10;
  EXPECT_NEAR(nearestArcFraction(sq, {12.0, 5.0}), 0.375, 1e-12);
  EXPECT_NEAR(nearestArcFraction(sq, {-1.0, 5.0}), 0.875, 1e-12);
}

TEST(Polyline, SelfIntersectionFound) {
  Points2 bowtie(4, 2);
  bowtie << 0, 0, 10, 10, 10, 0, 0, 10;
  const auto hit = findSelfIntersection(bowtie);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->first, 0);
  EXPECT_EQ(hit->second, 2);
  EXPECT_FALSE(findSelfIntersection(circle(500, 10.0)).has_value());
}

TEST(Polyline, TouchingVertexCountsAsIntersection) {
  // A figure-eight that touches itself at (5, 5) without crossing.
  Points2 P(6, 2);
  P << 0, 0, 5, 5, 10, 0, 10, 10, 5, 5, 0, 10;
  EXPECT_TRUE(findSelfIntersection(P).has_value());
}

// The axis-parallel square [x0, x0 + side] x [y0, y0 + side], counter-clockwise.
Points2 square(double x0, double y0, double side) {
  Points2 P(4, 2);
  P << x0, y0, x0 + side, y0, x0 + side, y0 + side, x0, y0 + side;
  return P;
}

TEST(Polyline, CrossingOfTwoPolygonsNamesOneEdgeOfEach) {
  const Points2 outer = square(0, 0, 10);
  EXPECT_FALSE(findCrossing(outer, square(3, 3, 4)).has_value());   // nested
  EXPECT_FALSE(findCrossing(outer, square(20, 0, 4)).has_value());  // apart
  // Overlapping the right edge (edge 1 of the outer square): its edges 0 and 2 cross it.
  const auto crossing = findCrossing(outer, square(8, 3, 4));
  ASSERT_TRUE(crossing.has_value());
  EXPECT_EQ(crossing->first, 1);
  EXPECT_TRUE(crossing->second == 0 || crossing->second == 2) << crossing->second;
  EXPECT_TRUE(findCrossing(outer, square(10, 2, 3)).has_value());  // touching counts
}

TEST(Polyline, InsideClosedByTheEvenOddRule) {
  const Points2 P = square(0, 0, 10);
  EXPECT_TRUE(insidePolygon(P, {5, 5}));
  EXPECT_FALSE(insidePolygon(P, {15, 5}));
  EXPECT_FALSE(insidePolygon(P, {5, -1}));
  Points2 clockwise = P.colwise().reverse();
  EXPECT_TRUE(insidePolygon(clockwise, {1, 9}));
}

TEST(Polyline, InsideAListOfPointsAsInsideTheMatrixOfThem) {
  const Points2 P = square(0, 0, 10);
  std::vector<Eigen::Vector2d> points;
  for (Eigen::Index i = 0; i < P.rows(); ++i) points.push_back(P.row(i).transpose());
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(5, 5), Eigen::Vector2d(15, 5),
                                   Eigen::Vector2d(5, -1), Eigen::Vector2d(0.5, 9.5)})
    EXPECT_EQ(insidePolygon(points, q), insidePolygon(P, q)) << q.transpose();
  EXPECT_FALSE(insidePolygon(std::vector<Eigen::Vector2d>{}, {0, 0}));
}

TEST(Polyline, NearTouchIsJudgedTheSameWhicheverWayTheSegmentsRun) {
  // From the SVG fuzz target: a vertex within rounding of another edge. Walked one way the edges
  // touched, walked the other they did not, so an outline passed the reader's check and crossed
  // itself once made counter-clockwise.
  const Eigen::Vector2d a(969.46283726682464, -149.92536010247301);
  const Eigen::Vector2d b(971.03560331969709, -158.20987566250454);
  const Eigen::Vector2d c(6489.7289345088511, -1629.0762028633792);
  const Eigen::Vector2d d(356.09993757326623, 14.424733537627674);
  const bool touch = segmentsIntersect(a, b, c, d);
  EXPECT_EQ(segmentsIntersect(b, a, c, d), touch);
  EXPECT_EQ(segmentsIntersect(a, b, d, c), touch);
  EXPECT_EQ(segmentsIntersect(b, a, d, c), touch);
  EXPECT_EQ(segmentsIntersect(c, d, a, b), touch);
  EXPECT_EQ(segmentsIntersect(d, c, b, a), touch);
}

}  // namespace
}  // namespace dform
