// SPDX-License-Identifier: GPL-3.0-or-later
// Every shipped sample, solved by the command line as a user would, exported with every shipped
// profile on A4 and on Letter (page profiles: --page; laser profiles: a sheet of that size) and
// read back: exit 0 (the layout check included), every piece on one sheet, the page count the
// fewest the pieces' sizes allow, the title block clear of the pieces, the seams' perimeters in
// the SVG within 0.1 mm of the solved ones times the scale. Everything is exported with
// --scale fit: a piece larger than the paper (circle+square's 257 mm square on A4) is scaled,
// and the scale is checked to be 1 wherever the pieces fit at true size, else the largest that
// fits, named by the refusal of a tenth of a percent more and stated on every sheet. A page
// profile's pages and assembly page share its paper; the laser profiles are laid out again in
// memory on 600 x 400 and 300 x 200 mm sheets, and on the larger with each sheet-material joint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "dform/io/model_files.h"
#include "shipped_samples.h"
#include "test_util.h"

namespace dform::test {
namespace {

namespace fs = std::filesystem;
using fab::Box;
using nlohmann::json;

std::string dform() { return DFORM_EXE; }

json readJson(const std::string& path) { return json::parse(std::ifstream(path)); }

struct Paper {
  const char* name;
  double w, h;  // portrait (mm)
};
constexpr Paper kPapers[] = {{"A4", 210, 297}, {"Letter", 215.9, 279.4}};

Box boxOfJson(const json& lines) {
  Box b;
  for (const auto& line : lines) b.add(toPolyline(line));
  return b;
}

// Where a profile lets artwork go on a W x H page (the rules of docs/export.md, restated).
Box artArea(const json& profile, double W, double H) {
  const double m = profile.value("margin_mm", 5.0);
  const std::string reg = profile.value("registration", std::string("none"));
  if (reg == "silhouette") {
    const double inset = 10 + 5 + profile.value("registration_clear_mm", 5.0);
    return Box::spanning(Vec2(inset, inset), Vec2(W - inset, H - inset));
  }
  if (reg == "cricut") {
    const Vec2 half(0.5 * std::min(6.75 * 25.4, W - 2 * m), 0.5 * std::min(9.25 * 25.4, H - 2 * m));
    return Box::spanning(Vec2(W, H) / 2 - half, Vec2(W, H) / 2 + half);
  }
  return Box::spanning(Vec2(m, m), Vec2(W - m, H - m));
}

// Whether two pieces of extents a and b (either turned a quarter) fit one W x H page together,
// side by side or stacked `gap` apart, with a title block `depth` deep under or beside them.
bool fitTogether(Vec2 a, Vec2 b, double gap, double depth, const Box& area) {
  for (int ta = 0; ta < 2; ++ta)
    for (int tb = 0; tb < 2; ++tb)
      for (bool stacked : {false, true}) {
        const Vec2 p = ta ? Vec2(a.y(), a.x()) : a, q = tb ? Vec2(b.y(), b.x()) : b;
        const Vec2 size = stacked ? Vec2(std::max(p.x(), q.x()), p.y() + gap + q.y())
                                  : Vec2(p.x() + gap + q.x(), std::max(p.y(), q.y()));
        if (size.x() > area.w() || size.y() > area.h()) continue;
        if (size.y() + gap + depth <= area.h() || size.x() + gap + depth <= area.w()) return true;
      }
  return false;
}

// Each piece is cut as one closed loop per boundary loop (its outline with its tabs in it, and
// each hole), counted in pattern.svg's Cut layer: a glue tab cut free would be one more.
void expectOneCutLoopPerBoundary(const std::string& dir) {
  const SvgDoc svg = readSvg(dir + "/pattern.svg");
  size_t loops = 0, boundaries = 0;
  for (const SvgPath& path : svg.paths)
    if ((path.layer == "Cut" || path.layer == "CutContour") && path.closed)
      loops += path.parts.size();
  const json pattern = readJson(dir + "/pattern.json");
  for (const auto& piece : pattern["pieces"]) boundaries += piece["boundaries"].size();
  EXPECT_EQ(loops, boundaries) << dir;
}

// A page profile's job is on one paper: every page of pattern.pdf (the pattern's, a landscape
// turn allowed, and the assembly page) and assembly.svg; and the PDF asks viewers not to scale
// it (the catalog's resolution through the trailer is ExportPattern.PdfPagesHaveTheSheetSize...).
void expectOnePaper(const std::string& dir, const Paper& paper) {
  std::string info;
  ASSERT_EQ(run("pdfinfo -f 1 -l 9999 " + dir + "/pattern.pdf", &info), 0) << info;
  const std::regex size(R"(Page +([0-9]+) size: +([0-9.]+) x ([0-9.]+) pts)");
  int pages = 0;
  for (auto it = std::sregex_iterator(info.begin(), info.end(), size); it != std::sregex_iterator();
       ++it) {
    ++pages;
    const double w = std::stod((*it)[2]) * 25.4 / 72, h = std::stod((*it)[3]) * 25.4 / 72;
    EXPECT_TRUE((std::abs(w - paper.w) < 0.1 && std::abs(h - paper.h) < 0.1) ||
                (std::abs(w - paper.h) < 0.1 && std::abs(h - paper.w) < 0.1))
        << "pattern.pdf page " << (*it)[1] << " is " << w << " x " << h << " mm";
  }
  EXPECT_GT(pages, 1) << info;
  const SvgDoc assembly = readSvg(dir + "/assembly.svg");
  EXPECT_NEAR(parseMm(assembly.width), paper.w, 1e-6);
  EXPECT_NEAR(parseMm(assembly.height), paper.h, 1e-6);
  EXPECT_NE(readText(dir + "/pattern.pdf").find("/PrintScaling /None"), std::string::npos);
}

// Each joint for sheet materials laid out with options `o`: its holes and slots are loops of their
// pieces, and the layout stays clean.
void expectJointsFit(const DForm& model, const ExportOptions& o) {
  for (Joint joint : {Joint::Holes, Joint::Lace, Joint::Slots}) {
    ExportOptions jo = o;
    jo.joint = joint;
    const Result<LaidOutExport> joined = layOutExport(model, jo);
    ASSERT_TRUE(joined.isOk()) << jointName(joint) << ": " << joined.status().message();
    EXPECT_EQ(joined.value().layout.problems(), 0)
        << jointName(joint) << ": " << joined.value().layout.example;
    const fab::PatternBuild& built = joined.value().pattern->build;
    EXPECT_GT(built.jointHoles.size() + built.jointSlots.size(), 4u) << jointName(joint);
    for (const fab::PieceInfo& piece : built.pieces)
      EXPECT_EQ(piece.cut.size() + piece.holeCuts.size(), piece.boundaries.size())
          << jointName(joint) << " " << piece.name;
  }
}

// A laser profile on the sheets a laser cuts (600 x 400 and 300 x 200 mm), laid out in memory
// from the solved model: scaled to fit where need be, one cut loop per boundary loop and a clean
// layout (with every joint too, on the larger sheet); a scale a tenth of a percent larger is
// refused naming the scale that fits.
void expectLaserSheets(const DForm& model, const std::string& profileName) {
  for (const auto& [w, h] : {std::pair{600.0, 400.0}, std::pair{300.0, 200.0}}) {
    SCOPED_TRACE(profileName + " on " + std::to_string(int(w)) + "x" + std::to_string(int(h)));
    ExportOptions o = options(profileName);
    o.sheetWidthMm = w;
    o.sheetHeightMm = h;
    o.sheetGiven = true;
    o.scaleToFit = true;
    const Result<LaidOutExport> laid = layOutExport(model, o);
    ASSERT_TRUE(laid.isOk()) << laid.status().message();
    EXPECT_EQ(laid.value().layout.problems(), 0) << laid.value().layout.example;
    const fab::PatternBuild& built = laid.value().pattern->build;
    for (const fab::PieceInfo& piece : built.pieces)
      EXPECT_EQ(piece.cut.size() + piece.holeCuts.size(), piece.boundaries.size()) << piece.name;
    if (w == 600.0) expectJointsFit(model, o);
    if (built.scale < 1.0) {
      o.scaleToFit = false;
      o.scale = built.scale + 0.001;
      const Result<LaidOutExport> larger = layOutExport(model, o);
      ASSERT_FALSE(larger.isOk());
      char named[64];
      std::snprintf(named, sizeof named, "largest scale that fits is %.1f %%", 100 * built.scale);
      EXPECT_NE(larger.status().message().find(named), std::string::npos)
          << larger.status().message();
    }
  }
}

class SamplePatterns : public ::testing::TestWithParam<std::string> {};

TEST_P(SamplePatterns, ExportOnA4AndLetterUnderEveryProfile) {
  const std::string sample = GetParam();
  const bool forward = sample.rfind("forward/", 0) == 0;
  const std::string solved = freshDir("solved");
  std::string out;
  // Solved under the lenient gate, which every sample passes (the pushed-in curve fails the
  // default one on its round trip): the export checks the result again under the gate it names.
  ASSERT_EQ(run(dform() + (forward ? " run " : " inverse ") + DFORM_SAMPLES_DIR + "/" + sample +
                    " --gate lenient --no-export -q -o " + solved,
                &out),
            0)
      << out;
  const Result<DForm> model = readModel(solved);
  ASSERT_TRUE(model.isOk()) << model.status().message();
  const json metrics = readJson(solved + "/report.json")["metrics"];
  const double seam[2] = {metrics["seam_length_a_mm"].get<double>(),
                          metrics["seam_length_b_mm"].get<double>()};
  int exports = 0, judged = 0;
  for (const std::string& profileName : listProfiles(DFORM_TEMPLATES_DIR)) {
    const json profile =
        readJson(std::string(DFORM_TEMPLATES_DIR) + "/profiles/" + profileName + ".json");
    const bool pageProfile = profile.contains("page");
    if (!pageProfile) expectLaserSheets(model.value(), profileName);
    for (const Paper& paper : kPapers) {
      SCOPED_TRACE(sample + " " + profileName + " " + paper.name);
      const std::string dir = freshDir("export");
      char sheet[64];
      std::snprintf(sheet, sizeof sheet, "%gx%gmm", paper.w, paper.h);
      const std::string paperOption =
          pageProfile ? std::string(" --page ") + paper.name : std::string(" --sheet ") + sheet;
      ASSERT_EQ(run(dform() + " export " + solved + " -o " + dir + " -q --scale fit --profile " +
                        profileName + paperOption,
                    &out),
                0)
          << out;
      ++exports;
      const json pattern = readJson(dir + "/pattern.json");
      const double scale = pattern["scale"].get<double>();
      const auto& sheets = pattern["sheets"];
      const auto& pages = pattern["pages"];
      if (pageProfile) expectOnePaper(dir, paper);
      expectOneCutLoopPerBoundary(dir);
      // No page shows another sheet's geometry: each page's window of the canvas lies within one
      // sheet (a page map or a cover page shows none).
      for (const auto& page : pages) {
        const Polyline window = toPolyline(page["window"]);
        const Box shown = Box::spanning(window[0], window[1]);
        if (shown.w() <= 0 || shown.h() <= 0) continue;
        bool within = false;
        for (const auto& s : sheets) {
          const Vec2 lo = toPolyline(json::array({s["origin"]}))[0];
          within = within ||
                   Box::spanning(lo, lo + Vec2(s["width"].get<double>(), s["height"].get<double>()))
                       .contains(shown, 1e-6);
        }
        EXPECT_TRUE(within) << page["kind"] << " page shows more than one sheet";
      }
      if (profileName == "laser") {  // tabs on the square, the Squaricle's square too
        const std::string onB = freshDir("tabs-b");
        ASSERT_EQ(run(dform() + " export " + solved + " -o " + onB + " -q --scale fit --tabs b" +
                          " --profile laser" + paperOption,
                      &out),
                  0)
            << out;
        expectOneCutLoopPerBoundary(onB);
      }
      // Each piece lies on its own sheet, wholly.
      Vec2 extent[2];
      for (int p = 0; p < 2; ++p) {
        const json& piece = pattern["pieces"][p];
        const json& onSheet = sheets[piece["sheet"].get<size_t>()];
        const Vec2 lo = toPolyline(json::array({onSheet["origin"]}))[0];
        const Box sheetBox = Box::spanning(
            lo, lo + Vec2(onSheet["width"].get<double>(), onSheet["height"].get<double>()));
        const Box cut = boxOfJson(piece["cut"]);
        EXPECT_TRUE(sheetBox.contains(cut, 1e-6)) << "piece " << p << " runs off its sheet";
        extent[p] = Vec2(cut.w(), cut.h()) + Vec2::Constant(2 * 1.5);  // ticks stick out 1.5 mm
        // The seam as drawn is the solved one, scaled.
        EXPECT_NEAR(length(toPolyline(piece["outline"]), true), scale * seam[p], kMmTol);
      }
      // The fewest pages: one sheet when both fit one page with the mark (the job's name over
      // the 50 mm bar, at most 15 mm deep with the scale's line) under or beside them, two when
      // they do not fit one page even bare; a tiled piece's pages are its map and its tiles.
      const double W = paper.w, H = paper.h;
      const double margin = profile.value("margin_mm", 5.0);
      const bool turnable = profile.value("kind", std::string()) == "print";
      auto together = [&](double d) {
        return fitTogether(extent[0], extent[1], margin, d, artArea(profile, W, H)) ||
               (turnable && fitTogether(extent[0], extent[1], margin, d, artArea(profile, H, W)));
      };
      if (together(15)) {
        EXPECT_EQ(sheets.size(), 1u) << "pieces that fit together with the mark share a page";
        ++judged;
      } else if (!together(0)) {
        EXPECT_EQ(sheets.size(), 2u);
        ++judged;
      }
      size_t expectedPages = 0;
      for (const auto& s : sheets) {
        const double sw = s["width"].get<double>(), sh = s["height"].get<double>();
        const bool paperSized = (std::abs(sw - W) < 1e-6 && std::abs(sh - H) < 1e-6) ||
                                (std::abs(sw - H) < 1e-6 && std::abs(sh - W) < 1e-6);
        if (paperSized) {
          ++expectedPages;
          continue;
        }
        // Tiles: windows of the page less 10 mm margins and a 12 mm header, overlapping.
        ASSERT_TRUE(turnable) << "only a print profile tiles";
        const double ov = profile.value("tile_overlap_mm", 10.0);
        auto count = [&](double length, double window) {
          return size_t(std::max(1.0, std::ceil((length - ov) / (window - ov) - 1e-9)));
        };
        expectedPages += 1 + count(sw, W - 20) * count(sh, H - 32);
      }
      EXPECT_EQ(pages.size(), expectedPages) << "a page per sheet, no cover page";
      // True size wherever the pieces fit at true size, else the largest tenth of a percent
      // that fits: a tenth more is refused as too large, with a message naming that scale. Every
      // sheet of a scaled pattern says so in words.
      if (scale < 1.0) {
        char larger[16], named[64];
        std::snprintf(larger, sizeof larger, "%.4f", scale + 0.001);
        std::snprintf(named, sizeof named, "largest scale that fits is %.1f %%", 100 * scale);
        EXPECT_EQ(run(dform() + " export " + solved + " -o " + freshDir("larger") + " -q --scale " +
                          larger + " --profile " + profileName + paperOption,
                      &out),
                  2)
            << out;
        EXPECT_NE(out.find("does not fit"), std::string::npos) << out;
        EXPECT_NE(out.find(named), std::string::npos) << out;
        size_t notes = 0;
        for (const SvgPath& path : readSvg(dir + "/pattern.svg").paths)
          notes += path.id.rfind("scale-note", 0) == 0;
        EXPECT_EQ(notes, sheets.size()) << "a sheet that does not state its scale";
      }
      // The seams' perimeters in the SVG and the DXF: exported again without tabs, each piece's
      // cut path is its seam (no shipped profile has a kerf).
      if (profileName == "laser" || profileName == "print-and-cut") {
        const std::string bare = freshDir("bare");
        ASSERT_EQ(run(dform() + " export " + solved + " -o " + bare + " -q --tabs none --scale " +
                          std::to_string(scale) + " --profile " + profileName + paperOption,
                      &out),
                  0)
            << out;
        const SvgDoc svg = readSvg(bare + "/pattern.svg");
        const std::vector<PdfPath> pdfPaths = readPdfPaths(bare + "/pattern.pdf");
        const json barePattern = readJson(bare + "/pattern.json");
        for (int p = 0; p < 2; ++p) {
          // A seam that is a hole's loop (anti and demi D-Forms) is cut as the piece's hole.
          const std::string id =
              std::string(p == 0 ? "A" : "B") +
              (barePattern["pieces"][p]["seam_is_hole"].get<bool>() ? "-cut-hole-1" : "-cut");
          const SvgPath* seamCut = svg.find(id);
          ASSERT_NE(seamCut, nullptr) << id;
          EXPECT_NEAR(length(seamCut->parts[0], true), scale * seam[p], kMmTol) << id;
          // The PDF draws the same seam (so its perimeter too); a print-and-cut PDF, whose cut
          // line is the cutter's, prints the piece's tint out to the bleed instead.
          const SvgPath* tint = svg.find(std::string(p == 0 ? "A" : "B") + "-bleed");
          if (tint) {
            for (const Polyline& loop : tint->parts)
              EXPECT_LT(closestDrawing(pdfPaths, loop), kMmTol) << id << "'s tint in pattern.pdf";
          } else {
            EXPECT_LT(closestDrawing(pdfPaths, seamCut->parts[0]), kMmTol)
                << id << " in pattern.pdf";
          }
        }
        // And in the DXF (and each sheet's), read back with ezdxf.
        expectDxfChecks(bare, "--seam " + std::to_string(scale * seam[0]) + " " +
                                  std::to_string(scale * seam[1]));
      }
    }
  }
  EXPECT_EQ(exports, 2 * int(listProfiles(DFORM_TEMPLATES_DIR).size()));
  EXPECT_GT(judged, exports / 2) << "most sheet counts are judged, not on the edge";
}

// The files of a folder and their contents.
std::map<std::string, std::string> snapshot(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir))
    files[entry.path().filename()] = readText(entry.path());
  return files;
}

TEST(SampleExport, IntoAnotherFolderLeavesTheResultAsItWasAndProfilesSitSideBySide) {
  const std::string solved = freshDir("solved-ellipses");
  std::string out;
  ASSERT_EQ(run(dform() + " run " + DFORM_SAMPLES_DIR +
                    "/forward/ellipses-quarter-turn.json -q -o " + solved,
                &out),
            0)
      << out;
  const auto before = snapshot(solved);
  const std::string laser = freshDir("side") + "/laser", print = freshDir("side") + "/print";
  ASSERT_EQ(run(dform() + " export " + solved + " -o " + laser + " -q --profile laser", &out), 0)
      << out;
  ASSERT_EQ(
      run(dform() + " export " + solved + " -o " + print + " -q --profile print --page Letter",
          &out),
      0)
      << out;
  EXPECT_EQ(snapshot(solved), before) << "the result folder is untouched";
  EXPECT_EQ(readJson(laser + "/pattern.json")["profile"], "laser");
  EXPECT_EQ(readJson(print + "/pattern.json")["profile"], "print");
  EXPECT_NEAR(readJson(print + "/pattern.json")["pages"][0]["width"].get<double>(), 215.9, 1e-9);
  // A page profile refuses a sheet size, a sheet profile a page, with a message.
  EXPECT_EQ(run(dform() + " export " + solved + " -o " + freshDir("refused") +
                    " --profile print --sheet 297x420mm",
                &out),
            2);
  EXPECT_NE(out.find("--page"), std::string::npos) << out;
  EXPECT_EQ(run(dform() + " export " + solved + " -o " + freshDir("refused") +
                    " --profile laser --page A4",
                &out),
            2);
  EXPECT_NE(out.find("--sheet"), std::string::npos) << out;
}

INSTANTIATE_TEST_SUITE_P(Shipped, SamplePatterns, ::testing::ValuesIn(shippedSamples()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param.substr(0, info.param.rfind('.'));
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace dform::test
