// SPDX-License-Identifier: GPL-3.0-or-later
// The 14 shipped samples (matrix_samples.h), one copy each, nested on 600 x 400 mm laser sheets:
// no more sheets than a greedy shelf packing of the same pieces, at least 60 % of the used
// sheets' area within the pieces' boxes, and every two pieces kerf + 1 mm apart in the sheets'
// DXF files, read back with ezdxf.
#include <gtest/gtest.h>

#include "dform/export/exporter.h"
#include "dform/io/model_files.h"
#include "matrix_samples.h"
#include "nest_check.h"
#include "test_util.h"

namespace dform::test {
namespace {

TEST(SampleNest, TheShippedSamplesNestOnFewSheetsWellFilledAndApart) {
  std::vector<DForm> models;
  std::vector<std::string> names;
  for (const MatrixSample& sample : matrixSamples()) {
    const Result<DForm> model = readModel(solveSample(sample, "--gate lenient"));
    ASSERT_TRUE(model.isOk()) << sample.name << ": " << model.status().message();
    models.push_back(model.value());
    names.push_back(sample.name);
  }
  ASSERT_EQ(models.size(), 14u);
  std::vector<NestItem> items;
  for (size_t i = 0; i < models.size(); ++i) items.push_back({&models[i], names[i], 1, {}});
  for (double kerf : {0.0, 0.2}) {
    SCOPED_TRACE("kerf " + std::to_string(kerf));
    ExportOptions o = options("laser");
    o.jobName = "samples";
    o.sheetWidthMm = 600;
    o.sheetHeightMm = 400;
    o.sheetGiven = true;
    o.kerfMm = kerf;
    const Result<LaidOutExport> laid = layOutNest(items, o);
    ASSERT_TRUE(laid.isOk()) << laid.status().message();
    EXPECT_EQ(laid.value().layout.problems(), 0) << laid.value().layout.example;
    const fab::PatternBuild& built = laid.value().pattern->build;
    EXPECT_EQ(built.pieces.size(), 28u);
    const int shelf = shelfSheets(built, 600, 400);
    const NestFigures figures = nestFigures(built);
    std::cout << "14 samples nested, kerf " << kerf << ": " << built.sheets.size()
              << " sheets (a greedy shelf packing: " << shelf << "), " << 100 * figures.boxShare
              << " % of their area in the pieces' boxes\n";
    EXPECT_LE(int(built.sheets.size()), shelf);
    EXPECT_GE(figures.boxShare, 0.60);
    const Result<PreparedExport> rendered = renderNest(laid.value());
    ASSERT_TRUE(rendered.isOk()) << rendered.status().message();
    const std::string dir = freshDir("nest-samples");
    ASSERT_TRUE(writeExport(rendered.value(), dir).isOk());
    expectPiecesApart(dir, built.sheets.size(), kerf + 1.0);
  }
}

}  // namespace
}  // namespace dform::test
