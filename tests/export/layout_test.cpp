// The layout check (the gate's pattern_layout): silent on the patterns the exporter lays out,
// and each kind of defect, planted in a built pattern, is counted by its own figure alone.
#include <gtest/gtest.h>

#include <functional>

#include "export/exporter.h"
#include "export/internal.h"
#include "synthetic.h"

namespace dform::test {
namespace {

using fab::Polyline;
using fab::Vec2;

ExportOptions options(const std::string& profile) {
  ExportOptions o;
  o.profile = profile;
  o.templatesDir = DFORM_TEMPLATES_DIR;
  return o;
}

fab::PatternBuild build(const DForm& model, const ExportOptions& o) {
  auto profile = fab::resolveProfile(o);
  EXPECT_TRUE(profile.isOk()) << profile.status().message();
  auto pattern = fab::buildPattern(model, o, profile.value());
  EXPECT_TRUE(pattern.isOk()) << pattern.status().message();
  return pattern.value();
}

fab::Path* findPath(fab::PatternBuild& p, const std::string& id) {
  for (fab::Layer& layer : p.drawing.layers)
    for (fab::Path& path : layer.paths)
      if (path.id == id) return &path;
  return nullptr;
}

void translate(Polyline& line, const Vec2& by) {
  for (Vec2& q : line) q += by;
}

Vec2 centroid(const Polyline& line) {
  Vec2 c = Vec2::Zero();
  for (const Vec2& q : line) c += q;
  return c / double(line.size());
}

TEST(ExportLayout, TheExportersPatternsLayOutCleanly) {
  const DForm model = ellipseCircleDForm(64, 8, 90, 35);  // tight curves: many short tabs
  for (const char* profile : {"laser", "laser-card", "print", "print-letter"})
    for (bool alternate : {false, true}) {
      ExportOptions o = options(profile);
      o.alternateTabs = alternate;
      Result<PreparedExport> prepared = prepareExport(model, o);
      ASSERT_TRUE(prepared.isOk()) << prepared.status().message();
      const LayoutFindings& f = prepared.value().layout;
      EXPECT_EQ(f.problems(), 0) << profile << (alternate ? " alternating: " : ": ") << f.example;
      EXPECT_TRUE(f.example.empty());
    }
}

TEST(ExportLayout, EachPlantedDefectIsCountedByItsOwnFigure) {
  const DForm model = ellipseCircleDForm();
  const fab::PatternBuild clean = build(model, options("laser"));
  ASSERT_EQ(fab::checkLayout(clean).problems(), 0) << fab::checkLayout(clean).example;
  ASSERT_GE(clean.tabs.size(), 3u);

  struct Plant {
    const char* what;
    std::function<void(fab::PatternBuild&)> apply;
    int LayoutFindings::*count;
    const char* example;  // a word the first-problem text must hold
  };
  const std::vector<Plant> plants = {
      {"a fold line pushed off the sheet",
       [](fab::PatternBuild& p) {
         for (Polyline& part : findPath(p, "A-fold-01")->parts)
           translate(part, {p.drawing.width, 0});
       },
       &LayoutFindings::outsideSheet, "off the"},
      {"one tab laid on another",
       [](fab::PatternBuild& p) { p.tabs[1].polygon = p.tabs[0].polygon; },
       &LayoutFindings::overlappingTabs, "glue tabs"},
      {"a tab moved into the middle of its piece",
       [](fab::PatternBuild& p) {
         translate(p.tabs[0].polygon, centroid(p.pieces[0].outline) - centroid(p.tabs[0].polygon));
       },
       &LayoutFindings::tabsOverPieces, "overlaps piece A"},
      {"piece B's cut laid on piece A",
       [](fab::PatternBuild& p) {
         translate(p.pieces[1].cut.front(),
                   centroid(p.pieces[0].outline) - centroid(p.pieces[1].outline));
       },
       &LayoutFindings::overlappingPieces, "cut paths"},
      {"A's tick label filed under piece B",
       [](fab::PatternBuild& p) { findPath(p, "A-tick-03-label")->id = "B-tick-03-label"; },
       &LayoutFindings::labelsOutside, "B-tick-03-label"},
      {"a second label printed over a tick number",
       [](fab::PatternBuild& p) {
         fab::Path copy = *findPath(p, "A-tick-03-label");
         copy.id = "A-extra-label";
         p.drawing.layers.front().paths.push_back(copy);
       },
       &LayoutFindings::overlappingLabels, "A-extra-label"},
  };
  for (const Plant& plant : plants) {
    fab::PatternBuild planted = clean;
    plant.apply(planted);
    const LayoutFindings f = fab::checkLayout(planted);
    EXPECT_EQ(f.*plant.count, 1) << plant.what << ": " << f.example;
    EXPECT_EQ(f.problems(), 1) << plant.what << ": " << f.example;
    EXPECT_NE(f.example.find(plant.example), std::string::npos) << plant.what << ": " << f.example;
  }
}

}  // namespace
}  // namespace dform::test
