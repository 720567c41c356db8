// SPDX-License-Identifier: GPL-3.0-or-later
// The assembly page, read back from assembly.svg and pattern.pdf: the pieces' thumbnails are the
// cut pieces scaled, with the start on tick 0 and the zip running to tick 1; the 3D view's tick
// dots lie on its seam in seam order; the steps are numbered, keep off the pictures and say how
// the pattern's joint closes the seam; the PDF's last page is the page.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <tuple>
#include <vector>

#include "export/internal.h"
#include "models.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

Vec2 centre(const Polyline& loop) {
  Vec2 sum = Vec2::Zero();
  for (const Vec2& q : loop) sum += q;
  return sum / double(loop.size());
}

Vec2 boxLo(const std::vector<Polyline>& parts) {
  Vec2 lo(1e300, 1e300);
  for (const Polyline& p : parts)
    for (const Vec2& q : p) lo = lo.cwiseMin(q);
  return lo;
}

Vec2 boxHi(const std::vector<Polyline>& parts) {
  Vec2 hi(-1e300, -1e300);
  for (const Polyline& p : parts)
    for (const Vec2& q : p) hi = hi.cwiseMax(q);
  return hi;
}

// Arc length along the closed polyline to its point nearest `q`, and that distance.
std::pair<double, double> arcOn(const Polyline& loop, const Vec2& q) {
  double acc = 0, best = 1e300, at = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    const double len = (b - a).norm();
    const double t = len > 0 ? std::clamp((q - a).dot(b - a) / (len * len), 0.0, 1.0) : 0.0;
    const double d = (a + t * (b - a) - q).norm();
    if (d < best) best = d, at = acc + t * len;
    acc += len;
  }
  return {at, best};
}

struct Assembly {
  Exported e;
  SvgDoc page;
};

Assembly exportAssembly(const std::string& name, const std::string& profile) {
  Assembly a;
  a.e = exportTo(name, ellipseCircleDForm(), options(profile));
  a.page = readSvg(a.e.dir + "/assembly.svg");
  return a;
}

TEST(Assembly, IsThePdfsLastPageAndAFileOfItsOwn) {
  for (const auto& [profile, W, H] :
       {std::tuple{"laser", 210.0, 297.0}, std::tuple{"print-letter", 215.9, 279.4}}) {
    const Assembly a = exportAssembly(std::string("asm-pages-") + profile, profile);
    EXPECT_DOUBLE_EQ(parseMm(a.page.width), W) << profile;
    EXPECT_DOUBLE_EQ(parseMm(a.page.height), H) << profile;
    ASSERT_NE(a.page.find("view-seam"), nullptr);
    // The PDF: the pattern's pages, then this one, which draws the same seam.
    const std::vector<PdfPath> pdf = readPdfPaths(a.e.dir + "/pattern.pdf");
    int lastPage = 0;
    for (const PdfPath& p : pdf) lastPage = std::max(lastPage, p.page);
    EXPECT_EQ(lastPage, a.e.summary.pages + 1) << profile;
    std::vector<PdfPath> onLast;
    for (const PdfPath& p : pdf)
      if (p.page == lastPage) onLast.push_back(p);
    EXPECT_LT(closestDrawing(onLast, a.page.find("view-seam")->parts[0]), 0.1) << profile;
  }
}

TEST(Assembly, SharesTheJobsPaperWithEveryPatternPage) {
  // --page over the profile's paper: every page of pattern.pdf (the pattern's, a landscape turn
  // of the paper allowed, and the assembly page) and assembly.svg are that paper.
  for (const auto& [profile, page, W, H] : {std::tuple{"print-letter", "A4", 210.0, 297.0},
                                            std::tuple{"print-and-cut-cricut", "A4", 210.0, 297.0},
                                            std::tuple{"print", "Letter", 215.9, 279.4},
                                            std::tuple{"print-and-cut", "Letter", 215.9, 279.4}}) {
    SCOPED_TRACE(std::string(profile) + " on " + page);
    ExportOptions o = options(profile);
    o.page = page;
    const Exported e = exportTo(std::string("asm-paper-") + profile, ellipseCircleDForm(), o);
    const SvgDoc assembly = readSvg(e.dir + "/assembly.svg");
    EXPECT_NEAR(parseMm(assembly.width), W, 1e-6);
    EXPECT_NEAR(parseMm(assembly.height), H, 1e-6);
    std::string info;
    ASSERT_EQ(run("pdfinfo -f 1 -l 999 " + e.dir + "/pattern.pdf", &info), 0) << info;
    const std::regex size(R"(Page +([0-9]+) size: +([0-9.]+) x ([0-9.]+) pts)");
    int pages = 0;
    for (auto it = std::sregex_iterator(info.begin(), info.end(), size);
         it != std::sregex_iterator(); ++it) {
      ++pages;
      const double w = std::stod((*it)[2]) * 25.4 / 72, h = std::stod((*it)[3]) * 25.4 / 72;
      const bool paper = (std::abs(w - W) < 0.1 && std::abs(h - H) < 0.1) ||
                         (std::abs(w - H) < 0.1 && std::abs(h - W) < 0.1);
      EXPECT_TRUE(paper) << "page " << (*it)[1] << " is " << w << " x " << h << " mm";
    }
    EXPECT_EQ(pages, e.summary.pages + 1) << info;
  }
}

TEST(Assembly, TheViewShowsMostOfTheSeamAndTheStart) {
  // A lens (two caps on an ellipse) seen from 25 degrees above hides the back half of its seam
  // whatever the azimuth; seen from higher up, all of it: the view chosen shows over 90 % of the
  // seam drawn (screen length of the seam in sight over the whole seam's), tick 0's dot in sight.
  const Assembly a = exportAssembly("asm-view", "laser");
  const SvgPath* seam = a.page.find("view-seam");
  const SvgPath* inSight = a.page.find("view-seam-in-sight");
  ASSERT_NE(seam, nullptr);
  ASSERT_NE(inSight, nullptr);
  double seen = 0;
  for (const Polyline& part : inSight->parts) seen += length(part, false);
  EXPECT_GT(seen / length(seam->parts[0], true), 0.9);
  const SvgPath* start = a.page.find("view-tick-0");
  ASSERT_NE(start, nullptr);
  EXPECT_EQ(start->layer, "Marks") << "tick 0 hidden";
}

TEST(Assembly, NoTwoLabelsOverlap) {
  // Ticks every 8 mm round long, thin ellipses crowd the numbers at the 3D view's tips: each
  // number takes a free spot (with a leader where it is not the nearest) or is left out, and a
  // note counts those left out. Label footprints are their drawn boxes in assembly.svg.
  for (const auto& [ax, by] : {std::pair{80.0, 50.0}, std::pair{120.0, 20.0}}) {
    SCOPED_TRACE("ellipse " + std::to_string(ax) + " x " + std::to_string(by));
    ExportOptions o = options("print");
    o.tickSpacingMm = 8;
    const Exported e = exportTo("asm-labels", ellipseCircleDForm(64, 8, ax, by), o);
    const SvgDoc page = readSvg(e.dir + "/assembly.svg");
    std::vector<std::pair<std::string, std::pair<Vec2, Vec2>>> boxes;
    int viewLabels = 0;
    bool note = false;
    for (const SvgPath& p : page.paths) {
      const bool label = p.id.size() > 6 && p.id.compare(p.id.size() - 6, 6, "-label") == 0;
      const bool name = p.id.size() > 5 && p.id.compare(p.id.size() - 5, 5, "-name") == 0;
      note = note || p.id == "view-dropped-note";
      if (!label && !name && p.id != "view-dropped-note") continue;
      viewLabels += p.id.rfind("view-tick-", 0) == 0;
      boxes.push_back({p.id, {boxLo(p.parts), boxHi(p.parts)}});
    }
    const int ticks = int(e.sidecar["ticks"].size());
    EXPECT_GE(ticks, 40);
    EXPECT_TRUE(viewLabels == ticks || note) << viewLabels << " of " << ticks << ", no note";
    for (size_t i = 0; i < boxes.size(); ++i)
      for (size_t j = i + 1; j < boxes.size(); ++j) {
        const auto& [lo1, hi1] = boxes[i].second;
        const auto& [lo2, hi2] = boxes[j].second;
        const bool overlap =
            lo1.x() < hi2.x() && lo2.x() < hi1.x() && lo1.y() < hi2.y() && lo2.y() < hi1.y();
        EXPECT_FALSE(overlap) << boxes[i].first << " and " << boxes[j].first;
      }
  }
}

TEST(Assembly, ThumbnailsAreThePiecesScaledWithTheStartOnTickZero) {
  const Assembly a = exportAssembly("asm-thumbs", "laser");
  const auto& ticks = a.e.sidecar["ticks"];
  ASSERT_GE(ticks.size(), 2u);
  for (int p = 0; p < 2; ++p) {
    const std::string name = p == 0 ? "A" : "B";
    const SvgPath* thumb = a.page.find("thumb-" + name + "-cut");
    ASSERT_NE(thumb, nullptr) << name;
    std::vector<Polyline> cut;
    for (const auto& loop : a.e.sidecar["pieces"][p]["cut"]) cut.push_back(toPolyline(loop));
    ASSERT_EQ(thumb->parts.size(), cut.size());
    ASSERT_EQ(thumb->parts[0].size(), cut[0].size());
    // One scale and a shift map the piece onto the thumbnail.
    const Vec2 tlo = boxLo(thumb->parts);
    const double k = (boxHi(thumb->parts) - tlo).x() / (boxHi(cut) - boxLo(cut)).x();
    EXPECT_GT(k, 0.05);
    EXPECT_LT(k, 1.0) << "smaller than the piece";
    auto map = [&](const Vec2& q) { return Vec2(tlo + k * (q - boxLo(cut))); };
    double worst = 0;
    for (size_t i = 0; i < cut[0].size(); ++i)
      worst = std::max(worst, (map(cut[0][i]) - thumb->parts[0][i]).norm());
    EXPECT_LT(worst, 1e-3) << name << ": the thumbnail is the piece, scaled";
    // The start dot on tick 0, and the zip from it to tick 1.
    const char* side = p == 0 ? "a" : "b";
    const SvgPath* start = a.page.find("thumb-" + name + "-start");
    ASSERT_NE(start, nullptr);
    const Vec2 tick0 = map(Vec2(ticks[0][side][0].get<double>(), ticks[0][side][1].get<double>()));
    const Vec2 tick1 = map(Vec2(ticks[1][side][0].get<double>(), ticks[1][side][1].get<double>()));
    EXPECT_LT((centre(start->parts[0]) - tick0).norm(), 1e-3) << name;
    const SvgPath* zip = a.page.find("thumb-" + name + "-zip");
    ASSERT_NE(zip, nullptr);
    EXPECT_LT((zip->parts[0].front() - tick0).norm(), 1e-3) << name;
    EXPECT_LT((zip->parts[0].back() - tick1).norm(), 1e-3) << name << ": the arrow ends at tick 1";
    EXPECT_LT((zip->parts[1][1] - tick1).norm(), 1e-3) << name << ": the arrowhead's tip";
  }
}

TEST(Assembly, TickDotsLieOnTheSeamInSeamOrder) {
  const Assembly a = exportAssembly("asm-view", "laser");
  const SvgPath* seam = a.page.find("view-seam");
  ASSERT_NE(seam, nullptr);
  const Polyline& loop = seam->parts[0];
  double L = 0;
  for (size_t i = 0; i < loop.size(); ++i) L += (loop[(i + 1) % loop.size()] - loop[i]).norm();
  const size_t n = a.e.sidecar["ticks"].size();
  double previous = -1, first = 0;
  for (size_t k = 0; k < n; ++k) {
    const SvgPath* dot = a.page.find("view-tick-" + std::to_string(k));
    ASSERT_NE(dot, nullptr) << k;
    ASSERT_NE(a.page.find("view-tick-" + std::to_string(k) + "-label"), nullptr) << k;
    const auto [s, off] = arcOn(loop, centre(dot->parts[0]));
    EXPECT_LT(off, 1e-3) << "tick " << k << " is on the seam";
    if (k == 0) first = s;
    const double along = std::fmod(s - first + L, L);  // from tick 0, the way the seam runs
    EXPECT_GT(along, previous) << "tick " << k << " follows tick " << k - 1;
    previous = along;
  }
  EXPECT_EQ(a.page.find("view-tick-" + std::to_string(n)), nullptr);
  // Seen from above (the view that shows the most of this lens's seam: from 25 degrees up its
  // far rim would be behind it, grey on the Hidden layer), every tick is in sight; the seam in
  // sight is drawn over its own line.
  int hidden = 0;
  for (size_t k = 0; k < n; ++k)
    hidden += a.page.find("view-tick-" + std::to_string(k))->layer == "Hidden";
  EXPECT_EQ(hidden, 0);
  const SvgPath* seen = a.page.find("view-seam-in-sight");
  ASSERT_NE(seen, nullptr);
  double seenLength = 0;
  for (const Polyline& part : seen->parts)
    for (size_t i = 0; i < part.size(); ++i) {
      EXPECT_LT(arcOn(loop, part[i]).second, 1e-6);
      if (i > 0) seenLength += (part[i] - part[i - 1]).norm();
    }
  EXPECT_GT(seenLength, 0.9 * L);
  EXPECT_LE(seenLength, L + 1e-6);
  // The picture is shaded faces in the colour of the piece seen, A (warm, the upper cap).
  int warm = 0, cool = 0;
  for (const SvgPath& p : a.page.paths) {
    if (p.id.rfind("view-faces-", 0) != 0) continue;
    const unsigned long rgb = std::stoul(p.fill.substr(1), nullptr, 16);
    const int r = int(rgb >> 16), b = int(rgb & 0xFF);
    (r > b ? warm : cool) += 1;
  }
  EXPECT_GT(warm, 0);
  EXPECT_EQ(cool, 0);
}

TEST(Assembly, StepsAreNumberedAndKeepOffThePictures) {
  for (const char* profile : {"laser", "print", "print-and-cut"}) {
    const Assembly a = exportAssembly(std::string("asm-steps-") + profile, profile);
    int steps = 0;
    while (a.page.find("step-" + std::to_string(steps + 1) + "-number")) ++steps;
    EXPECT_GE(steps, 4) << profile;
    EXPECT_LE(steps, 6) << profile;
    // Every drawn thing on the page inside its 10 mm margin; no step line on a picture.
    const double W = parseMm(a.page.width), H = parseMm(a.page.height);
    std::vector<std::pair<Vec2, Vec2>> pictures, lines;
    for (const SvgPath& p : a.page.paths) {
      const Vec2 lo = boxLo(p.parts), hi = boxHi(p.parts);
      EXPECT_TRUE(lo.x() >= 10 && lo.y() >= 10 && hi.x() <= W - 10 && hi.y() <= H - 10)
          << profile << ": " << p.id;
      if (p.id.rfind("step-", 0) == 0) lines.emplace_back(lo, hi);
      if (p.id.rfind("view-", 0) == 0 || p.id.rfind("thumb-", 0) == 0)
        pictures.emplace_back(lo, hi);
    }
    for (const auto& [llo, lhi] : lines)
      for (const auto& [plo, phi] : pictures)
        EXPECT_FALSE(llo.x() < phi.x() && plo.x() < lhi.x() && llo.y() < phi.y() &&
                     plo.y() < lhi.y())
            << profile << ": a step line on a picture";
  }
}

TEST(Assembly, TheStepsFollowTheJoint) {
  // Each joint's steps say how it closes the seam, and none but glue without tabs says tape.
  const DForm tetra = tetraDForm(6, 60.0);
  auto stepsFor = [&](Joint joint, std::optional<TabSide> tabs) {
    ExportOptions o = options();
    o.joint = joint;
    o.tabSide = tabs;
    std::string all;
    for (const std::string& step : fab::assemblySteps(build(tetra, o))) all += step + "\n";
    return all;
  };
  const std::map<Joint, std::string> says = {
      {Joint::Holes, "cable tie"}, {Joint::Lace, "lacing"}, {Joint::Slots, "through the slot"}};
  for (const auto& [joint, phrase] : says) {
    const std::string steps = stepsFor(joint, std::nullopt);
    EXPECT_NE(steps.find(phrase), std::string::npos) << jointName(joint) << ":\n" << steps;
    EXPECT_EQ(steps.find("tape"), std::string::npos) << jointName(joint) << ":\n" << steps;
    EXPECT_EQ(steps.find("tabs"), std::string::npos) << jointName(joint) << ":\n" << steps;
  }
  EXPECT_NE(stepsFor(Joint::Slots, std::nullopt).find("Crease each tongue"), std::string::npos);
  EXPECT_NE(stepsFor(Joint::Glue, TabSide::None).find("tape"), std::string::npos);
  const std::string glued = stepsFor(Joint::Glue, std::nullopt);
  EXPECT_NE(glued.find("Glue one tab at a time"), std::string::npos) << glued;
  EXPECT_NE(stepsFor(Joint::Holes, TabSide::B).find("tabs go inside"), std::string::npos);
}

}  // namespace
}  // namespace dform::test
