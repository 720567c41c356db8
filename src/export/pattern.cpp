// SPDX-License-Identifier: GPL-3.0-or-later
// The flat pattern: ticks and tabs along the seam (seam_marks.cpp, glue_tabs.cpp), cut paths
// (outline with tabs merged, holes, kerf offset), then fitted to the sheet (sheet_fit.cpp),
// arranged on it (arrangement.cpp), drawn (pattern_drawing.cpp), its title block and marks
// (title_block.cpp) and its pages (tiling.cpp); scaled down to fit where asked. Geometry is
// computed in each piece's flat frame (mm, y up), then mapped to the sheet (y down). A piece's
// seam may be its outer outline or a hole's loop (anti and demi D-Forms): ticks and tabs go along
// the seam only, on the side away from the material.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dform/core/setting.h"
#include "pattern_layout.h"
#include "plane_geometry.h"

namespace dform::fab {

namespace {

// The closed polygon turned counter-clockwise (ccw) or clockwise.
Polyline oriented(const Polyline& P, bool ccw) {
  return (signedArea(toPoints(P)) >= 0) == ccw ? P : Polyline(P.rbegin(), P.rend());
}

// `region` (outer loops positive, holes negative) grown by `mm`: the outer loops move out and the
// holes shrink, corners rounded within 5 um.
ClipperLib::Paths grownRegion(const ClipperLib::Paths& region, double mm) {
  ClipperLib::ClipperOffset offset(2.0, 0.005 * kClipScale);
  offset.AddPaths(region, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  ClipperLib::Paths grown;
  offset.Execute(grown, mm * kClipScale);
  return grown;
}

// The seam loop with piece `piece`'s tabs spliced into it, in the seam's own direction: at each
// tab's fold start the loop leaves the seam along the tab's outer edge and rejoins it at the
// fold's end. Built rather than united with the piece, so that a tab is part of the piece's one
// cut loop by construction: a polygon union leaves a tab lying along a straight stretch of the
// outline (a square's side) as a loop of its own, touching the piece along its fold line.
Polyline seamWithTabs(const Seam& seam, const std::vector<FlatTab>& tabs, int piece) {
  std::vector<const FlatTab*> own;
  for (const FlatTab& t : tabs)
    if (t.piece == piece) own.push_back(&t);
  std::sort(own.begin(), own.end(),
            [](const FlatTab* a, const FlatTab* b) { return a->own0 < b->own0; });
  Polyline loop;
  size_t next = 0;
  double coveredTo = -1;  // seam vertices up to this arc length lie under a tab's fold line
  auto splice = [&](const FlatTab& t) {
    const size_t folds = t.fold.size();
    loop.push_back(t.fold.front());
    loop.insert(loop.end(), t.polygon.rbegin(), t.polygon.rend() - long(folds));
    loop.push_back(t.fold.back());
    coveredTo = t.own1;
  };
  for (int i = 0; i < seam.n(); ++i) {
    const double s = seam.cum[size_t(i)];
    for (; next < own.size() && own[next]->own0 <= s; ++next) splice(*own[next]);
    if (s > coveredTo) loop.push_back(seam.P[size_t(i)]);
  }
  for (; next < own.size(); ++next) splice(*own[next]);
  return loop;
}

// The closed cut paths of one piece (flat frame): its outline with its tabs spliced in, and its
// holes, offset by half the kerf (outward from the material: the outline grows and the holes
// shrink), so that what the beam leaves has the drawn size.
// `freeLoops` are its free boundaries; `outer` is outerLoopIndex (0 the seam, k free loop k - 1).
// One cut loop per boundary loop, tabs or not.
CutPaths cutPaths(const Seam& seam, const std::vector<Polyline>& freeLoops, int outer,
                  const std::vector<FlatTab>& tabs, int piece, double kerf) {
  const double offset = 0.5 * kerf;
  std::vector<Polyline> loops{seamWithTabs(seam, tabs, piece)};
  loops.insert(loops.end(), freeLoops.begin(), freeLoops.end());
  CutPaths out;
  if (offset <= 0) {
    for (size_t k = 0; k < loops.size(); ++k)
      (int(k) == outer ? out.outer : out.holes).push_back(oriented(loops[k], int(k) == outer));
    return out;
  }
  // Non-zero winding: the outline counter-clockwise, holes clockwise.
  ClipperLib::Paths region;
  for (size_t k = 0; k < loops.size(); ++k) {
    region.push_back(toClip(loops[k]));
    if (int(k) != outer) ClipperLib::ReversePath(region.back());
  }
  for (const auto& p : grownRegion(region, offset))
    (ClipperLib::Orientation(p) ? out.outer : out.holes).push_back(fromClip(p));
  return out;
}

}  // namespace

// A piece's material in its flat frame: every boundary loop, the outer outline first (even-odd).
std::vector<Polyline> materialLoops(const Piece& piece) {
  const std::vector<std::vector<int>> loops = boundaryLoops(piece);
  const size_t outer = size_t(outerLoopIndex(piece));
  std::vector<Polyline> material{flatPolyline(piece.flat, loops[outer])};
  for (size_t k = 0; k < loops.size(); ++k)
    if (k != outer) material.push_back(flatPolyline(piece.flat, loops[k]));
  return material;
}

// A piece's printed tint (flat frame; outer loops counter-clockwise, holes clockwise): its cut
// region grown by `bleed`, each hole shrunk by it and left out.
std::vector<Polyline> bleedLoops(const std::vector<Polyline>& outer,
                                 const std::vector<Polyline>& holes, double bleed) {
  ClipperLib::Paths region;
  for (const Polyline& loop : outer) region.push_back(toClip(loop));
  for (const Polyline& loop : holes) {  // toClip turns every loop counter-clockwise
    region.push_back(toClip(loop));
    ClipperLib::ReversePath(region.back());
  }
  std::vector<Polyline> out;
  for (const auto& p : grownRegion(region, bleed)) out.push_back(fromClip(p));
  return out;
}

Points2 toPoints(const Polyline& p) {
  Points2 P(Eigen::Index(p.size()), 2);
  for (size_t i = 0; i < p.size(); ++i) P.row(Eigen::Index(i)) = p[i].transpose();
  return P;
}

std::string formatMm(double x, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

Polyline flatPolyline(const Points2& flat, const std::vector<int>& loop) {
  Polyline P;
  for (int v : loop) P.emplace_back(flat(v, 0), flat(v, 1));
  return P;
}

std::string twoDigits(int k) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", k);
  return buf;
}

std::string tickLabel(int k) {
  std::string s = std::to_string(k);
  std::string turned;
  for (auto it = s.rbegin(); it != s.rend(); ++it) {
    const char c = *it;
    if (c == '6')
      turned += '9';
    else if (c == '9')
      turned += '6';
    else if (c == '0' || c == '1' || c == '8')
      turned += c;
    else
      return s;
  }
  return turned != s ? s + "." : s;
}

Status checkModel(const DForm& model) {
  for (const Piece* p : {&model.a, &model.b}) {
    const std::string name = p->name.empty() ? (p == &model.a ? "A" : "B") : p->name;
    if (p->seam.size() < 3)
      return {ErrorCode::InputInvalid, "piece " + name + ": the seam has fewer than 3 points"};
    if (p->shape.rows() != p->flat.rows())
      return {ErrorCode::InputInvalid, "piece " + name + ": flat and 3D vertex counts differ"};
    auto inRange = [&](const std::vector<int>& line) {
      return std::all_of(line.begin(), line.end(),
                         [&](int v) { return v >= 0 && v < p->flat.rows(); });
    };
    if (!inRange(p->seam))
      return {ErrorCode::InputInvalid, "piece " + name + ": a seam index is out of range"};
    for (const auto& loop : p->freeBoundaries)
      if (loop.size() < 3 || !inRange(loop))
        return {
            ErrorCode::InputInvalid,
            "piece " + name + ": a free boundary has fewer than 3 points or an index out of range"};
    for (const auto& crease : p->creases)
      if (crease.size() < 2 || !inRange(crease))
        return {ErrorCode::InputInvalid,
                "piece " + name + ": a crease has fewer than 2 points or an index out of range"};
    if (p->F.size() > 0 && (p->F.minCoeff() < 0 || p->F.maxCoeff() >= p->flat.rows()))
      return {ErrorCode::InputInvalid, "piece " + name + ": a face index is out of range"};
    if (!p->flat.allFinite() || !p->shape.allFinite())
      return {ErrorCode::InputInvalid, "piece " + name + ": a vertex is not finite"};
  }
  if (model.a.seam.size() != model.b.seam.size())
    return {ErrorCode::InputInvalid, "the pieces' seams have different point counts (" +
                                         std::to_string(model.a.seam.size()) + " and " +
                                         std::to_string(model.b.seam.size()) + ")"};
  return Status::ok();
}

// Piece p's closed cut paths (flat frame): its seam and free boundaries with its tabs merged in,
// and its joint holes (`jointHoles`, flat frame).
CutPaths pieceCutPaths(const FlatPieces& flat, int p, const std::vector<FlatTab>& tabs,
                       const std::vector<Polyline>& jointHoles, double kerf) {
  const Piece& piece = *flat.piece[p];
  std::vector<Polyline> freeLoops;
  for (const auto& loop : piece.freeBoundaries) freeLoops.push_back(flatPolyline(piece.flat, loop));
  freeLoops.insert(freeLoops.end(), jointHoles.begin(), jointHoles.end());
  return cutPaths(flat.seams[p], freeLoops, outerLoopIndex(piece), tabs, p, kerf);
}

namespace {

// The pattern of `model` drawn at `scale` (its flat pieces already scaled by it). `tooLargeOut`
// is set when it fails because a piece does not fit its sheet or page.
Result<PatternBuild> buildAtScale(const DForm& model, const ExportOptions& o,
                                  const Profile& profile, const StrokeFont& font, double scale,
                                  BuildWork& work, bool& tooLargeOut, const NestLayout* nest) {
  PatternBuild out;
  out.scale = scale;
  out.profile = profile;
  out.tickSpacing = o.tickSpacingMm;
  const FlatPieces flat(model);
  Result<SheetFit> fitResult = sheetFit(o, profile, flat.creased, scale, tooLargeOut);
  if (!fitResult.isOk()) return fitResult.status();
  const SheetFit& fit = fitResult.value();
  if (Status s = checkOutlinesFit(fit, flat); !s.isOk()) return s;
  // Seam lengths agree to the gate's tolerance on a solved model; ticks and tabs mark matching
  // seam points on both pieces whatever the difference, which a fabricator sees as a slightly
  // different tick spacing on B (0.1 mm is the accuracy the ticks are held to).
  const Seam* seams = flat.seams;
  if (std::abs(seams[0].L - seams[1].L) > 0.1) {
    out.messages.push_back("the seams differ in length by " +
                           formatMm(std::abs(seams[0].L - seams[1].L), 2) +
                           " mm; partner ticks mark the same seam point, so B's tick spacing "
                           "differs slightly from A's");
  }
  // Everything along the seam is placed by the seam parameter: A's arc length.
  const double L = seams[0].L;
  const std::vector<double> tickS = tickParameters(L, o.tickSpacingMm, work);
  const std::vector<FlatTab> tabs =
      makeTabs(seams, flat.material, o, profile.tabs, L, out.messages, work);
  out.joint = jointSettings(o, profile);
  const FlatJoints joints = makeJoints(seams, flat.material, out.joint, out.messages);
  std::vector<Polyline> holeLoops[2];
  for (const FlatHole& h : joints.holes) holeLoops[h.piece].push_back(holeLoop(h));
  for (const FlatSlot& slot : joints.slots) holeLoops[1].push_back(slot.loop);
  // The tongues grow out of A's outline as its tabs do (resolveProfile keeps tabs off A then).
  std::vector<FlatTab> outlineParts = tabs;
  outlineParts.insert(outlineParts.end(), joints.tongues.begin(), joints.tongues.end());
  std::vector<Polyline> cuts[2], holeCuts[2];
  for (int p = 0; p < 2; ++p) {
    CutPaths c = pieceCutPaths(flat, p, outlineParts, holeLoops[p], profile.kerfMm);
    cuts[p] = std::move(c.outer);
    holeCuts[p] = std::move(c.holes);
  }
  const std::string perimeterText = formatMm(seams[0].L, 1);
  const std::string scaleText =
      scale == 1.0 ? std::string("1:1, mm") : "scale " + percentText(scale) + " of true size, mm";
  const TitleText title{o,
                        "D-Form " + flat.names[0] + " + " + flat.names[1],
                        scaleText,
                        "seam " + perimeterText + " mm",
                        {flat.names[0], flat.names[1]},
                        flat.creased,
                        font};
  Result<Arrangement> arranged =
      arrange(fit, cuts, flat.names, title, out.messages, nest ? nest->quarterTurns : -1);
  if (!arranged.isOk()) return arranged.status();
  const Arrangement& a = arranged.value();
  double canvasW = 0, canvasH = 0;
  for (const SheetPlan& plan : a.plans) {
    out.sheets.push_back(plan.box);
    canvasW = std::max(canvasW, plan.box.hi.x());
    canvasH = std::max(canvasH, plan.box.hi.y());
  }
  Placement place[2];
  for (int p = 0; p < 2; ++p) {
    place[p].M = flipRotate(a.rot[p]);
    place[p].t = a.corner[p] - a.box[p].lo;
    out.pieces.push_back(placedPiece(flat, p, cuts[p], holeCuts[p], place[p], a, profile.bleedMm));
    for (const Polyline& loop : holeLoops[p]) {  // the material has the joint holes too
      out.pieces.back().jointLoops.push_back(place[p].map(loop));
      out.pieces.back().boundaries.push_back(out.pieces.back().jointLoops.back());
    }
    out.pieces.back().scoredFolds = scoredFolds(o, p, place[p], scale, out.pieces.back());
  }
  out.ticks = placeTicks(tickS, seams, place);
  out.tabs = placeTabs(tabs, place);
  for (const FlatHole& h : joints.holes)
    out.jointHoles.push_back(
        {h.piece, h.index, h.s, h.own, place[h.piece].point(h.centre), h.diameter});
  const std::vector<TabInfo> tongues = placeTabs(joints.tongues, place);
  for (size_t k = 0; k < joints.slots.size(); ++k) {
    const FlatSlot& slot = joints.slots[k];
    out.jointSlots.push_back({slot.index, slot.s, tongues[k].s0, tongues[k].s1, tongues[k].polygon,
                              tongues[k].fold, place[1].map(slot.loop), place[1].point(slot.centre),
                              slot.length, slot.width});
  }

  DrawingBuilder b(profile, canvasW, canvasH);
  describe(b.drawing(), o, profile, scale, perimeterText);
  drawPieceLabels(flat, place, profile, font, b, out, work, nest != nullptr);
  drawCreases(out.pieces, profile, b);
  drawScoredFolds(out.pieces, b);
  drawTabFolds(out.tabs, flat.names, "", profile, b);
  drawTabFolds(tongues, flat.names, "tongue-", profile, b);
  addHinges(o, flat, holeLoops, place, scale, b, out);
  drawCuts(out.pieces, flat.names, profile, b);
  drawSheetFurniture(a.plans, fit, title, b);
  out.drawing = std::move(b.drawing());
  addPages(a.plans, fit, title, out);
  return out;
}

// The model with its flat pieces scaled by `scale` (the 3D shape, which the pattern does not
// draw, as it is).
DForm scaledFlat(const DForm& model, double scale) {
  DForm scaled = model;
  scaled.a.flat *= scale;
  scaled.b.flat *= scale;
  return scaled;
}

// The pattern of `model` at `scale` with options `o`; `tooLarge` is set when a piece does not fit.
Result<PatternBuild> buildScaled(const DForm& model, const ExportOptions& o, const Profile& profile,
                                 const StrokeFont& font, double scale, BuildWork& work,
                                 bool& tooLarge, const NestLayout* nest = nullptr) {
  tooLarge = false;
  return buildAtScale(scale == 1.0 ? model : scaledFlat(model, scale), o, profile, font, scale,
                      work, tooLarge, nest);
}

// The largest scale below `failsAt` (in tenths of a percent, where a piece does not fit) at which
// the pattern fits, found by bisection: a smaller scale never makes a piece's extent larger (its
// outline shrinks; its tabs and ticks keep their size). `built` is the pattern at that scale;
// with no such scale down to 0.1 % `permille` is 0 and `built` is `failure`; `otherError` when a
// build failed for another reason than a piece too large (`built` is that failure).
struct ScaleFit {
  int permille = 0;
  Result<PatternBuild> built;
  bool otherError = false;
};
ScaleFit largestFittingScale(const DForm& model, const ExportOptions& o, const Profile& profile,
                             const StrokeFont& font, int failsAt, const Status& failure,
                             BuildWork& work) {
  ScaleFit best{0, failure};
  while (failsAt - best.permille > 1) {
    const int mid = (best.permille + failsAt) / 2;
    bool tooLarge = false;
    Result<PatternBuild> attempt =
        buildScaled(model, o, profile, font, mid / 1000.0, work, tooLarge);
    if (attempt.isOk()) {
      best = ScaleFit{mid, std::move(attempt)};
    } else if (tooLarge) {
      failsAt = mid;
    } else {
      return ScaleFit{0, std::move(attempt), true};
    }
  }
  return best;
}

// What makes a pattern that does not fit at the scale asked fit: the largest scale that does
// (`permille`, 0 for none), a larger sheet, or a larger page where one fits at the scale asked.
// (The title block is never the obstacle: it goes on a page of its own where it does not fit.)
std::string fitAdvice(const DForm& model, const ExportOptions& o, const Profile& profile,
                      const StrokeFont& font, int permille, BuildWork& work) {
  std::string advice = permille >= 50
                           ? "; the largest scale that fits is " + percentText(permille / 1000.0) +
                                 ": " + mention(Setting::Scale) + " fit makes it so"
                           : "; it does not fit even at 5 %";
  bool tooLarge = false;
  const std::string page = o.page.empty() ? profile.page : o.page;
  if (page.empty()) return advice + ", or give a larger " + mention(Setting::Sheet);
  for (const char* larger : {"A3", "Tabloid"}) {
    const auto size = pageSizeMm(larger), now = pageSizeMm(page);
    if (!size || !now || size->first * size->second <= now->first * now->second) continue;
    ExportOptions onLarger = o;
    onLarger.page = larger;
    if (buildScaled(model, onLarger, profile, font, o.scale, work, tooLarge).isOk())
      return advice + ", or " + mention(Setting::Page) + " " + larger + " prints it at " +
             percentText(o.scale);
  }
  return advice;
}

// What prints a tiled pattern without tiles: the largest scale at which every piece fits a page
// (`--scale`), a larger page at the scale asked; empty when neither does.
std::string tileAdvice(const DForm& model, const ExportOptions& o, const Profile& profile,
                       const StrokeFont& font, BuildWork& work) {
  Profile untiled = profile;
  untiled.tile = false;
  bool tooLarge = false;
  Result<PatternBuild> whole = buildScaled(model, o, untiled, font, o.scale, work, tooLarge);
  if (whole.isOk() || !tooLarge) return "";
  std::vector<std::string> ways;
  const ScaleFit fit = largestFittingScale(model, o, untiled, font,
                                           int(std::lround(1000 * o.scale)), whole.status(), work);
  if (fit.permille >= 50 && !fit.otherError) {
    char flag[32];  // the option's value without the space percentText puts before "%"
    std::snprintf(flag, sizeof flag, "%.1f%%", fit.permille / 10.0);
    ways.push_back("at " + percentText(fit.permille / 1000.0) + " (" + mention(Setting::Scale) +
                   " " + flag + ") it fits one page a piece");
  }
  const std::string page = o.page.empty() ? profile.page : o.page;
  for (const char* larger : {"A3", "Tabloid"}) {
    const auto size = pageSizeMm(larger), now = pageSizeMm(page);
    if (!size || !now || size->first * size->second <= now->first * now->second) continue;
    ExportOptions onLarger = o;
    onLarger.page = larger;
    if (buildScaled(model, onLarger, untiled, font, o.scale, work, tooLarge).isOk()) {
      ways.push_back(mention(Setting::Page) + " " + larger + " prints it untiled at " +
                     percentText(o.scale));
      break;
    }
  }
  if (ways.empty()) return "";
  return "to print without tiles: " + ways.front() + (ways.size() > 1 ? ", or " + ways[1] : "");
}

}  // namespace

Result<PatternBuild> buildNestPattern(const DForm& model, const ExportOptions& o,
                                      const Profile& profile, const StrokeFont& font,
                                      const NestLayout& nest) {
  if (Status s = checkModel(model); !s.isOk()) return s;
  if (Status s = checkExportOptions(o); !s.isOk()) return s;
  BuildWork work;
  bool tooLarge = false;
  return buildScaled(model, o, profile, font, o.scale, work, tooLarge, &nest);
}

Result<PatternBuild> buildPattern(const DForm& model, const ExportOptions& o,
                                  const Profile& profile, BuildWork* workOut) {
  BuildWork unused;
  BuildWork& work = workOut ? *workOut : unused;
  if (Status s = checkModel(model); !s.isOk()) return s;
  if (Status s = checkExportOptions(o); !s.isOk()) return s;
  if (profile.page.empty() && !(o.sheetWidthMm > 0 && o.sheetHeightMm > 0))
    return Status{ErrorCode::Usage, "the sheet size must be positive (e.g. 600x400mm)"};
  auto fontResult = StrokeFont::load(o.fontPath);
  if (!fontResult.isOk()) return fontResult.status();
  const StrokeFont& font = fontResult.value();
  // The pattern's assembly page, once it is laid out.
  auto withAssembly = [&](Result<PatternBuild> built) {
    if (built.isOk()) built.value().assembly = assemblyPage(model, built.value(), o, font);
    return built;
  };
  bool tooLarge = false;
  Result<PatternBuild> built = buildScaled(model, o, profile, font, o.scale, work, tooLarge);
  if (built.isOk() && std::any_of(built.value().pages.begin(), built.value().pages.end(),
                                  [](const PageView& page) { return page.kind == "tile"; })) {
    BuildWork adviceWork;  // a refusal's advice is not the pattern's work
    if (std::string advice = tileAdvice(model, o, profile, font, adviceWork); !advice.empty())
      built.value().messages.push_back(advice);
  }
  if (built.isOk() || !tooLarge) return withAssembly(std::move(built));
  // A piece does not fit: the largest scale, to a tenth of a percent, at which every piece does.
  // Only a pattern scaled to fit counts the search as its work: a refusal's advice is the work of
  // patterns of an ordinary size.
  const Status atScale = built.status();
  BuildWork adviceWork;
  BuildWork& searchWork = o.scaleToFit ? work : adviceWork;
  ScaleFit fit = largestFittingScale(model, o, profile, font, int(std::lround(1000 * o.scale)),
                                     atScale, searchWork);
  if (!o.scaleToFit) {
    if (fit.otherError) return fit.built.status();
    return Status{atScale.code(),
                  atScale.message() + fitAdvice(model, o, profile, font, fit.permille, searchWork)};
  }
  if (fit.permille == 0 || fit.otherError) return fit.built;
  fit.built.value().messages.push_back("scaled to " + percentText(fit.permille / 1000.0) +
                                       " to fit: at " + percentText(o.scale) + " " +
                                       atScale.message());
  return withAssembly(std::move(fit.built));
}

}  // namespace dform::fab
