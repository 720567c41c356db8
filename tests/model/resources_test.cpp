// The memory check that stops a run too large for the machine before it meshes anything.
#include "model/resources.h"

#include <gtest/gtest.h>

#include <regex>

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
  const Status refused = checkMemory({vertices, 0.0}, resolution, "piece.svg: the run");
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.code(), ErrorCode::Usage);
  EXPECT_EQ(refused.message().rfind("piece.svg: the run at resolution 1000 would need about ", 0),
            0u)
      << refused.message();
  std::smatch suggestion;
  const std::string message = refused.message();
  ASSERT_TRUE(
      std::regex_search(message, suggestion, std::regex("a resolution of ([0-9]+) or less fits")));
  const int fits = std::stoi(suggestion[1]);
  EXPECT_LT(fits, resolution / 2);  // a quarter of the vertices at most: half the resolution
  const double s = double(fits) / resolution;
  EXPECT_TRUE(checkMemory({vertices * s * s, 0.0}, fits, "piece.svg: the run").isOk());
  EXPECT_TRUE(checkMemory({1000.0, 0.0}, 100, "piece.svg: the run").isOk());
}

// A run that ran out of memory past the check needed more than its estimate: the resolution
// offered is the highest (in 5 % steps) whose estimate is half this run's.
TEST(Resources, ARunOutOfMemoryOffersTheResolutionOfHalfItsEstimate) {
  const MemoryEstimate run{50000.0, 1e8};  // about 0.6 GB: within any machine that runs the suite
  const Status failed = outOfMemory(run, 400, "curve.obj: the run");
  EXPECT_EQ(failed.code(), ErrorCode::Usage);
  EXPECT_EQ(failed.message().rfind("curve.obj: the run at resolution 400 ran out of memory", 0), 0u)
      << failed.message();
  std::smatch offered;
  const std::string message = failed.message();
  ASSERT_TRUE(
      std::regex_search(message, offered, std::regex("a resolution of ([0-9]+) or less fits")));
  const int fits = std::stoi(offered[1]);
  const auto peakAt = [&run](int resolution) {
    const double s = resolution / 400.0;
    return double(estimatedPeakBytes(run.vertices * s * s, run.extraBytes * s * s));
  };
  const double half = 0.5 * double(estimatedPeakBytes(run.vertices, run.extraBytes));
  EXPECT_LE(peakAt(fits), half);
  EXPECT_GT(peakAt(int(fits / 0.95) + 1), half);
  // Before any estimate (reading, or past the solve): half the vertices.
  EXPECT_NE(outOfMemory({}, 100, "out: the run").message().find("a resolution of 70 or less fits"),
            std::string::npos);
}

}  // namespace
}  // namespace dform
