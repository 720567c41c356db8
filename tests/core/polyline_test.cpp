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

}  // namespace
}  // namespace dform
