// SPDX-License-Identifier: GPL-3.0-or-later
// Joints for sheet materials: matched hole pairs and lacing holes along the seam, the kerf offset
// of the cut paths, and the material presets. The holes are read back from pattern.json and the
// written files and checked against the 3D shape, not against the arc lengths that placed them.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "dform/export/exporter.h"
#include "export/internal.h"
#include "models.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

using nlohmann::json;
using Vec2 = Eigen::Vector2d;

// The outline's corners: vertices where it turns by 35 degrees or more.
std::vector<Vec2> corners(const Polyline& outline) {
  std::vector<Vec2> out;
  const size_t n = outline.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = outline[i] - outline[(i + n - 1) % n], b = outline[(i + 1) % n] - outline[i];
    const double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    if (std::abs(turn) >= 35 * M_PI / 180) out.push_back(outline[i]);
  }
  return out;
}

struct Hole {
  int piece = 0;
  Vec2 centre;
  double diameter = 0;
};

// pattern.json's joint holes by index (pair or place along the seam), each with its piece.
std::multimap<int, Hole> holesOf(const json& sidecar) {
  std::multimap<int, Hole> out;
  for (const json& h : sidecar["joint_holes"])
    out.insert({h["index"].get<int>(),
                {h["piece"] == "A" ? 0 : 1,
                 Vec2(h["centre"][0].get<double>(), h["centre"][1].get<double>()),
                 h["diameter_mm"].get<double>()}});
  return out;
}

// Every hole lies `edge` inside its piece from the seam, a diameter clear of the seam's corners
// and of the other holes of its piece.
void expectHolesClear(const json& sidecar, double edge) {
  const std::multimap<int, Hole> holes = holesOf(sidecar);
  for (const auto& [index, h] : holes) {
    const Polyline outline = toPolyline(sidecar["pieces"][h.piece]["outline"]);
    EXPECT_TRUE(inside(outline, h.centre)) << "hole " << index << " lies in its piece";
    EXPECT_NEAR(arcLengthOf(outline, h.centre).second, edge, 1e-6) << "hole " << index;
    for (const Vec2& c : corners(outline))
      EXPECT_GE((c - h.centre).norm() - 0.5 * h.diameter, h.diameter) << "hole " << index;
    for (const auto& [other, o] : holes) {
      if (other == index || o.piece != h.piece) continue;
      EXPECT_GE((o.centre - h.centre).norm() - h.diameter, h.diameter)
          << "holes " << index << " and " << other;
    }
  }
}

// For --joint holes, the holes of each pair lie at the same point of the 3D seam: each hole's
// seam foot on its own piece, mapped through that piece's 3D shape, within 0.1 mm of its
// partner's.
void expectPairsMeetIn3d(const DForm& model, const json& sidecar) {
  const std::multimap<int, Hole> holes = holesOf(sidecar);
  const Polyline outline[2] = {toPolyline(sidecar["pieces"][0]["outline"]),
                               toPolyline(sidecar["pieces"][1]["outline"])};
  const Piece* piece[2] = {&model.a, &model.b};
  ASSERT_GT(holes.size(), 8u);
  for (auto it = holes.begin(); it != holes.end(); it = holes.upper_bound(it->first)) {
    ASSERT_EQ(holes.count(it->first), 2u) << "hole pair " << it->first;
    const Hole& h0 = it->second;
    const Hole& h1 = std::next(it)->second;
    ASSERT_NE(h0.piece, h1.piece) << "one hole of pair " << it->first << " on each piece";
    const double apart = (seamPoint3d(*piece[h0.piece], outline[h0.piece], h0.centre).first -
                          seamPoint3d(*piece[h1.piece], outline[h1.piece], h1.centre).first)
                             .norm();
    EXPECT_LE(apart, 0.1) << "hole pair " << it->first;
  }
}

// The ellipse and circle D-Form with B's flat vertices slid round the centre by up to 0.3 rad
// (their 3D points as they were): B's seam is parametrised unlike A's, so equal arc lengths on
// A and B are different seam points (up to 20 mm apart), as on a solved model.
DForm warpedEllipseCircle() {
  DForm model = ellipseCircleDForm(64, 8);
  for (Eigen::Index v = 0; v < model.b.flat.rows(); ++v) {
    const Eigen::Vector2d q = model.b.flat.row(v).transpose();
    const double r = q.norm(), a = std::atan2(q.y(), q.x());
    const double warped = a + 0.3 * std::sin(a);
    model.b.flat.row(v) << r * std::cos(warped), r * std::sin(warped);
  }
  return model;
}

TEST(ExportJoints, HolePairsLieAtTheSame3DSeamPoints) {
  const DForm ellipse = warpedEllipseCircle();
  ExportOptions o = options();
  o.joint = Joint::Holes;
  const Exported e = exportTo("holes-ellipse", ellipse, o);
  expectPairsMeetIn3d(ellipse, e.sidecar);
  expectHolesClear(e.sidecar, 3.0);
  EXPECT_TRUE(e.sidecar["tabs"].empty()) << "holes join the pieces: no glue tabs unless asked";
  EXPECT_EQ(e.summary.jointHoles, int(e.sidecar["joint_holes"].size()));
  // A square-ish D-Form: its corners keep their holes away, its seams differ in parametrisation.
  const DForm tetra = tetraDForm(6, 60.0);
  o.holeSpacingMm = 12;
  const Exported t = exportTo("holes-tetra", tetra, o);
  expectPairsMeetIn3d(tetra, t.sidecar);
  expectHolesClear(t.sidecar, 3.0);
  // The holes are placed clear of the corners, not placed at them and dropped.
  for (const json& message : t.sidecar["messages"])
    EXPECT_EQ(message.get<std::string>().find("joint holes"), std::string::npos) << message;
  int corner = 0;  // and the corners are no further from their holes than the clearance needs
  const Polyline outlineA = toPolyline(t.sidecar["pieces"][0]["outline"]);
  for (const Vec2& c : corners(outlineA)) {
    double nearest = 1e300;
    for (const auto& [index, h] : holesOf(t.sidecar))
      if (h.piece == 0) nearest = std::min(nearest, (h.centre - c).norm());
    EXPECT_LT(nearest, 12.0) << "corner " << corner << " of A has a hole near it";
    ++corner;
  }
  EXPECT_EQ(corner, 4);
}

TEST(ExportJoints, HolesOnAHoleSeamGoIntoTheMaterial) {
  // Anti (both seams are hole loops) and demi (A's seam its outline, B's a hole loop) D-Forms:
  // the holes lie in the material, the edge distance from the seam, paired in 3D.
  for (const DForm& model : {annulusDForm(), demiDForm()}) {
    ExportOptions o = options();
    o.joint = Joint::Holes;
    o.holeSpacingMm = 10;
    const Exported e = exportTo("holes-hole-seam", model, o);
    expectPairsMeetIn3d(model, e.sidecar);
    for (const json& h : e.sidecar["joint_holes"]) {
      const json& piece = e.sidecar["pieces"][h["piece"] == "A" ? 0 : 1];
      const Vec2 c(h["centre"][0].get<double>(), h["centre"][1].get<double>());
      EXPECT_NEAR(arcLengthOf(toPolyline(piece["outline"]), c).second, 3.0, 1e-6);
      const Polyline outer = toPolyline(piece["boundaries"][0]);
      bool inAHole = false;  // the piece's own holes (its seam, if a hole), not the joint holes
      for (size_t k = 1; k < piece["boundaries"].size(); ++k) {
        const Polyline loop = toPolyline(piece["boundaries"][k]);
        const bool jointHole = (loop[0] - loop[loop.size() / 2]).norm() < 3;  // 2 mm across
        if (inside(loop, c) && !jointHole) inAHole = true;
      }
      EXPECT_TRUE(inside(outer, c) && !inAHole) << "hole " << h["index"] << " in the material";
    }
    const Result<PreparedExport> prepared = prepareExport(model, o);
    ASSERT_TRUE(prepared.isOk());
    EXPECT_EQ(prepared.value().layout.problems(), 0) << prepared.value().layout.example;
  }
}

TEST(ExportJoints, HolesAreClosedCutLoopsInEveryFile) {
  const DForm model = ellipseCircleDForm(64, 8);
  ExportOptions o = options();
  o.joint = Joint::Holes;
  o.holeDiameterMm = 3;
  o.holeEdgeMm = 4;
  const Exported e = exportTo("holes-files", model, o);
  const size_t holes = e.sidecar["joint_holes"].size();
  int closedCuts = 0;
  for (const auto& path : e.svg.paths)
    if (path.layer == "Cut" && path.closed) closedCuts += int(path.parts.size());
  EXPECT_EQ(size_t(closedCuts), 2 + holes) << "cut loops = pieces + holes";
  // Each hole's cut is its circle (chords within 5 um), at the designed diameter without a kerf.
  for (const json& h : e.sidecar["joint_holes"]) {
    const Vec2 c(h["centre"][0].get<double>(), h["centre"][1].get<double>());
    bool found = false;
    for (const auto& path : e.svg.paths)
      if (path.layer == "Cut" && path.closed && (path.parts[0][0] - c).norm() < 2)
        for (const Vec2& q : path.parts[0]) {
          found = true;
          EXPECT_NEAR((q - c).norm(), 1.5, 1e-3);
        }
    EXPECT_TRUE(found) << "a cut loop around hole " << h["index"];
  }
  expectDxfChecks(e.dir);
  // The layout check counts the holes as the pieces' own loops.
  const Result<PreparedExport> prepared = prepareExport(model, o);
  ASSERT_TRUE(prepared.isOk());
  EXPECT_EQ(prepared.value().layout.extraCutLoops, 0);
  EXPECT_EQ(prepared.value().layout.problems(), 0) << prepared.value().layout.example;
}

TEST(ExportJoints, LacingHolesAlternateBetweenThePieces) {
  const DForm model = ellipseCircleDForm(64, 8);
  ExportOptions o = options();
  o.joint = Joint::Lace;
  const Exported e = exportTo("lace", model, o);
  const json& holes = e.sidecar["joint_holes"];
  ASSERT_GT(holes.size(), 8u);
  EXPECT_EQ(holes.size() % 2, 0u) << "A, B, A, B all the way round";
  const Piece* piece[2] = {&model.a, &model.b};
  const Polyline outline[2] = {toPolyline(e.sidecar["pieces"][0]["outline"]),
                               toPolyline(e.sidecar["pieces"][1]["outline"])};
  // Along the 3D seam the holes alternate between A and B, at most half a spacing apart.
  for (size_t k = 0; k < holes.size(); ++k) {
    const json& h = holes[k];
    const json& next = holes[(k + 1) % holes.size()];
    EXPECT_NE(h["piece"], next["piece"]) << "lacing holes " << k << " and " << k + 1;
    const int p = h["piece"] == "A" ? 0 : 1, q = 1 - p;
    const Vec2 c(h["centre"][0].get<double>(), h["centre"][1].get<double>());
    const Vec2 d(next["centre"][0].get<double>(), next["centre"][1].get<double>());
    const double along =
        (seamPoint3d(*piece[p], outline[p], c).first - seamPoint3d(*piece[q], outline[q], d).first)
            .norm();
    // Half a spacing, and the seam points moved off convex vertices (edge * tan(turn / 2), under
    // 0.25 mm each on this seam).
    EXPECT_LE(along, 0.5 * 15 + 0.5) << "lacing holes " << k << " and " << k + 1;
    EXPECT_GT(along, 0.25 * 15) << "lacing holes " << k << " and " << k + 1;
  }
  expectHolesClear(e.sidecar, 3.0);
}

TEST(ExportJoints, KerfMovesCutsByHalfTheKerfAndTicksStay) {
  const DForm model = ellipseCircleDForm(64, 8);
  ExportOptions o = options();
  o.joint = Joint::Holes;
  o.kerfMm = 0;
  const Exported bare = exportTo("kerf-0", model, o);
  o.kerfMm = 0.4;
  const Exported cut = exportTo("kerf-04", model, o);
  EXPECT_EQ(cut.sidecar["kerf_mm"].get<double>(), 0.4);
  // In the DXF (ezdxf): outer loops 0.2 mm outside the seam, hole loops 0.2 mm inside the holes.
  std::string report;
  ASSERT_EQ(
      run(std::string(DFORM_PYTHON3) + " " + DFORM_KERF_CHECKER + " " + cut.dir + " 0.4", &report),
      0)
      << report;
  // Ticks cross the seam as without a kerf: 1.5 mm outside, 3 mm (the start 6 mm) inside.
  for (int p = 0; p < 2; ++p) {
    const std::string name = p == 0 ? "A" : "B";
    const Polyline outline = toPolyline(cut.sidecar["pieces"][p]["outline"]);
    const Polyline outline0 = toPolyline(bare.sidecar["pieces"][p]["outline"]);
    for (int k = 0; k < 5; ++k) {
      const std::string id = name + "-tick-0" + std::to_string(k);
      const auto* tick = cut.svg.find(id);
      const auto* tick0 = bare.svg.find(id);
      ASSERT_TRUE(tick && tick0) << id;
      for (size_t end = 0; end < 2; ++end) {
        const Vec2 q = tick->parts[0][end], q0 = tick0->parts[0][end];
        EXPECT_NEAR(arcLengthOf(outline, q).second, arcLengthOf(outline0, q0).second, 1e-3) << id;
        EXPECT_NEAR(arcLengthOf(outline, q).first, arcLengthOf(outline0, q0).first, 1e-3) << id;
      }
      EXPECT_NEAR(arcLengthOf(outline, tick->parts[0][0]).second, 1.5, 1e-3) << id;
    }
  }
}

// The point at half the arc length of an open polyline.
Vec2 arcMidpoint(const Polyline& line) {
  double half = 0.5 * length(line, false);
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double l = (line[i + 1] - line[i]).norm();
    if (half <= l) return line[i] + (half / std::max(l, 1e-300)) * (line[i + 1] - line[i]);
    half -= l;
  }
  return line.back();
}

// For --joint slots: tongue k grows out of A's outline along its fold line and lies outside A;
// slot k lies `edge` inside B's outline, inside B, its long sides along B's seam, longer than the
// tongue's neck and shorter than its barbed head (`barbed`; else the head is as wide as the
// neck); and the two are at the same point of the 3D seam (within 0.1 mm): the fold line's
// midpoint on A, the slot centre's nearest seam point on B. Slots and the hole pairs left where
// a tongue does not fit share one numbering. Returns the slot count.
size_t expectSlotsMeetIn3d(const DForm& model, const json& sidecar, double edge,
                           bool barbed = true) {
  const Polyline outline[2] = {toPolyline(sidecar["pieces"][0]["outline"]),
                               toPolyline(sidecar["pieces"][1]["outline"])};
  std::set<int> indices;
  for (const json& j : sidecar["joint_slots"]) {
    const int index = j["index"].get<int>();
    EXPECT_TRUE(indices.insert(index).second) << "slot " << index;
    const Polyline fold = toPolyline(j["fold"]), tongue = toPolyline(j["tongue"]);
    const Polyline slot = toPolyline(j["slot"]);
    const Vec2 centre(j["slot_centre"][0].get<double>(), j["slot_centre"][1].get<double>());
    for (const Vec2& q : fold) EXPECT_LT(arcLengthOf(outline[0], q).second, 1e-6) << index;
    for (size_t i = fold.size(); i < tongue.size(); ++i)
      EXPECT_FALSE(inside(outline[0], tongue[i])) << "tongue " << index << " point " << i;
    const auto [onA, foldOff] = seamPoint3d(model.a, outline[0], arcMidpoint(fold));
    const auto [onB, slotOff] = seamPoint3d(model.b, outline[1], centre);
    EXPECT_NEAR(slotOff, edge, 1e-6) << "slot " << index << " lies the edge distance inside B";
    EXPECT_LE((onA - onB).norm(), 0.1) << "tongue and slot " << index;
    EXPECT_EQ(slot.size(), 4u) << "slot " << index << " is a rectangle";
    if (slot.size() != 4) continue;
    for (const Vec2& q : slot) EXPECT_TRUE(inside(outline[1], q)) << "slot " << index;
    // Along the fold: the neck's width (the fold's chord), the head's (the tongue's extent).
    const Vec2 t = (fold.back() - fold.front()).normalized();
    double lo = 1e300, hi = -1e300;
    for (const Vec2& q : tongue) {
      lo = std::min(lo, t.dot(q - fold.front()));
      hi = std::max(hi, t.dot(q - fold.front()));
    }
    const double neck = (fold.back() - fold.front()).norm(),
                 slotLength = (slot[1] - slot[0]).norm() > (slot[2] - slot[1]).norm()
                                  ? (slot[1] - slot[0]).norm()
                                  : (slot[2] - slot[1]).norm();
    EXPECT_NEAR(j["slot_length_mm"].get<double>(), slotLength, 1e-9) << index;
    EXPECT_GT(slotLength, neck) << "tongue " << index << " slides into its slot";
    EXPECT_LT(slotLength, neck + 1) << "slot " << index;
    if (barbed)
      EXPECT_GT(hi - lo, slotLength) << "tongue " << index << "'s barbs hold it in the slot";
    else
      EXPECT_NEAR(hi - lo, neck, 1e-9) << "tongue " << index << " has no barbs";
  }
  for (const json& h : sidecar["joint_holes"])
    if (h["piece"] == "A") {
      EXPECT_TRUE(indices.insert(h["index"].get<int>()).second);
    }
  EXPECT_EQ(indices.empty() ? 0 : *indices.rbegin() + 1, int(indices.size()))
      << "joints numbered 0.. along the seam";
  return sidecar["joint_slots"].size();
}

TEST(ExportJoints, TonguesAndSlotsLieAtTheSame3DSeamPoints) {
  // The square-ish D-Form: straight seams, a tongue and slot between every pair of corners.
  const DForm tetra = tetraDForm(6, 60.0);
  ExportOptions o = options();
  o.joint = Joint::Slots;
  const Exported t = exportTo("slots-tetra", tetra, o);
  EXPECT_GT(expectSlotsMeetIn3d(tetra, t.sidecar, 3.0), 8u);
  EXPECT_TRUE(t.sidecar["joint_holes"].empty()) << "straight seams: tongues only";
  EXPECT_TRUE(t.sidecar["tabs"].empty()) << "slots join the pieces: no glue tabs unless asked";
  EXPECT_EQ(t.summary.jointSlots, int(t.sidecar["joint_slots"].size()));
  EXPECT_NE(t.svg.find("A-tongue-fold-01"), nullptr) << "the tongues' folds are scored";
  // Polypropylene's slots sit its hole edge (4 mm) in, every tongue made (plywood cannot fold
  // its tongues back at all: refused, ExportShopOptions).
  o.material = "polypropylene";
  const Exported pp = exportTo("slots-tetra-polypropylene", tetra, o);
  EXPECT_GT(expectSlotsMeetIn3d(tetra, pp.sidecar, 4.0), 4u);
  EXPECT_TRUE(pp.sidecar["joint_holes"].empty()) << pp.sidecar["messages"];
  o.material.clear();
  // Curved seams, B's parametrised unlike A's: longer tongues fit where the ellipse is flat and
  // become hole pairs at its tight ends, with a message saying how many.
  const DForm ellipse = warpedEllipseCircle();
  o.holeSpacingMm = 25;
  o.slotLengthMm = 10;
  const Exported e = exportTo("slots-ellipse", ellipse, o);
  EXPECT_GT(expectSlotsMeetIn3d(ellipse, e.sidecar, 3.0), 2u);
  expectPairsMeetIn3d(ellipse, e.sidecar);
  bool said = false;
  for (const json& message : e.sidecar["messages"])
    said = said || message.get<std::string>().find("joints are hole pairs") != std::string::npos;
  EXPECT_TRUE(said) << e.sidecar["messages"];
}

TEST(ExportJoints, SlotsAreHoleLoopsAndTonguesPartOfTheOutlineInEveryFile) {
  const DForm tetra = tetraDForm(6, 60.0);
  ExportOptions o = options();
  o.joint = Joint::Slots;
  o.material = "card";
  o.kerfMm = 0.3;
  const Exported e = exportTo("slots-files", tetra, o);
  const size_t slots = e.sidecar["joint_slots"].size();
  ASSERT_GT(slots, 8u);
  EXPECT_EQ(e.sidecar["joint"]["slot_width_mm"].get<double>(), 0.5) << "card 0.3 mm + 0.2 mm";
  int closedCuts = 0;
  for (const auto& path : e.svg.paths)
    if (path.layer == "Cut" && path.closed) closedCuts += int(path.parts.size());
  EXPECT_EQ(size_t(closedCuts), 2 + slots) << "cut loops = pieces + slots";
  expectDxfChecks(e.dir);
  // In the DXF: the outlines with their tongues 0.15 mm out, the slots 0.15 mm in.
  std::string report;
  ASSERT_EQ(
      run(std::string(DFORM_PYTHON3) + " " + DFORM_KERF_CHECKER + " " + e.dir + " 0.3", &report), 0)
      << report;
  const Result<PreparedExport> prepared = prepareExport(tetra, o);
  ASSERT_TRUE(prepared.isOk());
  EXPECT_EQ(prepared.value().layout.extraCutLoops, 0);
  EXPECT_EQ(prepared.value().layout.problems(), 0) << prepared.value().layout.example;
  // A kerf wider than a slot: the slot widens to stay a loop the beam can follow.
  o.kerfMm = 0.8;
  EXPECT_NEAR(build(tetra, o).jointSlots.front().width, 0.9, 1e-12);
  // Glue tabs on A would cross the tongues: asked for, they are a usage error; on B they fit.
  o.tabSide = TabSide::A;
  const Result<PreparedExport> clash = prepareExport(tetra, o);
  ASSERT_FALSE(clash.isOk());
  EXPECT_EQ(clash.status().code(), ErrorCode::Usage);
  EXPECT_EQ(clash.status().setting(), Setting::Joint);
  EXPECT_NE(clash.status().message().find(std::string(settingKey(Setting::Tabs)) + " b"),
            std::string::npos);
  o.tabSide = TabSide::B;
  const fab::PatternBuild tabbed = build(tetra, o);
  EXPECT_FALSE(tabbed.tabs.empty());
  EXPECT_FALSE(tabbed.jointSlots.empty());
}

// The distance from q to the segment [a, b].
double distanceToSegment(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((q - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * ab - q).norm();
}

TEST(ExportJoints, TicksStopHalfAMillimetreShortOfJointHolesAndSlots) {
  // Hole 0 is at the seam's start, on tick 0's line; B's slots sit where ticks fall.
  const DForm ellipse = ellipseCircleDForm(64, 8);
  const DForm tetra = tetraDForm(6, 60.0);
  int shortened = 0;
  for (const auto& [name, model, joint] : {std::tuple{"ticks-holes", &ellipse, Joint::Holes},
                                           std::tuple{"ticks-slots", &tetra, Joint::Slots}}) {
    ExportOptions o = options();
    o.joint = joint;
    const Exported e = exportTo(name, *model, o);
    std::vector<Polyline> loops[2];  // each piece's joint holes and slots (sheet mm)
    for (const json& h : e.sidecar["joint_holes"]) {
      const Vec2 c(h["centre"][0].get<double>(), h["centre"][1].get<double>());
      Polyline circle;
      for (int k = 0; k < 64; ++k)
        circle.push_back(c + 0.5 * h["diameter_mm"].get<double>() *
                                 Vec2(std::cos(k * M_PI / 32), std::sin(k * M_PI / 32)));
      loops[h["piece"] == "A" ? 0 : 1].push_back(circle);
    }
    for (const json& slot : e.sidecar.value("joint_slots", json::array()))
      loops[1].push_back(toPolyline(slot["slot"]));
    for (int p = 0; p < 2; ++p) {
      for (const auto& path : e.svg.paths) {
        if (path.id.rfind(std::string(p == 0 ? "A" : "B") + "-tick-", 0) != 0 ||
            path.id.find("label") != std::string::npos)
          continue;
        const Vec2 a = path.parts[0][0], b = path.parts[0][1];
        const double in = (b - a).norm() - 1.5;  // 1.5 mm of the tick lie outside
        EXPECT_GE(in, 0.5) << name << " " << path.id << " reaches into its piece";
        shortened += in < (path.id.find("-00") != std::string::npos ? 6.0 : 3.0) - 1e-6;
        for (const Polyline& loop : loops[p])
          for (size_t i = 0; i < loop.size(); ++i)
            EXPECT_GE(std::min(distanceToSegment(loop[i], a, b),
                               distanceToSegment(b, loop[i], loop[(i + 1) % loop.size()])),
                      0.5 - 0.006)  // a hole is cut as a polygon within 5 um of its circle
                << path.id << " comes within half a millimetre of a joint";
      }
    }
  }
  EXPECT_GT(shortened, 2) << "ticks met joints and stopped short";
}

TEST(ExportJoints, MaterialPresetsSetTheJointAndExplicitOptionsWin) {
  const DForm model = ellipseCircleDForm(48, 4);
  ExportOptions o = options();
  o.material = "plywood";
  const fab::PatternBuild ply = build(model, o);
  EXPECT_EQ(ply.joint.joint, Joint::Holes);
  EXPECT_EQ(ply.joint.thicknessMm, 3.0);
  EXPECT_EQ(ply.joint.diameterMm, 4.0);
  EXPECT_TRUE(ply.tabs.empty());
  EXPECT_FALSE(ply.jointHoles.empty());
  o.material = "polypropylene";
  EXPECT_EQ(build(model, o).joint.joint, Joint::Lace);
  o.joint = Joint::Glue;  // an explicit joint wins over the material's
  const fab::PatternBuild glued = build(model, o);
  EXPECT_TRUE(glued.jointHoles.empty());
  EXPECT_FALSE(glued.tabs.empty());
  o.material = "card";
  o.joint.reset();
  EXPECT_EQ(build(model, o).joint.joint, Joint::Glue);
  o.material = "plywood";
  o.holeDiameterMm = 2.5;  // and an explicit size over the material's
  o.tabSide = TabSide::A;  // tabs where asked for, holes or not
  const fab::PatternBuild both = build(model, o);
  EXPECT_EQ(both.joint.diameterMm, 2.5);
  EXPECT_FALSE(both.tabs.empty());
  for (const auto& h : both.jointHoles) EXPECT_EQ(h.diameter, 2.5);
}

// The joint sizes against each other (each alone is in its range: the settings table's rows,
// pipeline's SettingsTable tests): a usage error naming the setting that must change.
TEST(ExportJoints, JointSizesThatDoNotFitEachOtherAreUsageErrors) {
  ExportOptions o = options();
  auto expectUsage = [&](const ExportOptions& bad, Setting named) {
    const Status s = checkExportOptions(bad);
    EXPECT_EQ(s.code(), ErrorCode::Usage) << settingKey(named);
    EXPECT_EQ(s.setting(), named) << s.message();
    EXPECT_EQ(s.message().find('\n'), std::string::npos) << "one line";
  };
  ExportOptions bad = o;
  bad.holeEdgeMm = 1.5;  // less than the 2 mm diameter
  expectUsage(bad, Setting::HoleEdge);
  bad = o;
  bad.holeSpacingMm = 3;  // less than twice the diameter
  expectUsage(bad, Setting::HoleSpacing);
  bad = o;
  bad.material = "plywood";
  bad.holeSpacingMm = 7;  // plywood's 4 mm holes need 8
  expectUsage(bad, Setting::HoleSpacing);
  bad = o;
  bad.slotLengthMm = 14;  // the 15 mm spacing less a 2 mm hole leaves 13
  expectUsage(bad, Setting::SlotLength);
  bad.slotLengthMm = 13;
  EXPECT_TRUE(checkExportOptions(bad).isOk());
  EXPECT_TRUE(checkExportOptions(o).isOk());
}

}  // namespace
}  // namespace dform::test
