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

TEST(SeamLayout, CornersCloserThanHalfAnEdgeMergeAndTooManyFallBackToUniform) {
  const std::vector<double> t = seamFractions(10, {0.5, 0.51, 0.97});
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.5), 1);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.51), 0);  // within 0.05 of 0.5
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.97), 0);  // within 0.05 of the start (1.0)
  std::vector<double> many;
  for (int i = 1; i < 40; ++i) many.push_back(i / 40.0);
  const std::vector<double> u = seamFractions(100, many);
  for (int k = 0; k < 100; ++k) EXPECT_NEAR(u[k], k / 100.0, 1e-15);
}

}  // namespace
}  // namespace dform
