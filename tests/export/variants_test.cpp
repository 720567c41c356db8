// SPDX-License-Identifier: GPL-3.0-or-later
// The pattern of the D-Form variants, read back from the written files: anti and demi D-Forms
// (a seam that is a hole's loop, free outer outlines) and creased pieces.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "dform/core/polyline.h"
#include "dform/export/exporter.h"
#include "dform/validate/metrics.h"
#include "export/internal.h"
#include "export/plane_geometry.h"
#include "models.h"
#include "test_util.h"

namespace dform::test {
namespace {

using nlohmann::json;

// The bar: printed or cut dimensions within 0.1 mm of the solved ones.

double area(const Polyline& p) {
  Points2 P(Eigen::Index(p.size()), 2);
  for (size_t i = 0; i < p.size(); ++i) P.row(Eigen::Index(i)) = p[i].transpose();
  return std::abs(signedArea(P));
}

double flatLength(const Piece& piece, const std::vector<int>& loop, bool closed) {
  double length = 0;
  for (size_t i = 0; i + (closed ? 0 : 1) < loop.size(); ++i)
    length += (piece.flat.row(loop[(i + 1) % loop.size()]) - piece.flat.row(loop[i])).norm();
  return length;
}

// The index of the path with this id in document order, or -1.
int orderOf(const SvgDoc& svg, const std::string& id) {
  for (size_t i = 0; i < svg.paths.size(); ++i)
    if (svg.paths[i].id == id) return int(i);
  return -1;
}

// A D-Form whose pieces are an 84 mm grid square folded along two creases (a mountain and a
// valley) and its mirror image.
DForm creasedSquares() {
  const Piece a = foldedSquare(12, 84.0, {{4, 0, 4, 12, 40.0}, {8, 0, 8, 12, -60.0}});
  return {a, mirroredCopy(a, "B")};
}

TEST(ExportVariants, AntiDFormCutsItsHolesFirstAtTheirExactPerimeter) {
  const DForm model = annulusDForm();
  const Exported w = exportTo("anti-cuts", model, options());
  for (const char* id : {"A-cut-hole-1", "B-cut-hole-1", "A-cut", "B-cut"}) {
    const SvgPath* cut = w.svg.find(id);
    ASSERT_NE(cut, nullptr) << id;
    EXPECT_EQ(cut->layer, "Cut") << id;
    EXPECT_TRUE(cut->closed) << id;
  }
  // Inner cuts before outer ones: a part never drops out of the sheet before its hole is cut.
  EXPECT_LT(std::max(orderOf(w.svg, "A-cut-hole-1"), orderOf(w.svg, "B-cut-hole-1")),
            std::min(orderOf(w.svg, "A-cut"), orderOf(w.svg, "B-cut")));
  EXPECT_EQ(w.svg.find("A-cut-hole-2"), nullptr);
  // B has no tabs: its hole is cut exactly along the seam, its outline along the free boundary.
  EXPECT_NEAR(length(w.svg.find("B-cut-hole-1")->parts[0], true),
              flatLength(model.b, model.b.seam, true), kMmTol);
  EXPECT_NEAR(length(w.svg.find("B-cut")->parts[0], true),
              flatLength(model.b, model.b.freeBoundaries[0], true), kMmTol);
  for (const json& piece : w.sidecar["pieces"]) {
    EXPECT_TRUE(piece["seam_is_hole"].get<bool>());
    ASSERT_EQ(piece["boundaries"].size(), 2u);  // the outline first, then the hole
    EXPECT_GT(area(toPolyline(piece["boundaries"][0])), area(toPolyline(piece["boundaries"][1])));
    EXPECT_EQ(piece["hole_cuts"].size(), 1u);
    EXPECT_EQ(piece["cut"].size(), 1u);
    EXPECT_NEAR(length(toPolyline(piece["outline"]), true), piece["perimeter_mm"].get<double>(),
                1e-9);
  }
}

TEST(ExportVariants, TicksAndTabsFollowTheSeamIntoTheHole) {
  const DForm model = annulusDForm();
  const fab::PatternBuild pattern = build(model, options());
  ASSERT_FALSE(pattern.tabs.empty());
  ASSERT_GE(pattern.ticks.size(), 5u);  // 2 pi 20 mm of seam, a tick every 20 mm
  const double seamLength = pattern.pieces[0].perimeter;
  for (const fab::TickInfo& t : pattern.ticks) {
    // On each piece's seam at the same arc length from seam[0], never on the free outline.
    for (int p = 0; p < 2; ++p) {
      const fab::PieceInfo& piece = pattern.pieces[size_t(p)];
      const auto [s, distance] = arcLengthOf(piece.outline, p == 0 ? t.onA : t.onB);
      EXPECT_LT(distance, 1e-6) << "tick " << t.id;
      EXPECT_NEAR(std::fmod(s + 1e-6, seamLength) - 1e-6, t.s, 1e-6) << "tick " << t.id;
    }
  }
  for (const fab::TabInfo& tab : pattern.tabs) {
    const fab::PieceInfo& piece = pattern.pieces[size_t(tab.piece)];
    for (const Vec2& q : tab.fold) EXPECT_LT(arcLengthOf(piece.outline, q).second, 1e-6);
    // The tab lies in the hole (the side away from the material) and shares no area with it.
    Vec2 centre = Vec2::Zero();
    for (const Vec2& q : tab.polygon) centre += q / double(tab.polygon.size());
    EXPECT_TRUE(inside(piece.outline, centre));
    EXPECT_LT(fab::overlapArea({tab.polygon}, piece.boundaries), fab::kOverlapTolMm2);
  }
  EXPECT_EQ(fab::checkLayout(pattern).problems(), 0) << fab::checkLayout(pattern).example;
  // Tick numbers sit in the ring, not in the hole.
  for (const fab::Layer& layer : pattern.drawing.layers)
    for (const fab::Path& path : layer.paths) {
      if (path.id.rfind("A-tick-", 0) != 0 || path.id.find("-label") == std::string::npos) continue;
      for (const Polyline& part : path.parts)
        for (const Vec2& q : part)
          EXPECT_TRUE(fab::insideRegion(pattern.pieces[0].boundaries, q)) << path.id;
    }
}

TEST(ExportVariants, DemiDFormTabsPointOutOfTheDiscAndIntoTheAnnulusHole) {
  const DForm model = demiDForm();
  ExportOptions o = options();
  o.tabSide = TabSide::Alternate;
  const fab::PatternBuild pattern = build(model, o);
  EXPECT_FALSE(pattern.pieces[0].seamIsHole);
  EXPECT_TRUE(pattern.pieces[1].seamIsHole);
  int onA = 0, onB = 0;
  for (const fab::TabInfo& tab : pattern.tabs) {
    Vec2 centre = Vec2::Zero();
    for (const Vec2& q : tab.polygon) centre += q / double(tab.polygon.size());
    const fab::PieceInfo& piece = pattern.pieces[size_t(tab.piece)];
    // Away from the material: outside the disc, inside the annulus's hole.
    EXPECT_EQ(inside(piece.outline, centre), piece.seamIsHole) << "tab on " << piece.name;
    ++(tab.piece == 0 ? onA : onB);
  }
  EXPECT_GT(onA, 0);
  EXPECT_GT(onB, 0);
  for (const char* profile : {"laser", "print", "laser-card"}) {
    o.profile = profile;
    Result<PreparedExport> prepared = prepareExport(model, o);
    ASSERT_TRUE(prepared.isOk()) << prepared.status().message();
    EXPECT_EQ(prepared.value().layout.problems(), 0)
        << profile << ": " << prepared.value().layout.example;
  }
}

TEST(ExportVariants, KerfGrowsTheOutlineAndShrinksTheHole) {
  const DForm model = annulusDForm();
  ExportOptions o = options();
  o.tabWidthMm = 0;
  o.kerfMm = 0.4;  // the beam's width: the cut loops move half of it
  const fab::PatternBuild pattern = build(model, o);
  for (const fab::PieceInfo& piece : pattern.pieces) {
    ASSERT_EQ(piece.cut.size(), 1u);
    ASSERT_EQ(piece.holeCuts.size(), 1u);
    const Polyline& outline = piece.boundaries[0];
    const Polyline& hole = piece.boundaries[1];
    // Every cut point lies half the kerf away from its loop, outside the material (round joins are
    // drawn within 5 um, Clipper's grid is 0.1 um).
    for (const Vec2& q : piece.cut[0]) {
      EXPECT_NEAR(fab::distanceToPolylines({outline}, q, true), 0.2, 0.01);
      EXPECT_FALSE(insidePolygon(outline, q));
    }
    for (const Vec2& q : piece.holeCuts[0]) {
      EXPECT_NEAR(fab::distanceToPolylines({hole}, q, true), 0.2, 0.01);
      EXPECT_TRUE(insidePolygon(hole, q));
    }
    EXPECT_LT(area(piece.holeCuts[0]), area(hole));
    EXPECT_GT(area(piece.cut[0]), area(outline));
  }
}

TEST(ExportVariants, CreasesAreScoredFoldLinesWithTheirDirection) {
  const DForm model = creasedSquares();
  const Exported w = exportTo("creases-laser", model, options());
  EXPECT_EQ(w.summary.creases, 4);
  for (const Piece* piece : {&model.a, &model.b}) {
    const std::vector<CreaseFold> folds = creaseFolds(*piece);
    for (size_t k = 0; k < folds.size(); ++k) {
      const std::string id = piece->name + "-crease-" + std::to_string(k + 1) + "-" +
                             foldDirectionName(folds[k].direction);
      const SvgPath* line = w.svg.find(id);
      ASSERT_NE(line, nullptr) << id;
      EXPECT_EQ(line->layer, "Score");
      EXPECT_EQ(line->stroke, "#0000FF");
      EXPECT_EQ(line->style.find("dasharray"), std::string::npos) << "a laser scores a solid line";
      EXPECT_NEAR(length(line->parts.at(0), false), 84.0, kMmTol);  // true scale
      const SvgPath* label = w.svg.find(id + "-label");
      ASSERT_NE(label, nullptr) << id;
      EXPECT_EQ(label->layer, "Engrave");
    }
  }
  // A's creases: the first a 40 degree mountain, the second a 60 degree valley.
  EXPECT_NE(w.svg.find("A-crease-1-mountain"), nullptr);
  EXPECT_NE(w.svg.find("A-crease-2-valley"), nullptr);
  const json& creases = w.sidecar["pieces"][0]["creases"];
  ASSERT_EQ(creases.size(), 2u);
  EXPECT_EQ(creases[0]["direction"], "mountain");
  EXPECT_NEAR(creases[0]["angle_deg"].get<double>(), 40.0, 1e-6);
  EXPECT_EQ(creases[1]["direction"], "valley");
  EXPECT_NEAR(creases[1]["angle_deg"].get<double>(), 60.0, 1e-6);
  // Boundary to boundary: both ends on the piece's outline.
  const Polyline outline = toPolyline(w.sidecar["pieces"][0]["outline"]);
  for (const json& crease : creases) {
    const Polyline line = toPolyline(crease["line"]);
    EXPECT_LT(arcLengthOf(outline, line.front()).second, 1e-6);
    EXPECT_LT(arcLengthOf(outline, line.back()).second, 1e-6);
  }
  EXPECT_NE(w.svg.find("crease-legend-label"), nullptr);
}

TEST(ExportVariants, PrintedCreasesAreDashedValleysAndDashDotMountains) {
  const Exported w = exportTo("creases-print", creasedSquares(), options("print"));
  const SvgPath* mountain = w.svg.find("A-crease-1-mountain");
  const SvgPath* valley = w.svg.find("A-crease-2-valley");
  ASSERT_NE(mountain, nullptr);
  ASSERT_NE(valley, nullptr);
  EXPECT_EQ(mountain->layer, "Fold");
  auto dashes = [](const SvgPath* p) {
    const std::string& style = p->style;
    const size_t at = style.find("stroke-dasharray:");
    if (at == std::string::npos) return std::vector<double>{};
    std::vector<double> out;
    std::string list = style.substr(at + 17, style.find(';', at) - at - 17);
    for (size_t from = 0; from <= list.size();) {
      const size_t comma = std::min(list.find(',', from), list.size());
      out.push_back(std::stod(list.substr(from, comma - from)));
      from = comma + 1;
    }
    return out;
  };
  EXPECT_EQ(dashes(valley), (std::vector<double>{2, 2}));  // dash_mm 2: dashed
  const std::vector<double> dashDot = dashes(mountain);
  ASSERT_EQ(dashDot.size(), 4u);  // dash, gap, dot, gap
  EXPECT_LT(dashDot[2], 0.5 * dashDot[0]);
}

TEST(ExportVariants, PerforatedCreasesAreBridgedCutsBeforeTheOuterCut) {
  const Exported w = exportTo("creases-card", creasedSquares(), options("laser-card"));
  const SvgPath* crease = w.svg.find("A-crease-1-mountain");
  ASSERT_NE(crease, nullptr);
  EXPECT_EQ(crease->layer, "Cut");
  EXPECT_GT(crease->parts.size(), 10u);
  EXPECT_LT(orderOf(w.svg, "A-crease-1-mountain"), orderOf(w.svg, "A-cut"));
  // Both ends are bridges: the first and last cut start a gap away from the outline.
  const Polyline outline = toPolyline(w.sidecar["pieces"][0]["outline"]);
  EXPECT_GT(arcLengthOf(outline, crease->parts.front().front()).second, 0.4);
  EXPECT_GT(arcLengthOf(outline, crease->parts.back().back()).second, 0.4);
}

TEST(ExportVariants, LabelsKeepOffCreasesAndCreasedPatternsLayOutCleanly) {
  const DForm model = creasedSquares();
  for (const char* profile : {"laser", "print", "laser-card", "print-and-cut"}) {
    ExportOptions o = options(profile);
    const fab::PatternBuild pattern = build(model, o);
    EXPECT_EQ(fab::checkLayout(pattern).problems(), 0)
        << profile << ": " << fab::checkLayout(pattern).example;
    for (const fab::PieceInfo& piece : pattern.pieces)
      for (const fab::Layer& layer : pattern.drawing.layers)
        for (const fab::Path& path : layer.paths) {
          if (path.id.rfind(piece.name + "-", 0) != 0 ||
              path.id.find("-label") == std::string::npos)
            continue;
          for (const fab::CreaseInfo& crease : piece.creases)
            for (const Polyline& part : path.parts)
              for (const Vec2& q : part)
                EXPECT_GT(fab::distanceToPolylines({crease.line}, q, false), 0.3)
                    << profile << " " << path.id;
        }
  }
}

TEST(ExportVariants, ClassicPatternHasNoVariantPaths) {
  const DForm model = tetraDForm(6);
  const Exported w = exportTo("classic", model, options());
  for (const SvgPath& path : w.svg.paths) {
    EXPECT_EQ(path.id.find("hole"), std::string::npos) << path.id;
    EXPECT_EQ(path.id.find("crease"), std::string::npos) << path.id;
  }
  EXPECT_EQ(w.summary.creases, 0);
  for (const json& piece : w.sidecar["pieces"]) {
    EXPECT_FALSE(piece["seam_is_hole"].get<bool>());
    EXPECT_EQ(piece["boundaries"].size(), 1u);
    EXPECT_TRUE(piece["hole_cuts"].empty());
    EXPECT_TRUE(piece["creases"].empty());
  }
}

TEST(ExportVariants, GltfSeamLineIsTheSeamOnly) {
  const DForm model = annulusDForm();
  const Exported w = exportTo("anti-gltf", model, options());
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, w.dir + "/dform.glb")) << err;
  ASSERT_EQ(m.meshes.size(), 3u);
  const auto& seam = m.meshes[2].primitives.at(0);
  EXPECT_EQ(seam.mode, TINYGLTF_MODE_LINE);
  EXPECT_EQ(m.accessors[size_t(seam.indices)].count, 2 * model.a.seam.size());  // not the outlines
}

}  // namespace
}  // namespace dform::test
