// SPDX-License-Identifier: GPL-3.0-or-later
// The layout check (the gate's pattern_layout): silent on the patterns the exporter lays out,
// and each kind of defect, planted in a built pattern, is counted by its own figure alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>

#include "dform/export/exporter.h"
#include "export/internal.h"
#include "export/pattern_parts.h"
#include "export/plane_geometry.h"
#include "models.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

using fab::Polyline;
using fab::Vec2;

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
    for (TabSide side : {TabSide::A, TabSide::B, TabSide::Alternate}) {
      ExportOptions o = options(profile);
      o.tabSide = side;
      Result<PreparedExport> prepared = prepareExport(model, o);
      ASSERT_TRUE(prepared.isOk()) << prepared.status().message();
      const LayoutFindings& f = prepared.value().layout;
      EXPECT_EQ(f.problems(), 0) << profile << " tabs " << tabSideName(side) << ": " << f.example;
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
      {"a tab cut free of its piece as a loop of its own",
       [](fab::PatternBuild& p) {
         fab::Path loose;
         loose.id = "A-cut-2";
         loose.closed = true;
         loose.parts = {p.tabs[0].polygon};
         for (fab::Layer& layer : p.drawing.layers)
           if (layer.name == "Cut") layer.paths.push_back(loose);
       },
       &LayoutFindings::extraCutLoops, "cut free"},
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

// The distance from q to the closed polyline `loop`.
double distanceToLoop(const Polyline& loop, const Vec2& q) {
  double best = 1e300;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    const double len2 = (b - a).squaredNorm();
    const double t = len2 > 0 ? std::clamp((q - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * (b - a) - q).norm());
  }
  return best;
}

TEST(ExportLayout, EveryTabIsPartOfItsPiecesOneCutLoop) {
  // Straight sides and corners (the disphenoid's rhombi) and a curved pair, tabs on either piece
  // or alternating: each piece is cut as one loop per boundary loop, every point of every tab on
  // it, and the layout check counts no loop cut free.
  for (const DForm& model : {tetraDForm(8, 80.0), ellipseCircleDForm(64, 8, 90, 35)})
    for (TabSide side : {TabSide::A, TabSide::B, TabSide::Alternate}) {
      ExportOptions o = options("laser-lightburn");
      o.tabSide = side;
      const fab::PatternBuild p = build(model, o);
      ASSERT_FALSE(p.tabs.empty());
      for (const fab::PieceInfo& piece : p.pieces)
        EXPECT_EQ(piece.cut.size() + piece.holeCuts.size(), piece.boundaries.size())
            << piece.name << " tabs " << tabSideName(side);
      for (const fab::TabInfo& tab : p.tabs) {
        const fab::PieceInfo& piece = p.pieces[size_t(tab.piece)];
        ASSERT_EQ(piece.cut.size(), 1u);
        // The fold line's ends and the tab's outer edge (the polygon after its fold line) are
        // cut; the fold line between them is not.
        double off = 0;
        for (size_t i = tab.fold.size() - 1; i <= tab.polygon.size(); ++i)
          off = std::max(off, distanceToLoop(piece.cut[0], tab.polygon[i % tab.polygon.size()]));
        EXPECT_LT(off, 1e-6) << piece.name << "'s tab at s = " << tab.s0 << " is not on its cut";
      }
      EXPECT_EQ(fab::checkLayout(p).extraCutLoops, 0) << fab::checkLayout(p).example;
    }
}

// The winding number of `loops` around q (a point on no loop): what a non-zero fill, the SVG's and
// Cairo's default, paints where it is not 0.
int windingNumber(const std::vector<Polyline>& loops, const Vec2& q) {
  int w = 0;
  for (const Polyline& loop : loops)
    for (size_t i = 0; i < loop.size(); ++i) {
      const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
      const double side = (b - a).x() * (q - a).y() - (b - a).y() * (q - a).x();
      if (a.y() <= q.y() && b.y() > q.y() && side > 0) ++w;
      if (a.y() > q.y() && b.y() <= q.y() && side < 0) --w;
    }
  return w;
}

TEST(ExportLayout, APrintedTintLeavesItsPiecesHolesOut) {
  // An anti D-Form printed for a cutter: each piece's tint is its ring grown by the bleed, the
  // hole (with the tabs in it) shrunk by it, under the non-zero rule the renderers fill with.
  const fab::PatternBuild p = build(annulusDForm(), options("print-and-cut"));
  const double bleed = p.profile.bleedMm;
  ASSERT_GT(bleed, 0);
  for (const fab::PieceInfo& piece : p.pieces) {
    ASSERT_EQ(piece.boundaries.size(), 2u) << piece.name;
    ASSERT_EQ(piece.bleed.size(), 2u) << piece.name << ": one tint loop per boundary loop";
    const Vec2 holeCentre = centroid(piece.boundaries[1]);
    EXPECT_EQ(windingNumber(piece.bleed, holeCentre), 0) << piece.name << "'s hole is tinted";
    // The ring between the hole's cut (35 mm radius on a 50/20 annulus: 15 mm clear of the
    // cut, tabs included) and the outline is tinted.
    const Vec2 inRing = holeCentre + 35 * (piece.boundaries[0][0] - holeCentre).normalized();
    EXPECT_NE(windingNumber(piece.bleed, inRing), 0) << piece.name << "'s ring is not tinted";
    // Every vertex of the tint lies the bleed off a cut line (within 0.02 mm: where two offset
    // edges meet at the tabs' inner corners, Clipper's grid moves the corner by up to ~0.01 mm).
    std::vector<Polyline> cuts = piece.cut;
    cuts.insert(cuts.end(), piece.holeCuts.begin(), piece.holeCuts.end());
    for (const Polyline& loop : piece.bleed)
      for (const Vec2& q : loop)
        EXPECT_NEAR(fab::distanceToPolylines(cuts, q, true), bleed, 0.02) << piece.name;
  }
}

TEST(ExportLayout, AHoleIsOutsideItsPiece) {
  // An anti D-Form: its tabs lie in the holes, which is no overlap with the pieces; a label or a
  // tab moved across the hole's edge is.
  const fab::PatternBuild clean = build(annulusDForm(), options("laser"));
  ASSERT_EQ(fab::checkLayout(clean).problems(), 0) << fab::checkLayout(clean).example;
  ASSERT_FALSE(clean.tabs.empty());
  ASSERT_EQ(clean.pieces[0].boundaries.size(), 2u);
  const Vec2 holeCentre = centroid(clean.pieces[0].boundaries[1]);

  fab::PatternBuild labelInHole = clean;
  fab::Path* label = findPath(labelInHole, "A-tick-02-label");
  ASSERT_NE(label, nullptr);
  for (Polyline& part : label->parts) translate(part, holeCentre - centroid(label->parts[0]));
  const LayoutFindings f = fab::checkLayout(labelInHole);
  EXPECT_EQ(f.labelsOutside, 1) << f.example;
  EXPECT_EQ(f.problems(), 1) << f.example;

  fab::PatternBuild tabInRing = clean;
  fab::TabInfo& tab = tabInRing.tabs[0];
  ASSERT_EQ(tab.piece, 0);
  // Out of the hole by twice its width, across the seam into the ring.
  const Vec2 outward = (centroid(tab.fold) - holeCentre).normalized();
  translate(tab.polygon, 2 * tab.width * outward);
  const LayoutFindings g = fab::checkLayout(tabInRing);
  EXPECT_EQ(g.tabsOverPieces, 1) << g.example;
  EXPECT_EQ(g.problems(), 1) << g.example;
}

TEST(ExportLayout, TheTitleBlockOverAPieceOrAMarkIsCounted) {
  const DForm model = ellipseCircleDForm();
  // The calibration bar moved inside piece A, halfway between its leftmost point and its middle
  // (clear of the piece's name and tick numbers).
  fab::PatternBuild print = build(model, options("print"));
  ASSERT_EQ(fab::checkLayout(print).problems(), 0) << fab::checkLayout(print).example;
  const Polyline& outline = print.pieces[0].outline;
  const Vec2 left = *std::min_element(outline.begin(), outline.end(),
                                      [](const Vec2& a, const Vec2& b) { return a.x() < b.x(); });
  fab::Path* bar = findPath(print, "calibration-bar");
  ASSERT_NE(bar, nullptr);
  const Vec2 by = 0.5 * (left + centroid(outline)) - centroid(bar->parts[0]);
  for (Polyline& part : bar->parts) translate(part, by);
  const LayoutFindings f = fab::checkLayout(print);
  EXPECT_EQ(f.titleOverlaps, 1) << f.example;
  EXPECT_EQ(f.problems(), 1) << f.example;
  EXPECT_NE(f.example.find("calibration-bar overlaps piece A"), std::string::npos) << f.example;

  // The title line moved onto the Silhouette square (its far end may reach the top-right mark
  // too: every problem counted is the title's).
  fab::PatternBuild pnc = build(model, options("print-and-cut"));
  ASSERT_EQ(fab::checkLayout(pnc).problems(), 0) << fab::checkLayout(pnc).example;
  fab::Path* title = findPath(pnc, "title");
  fab::Path* square = findPath(pnc, "regmark-square");
  ASSERT_NE(title, nullptr);
  ASSERT_NE(square, nullptr);
  fab::Box box = fab::boxOf(title->parts);
  const Vec2 onSquare =
      square->parts[0][0] + Vec2(1, 1) - Vec2(box.lo.x(), 0.5 * (box.lo.y() + box.hi.y()));
  for (Polyline& part : title->parts) translate(part, onSquare);
  const LayoutFindings g = fab::checkLayout(pnc);
  EXPECT_GE(g.titleOverlaps, 1) << g.example;
  EXPECT_EQ(g.problems(), g.titleOverlaps) << g.example;
  EXPECT_NE(g.example.find("registration mark regmark-square"), std::string::npos) << g.example;
}

TEST(ExportLayout, TheTitleBlockOnAPrintedBleedIsCounted) {
  // The calibration bar moved to lie half a millimetre under piece B's lowest cut point, centred
  // on it: clear of the cut line, on the 1.5 mm tint printed around it. Counted with a bleed, not
  // without.
  const DForm model = ellipseCircleDForm();
  ExportOptions o = options("print-and-cut");
  for (const bool bleed : {true, false}) {
    o.profileOverride = loadProfile("print-and-cut", DFORM_TEMPLATES_DIR).value();
    if (!bleed) o.profileOverride.bleedMm = 0;
    o.useProfileOverride = true;
    fab::PatternBuild pnc = build(model, o);
    ASSERT_EQ(fab::checkLayout(pnc).problems(), 0) << fab::checkLayout(pnc).example;
    const Polyline& cut = pnc.pieces[1].cut[0];
    const Vec2 low = *std::max_element(cut.begin(), cut.end(),
                                       [](const Vec2& a, const Vec2& b) { return a.y() < b.y(); });
    const int sheet = pnc.pieces[1].sheet;  // the bar of B's own page
    fab::Path* bar = findPath(
        pnc, sheet == 0 ? "calibration-bar" : "calibration-bar-page-" + std::to_string(sheet + 1));
    ASSERT_NE(bar, nullptr);
    const fab::Box box = fab::boxOf(bar->parts);
    const Vec2 by = low + Vec2(0, 0.5) - Vec2(0.5 * (box.lo.x() + box.hi.x()), box.lo.y());
    for (Polyline& part : bar->parts) translate(part, by);
    const LayoutFindings f = fab::checkLayout(pnc);
    EXPECT_EQ(f.titleOverlaps, bleed ? 1 : 0) << f.example;
    EXPECT_EQ(f.problems(), f.titleOverlaps) << f.example;
    if (bleed) {  // braces: EXPECT_NE expands to an if-else of its own
      EXPECT_NE(f.example.find(bar->id + " overlaps piece B's printed bleed"), std::string::npos)
          << f.example;
    }
  }
}

TEST(ExportLayout, TightTickSpacingThinsTheNumbersAndKeepsEveryTick) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = options("print");
  o.tickSpacingMm = 2;  // closer than a one-digit number at 3 mm is wide
  const fab::PatternBuild pattern = build(model, o);
  const LayoutFindings f = fab::checkLayout(pattern);
  EXPECT_EQ(f.problems(), 0) << f.example;
  for (const char* piece : {"A", "B"}) {
    int ticks = 0, numbers = 0;
    for (const fab::Layer& layer : pattern.drawing.layers)
      for (const fab::Path& path : layer.paths) {
        if (path.id.rfind(std::string(piece) + "-tick-", 0) != 0) continue;
        const bool label =
            path.id.size() > 6 && path.id.compare(path.id.size() - 6, 6, "-label") == 0;
        (label ? numbers : ticks) += 1;
      }
    EXPECT_EQ(ticks, int(pattern.ticks.size())) << piece << ": every tick is drawn";
    EXPECT_LT(numbers, ticks) << piece << ": some numbers thinned out";
    EXPECT_GT(numbers, ticks / 4) << piece << ": most of every other number kept";
  }
  EXPECT_TRUE(
      std::any_of(pattern.messages.begin(), pattern.messages.end(),
                  [](const std::string& m) { return m.find("thinned") != std::string::npos; }));
}

// The strokes of a laid-out number, as distances from its first point: the same number laid out
// anywhere, at any angle, gives the same list (a different one does not: "07" and "08" differ).
std::vector<double> numberShape(const fab::Path& label) {
  std::vector<double> shape;
  const Vec2 first = label.parts.at(0).at(0);
  for (const auto& stroke : label.parts) {
    shape.push_back(-1.0 * double(stroke.size()));  // where each stroke begins
    for (const Vec2& q : stroke) shape.push_back((q - first).norm());
  }
  return shape;
}

TEST(ExportLayout, PartnerTicksCarryTheSameNumberOnBothPieces) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = options("print");
  o.tickSpacingMm = 15;
  o.numbers = TickNumbers::Face;  // the print profile's numbers go on the tabs, one piece's
  const fab::PatternBuild pattern = build(model, o);
  std::map<std::string, const fab::Path*> labels;
  for (const fab::Layer& layer : pattern.drawing.layers)
    for (const fab::Path& path : layer.paths)
      if (path.id.size() > 6 && path.id.compare(path.id.size() - 6, 6, "-label") == 0 &&
          path.id.find("-tick-") != std::string::npos)
        labels[path.id] = &path;
  int compared = 0, distinct = 0;
  std::vector<double> previous;
  for (const fab::TickInfo& t : pattern.ticks) {
    char id[16];
    std::snprintf(id, sizeof id, "-tick-%02d-label", t.id);
    const auto a = labels.find(std::string("A") + id), b = labels.find(std::string("B") + id);
    if (a == labels.end() || b == labels.end()) continue;  // thinned out on one piece
    const std::vector<double> onA = numberShape(*a->second), onB = numberShape(*b->second);
    ASSERT_EQ(onA.size(), onB.size()) << "tick " << t.id << ": A and B show different numbers";
    for (std::size_t k = 0; k < onA.size(); ++k)
      EXPECT_NEAR(onA[k], onB[k], 1e-9) << "tick " << t.id << ": A and B show different numbers";
    distinct += onA != previous;  // the check can tell numbers apart
    previous = onA;
    ++compared;
  }
  EXPECT_GE(compared, int(pattern.ticks.size()) / 2);
  EXPECT_GE(distinct, compared - 1);
}

TEST(ExportLayout, CornerTickNumbersAreMovedInwardNotDropped) {
  // The disphenoid's pieces are rhombi: with ticks every 10 mm some fall on or next to a corner,
  // where the spot beside the tick is outside the piece.
  const DForm model = tetraDForm(8, 60.0);
  ExportOptions o = options("laser");
  o.tickSpacingMm = 10;
  fab::PatternBuild pattern = build(model, o);
  EXPECT_EQ(fab::checkLayout(pattern).problems(), 0) << fab::checkLayout(pattern).example;
  for (const std::string& m : pattern.messages)
    EXPECT_EQ(m.find("left out"), std::string::npos) << m;
  for (const fab::TickInfo& t : pattern.ticks)
    for (const char* piece : {"A", "B"}) {
      char id[32];
      std::snprintf(id, sizeof id, "%s-tick-%02d-label", piece, t.id);
      EXPECT_NE(findPath(pattern, id), nullptr) << id;
    }
}

}  // namespace
}  // namespace dform::test

namespace dform::test {
namespace {

// A circle of radius r about c, as a hole winds (clockwise on screen, y down), 64 sides.
Polyline circleLoop(const Vec2& c, double r) {
  Polyline loop;
  for (int k = 0; k < 64; ++k)
    loop.push_back(c + r * Vec2(std::cos(-k * M_PI / 32), std::sin(-k * M_PI / 32)));
  return loop;
}

TEST(ExportLabels, ANumberKeepsClearOfAHoleAlongItsWholeOutline) {
  // A 10 x 3 mm label box at the middle of a 100 mm square, and a 4 mm hole whose edge comes
  // 0.1 mm from the box's long side halfway between its middle and its corner: 1.3 mm from
  // every corner and side midpoint, so a check at those six points passes it.
  const Polyline square{{0, 0}, {100, 0}, {100, 100}, {0, 100}};
  const Vec2 c(50, 50), d(1, 0);
  const double halfW = 5, halfH = 1.5, r = 2;
  for (double gap : {0.1, 0.29, 0.31, 1.0}) {
    const Polyline hole = circleLoop(c + Vec2(0.5 * halfW, halfH + gap + r), r);
    EXPECT_EQ(fab::boxFits({square, hole}, {}, c, d, halfW, halfH, 0.3), gap >= 0.3)
        << "a hole " << gap << " mm from the box";
  }
  // A hole wholly inside the box, a crease through it, and a box across the outline.
  EXPECT_FALSE(fab::boxFits({square, circleLoop(c, 0.5)}, {}, c, d, halfW, halfH, 0.3));
  EXPECT_FALSE(fab::boxFits({square}, {{{50, 40}, {50, 60}}}, c, d, halfW, halfH, 0.3));
  EXPECT_TRUE(fab::boxFits({square}, {{{60, 40}, {60, 60}}}, c, d, halfW, halfH, 0.3));
  EXPECT_FALSE(fab::boxFits({square}, {}, Vec2(3, 50), d, halfW, halfH, 0.3));
  EXPECT_FALSE(fab::boxFits({square}, {}, Vec2(5.2, 50), d, halfW, halfH, 0.3));
  EXPECT_TRUE(fab::boxFits({square}, {}, Vec2(5.4, 50), d, halfW, halfH, 0.3));
}

}  // namespace
}  // namespace dform::test
