// SPDX-License-Identifier: GPL-3.0-or-later
// pattern.json: the pattern's geometry in sheet millimetres (y down, the SVG's user units), for
// tests, the report and anyone who wants to check a cut file without parsing SVG.
#include <nlohmann/json.hpp>

#include "pattern_layout.h"

namespace dform::fab {

namespace {

using nlohmann::json;

json point(const Vec2& p) { return json::array({p.x(), p.y()}); }

json polyline(const Polyline& p) {
  json out = json::array();
  for (const Vec2& q : p) out.push_back(point(q));
  return out;
}

const char* kindName(ProfileKind kind) {
  switch (kind) {
    case ProfileKind::Laser: return "laser";
    case ProfileKind::Print: return "print";
    case ProfileKind::PrintAndCut: return "print-and-cut";
  }
  return "?";
}

// The joint and its holes (pattern.json's "joint" and "joint_holes").
void addJoint(json& j, const PatternBuild& pattern) {
  // A glued pattern's sidecar is as it always was; holes and lace, or a material, add these.
  const JointSettings& joint = pattern.joint;
  if (joint.joint == Joint::Glue && joint.material.empty()) return;
  j["joint"] = {{"kind", jointName(joint.joint)},
                {"material", joint.material.empty() ? json(nullptr) : json(joint.material)},
                {"thickness_mm", joint.material.empty() ? json(nullptr) : json(joint.thicknessMm)},
                {"hole_spacing_mm", joint.spacingMm},
                {"hole_diameter_mm", joint.diameterMm},
                {"hole_edge_mm", joint.edgeMm}};
  if (joint.joint == Joint::Slots) {
    j["joint"]["slot_length_mm"] = joint.slotLengthMm;
    j["joint"]["slot_width_mm"] = joint.slotWidthMm;
  }
  // Each hole's seam point: `s` along A's seam (the seam parameter, as the ticks' `s`) and
  // `s_own` along its own piece's seam; holes of one pair (holes) share `index`.
  json holes = json::array();
  for (const JointHoleInfo& h : pattern.jointHoles)
    holes.push_back({{"piece", pattern.pieces[size_t(h.piece)].name},
                     {"index", h.index},
                     {"s", h.s},
                     {"s_own", h.own},
                     {"centre", point(h.centre)},
                     {"diameter_mm", h.diameter}});
  j["joint_holes"] = holes;
  if (joint.joint != Joint::Slots) return;
  // Tongue k of A and slot k of B: `s` the slot's seam point, `s0`..`s1` the tongue's fold line
  // (A's seam there), both as the ticks' `s`; a hole pair left where a tongue does not fit shares
  // the joints' numbering.
  json slots = json::array();
  for (const JointSlotInfo& slot : pattern.jointSlots)
    slots.push_back({{"index", slot.index},
                     {"s", slot.s},
                     {"s0", slot.s0},
                     {"s1", slot.s1},
                     {"tongue", polyline(slot.tongue)},
                     {"fold", polyline(slot.fold)},
                     {"slot", polyline(slot.slot)},
                     {"slot_centre", point(slot.slotCentre)},
                     {"slot_length_mm", slot.length},
                     {"slot_width_mm", slot.width}});
  j["joint_slots"] = slots;
}

// What the cutter is set to and where its marks are (pattern.json's "registration"): Silhouette
// type-1 marks with their sizes (Silhouette Studio's registration settings) and each sheet's
// square and L-marks; the Print Then Cut area on a Cricut's pages; a RIP's spot cut colour.
void addRegistration(json& j, const PatternBuild& pattern) {
  const Profile& profile = pattern.profile;
  json r = {{"type", profile.registration == Registration::Silhouette ? "silhouette"
                     : profile.registration == Registration::Cricut   ? "cricut"
                                                                      : "none"}};
  if (!profile.cutSpotColor.empty()) r["cut_spot_color"] = profile.cutSpotColor;
  if (profile.registration == Registration::Silhouette) {
    r["style"] = "Type 1";
    r["inset_mm"] = kRegInset;
    r["square_mm"] = kRegSquare;
    r["length_mm"] = kRegArm;
    r["thickness_mm"] = kRegLine;
    r["clear_mm"] = profile.registrationClearMm;
    json marks = json::array();
    for (const Layer& layer : pattern.drawing.layers)
      if (layer.name == "Regmarks")
        for (const Path& mark : layer.paths) {
          const Box b = boxOf(mark.parts);
          int sheet = 0;
          for (size_t k = 0; k < pattern.sheets.size(); ++k)
            if (pattern.sheets[k].contains(b, 1e-6)) sheet = int(k);
          marks.push_back({{"id", mark.id}, {"sheet", sheet}, {"lines", [&] {
                                                                 json lines = json::array();
                                                                 for (const Polyline& part :
                                                                      mark.parts)
                                                                   lines.push_back(polyline(part));
                                                                 return lines;
                                                               }()}});
        }
    r["marks"] = marks;
  }
  if (profile.registration == Registration::Cricut) {
    json areas = json::array();
    for (const PageView& page : pattern.pages)
      if (page.kind == "sheet")
        areas.push_back(
            {point(page.origin + page.printArea.lo), point(page.origin + page.printArea.hi)});
    r["print_then_cut_areas"] = areas;
  }
  j["registration"] = r;
}

// A piece's hinges: where each is (its folds and rows of slits), the radius each row lets the
// sheet bend to and the radius the shape needs there.
json hingesJson(const PieceInfo& p) {
  json out = json::array();
  for (const HingeInfo& h : p.hinges) {
    json folds = json::array(), rows = json::array();
    for (const HingeFoldInfo& f : h.folds) {
      json margin = json::array();
      double marginMm = 0;
      for (const Polyline& part : f.inSeamMargin) {
        margin.push_back(polyline(part));
        marginMm += (part.back() - part.front()).norm();
      }
      folds.push_back(
          {{"fold", f.index},
           {"angle_deg", f.angleDeg},
           {"radius_needed_mm", f.radiusMm},
           {"radius_allowed_mm", f.radiusAllowedMm > 0 ? json(f.radiusAllowedMm) : json()},
           {"radius_met", f.radiusMet()},
           {"bend_deg", f.bendDeg},
           {"band_mm", {f.bandFromMm, f.bandToMm}},
           {"line", polyline(f.line)},
           {"in_seam_margin", margin},
           {"in_seam_margin_mm", marginMm}});
    }
    for (const HingeRow& r : h.rows) {
      json cuts = json::array();
      for (const Polyline& c : r.cuts) cuts.push_back(polyline(c));
      rows.push_back({{"from_mm", r.fromMm},
                      {"pitch_mm", r.pitchMm},
                      {"radius_allowed_mm", r.cuts.empty() ? json() : json(r.radiusAllowedMm)},
                      {"radius_needed_mm", r.radiusNeededMm},
                      {"cuts", cuts}});
    }
    out.push_back({{"id", h.id},
                   {"direction", point(h.direction)},
                   {"turn_deg", hingeTurnDeg(h)},
                   {"bend_deg", hingeBendDeg(h)},
                   {"folds", folds},
                   {"rows", rows}});
  }
  return out;
}

}  // namespace

std::string sidecarJson(const PatternBuild& pattern, const std::string& jobName) {
  json j;
  j["version"] = 1;
  j["job"] = jobName;
  j["profile"] = pattern.profile.name;
  j["kind"] = kindName(pattern.profile.kind);
  j["frame"] = "sheet millimetres, y down (SVG user units)";
  j["sheet"] = {{"width", pattern.drawing.width}, {"height", pattern.drawing.height}};
  j["scale"] = pattern.scale;
  j["tick_spacing_mm"] = pattern.tickSpacing;
  j["kerf_mm"] = pattern.profile.kerfMm;  // the cutter's kerf; cut paths move half of it
  j["bleed_mm"] = pattern.profile.bleedMm;
  j["tabs_on"] = tabSideName(pattern.profile.tabs);
  // Exported after a failed quality gate (--export-anyway): not for fabrication.
  j["failed_gate"] = pattern.failedGate;
  json pieces = json::array();
  auto polylines = [](const std::vector<Polyline>& lines) {
    json out = json::array();
    for (const Polyline& line : lines) out.push_back(polyline(line));
    return out;
  };
  for (const PieceInfo& p : pattern.pieces) {
    json creases = json::array();
    for (const CreaseInfo& c : p.creases)
      creases.push_back({{"id", c.id},
                         {"direction", foldDirectionName(c.fold.direction)},
                         {"angle_deg", c.fold.angleDeg},
                         {"min_angle_deg", c.fold.minAngleDeg},
                         {"max_angle_deg", c.fold.maxAngleDeg},
                         {"length_mm", c.fold.lengthMm},
                         {"line", polyline(c.line)}});
    json scored = json::array();
    for (const ScoredFoldInfo& f : p.scoredFolds)
      scored.push_back({{"id", f.id},
                        {"kind", "fold"},
                        {"angle_deg", f.angleDeg},
                        {"lines", polylines(f.lines)}});
    pieces.push_back({{"name", p.name},
                      {"perimeter_mm", p.perimeter},
                      {"rotation_deg", p.rotationDeg},
                      {"sheet", p.sheet},
                      {"outline", polyline(p.outline)},
                      {"seam_is_hole", p.seamIsHole},
                      {"boundaries", polylines(p.boundaries)},
                      {"cut", polylines(p.cut)},
                      {"hole_cuts", polylines(p.holeCuts)},
                      {"bleed", polylines(p.bleed)},
                      {"creases", creases}});
    if (!p.scoredFolds.empty()) pieces.back()["score_lines"] = scored;
    if (!p.hinges.empty()) pieces.back()["hinges"] = hingesJson(p);
  }
  j["pieces"] = pieces;
  json ticks = json::array();
  for (const TickInfo& t : pattern.ticks)
    ticks.push_back(
        {{"id", t.id}, {"s", t.s}, {"s_b", t.sB}, {"a", point(t.onA)}, {"b", point(t.onB)}});
  j["ticks"] = ticks;
  json tabs = json::array();
  for (const TabInfo& t : pattern.tabs)
    tabs.push_back({{"piece", pattern.pieces[size_t(t.piece)].name},
                    {"s0", t.s0},
                    {"s1", t.s1},
                    {"width", t.width},
                    {"polygon", polyline(t.polygon)},
                    {"fold", polyline(t.fold)}});
  j["tabs"] = tabs;
  addJoint(j, pattern);
  json pages = json::array();
  for (const PageView& p : pattern.pages)
    pages.push_back({{"kind", p.kind},
                     {"width", p.width},
                     {"height", p.height},
                     {"origin", point(p.origin)},
                     {"window",
                      {point(p.origin + Vec2(p.clipX0, p.clipY0)),
                       point(p.origin + Vec2(p.clipX1, p.clipY1))}}});
  j["pages"] = pages;
  // The sheets (pages) the pieces are laid out on, on the canvas; each piece's `sheet` indexes
  // them, and with more than one each is also a file of its own (`file`).
  json sheets = json::array();
  for (size_t k = 0; k < pattern.sheets.size(); ++k) {
    const Box& b = pattern.sheets[k];
    const bool alone = pattern.sheets.size() > 1;
    sheets.push_back({{"origin", point(b.lo)},
                      {"width", b.w()},
                      {"height", b.h()},
                      {"file", alone ? sheetFileName(int(k) + 1, "svg") : "pattern.svg"},
                      {"dxf", alone ? sheetFileName(int(k) + 1, "dxf") : "pattern.dxf"}});
  }
  j["sheets"] = sheets;
  addRegistration(j, pattern);
  if (!pattern.nestParts.empty()) {  // a nest: which D-Form each piece belongs to
    json parts = json::array();
    for (const NestPartInfo& part : pattern.nestParts)
      parts.push_back({{"name", part.name},
                       {"job", part.job},
                       {"copy", part.copy},
                       {"piece", part.piece == 0 ? "A" : "B"},
                       {"sheet", part.sheet},
                       {"turn_deg", part.turnDeg}});
    j["nest"] = {{"gap_mm", pattern.profile.kerfMm + 1.0}, {"parts", parts}};
  }
  j["messages"] = pattern.messages;
  if (!pattern.warnings.empty()) j["warnings"] = pattern.warnings;
  return j.dump(1, ' ', false, json::error_handler_t::replace);
}

}  // namespace dform::fab
