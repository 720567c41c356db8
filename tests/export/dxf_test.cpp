// SPDX-License-Identifier: GPL-3.0-or-later
// pattern.dxf read back with ezdxf (python3-ezdxf) by check_dxf.py: units, layers, closed cut
// polylines, perimeters against the SVG and the solved seam, extents, y up; and the checker
// itself fails a DXF drawn 2 % too large or not flipped. A pattern on two sheets, each with its own
// DXF: ExportPattern.LaserPiecesThatDoNotFitOneSheetTogetherGetASheetEach.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "dform/core/atomic_file.h"
#include "dform/export/exporter.h"
#include "export/internal.h"
#include "models.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

namespace fs = std::filesystem;

TEST(ExportDxf, EveryExportWritesPatternDxfInItsFileList) {
  const Exported e = exportTo("dxf-files", ellipseCircleDForm(), options("laser"));
  ASSERT_TRUE(fs::exists(e.dir + "/pattern.dxf"));
  EXPECT_NE(std::find(e.summary.files.begin(), e.summary.files.end(), e.dir + "/pattern.dxf"),
            e.summary.files.end());
  EXPECT_EQ(e.sidecar["sheets"][0]["dxf"].get<std::string>(), "pattern.dxf");
  const std::vector<std::string> names = exportFileNames();
  for (const std::string& name :
       {std::string("pattern.dxf"), sheetFileName(1, "dxf"), sheetFileName(2, "dxf")})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  const std::string text = readText(e.dir + "/pattern.dxf");
  EXPECT_NE(text.find("$INSUNITS\n 70\n4\n"), std::string::npos);
  EXPECT_NE(text.find("LWPOLYLINE"), std::string::npos);
}

TEST(ExportDxf, AFailedWriteIsAnOutputErrorNamingTheDxf) {
  const std::string blocked = freshDir("dxf-blocked");
  fs::create_directory(blocked + "/pattern.dxf");  // a folder holds its name
  auto clash = exportAll(ellipseCircleDForm(), options(), blocked);
  ASSERT_FALSE(clash.isOk());
  EXPECT_EQ(clash.status().code(), ErrorCode::OutputFailed);
  EXPECT_NE(clash.status().message().find("pattern.dxf"), std::string::npos)
      << clash.status().message();
}

TEST(ExportDxf, LaserPatternReadsBackWithEzdxf) {
  const Exported e = exportTo("dxf-laser", ellipseCircleDForm(), options("laser"));
  expectDxfChecks(e.dir);
}

TEST(ExportDxf, CutPerimetersAreTheSolvedSeamTimesTheScale) {
  // No tabs and no kerf: each piece's closed cut is its seam, the solved length times the scale.
  const DForm model = ellipseCircleDForm();
  for (double scale : {1.0, 0.8}) {
    ExportOptions o = options("laser");
    o.tabWidthMm = 0;
    o.kerfMm = 0;
    o.scale = scale;
    const Exported e = exportTo("dxf-seam-" + std::to_string(int(100 * scale)), model, o);
    const std::string seams = "--seam " + std::to_string(scale * solvedPerimeter(model.a)) + " " +
                              std::to_string(scale * solvedPerimeter(model.b));
    expectDxfChecks(e.dir, seams);
  }
}

TEST(ExportDxf, EveryShippedProfileReadsBack) {
  const DForm model = ellipseCircleDForm(64, 8, 56, 35, 20);  // fits every page
  for (const std::string& profile : listProfiles(DFORM_TEMPLATES_DIR)) {
    SCOPED_TRACE(profile);
    const Exported e = exportTo("dxf-profile-" + profile, model, options(profile));
    expectDxfChecks(e.dir);
  }
}

// The DXF's group pairs (code, value) of each table record or entity, in file order.
std::vector<std::map<std::string, std::string>> dxfRecords(const std::string& path) {
  std::vector<std::map<std::string, std::string>> records;
  std::ifstream in(path);
  const auto trimmed = [](std::string s) {
    s.erase(0, s.find_first_not_of(" \r"));
    s.erase(s.find_last_not_of(" \r") + 1);
    return s;
  };
  for (std::string code, value; std::getline(in, code) && std::getline(in, value);) {
    if (trimmed(code) == "0") records.emplace_back();
    if (!records.empty()) records.back().emplace(trimmed(code), trimmed(value));  // first kept
  }
  return records;
}

// dxflib points the dimension style at the text style named exactly "Standard" (group 340); under
// any other name that handle is left unset, and the file held different bytes on every export.
TEST(ExportDxf, TheDimensionStylePointsAtTheStandardTextStyle) {
  const Exported e = exportTo("dxf_dimension_style", ellipseCircleDForm(), options("laser"));
  std::string standard, pointedAt;
  for (const auto& record : dxfRecords(e.dir + "/pattern.dxf")) {
    if (record.at("0") == "STYLE" && record.count("2") && record.at("2") == "Standard")
      standard = record.count("5") ? record.at("5") : "";
    if (record.at("0") == "DIMSTYLE" && record.count("340")) pointedAt = record.at("340");
  }
  ASSERT_FALSE(standard.empty()) << "no text style named Standard with a handle";
  EXPECT_EQ(pointedAt, standard);
}

TEST(ExportDxf, HolesAreClosedCutsOfTheirOwn) {
  const Exported e = exportTo("dxf-anti", annulusDForm(), options("laser"));
  ASSERT_NE(e.svg.find("A-cut-hole-1"), nullptr);
  expectDxfChecks(e.dir);
}

// The export's pattern.dxf replaced by one written from the drawing as `change` leaves it.
template <typename Change>
std::string exportWithAlteredDxf(const std::string& name, Change change) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = options("laser");
  o.tabWidthMm = 0;
  const Exported e = exportTo(name, model, o);
  fab::Drawing drawing = build(model, o).drawing;
  for (fab::Layer& layer : drawing.layers)
    for (fab::Path& path : layer.paths)
      for (fab::Polyline& part : path.parts)
        for (fab::Vec2& q : part) q = change(q, drawing.height);
  EXPECT_TRUE(writeFileAtomically(e.dir + "/pattern.dxf", fab::dxfDocument(drawing)).isOk());
  return e.dir;
}

TEST(ExportDxf, TheCheckFailsADxfTwoPercentOffOrNotFlipped) {
  const DForm model = ellipseCircleDForm();
  const std::string seams = "--seam " + std::to_string(solvedPerimeter(model.a)) + " " +
                            std::to_string(solvedPerimeter(model.b));
  std::string out;
  // Unaltered: passes.
  const std::string same =
      exportWithAlteredDxf("dxf-same", [](const fab::Vec2& q, double) { return q; });
  EXPECT_EQ(checkDxf(same, &out, seams), 0) << out;
  // 2 % too large about the sheet's corner: the perimeters and the tick's position are off.
  const std::string large =
      exportWithAlteredDxf("dxf-large", [](const fab::Vec2& q, double) { return 1.02 * q; });
  EXPECT_NE(checkDxf(large, &out, seams), 0) << out;
  EXPECT_NE(out.find("the seam x scale is"), std::string::npos) << out;
  EXPECT_NE(out.find("tick 0 of A"), std::string::npos) << out;
  // Not flipped (the writer's flip undone): the perimeters agree, the positions do not.
  const std::string mirrored = exportWithAlteredDxf(
      "dxf-mirrored", [](const fab::Vec2& q, double h) { return fab::Vec2(q.x(), h - q.y()); });
  EXPECT_NE(checkDxf(mirrored, &out, seams), 0) << out;
  EXPECT_EQ(out.find("the seam x scale is"), std::string::npos) << out;
  EXPECT_NE(out.find("tick 0 of A"), std::string::npos) << out;
  EXPECT_NE(out.find("extents"), std::string::npos) << out;
}

}  // namespace
}  // namespace dform::test
