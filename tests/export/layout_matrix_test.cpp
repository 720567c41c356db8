// SPDX-License-Identifier: GPL-3.0-or-later
// The shop floor's matrix: every shipped sample laid out under every shipped profile on its papers
// (page profiles: A4, Letter and A3; sheet profiles: 600 x 400 and 300 x 200 mm), with the title
// and without, with each joint. Over all of it: the title never costs a page or a sheet, every
// page that is cut carries a 50 mm bar and the job's name, and no tick number comes within
// 0.3 mm of a joint hole or slot.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "dform/io/model_files.h"
#include "matrix_samples.h"
#include "test_util.h"

namespace dform::test {
namespace {

using fab::Box;

// The id without a "-page-N" suffix (a later sheet's copy of the sheet furniture).
std::string baseId(const std::string& id) {
  const size_t at = id.rfind("-page-");
  return at == std::string::npos ? id : id.substr(0, at);
}

const fab::Path* pathOn(const std::vector<fab::Layer>& layers, const std::string& id,
                        const Box& sheet) {
  for (const fab::Layer& layer : layers)
    for (const fab::Path& path : layer.paths)
      if (baseId(path.id) == id && sheet.contains(fab::boxOf(path.parts), 1e-6)) return &path;
  return nullptr;
}

// What one layout showed: its sheets and pages, and the problems the matrix counts.
struct Counts {
  size_t sheets = 0, pages = 0;
  int cutPages = 0, missingBar = 0, missingName = 0, labelsNearJoints = 0, labelsChecked = 0;
  std::string example;
};

double segmentDistance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  auto toSegment = [](const Vec2& q, const Vec2& p0, const Vec2& p1) {
    const Vec2 e = p1 - p0;
    const double t = std::clamp((q - p0).dot(e) / std::max(e.squaredNorm(), 1e-300), 0.0, 1.0);
    return (p0 + t * e - q).norm();
  };
  Vec2 at;
  if (crossing({c, d}, a, b, &at)) return 0;
  return std::min({toSegment(a, c, d), toSegment(b, c, d), toSegment(c, a, b), toSegment(d, a, b)});
}

// Every tick number of each piece at least 0.3 mm from its joint holes and slots, stroke by
// stroke (the loops as designed, before any kerf).
void countLabelsNearJoints(const fab::PatternBuild& built, Counts& counts) {
  for (const fab::PieceInfo& piece : built.pieces) {
    if (piece.jointLoops.empty()) continue;
    for (const fab::Layer& layer : built.drawing.layers)
      for (const fab::Path& path : layer.paths) {
        if (path.id.rfind(piece.name + "-tick-", 0) != 0 ||
            path.id.find("-label") == std::string::npos)
          continue;
        ++counts.labelsChecked;
        double nearest = 1e300;
        const Box near = fab::boxOf(path.parts);
        for (const Polyline& loop : piece.jointLoops) {
          const Box lb = fab::boxOf({loop});
          if (lb.lo.x() > near.hi.x() + 1 || lb.hi.x() < near.lo.x() - 1 ||
              lb.lo.y() > near.hi.y() + 1 || lb.hi.y() < near.lo.y() - 1)
            continue;
          for (const Polyline& stroke : path.parts)
            for (size_t i = 0; i + 1 < stroke.size(); ++i)
              for (size_t j = 0; j < loop.size(); ++j)
                nearest = std::min(nearest, segmentDistance(stroke[i], stroke[i + 1], loop[j],
                                                            loop[(j + 1) % loop.size()]));
        }
        if (nearest < 0.3 - 1e-9) {
          ++counts.labelsNearJoints;
          if (counts.example.empty())
            counts.example = path.id + " is " + std::to_string(nearest) + " mm from a joint";
        }
      }
  }
}

Counts measure(const fab::PatternBuild& built, const ExportOptions& o,
               const fab::StrokeFont& font) {
  Counts counts;
  counts.sheets = built.sheets.size();
  counts.pages = built.pages.size();
  const bool bar = built.profile.calibrationBar;
  auto note = [&](const std::string& what) {
    if (counts.example.empty()) counts.example = what;
  };
  for (size_t k = 0; k < built.pages.size(); ++k) {
    const fab::PageView& page = built.pages[k];
    if (page.kind == "tile") {  // its own header and bar, in its furniture
      ++counts.cutPages;
      const fab::Path* header = nullptr;
      const fab::Path* tileBar = nullptr;
      for (const fab::Layer& layer : page.overlay)
        for (const fab::Path& path : layer.paths) {
          if (path.id == "tile-header") header = &path;
          if (path.id == "tile-calibration-bar") tileBar = &path;
        }
      if (!tileBar || std::abs(length(tileBar->parts[0], false) - 50.0) > 0.05) {
        ++counts.missingBar;
        note("tile page " + std::to_string(k + 1) + " has no 50 mm bar");
      }
      if (!header || !startsWithText(*header, o.jobName, font)) {
        ++counts.missingName;
        note("tile page " + std::to_string(k + 1) + " does not name the job");
      }
      continue;
    }
    if (page.kind != "sheet") continue;
    // The sheet this page shows, and what is drawn on it.
    const Box shown = Box::spanning(page.origin, page.origin + Vec2(page.width, page.height));
    bool tiledSheet = false;
    for (const Box& sheet : built.sheets)
      tiledSheet = tiledSheet || (sheet.contains(shown, 1e-6) && !shown.contains(sheet, 1e-6));
    if (tiledSheet) continue;
    ++counts.cutPages;
    const std::vector<fab::Layer>& layers = built.drawing.layers;
    const fab::Path* calibration = pathOn(layers, "calibration-bar", shown);
    if (bar && (!calibration || std::abs(length(calibration->parts[0], false) - 50.0) > 0.05)) {
      ++counts.missingBar;
      note("sheet page " + std::to_string(k + 1) + " has no 50 mm bar");
    }
    const fab::Path* title = pathOn(layers, "title", shown);
    const fab::Path* name = pathOn(layers, "job-name", shown);
    if (!(title && startsWithText(*title, o.jobName, font)) &&
        !(name && startsWithText(*name, o.jobName, font))) {
      ++counts.missingName;
      note("sheet page " + std::to_string(k + 1) + " does not name the job");
    }
  }
  countLabelsNearJoints(built, counts);
  return counts;
}

struct PaperSize {
  std::string page;  // a page profile's --page, or empty
  double w = 0, h = 0;
};

std::vector<PaperSize> papersFor(const Profile& profile) {
  if (!profile.page.empty()) return {{"A4"}, {"Letter"}, {"A3"}};
  return {{"", 600, 400}, {"", 300, 200}};
}

class SampleMatrix : public ::testing::TestWithParam<MatrixSample> {};

TEST_P(SampleMatrix, TitleCostsNoPageAndEveryCutPageHasTheBarTheNameAndClearNumbers) {
  const MatrixSample& sample = GetParam();
  const std::string solved = solveSample(sample, "--gate lenient");
  const Result<DForm> model = readModel(solved);
  ASSERT_TRUE(model.isOk()) << model.status().message();
  const Result<fab::StrokeFont> font = fab::StrokeFont::load(ExportOptions{}.fontPath);
  ASSERT_TRUE(font.isOk());
  int layouts = 0, titledMore = 0, cutPages = 0, missingBar = 0, missingName = 0, nearJoints = 0,
      labels = 0;
  for (const std::string& profileName : listProfiles(DFORM_TEMPLATES_DIR)) {
    const Result<Profile> profile = loadProfile(profileName, DFORM_TEMPLATES_DIR);
    ASSERT_TRUE(profile.isOk());
    for (const PaperSize& paper : papersFor(profile.value()))
      for (Joint joint : {Joint::Glue, Joint::Holes, Joint::Lace, Joint::Slots}) {
        Counts byTitle[2];
        for (bool title : {true, false}) {
          std::ostringstream where;
          where << sample.name << " " << profileName << " "
                << (paper.page.empty()
                        ? std::to_string(int(paper.w)) + "x" + std::to_string(int(paper.h))
                        : paper.page)
                << " " << jointName(joint) << (title ? "" : " --no-title");
          SCOPED_TRACE(where.str());
          ExportOptions o = options(profileName);
          o.jobName = sample.name;
          o.page = paper.page;
          if (paper.page.empty()) {
            o.sheetWidthMm = paper.w;
            o.sheetHeightMm = paper.h;
            o.sheetGiven = true;
          }
          o.scaleToFit = true;
          o.title = title;
          o.joint = joint;
          const Result<LaidOutExport> laid = layOutExport(model.value(), o);
          ASSERT_TRUE(laid.isOk()) << laid.status().message();
          EXPECT_EQ(laid.value().layout.problems(), 0) << laid.value().layout.example;
          const Counts c = measure(laid.value().pattern->build, o, font.value());
          EXPECT_EQ(c.missingBar + c.missingName + c.labelsNearJoints, 0) << c.example;
          byTitle[title ? 0 : 1] = c;
          ++layouts;
          cutPages += c.cutPages;
          missingBar += c.missingBar;
          missingName += c.missingName;
          nearJoints += c.labelsNearJoints;
          labels += c.labelsChecked;
        }
        const bool more =
            byTitle[0].pages > byTitle[1].pages || byTitle[0].sheets > byTitle[1].sheets;
        titledMore += more;
        EXPECT_FALSE(more) << sample.name << " " << profileName << " " << paper.page
                           << ": the title costs a page (" << byTitle[0].pages << " pages, "
                           << byTitle[0].sheets << " sheets, against " << byTitle[1].pages
                           << " and " << byTitle[1].sheets << ")";
      }
  }
  std::cout << sample.name << ": " << layouts << " layouts, " << titledMore
            << " titled with more pages, " << cutPages << " cut pages (" << missingBar
            << " without a bar, " << missingName << " without the name), " << labels
            << " tick numbers beside joints (" << nearJoints << " within 0.3 mm)\n";
  EXPECT_GT(cutPages, layouts) << "every layout has a cut page";
  EXPECT_GT(labels, 0) << "the joints had numbers beside them";
}

INSTANTIATE_TEST_SUITE_P(Shipped, SampleMatrix, ::testing::ValuesIn(matrixSamples()),
                         [](const ::testing::TestParamInfo<MatrixSample>& info) {
                           return testName(info.param);
                         });

}  // namespace
}  // namespace dform::test
