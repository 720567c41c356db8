// SPDX-License-Identifier: GPL-3.0-or-later
// The memory check that stops a run too large for the machine before it meshes anything.
#include "dform/model/resources.h"

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

// The resolution offered in a refusal's message.
int offered(const Status& refusal) {
  std::smatch match;
  const std::string message = refusal.message();
  if (!std::regex_search(message, match, std::regex("a resolution of ([0-9]+) or less fits")))
    return -1;
  return std::stoi(match[1]);
}

// A run at resolution 1000 estimated at four times what the machine has, with a seam-like term
// that grows linearly (a count the square of the resolution would scale down too far): the
// resolution offered is the highest that the same check accepts, by the run's own formula.
TEST(Resources, ATooLargeRunIsAUsageErrorWhoseOfferedResolutionPassesTheCheck) {
  const double available = double(availableMemoryBytes());
  const int resolution = 1000;
  const double perSquare = 4.0 * available / (9.0 * 1024) / (resolution * resolution);
  const MemoryAtResolution estimateAt = [perSquare](int r) {
    return MemoryEstimate{perSquare * r * r + 2000.0 * r, 0.0};
  };
  const Status refused = checkMemory(estimateAt, resolution, "piece.svg: the run");
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.code(), ErrorCode::Usage);
  EXPECT_EQ(refused.message().rfind("piece.svg: the run at resolution 1000 would need about ", 0),
            0u)
      << refused.message();
  const int fits = offered(refused);
  ASSERT_GT(fits, 8) << refused.message();
  EXPECT_LT(fits, resolution / 2);  // a quarter of the vertices at most: half the resolution
  EXPECT_TRUE(checkMemory(estimateAt, fits, "piece.svg: the run").isOk());
  EXPECT_TRUE(checkMemory([](int) { return MemoryEstimate{1000.0, 0.0}; }, 100, "p").isOk());
}

// The offer follows the run's formula, whatever its shape: here a run fits up to resolution 100
// and needs four times the machine above it, so 100 is offered (a scaling by the resolution's
// square would offer 50), and every time alike. Where no resolution fits, the message says so.
TEST(Resources, TheOfferIsTheHighestResolutionTheFormulaFits) {
  const double huge = 4.0 * double(availableMemoryBytes()) / (9.0 * 1024);
  const MemoryAtResolution steps = [huge](int r) {
    return MemoryEstimate{r <= 100 ? 1000.0 : huge, 0.0};
  };
  for (int attempt = 0; attempt < 3; ++attempt)
    EXPECT_EQ(offered(checkMemory(steps, 200, "piece.svg: the run")), 100);
  const Status none = checkMemory(
      [huge](int) {
        return MemoryEstimate{huge, 0.0};
      },
      200, "piece.svg: the run");
  EXPECT_EQ(none.code(), ErrorCode::Usage);
  EXPECT_NE(none.message().find("; no resolution fits"), std::string::npos) << none.message();
}

// A refusal's figures say why: the need (rounded up) above what a run may use (rounded down),
// never the same figure printed twice, and what a run may use 80 % of what is available.
TEST(Resources, ARefusalPrintsItsNeedAboveWhatARunMayUse) {
  const double available = double(availableMemoryBytes());
  // Just above the budget: 0.01 % more, the case that printed alike at one decimal of a GB.
  const double vertices = (0.8 * available * 1.0001 - double(estimatedPeakBytes(0))) / (9 * 1024);
  const Status refused = checkMemory(
      [vertices](int) {
        return MemoryEstimate{vertices, 0.0};
      },
      60, "p: the run");
  ASSERT_FALSE(refused.isOk());
  std::smatch m;
  const std::string message = refused.message();
  ASSERT_TRUE(std::regex_search(
      message, m,
      std::regex("need about ([0-9.]+) (MB|GB) of memory .* more than the ([0-9.]+) (MB|GB) a "
                 "run may use \\(80 % of the ([0-9.]+) (MB|GB) available to it\\)")))
      << message;
  const auto bytes = [&m](int k) { return std::stod(m[k]) * (m[k + 1] == "GB" ? 1e9 : 1e6); };
  EXPECT_GT(bytes(1), bytes(3)) << message;
  EXPECT_NEAR(bytes(3), 0.8 * bytes(5), 0.002 * bytes(5)) << message;
}

// A run that ran out of memory past the check needed more than its estimate: the resolution
// offered is the highest whose estimate adds half of what this run's adds to the program's own.
TEST(Resources, ARunOutOfMemoryOffersTheResolutionOfHalfItsEstimate) {
  // About 0.6 GB at resolution 400: within any machine that runs the suite.
  const MemoryAtResolution estimateAt = [](int r) {
    const double s = r / 400.0;
    return MemoryEstimate{50000.0 * s * s, 1e8 * s * s};
  };
  const Status failed = outOfMemory(estimateAt, 400, "curve.obj: the run");
  EXPECT_EQ(failed.code(), ErrorCode::Usage);
  EXPECT_EQ(failed.message().rfind("curve.obj: the run at resolution 400 ran out of memory", 0), 0u)
      << failed.message();
  const int fits = offered(failed);
  const auto peakAt = [&estimateAt](int resolution) {
    const MemoryEstimate at = estimateAt(resolution);
    return double(estimatedPeakBytes(at.vertices, at.extraBytes));
  };
  const double program = double(estimatedPeakBytes(0.0));
  const double half = program + 0.5 * (peakAt(400) - program);
  EXPECT_LE(peakAt(fits), half);
  EXPECT_GT(peakAt(fits + 1), half);
  // Before any estimate (reading, or past the solve): half the vertices.
  EXPECT_NE(
      outOfMemory(nullptr, 100, "out: the run").message().find("a resolution of 70 or less fits"),
      std::string::npos);
}

}  // namespace
}  // namespace dform
