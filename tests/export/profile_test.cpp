// SPDX-License-Identifier: GPL-3.0-or-later
// Profiles: every shipped template loads; every kind of bad profile file is an error that names
// the file and the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dform/export/exporter.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

std::string writeProfile(const std::string& name, const std::string& text) {
  const std::string path = freshDir("profiles-" + name) + "/" + name + ".json";
  std::ofstream(path) << text;
  return path;
}

TEST(ExportProfile, EveryTemplateLoads) {
  const auto names = listProfiles(DFORM_TEMPLATES_DIR);
  for (const char* expected : {"laser", "laser-ponoko", "laser-lightburn", "laser-card", "print",
                               "print-letter", "print-and-cut", "print-and-cut-cricut"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
  for (const auto& name : names) {
    auto p = loadProfile(name, DFORM_TEMPLATES_DIR);
    ASSERT_TRUE(p.isOk()) << p.status().message();
    EXPECT_EQ(p.value().name, name);
    EXPECT_FALSE(p.value().description.empty()) << name;
  }
}

TEST(ExportProfile, ShopColourConventions) {
  auto laser = loadProfile("laser", DFORM_TEMPLATES_DIR).value();
  EXPECT_EQ(laser.cutColor, "#FF0000");
  EXPECT_EQ(laser.scoreColor, "#0000FF");
  EXPECT_EQ(laser.engraveColor, "#000000");
  auto ponoko = loadProfile("laser-ponoko", DFORM_TEMPLATES_DIR).value();
  EXPECT_EQ(ponoko.cutColor, "#0000FF");
  EXPECT_EQ(ponoko.scoreColor, "#FF0000");
  EXPECT_DOUBLE_EQ(ponoko.cutWidthMm, 0.01);
  auto print = loadProfile("print", DFORM_TEMPLATES_DIR).value();
  EXPECT_EQ(print.kind, ProfileKind::Print);
  EXPECT_EQ(print.fold, FoldStyle::Dashed);
  EXPECT_TRUE(print.tile && print.calibrationBar);
  EXPECT_EQ(loadProfile("print-and-cut", DFORM_TEMPLATES_DIR).value().registration,
            Registration::Silhouette);
  EXPECT_EQ(loadProfile("print-and-cut-cricut", DFORM_TEMPLATES_DIR).value().page, "Letter");
}

TEST(ExportProfile, ProfileByPathAndLowerCaseColour) {
  const std::string path = writeProfile("mine", R"({"name": "mine", "cut_color": "#00ff00"})");
  auto p = loadProfile(path, "");
  ASSERT_TRUE(p.isOk()) << p.status().message();
  EXPECT_EQ(p.value().cutColor, "#00FF00");
  EXPECT_EQ(p.value().kind, ProfileKind::Laser);  // defaults for what is left out
}

TEST(ExportProfile, TheTabSideIsAProfileFieldThatAnOptionOverrides) {
  EXPECT_EQ(loadProfile("laser", DFORM_TEMPLATES_DIR).value().tabs, TabSide::A);
  EXPECT_EQ(loadProfile("laser-lightburn", DFORM_TEMPLATES_DIR).value().tabs, TabSide::Alternate);
  for (TabSide side : {TabSide::A, TabSide::B, TabSide::Alternate, TabSide::None}) {
    const std::string name = tabSideName(side);
    EXPECT_EQ(tabSideNamed(name), side) << name;
    auto p = loadProfile(writeProfile("tabs-" + name, R"({"tabs": ")" + name + R"("})"), "");
    ASSERT_TRUE(p.isOk()) << p.status().message();
    EXPECT_EQ(p.value().tabs, side) << name;
  }
  EXPECT_FALSE(tabSideNamed("both"));
  // As shipped, laser-lightburn alternates: tabs on both pieces, by turns along the seam.
  const DForm model = ellipseCircleDForm();
  ExportOptions o = options("laser-lightburn");
  const fab::PatternBuild shipped = build(model, o);
  int perPiece[2] = {0, 0};
  for (size_t k = 0; k < shipped.tabs.size(); ++k) ++perPiece[shipped.tabs[k].piece];
  for (size_t k = 1; k < shipped.tabs.size(); ++k)
    EXPECT_NE(shipped.tabs[k].piece, shipped.tabs[k - 1].piece) << "tab " << k;
  EXPECT_GT(perPiece[0], 5);
  EXPECT_GT(perPiece[1], 5);
  o.tabSide = TabSide::None;  // the option wins over the profile
  EXPECT_TRUE(build(model, o).tabs.empty());
}

TEST(ExportProfile, TheJointIsAProfileFieldThatAMaterialAndAnOptionOverride) {
  EXPECT_EQ(loadProfile("laser", DFORM_TEMPLATES_DIR).value().joint, Joint::Glue);
  for (Joint joint : {Joint::Glue, Joint::Holes, Joint::Lace, Joint::Slots}) {
    const std::string name = jointName(joint);
    EXPECT_EQ(jointNamed(name), joint) << name;
    auto p = loadProfile(writeProfile("joint-" + name, R"({"joint": ")" + name + R"("})"), "");
    ASSERT_TRUE(p.isOk()) << p.status().message();
    EXPECT_EQ(p.value().joint, joint) << name;
  }
  EXPECT_FALSE(jointNamed("slot"));
  EXPECT_FALSE(jointNamed("Slots"));
  // A laced profile: holes in the pattern, no glue tabs; a material, then the option, override.
  const DForm model = ellipseCircleDForm(48, 4);
  ExportOptions o = options();
  o.profileOverride =
      loadProfile(writeProfile("joint-lace-model", R"({"joint": "lace"})"), "").value();
  o.useProfileOverride = true;
  const fab::PatternBuild laced = build(model, o);
  EXPECT_EQ(laced.joint.joint, Joint::Lace);
  EXPECT_FALSE(laced.jointHoles.empty());
  EXPECT_TRUE(laced.tabs.empty());
  o.material = "paper";
  EXPECT_EQ(build(model, o).joint.joint, Joint::Glue);
  o.joint = Joint::Holes;
  EXPECT_EQ(build(model, o).joint.joint, Joint::Holes);
}

TEST(ExportProfile, BadProfilesNameTheFileAndField) {
  struct Case {
    const char* name;
    const char* text;
    ErrorCode code;
    const char* mentions;
  };
  const Case cases[] = {
      {"unknown-field", R"({"cut_colour": "#FF0000"})", ErrorCode::InputInvalid, "cut_colour"},
      {"bad-colour", R"({"cut_color": "red"})", ErrorCode::InputInvalid, "cut_color"},
      {"bad-type", R"({"margin_mm": "5"})", ErrorCode::InputInvalid, "margin_mm"},
      {"out-of-range", R"({"cut_width_mm": 0.5})", ErrorCode::InputInvalid, "cut_width_mm"},
      {"zero-width", R"({"cut_width_mm": 0})", ErrorCode::InputInvalid, "cut_width_mm"},
      {"bad-kind", R"({"kind": "plasma"})", ErrorCode::InputInvalid, "kind"},
      {"bad-page", R"({"kind": "print", "page": "A5x"})", ErrorCode::InputInvalid, "page"},
      {"tiny-page", R"({"kind": "print", "page": "40x40mm"})", ErrorCode::InputInvalid, "page"},
      {"pnc-no-page", R"({"kind": "print-and-cut"})", ErrorCode::InputInvalid, "page"},
      {"bad-tabs", R"({"tabs": "both"})", ErrorCode::InputInvalid, "tabs"},
      {"bad-joint", R"({"joint": "tape"})", ErrorCode::InputInvalid, "joint"},
      {"bad-kerf", R"({"kerf_mm": 6})", ErrorCode::InputInvalid, "kerf_mm"},
      {"laser-bleed", R"({"kind": "laser", "bleed_mm": 1})", ErrorCode::InputInvalid, "bleed_mm"},
      {"print-bleed", R"({"kind": "print", "page": "A4", "bleed_mm": 1})", ErrorCode::InputInvalid,
       "bleed_mm"},
      {"wide-bleed", R"({"kind": "print-and-cut", "page": "A4", "bleed_mm": 3.5})",
       ErrorCode::InputInvalid, "bleed_mm"},
      {"bad-tint", R"({"fill_color_b": "blue"})", ErrorCode::InputInvalid, "fill_color_b"},
      {"not-json", R"({"kind": )", ErrorCode::InputUnreadable, "not JSON"},
      {"not-object", R"([1, 2])", ErrorCode::InputInvalid, "object"},
  };
  for (const Case& c : cases) {
    const std::string path = writeProfile(c.name, c.text);
    auto p = loadProfile(path, "");
    ASSERT_FALSE(p.isOk()) << c.name;
    EXPECT_EQ(p.status().code(), c.code) << c.name << ": " << p.status().message();
    EXPECT_NE(p.status().message().find(path), std::string::npos) << p.status().message();
    EXPECT_NE(p.status().message().find(c.mentions), std::string::npos) << p.status().message();
  }
  auto missing = loadProfile("/nonexistent/profile.json", "");
  EXPECT_EQ(missing.status().code(), ErrorCode::InputUnreadable);
  const std::string huge = writeProfile("huge", "");
  std::filesystem::resize_file(huge, (std::uintmax_t(1) << 20) + 1);  // sparse: nothing is written
  auto big = loadProfile(huge, "");
  EXPECT_EQ(big.status().code(), ErrorCode::InputUnreadable);
  EXPECT_EQ(big.status().message().rfind(huge + ": file is too large", 0), 0u)
      << big.status().message();
  auto unknown = loadProfile("plasma", DFORM_TEMPLATES_DIR);
  EXPECT_EQ(unknown.status().code(), ErrorCode::Usage);
  EXPECT_NE(unknown.status().message().find("laser"), std::string::npos);
}

}  // namespace
}  // namespace dform::test
