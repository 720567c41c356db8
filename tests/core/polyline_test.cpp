#include "core/polyline.h"

#include <gtest/gtest.h>

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
