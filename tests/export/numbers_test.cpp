// SPDX-License-Identifier: GPL-3.0-or-later
// Tick numbers where the glue hides them: on the glue tab over a tick (`numbers: tabs`, the print
// profiles'), on the face (`face`), or both. Read back from the laid-out pattern: a number on a tab
// writes its tick's number, lies inside that tab 0.3 mm clear of its edges, and the layout check
// stays clean; the partner piece, without tabs, keeps every number on its face.
#include <gtest/gtest.h>

#include <map>

#include "dform/export/exporter.h"
#include "export/internal.h"
#include "export/pattern_parts.h"
#include "export/plane_geometry.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

std::map<std::string, const fab::Path*> pathsById(const fab::PatternBuild& built) {
  std::map<std::string, const fab::Path*> out;
  for (const fab::Layer& layer : built.drawing.layers)
    for (const fab::Path& path : layer.paths) out[path.id] = &path;
  return out;
}

TEST(ExportNumbers, OnTheTabsOnTheFaceOrBoth) {
  const DForm model = ellipseCircleDForm();
  const Result<fab::StrokeFont> font = fab::StrokeFont::load(ExportOptions{}.fontPath);
  ASSERT_TRUE(font.isOk());
  for (TickNumbers numbers : {TickNumbers::Face, TickNumbers::Tabs, TickNumbers::Both}) {
    SCOPED_TRACE(tickNumbersName(numbers));
    ExportOptions o = options("print");
    o.page = "A3";
    o.numbers = numbers;
    const fab::PatternBuild built = build(model, o);
    EXPECT_EQ(fab::checkLayout(built).problems(), 0) << fab::checkLayout(built).example;
    const auto paths = pathsById(built);
    int onTabs = 0, covered = 0;
    for (const fab::TickInfo& t : built.ticks) {
      const std::string a = "A-tick-" + fab::twoDigits(t.id), b = "B-tick-" + fab::twoDigits(t.id);
      EXPECT_TRUE(paths.count(b + "-label")) << "B, without tabs, numbers tick " << t.id;
      EXPECT_FALSE(paths.count(b + "-tab-label"));
      const fab::TabInfo* tab = nullptr;
      for (const fab::TabInfo& candidate : built.tabs)
        if (candidate.piece == 0 && t.s > candidate.s0 && t.s < candidate.s1) tab = &candidate;
      covered += tab != nullptr;
      const auto onTab = paths.find(a + "-tab-label");
      if (numbers == TickNumbers::Face || !tab) {
        EXPECT_EQ(onTab, paths.end()) << a;
        EXPECT_TRUE(paths.count(a + "-label")) << a;
        continue;
      }
      if (onTab == paths.end()) {  // at a tab's slanted end: on the face
        EXPECT_TRUE(paths.count(a + "-label")) << a;
        continue;
      }
      ++onTabs;
      EXPECT_TRUE(startsWithText(*onTab->second, fab::tickLabel(t.id), font.value())) << a;
      for (const Polyline& stroke : onTab->second->parts)
        for (const Vec2& q : stroke) {
          EXPECT_TRUE(fab::insideRegion({tab->polygon}, q)) << a;
          EXPECT_GE(fab::distanceToPolylines({tab->polygon}, q, true), 0.3 - 1e-9) << a;
        }
      EXPECT_EQ(paths.count(a + "-label"), numbers == TickNumbers::Both ? 1u : 0u) << a;
    }
    if (numbers != TickNumbers::Face) {
      std::cout << tickNumbersName(numbers) << ": " << onTabs << " of the " << covered
                << " ticks under a tab numbered on it\n";
      EXPECT_GE(onTabs, covered * 4 / 5) << "most ticks under a tab have their number on it";
    }
  }
}

TEST(ExportNumbers, TheProfileFieldIsReadAndAnUnknownPlaceRefused) {
  EXPECT_EQ(parseProfileJson(R"({"numbers": "tabs"})", "p").value().numbers, TickNumbers::Tabs);
  EXPECT_EQ(parseProfileJson("{}", "p").value().numbers, TickNumbers::Face);
  const Result<Profile> bad = parseProfileJson(R"({"numbers": "edge"})", "p.json");
  ASSERT_FALSE(bad.isOk());
  EXPECT_EQ(bad.status().code(), ErrorCode::InputInvalid);
  EXPECT_NE(bad.status().message().find("numbers"), std::string::npos);
  EXPECT_EQ(tickNumbersNamed("both"), TickNumbers::Both);
  EXPECT_FALSE(tickNumbersNamed("Both").has_value());
}

}  // namespace
}  // namespace dform::test
