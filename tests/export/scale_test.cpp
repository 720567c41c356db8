// Very large pieces: the export's work grows with the pattern's ticks, tabs and labels, not with
// the square of their number, and a pattern too large for its sheet, page or tiling fails before
// a single tick or tab is made. Work is counted (fab::BuildWork), never timed.
#include <gtest/gtest.h>

#include <regex>

#include "dform/export/exporter.h"
#include "dform/export/internal.h"
#include "models.h"
#include "test_util.h"

namespace dform::test {
namespace {

// Two flat squares of side `side` mm (a k by k grid and its mirrored copy) zipped along their
// outlines: a seam of 4 * side mm with 4k points, equal on both pieces.
DForm squareDForm(double side, int k) {
  const Piece a = foldedSquare(k, side, {}, "A");
  return DForm{a, mirroredCopy(a, "B")};
}

// The W x H of a "needs at least W x H mm" message.
Vec2 sizeNeeded(const std::string& message) {
  std::smatch m;
  const std::regex needs(R"(needs at least ([0-9.]+) x ([0-9.]+) mm)");
  if (!std::regex_search(message, m, needs)) {
    ADD_FAILURE() << "no size needed in: " << message;
    return Vec2::Zero();
  }
  return {std::stod(m[1]), std::stod(m[2])};
}

// Builds the pattern, counting the work.
Result<fab::PatternBuild> buildCounted(const DForm& model, const ExportOptions& o,
                                       fab::BuildWork& work) {
  auto profile = fab::resolveProfile(o);
  if (!profile.isOk()) return profile.status();
  return fab::buildPattern(model, o, profile.value(), &work);
}

TEST(ExportScale, AVeryLongSeamExportsWithWorkProportionalToItsShapes) {
  const double side = 2500;  // a 10 m seam
  const DForm model = squareDForm(side, 50);
  ExportOptions o = options("laser");
  o.sheetWidthMm = 5300;
  o.sheetHeightMm = 2700;
  fab::BuildWork work;
  auto built = buildCounted(model, o, work);
  ASSERT_TRUE(built.isOk()) << built.status().message();
  const fab::PatternBuild& pattern = built.value();
  const LayoutFindings layout = fab::checkLayout(pattern, &work);
  EXPECT_EQ(layout.problems(), 0) << layout.example;

  // Correct: a tick every 20 mm of the 4 * side mm seam, partners at the same seam point (the
  // pieces are congruent, so at the same arc length); tabs of up to 40 mm, 1.5 mm apart, along
  // each straight side.
  EXPECT_EQ(pattern.ticks.size(), size_t(4 * side / o.tickSpacingMm));
  for (const fab::TickInfo& t : pattern.ticks) EXPECT_NEAR(t.s, t.sB, 1e-6) << t.id;
  const double tabsPerSide = std::floor((side - o.tabGapMm) / (o.tabMaxLengthMm + o.tabGapMm));
  EXPECT_GE(pattern.tabs.size(), size_t(4 * tabsPerSide)) << "tabs";

  // Linear: shape pairs are compared only where their boxes meet, a few per shape. Comparing
  // every tab with every accepted tab and every label with every label would take
  // tabs^2 / 2 + labels^2 / 2 (over 500,000 here).
  size_t labels = 0;
  for (const fab::Layer& layer : pattern.drawing.layers)
    for (const fab::Path& path : layer.paths) labels += path.id.find("-label") != std::string::npos;
  // Numbered ticks on both pieces, but for the four at the corners, where the outline turns
  // under the number.
  EXPECT_GE(labels, 2 * (pattern.ticks.size() - 4));
  const long shapes = work.tabCandidates + long(pattern.tabs.size()) + long(labels);
  EXPECT_LE(work.pairTests, 4 * shapes)
      << work.pairTests << " pair tests for " << shapes << " shapes";
  RecordProperty("pair_tests", std::to_string(work.pairTests));
  RecordProperty("shapes", std::to_string(shapes));

  // And every file renders.
  Result<PreparedExport> prepared = prepareExport(model, o);
  ASSERT_TRUE(prepared.isOk()) << prepared.status().message();
  for (const auto& [name, content] : prepared.value().files)
    EXPECT_GT(content.size(), 100u) << name;
}

TEST(ExportScale, AnOversizedPatternFailsBeforeAnyTickOrTab) {
  // The audit's 900 m square: 3.6 km of seam, 180,000 ticks and some 87,000 tabs if it got
  // that far.
  const double side = 900000;
  const DForm model = squareDForm(side, 4);
  fab::BuildWork work;
  auto laser = buildCounted(model, options("laser"), work);  // 600 x 400 mm
  ASSERT_FALSE(laser.isOk());
  EXPECT_EQ(laser.status().code(), ErrorCode::Usage);
  const Vec2 need = sizeNeeded(laser.status().message());
  EXPECT_GE(need.minCoeff(), side) << laser.status().message();
  EXPECT_NE(laser.status().message().find("the sheet is 600.0 x 400.0 mm"), std::string::npos)
      << laser.status().message();
  EXPECT_EQ(work.ticks, 0);
  EXPECT_EQ(work.tabCandidates, 0);

  // Print-and-cut gives each piece a page if need be; a piece larger than a page is refused.
  auto pnc = buildCounted(model, options("print-and-cut"), work);
  ASSERT_FALSE(pnc.isOk());
  EXPECT_EQ(pnc.status().code(), ErrorCode::Usage);
  EXPECT_EQ(pnc.status().message().rfind("piece A does not fit the A4 page", 0), 0u)
      << pnc.status().message();
  EXPECT_GE(sizeNeeded(pnc.status().message()).minCoeff(), side);

  // Print tiles, but not across millions of pages.
  auto print = buildCounted(model, options("print"), work);
  ASSERT_FALSE(print.isOk());
  EXPECT_EQ(print.status().code(), ErrorCode::Usage);
  std::smatch pages;
  const std::string message = print.status().message();
  ASSERT_TRUE(std::regex_search(message, pages, std::regex("needs at least ([0-9]+) A4 pages")))
      << message;
  EXPECT_GT(std::stol(pages[1]), 1000000L) << message;
  EXPECT_EQ(work.ticks, 0);
  EXPECT_EQ(work.tabCandidates, 0);
  EXPECT_EQ(work.pairTests, 0);
}

TEST(ExportScale, ThePageLimitHoldsForATiledPattern) {
  // Two 600 mm squares tile across a few dozen A4 pages; two 5 m squares would take over a
  // thousand and are refused.
  fab::BuildWork work;
  auto fits = buildCounted(squareDForm(600, 12), options("print"), work);
  ASSERT_TRUE(fits.isOk()) << fits.status().message();
  EXPECT_GT(fits.value().pages.size(), 1u);
  auto tooMany = buildCounted(squareDForm(5000, 12), options("print"), work);
  ASSERT_FALSE(tooMany.isOk());
  EXPECT_NE(tooMany.status().message().find("more than the 500"), std::string::npos)
      << tooMany.status().message();
}

}  // namespace
}  // namespace dform::test
