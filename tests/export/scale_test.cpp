// SPDX-License-Identifier: GPL-3.0-or-later
// Very large pieces: the export's work grows with the pattern's ticks, tabs and labels, not with
// the square of their number, and a pattern too large for its sheet, page or tiling fails before
// a single tick or tab is made. Work is counted (fab::BuildWork), never timed.
#include <gtest/gtest.h>

#include <regex>

#include "dform/export/exporter.h"
#include "export/internal.h"
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

// The scale a refusal names: "the largest scale that fits is 61.7 %", as a fraction.
double scaleNamed(const std::string& message) {
  std::smatch m;
  if (!std::regex_search(message, m, std::regex(R"(largest scale that fits is ([0-9.]+) %)"))) {
    ADD_FAILURE() << "no scale in: " << message;
    return 0;
  }
  return std::stod(m[1]) / 100;
}

// Whether the pattern builds at `scale` (true size otherwise asked).
bool buildsAt(const DForm& model, ExportOptions o, double scale) {
  o.scale = scale;
  fab::BuildWork work;
  return buildCounted(model, o, work).isOk();
}

// The scale notes drawn: on the sheets, or on cover pages where the title lines go.
size_t scaleNotes(const fab::PatternBuild& pattern) {
  size_t notes = 0;
  auto count = [&](const std::vector<fab::Layer>& layers) {
    for (const fab::Layer& layer : layers)
      for (const fab::Path& path : layer.paths) notes += path.id.rfind("scale-note", 0) == 0;
  };
  count(pattern.drawing.layers);
  for (const fab::PageView& page : pattern.pages) count(page.overlay);
  return notes;
}

TEST(ExportScale, ARefusalNamesTheLargestScaleThatFitsAndScaleFitUsesIt) {
  // A 200 mm square: too large for a Silhouette A4 page (a 170 x 257 mm area inside the marks)
  // and for the Cricut Print Then Cut area (6.75 x 9.25 in on any paper), and for a 200 mm sheet.
  const DForm model = squareDForm(200, 10);
  ExportOptions small = options("laser");
  small.sheetWidthMm = small.sheetHeightMm = 200;
  for (const ExportOptions& base :
       {options("print-and-cut"), options("print-and-cut-cricut"), small}) {
    SCOPED_TRACE(base.profile);
    fab::BuildWork work;
    auto refused = buildCounted(model, base, work);
    ASSERT_FALSE(refused.isOk());
    const std::string message = refused.status().message();
    EXPECT_EQ(refused.status().code(), ErrorCode::Usage);
    // The largest scale that fits, to a tenth of a percent: it fits, a tenth more does not.
    const double fits = scaleNamed(message);
    EXPECT_TRUE(buildsAt(model, base, fits)) << message;
    EXPECT_FALSE(buildsAt(model, base, fits + 0.001)) << message;
    // The way out names the scale setting (the command line words it --scale, Python scale=).
    EXPECT_EQ(refused.status().setting(), Setting::Scale) << message;
    EXPECT_NE(message.find(std::string(settingKey(Setting::Scale)) + " fit"), std::string::npos)
        << message;
    // --scale fit takes that scale and says so in words on every sheet, with or without the
    // title lines (on a cover page where they do not fit beside a piece).
    for (bool title : {true, false}) {
      ExportOptions fit = base;
      fit.scaleToFit = true;
      fit.title = title;
      auto scaled = buildCounted(model, fit, work);
      ASSERT_TRUE(scaled.isOk()) << scaled.status().message();
      EXPECT_DOUBLE_EQ(scaled.value().scale, fits);
      EXPECT_EQ(scaleNotes(scaled.value()), scaled.value().sheets.size()) << "title " << title;
    }
  }
  // Cricut: the area is the limit, not the paper, so no page size is named as the way out; a
  // Silhouette page is, where the piece fits it.
  fab::BuildWork work;
  const std::string cricut =
      buildCounted(model, options("print-and-cut-cricut"), work).status().message();
  EXPECT_NE(cricut.find("Print Then Cut area"), std::string::npos) << cricut;
  EXPECT_EQ(cricut.find("needs at least"), std::string::npos) << cricut;
  EXPECT_EQ(cricut.find(settingKey(Setting::Page)), std::string::npos) << cricut;
  const std::string silhouette =
      buildCounted(model, options("print-and-cut"), work).status().message();
  EXPECT_NE(silhouette.find(std::string(settingKey(Setting::Page)) + " A3"), std::string::npos)
      << silhouette;
  ExportOptions onA3 = options("print-and-cut");
  onA3.page = "A3";
  EXPECT_TRUE(buildsAt(model, onA3, 1.0));
  // At true size no sheet states a scale.
  auto trueSize = buildCounted(model, onA3, work);
  ASSERT_TRUE(trueSize.isOk());
  EXPECT_EQ(scaleNotes(trueSize.value()), 0u);
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
