#include "forward/seam_layout.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace dform {
namespace {

TEST(SeamLayout, WithoutCornersTheSeamIsUniform) {
  const std::vector<double> t = seamFractions(100, {});
  ASSERT_EQ(t.size(), 100u);
  for (int k = 0; k < 100; ++k) EXPECT_NEAR(t[k], k / 100.0, 1e-15);
}

TEST(SeamLayout, EveryCornerIsAVertexAndStretchesAreUniform) {
  const std::vector<double> corners = {0.125, 0.375, 0.625, 0.875, 0.3};
  const std::vector<double> t = seamFractions(100, corners);
  ASSERT_EQ(t.size(), 100u);
  EXPECT_EQ(t[0], 0.0);
  EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
  for (double c : corners)
    EXPECT_NE(std::find_if(t.begin(), t.end(), [&](double v) { return std::abs(v - c) < 1e-15; }),
              t.end())
        << c;
  // Spacing is constant between consecutive corners and close to the uniform 1/n.
  for (int k = 0; k + 1 < 100; ++k) EXPECT_NEAR(t[k + 1] - t[k], 0.01, 0.0026);
}

TEST(SeamLayout, CornersCloseToEachOtherAreBothVerticesUnlessTheyAreOne) {
  // 0.01 apart, a tenth of a seam edge: two vertices, a short chord between them.
  const std::vector<double> t = seamFractions(10, {0.5, 0.51});
  ASSERT_EQ(t.size(), 10u);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.5), 1);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.51), 1);
  EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
  // Closer than kSameCorner of a seam edge: one vertex, the first corner's.
  const std::vector<double> u = seamFractions(10, {0.5, 0.5 + 0.5 * kSameCorner / 10});
  EXPECT_EQ(std::count(u.begin(), u.end(), 0.5), 1);
  EXPECT_EQ(std::count(u.begin(), u.end(), 0.5 + 0.5 * kSameCorner / 10), 0);
  // With more than n / 2 corners the seam is uniform.
  std::vector<double> many;
  for (int i = 1; i < 60; ++i) many.push_back(i / 60.0);
  const std::vector<double> w = seamFractions(100, many);
  for (int k = 0; k < 100; ++k) EXPECT_NEAR(w[k], k / 100.0, 1e-15);
}

TEST(SeamLayout, ACornerWithinHalfAnEdgeOfTheStartIsTheFirstVertex) {
  // Behind the start (0.97 = -0.03, within 0.05 of it): the seam runs from -0.03 to 0.97, every
  // corner a vertex, none cut off by the last chord.
  const std::vector<double> t = seamFractions(10, {0.97, 0.5});
  ASSERT_EQ(t.size(), 10u);
  EXPECT_DOUBLE_EQ(t[0], 0.97 - 1.0);
  EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
  EXPECT_LT(t.back(), 0.97);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.5), 1);
  // Ahead of it: the seam runs from the corner; the nearer of two corners is taken.
  const std::vector<double> u = seamFractions(10, {0.04, 0.02, 0.6});
  EXPECT_DOUBLE_EQ(u[0], 0.02);
  EXPECT_EQ(std::count(u.begin(), u.end(), 0.04), 1);
  EXPECT_LT(u.back(), 1.02);
  // Half an edge or more away: the start stays the first vertex.
  EXPECT_EQ(seamFractions(10, {0.05, 0.6})[0], 0.0);
}

}  // namespace
}  // namespace dform
