// SPDX-License-Identifier: GPL-3.0-or-later
// The shop-floor options: page names in any case, a kerf refused where scissors cut, slots refused
// on a sheet too stiff to fold its tongues back, a hinge only on a rigid sheet, and a tiled
// pattern's message naming the scale and the page that print it untiled.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>

#include "dform/core/setting.h"
#include "dform/export/exporter.h"
#include "export/internal.h"
#include "models.h"
#include "test_util.h"

namespace dform::test {
namespace {

TEST(ExportShopOptions, PageNamesAreReadInAnyCaseAndSpeltOneWay) {
  for (const char* name : {"a4", "A4", "a3", "letter", "LETTER", "tabloid", "200X300MM"})
    EXPECT_TRUE(pageSizeMm(name)) << name;
  EXPECT_EQ(*pageSizeMm("letter"), *pageSizeMm("Letter"));
  EXPECT_EQ(pageSizeMm("a3")->first, 297.0);
  EXPECT_EQ(pageSizeMm("20x30CM")->second, 300.0);
  EXPECT_EQ(pageName("a4"), "A4");
  EXPECT_EQ(pageName("lEtTeR"), "Letter");
  EXPECT_EQ(pageName("200X300MM"), "200x300mm");
  for (const char* bad : {"a5", "200x300", "letters", "200x300mmm", ""})
    EXPECT_FALSE(pageSizeMm(bad)) << bad;
}

TEST(ExportShopOptions, AKerfIsRefusedWhereScissorsCut) {
  ExportOptions o = options("print");
  o.kerfMm = 0.2;
  const Status s = checkProfileOptions(o);
  EXPECT_EQ(s.code(), ErrorCode::Usage);
  EXPECT_NE(s.message().find("kerf"), std::string::npos) << s.message();
  EXPECT_EQ(s.message().find('\n'), std::string::npos);
  o.kerfMm = 0.0;  // no kerf is what scissors have
  EXPECT_TRUE(checkProfileOptions(o).isOk());
  for (const char* cutter : {"laser", "print-and-cut"}) {
    ExportOptions c = options(cutter);
    c.kerfMm = 0.2;
    EXPECT_TRUE(checkProfileOptions(c).isOk())
        << cutter << ": " << checkProfileOptions(c).message();
  }
}

TEST(ExportShopOptions, SlotsAndHingesFollowTheMaterial) {
  ExportOptions o = options();
  o.material = "plywood";
  o.joint = Joint::Slots;
  Status s = checkExportOptions(o);
  EXPECT_EQ(s.code(), ErrorCode::Usage);
  EXPECT_NE(s.message().find("slots"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("holes"), std::string::npos) << "names the joint that suits it";
  for (const char* flexible : {"paper", "card", "polypropylene"}) {
    o.material = flexible;
    EXPECT_TRUE(checkExportOptions(o).isOk()) << flexible;
  }
  o = options();
  o.hinge = true;
  for (const char* material : {"", "card", "paper"}) {
    o.material = material;
    s = checkExportOptions(o);
    EXPECT_EQ(s.code(), ErrorCode::Usage) << material;
    EXPECT_NE(s.message().find("hinge"), std::string::npos) << s.message();
    EXPECT_NE(s.message().find("plywood"), std::string::npos) << s.message();
  }
  o.material = "plywood";
  EXPECT_TRUE(checkExportOptions(o).isOk());
  o.material = "card";
  o.hinge = false;  // asking for none is fine on any sheet
  EXPECT_TRUE(checkExportOptions(o).isOk());
}

// Whether the pattern has tile pages.
bool tiled(const fab::PatternBuild& p) {
  return std::any_of(p.pages.begin(), p.pages.end(),
                     [](const fab::PageView& page) { return page.kind == "tile"; });
}

TEST(ExportShopOptions, ATiledPatternIsToldTheScaleAndThePageThatPrintItUntiled) {
  // A 200 mm square does not fit A4's printable width: tiled, with a strip on a second page.
  const Piece a = foldedSquare(8, 200.0, {}, "A");
  const DForm square{a, mirroredCopy(a, "B")};
  ExportOptions o = options("print");
  o.page = "A4";
  const fab::PatternBuild onA4 = build(square, o);
  ASSERT_TRUE(tiled(onA4));
  std::string advice;
  for (const std::string& m : onA4.messages)
    if (m.find("to print without tiles") != std::string::npos) advice = plainSettings(m);
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(advice, m, std::regex(R"(at ([0-9.]+) % \(export\.scale ([0-9.]+)%\))")))
      << "no scale in: " << advice;
  EXPECT_NE(advice.find("export.page A3"), std::string::npos) << advice;
  // The scale named is the largest (to 0.1 %) at which no piece tiles.
  const double percent = std::stod(m[1]);
  EXPECT_EQ(m[1], m[2]) << "the option's value is the scale named";
  ExportOptions scaled = o;
  scaled.scale = percent / 100;
  EXPECT_FALSE(tiled(build(square, scaled))) << advice;
  scaled.scale = (percent + 0.1) / 100;
  EXPECT_TRUE(tiled(build(square, scaled))) << advice;
  ExportOptions onA3 = o;
  onA3.page = "A3";
  const fab::PatternBuild larger = build(square, onA3);
  EXPECT_FALSE(tiled(larger));
  for (const std::string& message : larger.messages)
    EXPECT_EQ(message.find("to print without tiles"), std::string::npos) << message;
}

}  // namespace
}  // namespace dform::test
