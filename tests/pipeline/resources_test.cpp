// The memory check that stops a run too large for the machine before it meshes anything.
#include <gtest/gtest.h>

#include <regex>

#include "pipeline/resources.h"

namespace dform {
namespace {

TEST(Resources, TheMachineReportsItsMemory) {
  EXPECT_GT(availableMemoryBytes(), std::size_t(64) << 20);  // this machine runs the suite
}

TEST(Resources, TheEstimateGrowsWithTheMeshAndIsCheaperPerVertexWithoutLevenbergMarquardt) {
  EXPECT_LT(estimatedPeakBytes(1000), estimatedPeakBytes(2000));
  EXPECT_LT(estimatedPeakBytes(1000), estimatedPeakBytes(1000, 1e9));
  // Per vertex, above the direct-solve limit (10k vertices) the estimate is about a quarter.
  const double below = double(estimatedPeakBytes(10000) - estimatedPeakBytes(0)) / 10000;
  const double above = double(estimatedPeakBytes(100000) - estimatedPeakBytes(0)) / 100000;
  EXPECT_NEAR(above / below, 0.25, 0.01);
}

TEST(Resources, ATooLargeRunIsAUsageErrorWhoseSuggestedResolutionFits) {
  const double available = double(availableMemoryBytes());
  const int resolution = 1000;
  // Four times what the machine has, at resolution 1000.
  const double vertices = 4.0 * available / (9.0 * 1024);
  const Status refused = checkMemory(vertices, 0.0, resolution, "piece.svg: the run");
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.code(), ErrorCode::Usage);
  EXPECT_EQ(refused.message().rfind("piece.svg: the run at resolution 1000 would need about ", 0), 0u)
      << refused.message();
  std::smatch suggestion;
  const std::string message = refused.message();
  ASSERT_TRUE(std::regex_search(message, suggestion, std::regex("a resolution of ([0-9]+) or less fits")));
  const int fits = std::stoi(suggestion[1]);
  EXPECT_LT(fits, resolution / 2);  // a quarter of the vertices at most: half the resolution
  const double s = double(fits) / resolution;
  EXPECT_TRUE(checkMemory(vertices * s * s, 0.0, fits, "piece.svg: the run").isOk());
  EXPECT_TRUE(checkMemory(1000.0, 0.0, 100, "piece.svg: the run").isOk());
}

}  // namespace
}  // namespace dform
