// SPDX-License-Identifier: GPL-3.0-or-later
// The labels of every shipped sample under every shipped profile, at true size, on small pieces
// (20 %) and on a dense seam (a tick every 3 mm): on the assembly page no two labels (the title,
// the steps, the thumbnails' names and start numbers, the 3D view's tick numbers and its note)
// overlap, each label's box being the box of the strokes it draws (they all read across the
// page); on the pattern no two labels' footprints overlap (the layout check's convex hulls: the
// seam's numbers turn with the seam).
#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "dform/io/model_files.h"
#include "matrix_samples.h"
#include "test_util.h"

namespace dform::test {
namespace {

using fab::Box;

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A text path of the assembly page, by its id.
bool isLabel(const std::string& id) {
  return id == "assembly-title" || id == "view-dropped-note" || id.rfind("step-", 0) == 0 ||
         endsWith(id, "-label") || endsWith(id, "-name");
}

// The page's labels and the pairs of them whose boxes share area, by id.
std::vector<std::pair<std::string, std::string>> overlappingLabels(const fab::Drawing& page,
                                                                   int& labels) {
  std::vector<std::pair<std::string, Box>> boxes;
  for (const fab::Layer& layer : page.layers)
    for (const fab::Path& path : layer.paths)
      if (isLabel(path.id) && !path.parts.empty())
        boxes.emplace_back(path.id, fab::boxOf(path.parts));
  labels += int(boxes.size());
  std::vector<std::pair<std::string, std::string>> out;
  for (size_t i = 0; i < boxes.size(); ++i)
    for (size_t j = i + 1; j < boxes.size(); ++j) {
      const Box& a = boxes[i].second;
      const Box& b = boxes[j].second;
      if (a.lo.x() < b.hi.x() && b.lo.x() < a.hi.x() && a.lo.y() < b.hi.y() && b.lo.y() < a.hi.y())
        out.emplace_back(boxes[i].first, boxes[j].first);
    }
  return out;
}

TEST(AssemblyLabels, BoxesThatShareAreaAreFoundAndOnlyThose) {
  fab::Drawing page;
  page.layers.emplace_back();
  auto add = [&](const std::string& id, double x0, double y0, double x1, double y1) {
    fab::Path p;
    p.id = id;
    p.parts = {{Vec2(x0, y0), Vec2(x1, y1)}};
    page.layers.back().paths.push_back(p);
  };
  add("view-tick-1-label", 0, 0, 4, 2);
  add("view-tick-2-label", 3.9, 1.9, 8, 4);  // shares a corner's area with tick 1's
  add("thumb-A-name", 4, 4, 6, 6);           // touches tick 2's box along an edge only
  add("view-tick-1", 0, 0, 10, 10);          // a dot: not a label
  int labels = 0;
  const auto found = overlappingLabels(page, labels);
  EXPECT_EQ(labels, 3);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0],
            std::make_pair(std::string("view-tick-1-label"), std::string("view-tick-2-label")));
}

class SampleAssembly : public ::testing::TestWithParam<MatrixSample> {};

TEST_P(SampleAssembly, NoTwoLabelsOverlap) {
  const MatrixSample& sample = GetParam();
  const std::string solved = solveSample(sample, "--gate lenient");
  const Result<DForm> model = readModel(solved);
  ASSERT_TRUE(model.isOk()) << model.status().message();
  int pages = 0, labels = 0, overlaps = 0, patternOverlaps = 0;
  for (const std::string& profileName : listProfiles(DFORM_TEMPLATES_DIR))
    for (const auto& [scale, spacing] : {std::pair{1.0, 0.0}, {0.2, 0.0}, {1.0, 3.0}}) {
      SCOPED_TRACE(sample.name + " " + profileName + " at " + std::to_string(scale) +
                   (spacing > 0 ? ", a tick every " + std::to_string(spacing) + " mm" : ""));
      ExportOptions o = options(profileName);
      o.jobName = sample.name;
      o.scaleToFit = true;
      o.scale = scale;
      if (spacing > 0) o.tickSpacingMm = spacing;
      const Result<LaidOutExport> laid = layOutExport(model.value(), o);
      ASSERT_TRUE(laid.isOk()) << laid.status().message();
      for (const auto& [a, b] : overlappingLabels(laid.value().pattern->build.assembly, labels)) {
        ADD_FAILURE() << a << " overlaps " << b;
        ++overlaps;
      }
      patternOverlaps += laid.value().layout.overlappingLabels;
      EXPECT_EQ(laid.value().layout.overlappingLabels, 0) << laid.value().layout.example;
      ++pages;
    }
  std::cout << sample.name << ": " << pages << " assembly pages, " << labels << " labels, "
            << overlaps << " overlapping pairs; " << patternOverlaps
            << " overlapping label pairs on the patterns\n";
  EXPECT_GT(labels, 20 * pages) << "the pages have their labels";
}

INSTANTIATE_TEST_SUITE_P(Shipped, SampleAssembly, ::testing::ValuesIn(matrixSamples()),
                         [](const ::testing::TestParamInfo<MatrixSample>& info) {
                           return testName(info.param);
                         });

}  // namespace
}  // namespace dform::test
