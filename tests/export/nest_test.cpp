// SPDX-License-Identifier: GPL-3.0-or-later
// Nests: the pieces of several D-Forms, and copies, on as few sheets as hold them. Read back: every
// piece on a sheet and labelled with its D-Form, the layout clean, the cut loops of any two pieces
// kerf + 1 mm apart in the sheets' DXF files (ezdxf, check_nest.py), pattern.json's parts.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "dform/export/exporter.h"
#include "export/internal.h"
#include "nest_check.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

using nlohmann::json;

TEST(ExportNest, PiecesOfSeveralDFormsAndCopiesShareSheetsApartAndNamed) {
  const DForm small = ellipseCircleDForm(48, 6, 50, 30, 20);
  const DForm round = ellipseCircleDForm(48, 6, 60, 60, 30);
  const DForm large = ellipseCircleDForm(64, 8, 120, 70, 40);
  std::vector<NestItem> items{
      {&small, "small", 3, {}}, {&round, "round", 1, {}}, {&large, "large", 2, {}}};
  ExportOptions o = options("laser");
  o.sheetWidthMm = 600;
  o.sheetHeightMm = 400;
  o.sheetGiven = true;
  o.kerfMm = 0.2;
  const Result<LaidOutExport> laid = layOutNest(items, o);
  ASSERT_TRUE(laid.isOk()) << laid.status().message();
  EXPECT_EQ(laid.value().layout.problems(), 0) << laid.value().layout.example;
  const fab::PatternBuild& built = laid.value().pattern->build;
  ASSERT_EQ(built.pieces.size(), 12u) << "two pieces of six D-Forms";
  const NestFigures figures = nestFigures(built);
  EXPECT_LE(built.sheets.size(), size_t(shelfSheets(built, 600, 400)));
  std::cout << "nest of 12 pieces: " << built.sheets.size() << " sheets, " << figures.boxShare
            << " of them in the pieces' boxes\n";
  // Every piece on its sheet, its name label writing its D-Form's name.
  const Result<fab::StrokeFont> font = fab::StrokeFont::load(o.fontPath);
  ASSERT_TRUE(font.isOk());
  std::set<std::string> names;
  for (const fab::PieceInfo& piece : built.pieces) {
    names.insert(piece.name);
    EXPECT_TRUE(built.sheets[size_t(piece.sheet)].contains(fab::boxOf(piece.cut), 1e-6))
        << piece.name;
    const fab::Path* label = nullptr;
    for (const fab::Layer& layer : built.drawing.layers)
      for (const fab::Path& path : layer.paths)
        if (path.id == piece.name + "-name") label = &path;
    ASSERT_NE(label, nullptr) << piece.name << " has its name";
    EXPECT_TRUE(startsWithText(*label, piece.name, font.value())) << piece.name;
  }
  for (const char* name :
       {"small-A", "small-B", "small-copy2-A", "small-copy3-B", "round-A", "large-copy2-B"})
    EXPECT_TRUE(names.count(name)) << name;
  // Written: each sheet's DXF read back with ezdxf, the pieces kerf + 1 mm apart.
  const Result<PreparedExport> rendered = renderNest(laid.value());
  ASSERT_TRUE(rendered.isOk()) << rendered.status().message();
  const std::string dir = freshDir("nest");
  ASSERT_TRUE(writeExport(rendered.value(), dir).isOk());
  expectPiecesApart(dir, built.sheets.size(), 1.2);
  const json sidecar = json::parse(readText(dir + "/pattern.json"));
  ASSERT_TRUE(sidecar.contains("nest"));
  EXPECT_NEAR(sidecar["nest"]["gap_mm"].get<double>(), 1.2, 1e-12);
  ASSERT_EQ(sidecar["nest"]["parts"].size(), 12u);
  for (size_t k = 0; k < 12; ++k) {
    const json& part = sidecar["nest"]["parts"][k];
    EXPECT_EQ(part["name"], sidecar["pieces"][k]["name"]);
    EXPECT_EQ(part["sheet"], sidecar["pieces"][k]["sheet"]);
  }
}

TEST(ExportNest, BadNestsAreRefused) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = options("laser");
  EXPECT_EQ(layOutNest({}, o).status().code(), ErrorCode::Usage);
  EXPECT_EQ(layOutNest({{&model, "m", 0, {}}}, o).status().code(), ErrorCode::Usage);
  o.sheetWidthMm = 120;
  o.sheetHeightMm = 100;
  const Result<LaidOutExport> small = layOutNest({{&model, "m", 1, {}}}, o);
  ASSERT_FALSE(small.isOk());
  EXPECT_EQ(small.status().code(), ErrorCode::Usage);
  EXPECT_NE(small.status().message().find("does not fit"), std::string::npos)
      << small.status().message();
}

}  // namespace
}  // namespace dform::test
