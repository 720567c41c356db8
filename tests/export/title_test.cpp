// SPDX-License-Identifier: GPL-3.0-or-later
// The title block never costs a sheet: pieces that fit a sheet together share it with the title
// or without, the title going where there is room (smaller if need be) and, where the full block
// finds none, the mark every cut sheet carries (the job's name over the 50 mm bar) in its place.
#include <gtest/gtest.h>

#include <algorithm>

#include "dform/export/exporter.h"
#include "export/internal.h"
#include "export/pattern_layout.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

using fab::Box;

const fab::Path* findPath(const fab::PatternBuild& p, const std::string& id) {
  for (const fab::Layer& layer : p.drawing.layers)
    for (const fab::Path& path : layer.paths)
      if (path.id == id) return &path;
  return nullptr;
}

// The box of both pieces as laid out, ticks (1.5 mm out) included.
Box piecesExtent(const fab::PatternBuild& built) {
  Box b;
  for (const fab::PieceInfo& piece : built.pieces)
    for (const Polyline& cut : piece.cut) b.add(cut);
  b.lo -= Vec2::Constant(1.5);
  b.hi += Vec2::Constant(1.5);
  return b;
}

TEST(ExportTitle, PiecesThatFitTogetherShareASheetTitleOrNot) {
  // Two circles of one size: side by side they leave no room beside either.
  const DForm model = ellipseCircleDForm(64, 8, 60, 60);
  ExportOptions o = options("laser");
  o.sheetWidthMm = o.sheetHeightMm = 2000;
  o.sheetGiven = true;
  const fab::PatternBuild roomy = build(model, o);
  ASSERT_EQ(roomy.sheets.size(), 1u);
  ASSERT_NE(findPath(roomy, "title"), nullptr) << "a roomy sheet has the full block";
  const Box extent = piecesExtent(roomy);
  const double margin = roomy.profile.marginMm;
  // Room under the pieces for the mark's line and bar (7.6 mm at 1.5 mm text), not for the
  // title's four lines; then room for them.
  for (double below : {8.0, 40.0}) {
    SCOPED_TRACE("room below: " + std::to_string(below) + " mm");
    ExportOptions tight = o;
    tight.sheetWidthMm = extent.w() + 2 * margin + 0.5;
    tight.sheetHeightMm = extent.h() + 2 * margin + margin + below;
    size_t sheets[2] = {0, 0};
    for (bool title : {true, false}) {
      tight.title = title;
      const fab::PatternBuild built = build(model, tight);
      sheets[title] = built.sheets.size();
      EXPECT_EQ(built.sheets.size(), 1u) << (title ? "titled" : "untitled");
      EXPECT_EQ(built.pages.size(), 1u) << "no cover page";
      const LayoutFindings findings = fab::checkLayout(built);
      EXPECT_EQ(findings.problems(), 0) << findings.example;
      const fab::Path* bar = findPath(built, "calibration-bar");
      ASSERT_NE(bar, nullptr);
      EXPECT_NEAR(length(bar->parts[0], false), 50.0, 1e-9);
      const bool full = title && below > 20;
      EXPECT_EQ(findPath(built, "title") != nullptr, full);
      EXPECT_EQ(findPath(built, "job-name") != nullptr, !full);
      const bool said =
          std::any_of(built.messages.begin(), built.messages.end(), [](const std::string& m) {
            return m.find("title lines do not fit") != std::string::npos;
          });
      EXPECT_EQ(said, title && !full);
    }
    EXPECT_EQ(sheets[0], sheets[1]);
  }
}

TEST(ExportTitle, FreeRectanglesAvoidTheTakenBoxesAndStartUnderThem) {
  const Box region = Box::spanning(Vec2(0, 0), Vec2(100, 80));
  const std::vector<Box> taken{Box::spanning(Vec2(0, 0), Vec2(40, 50)),
                               Box::spanning(Vec2(45, 0), Vec2(70, 20))};
  const std::vector<Box> rects = fab::freeRectangles(region, taken, 5);
  ASSERT_GE(rects.size(), 3u);
  // Under everything across the region, then the column right of everything.
  EXPECT_NEAR(rects[0].lo.y(), 55, 1e-12);
  EXPECT_NEAR(rects[0].w(), 100, 1e-12);
  EXPECT_NEAR(rects[1].lo.x(), 75, 1e-12);
  bool underTheSmaller = false;
  for (const Box& r : rects) {
    EXPECT_TRUE(region.contains(r, 1e-12));
    for (const Box& t : taken) {
      const Box grown = Box::spanning(t.lo - Vec2::Constant(5), t.hi + Vec2::Constant(5));
      const bool apart = r.hi.x() <= grown.lo.x() + 1e-9 || grown.hi.x() <= r.lo.x() + 1e-9 ||
                         r.hi.y() <= grown.lo.y() + 1e-9 || grown.hi.y() <= r.lo.y() + 1e-9;
      EXPECT_TRUE(apart) << "a free rectangle meets a taken box";
    }
    underTheSmaller = underTheSmaller || (r.lo.x() <= 45 && r.lo.y() <= 25 && r.hi.x() >= 75);
  }
  EXPECT_TRUE(underTheSmaller) << "the room beside the taller box, under the smaller one, is found";
}

}  // namespace
}  // namespace dform::test
