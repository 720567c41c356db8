// SPDX-License-Identifier: GPL-3.0-or-later
// Arranging the pieces on sheets: each piece's turn (the smallest bounding box, or a quarter turn
// more), both on one sheet side by side or stacked where they fit, else each on its own (a print
// page turned to landscape, or tiled); then a piece placed on its sheet.
#include <algorithm>
#include <cmath>

#include "pattern_layout.h"

namespace dform::fab {

Eigen::Matrix2d flipRotate(double deg) {
  const double a = deg * kPi / 180.0;
  Eigen::Matrix2d R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R * Eigen::Vector2d(1, -1).asDiagonal();
}

namespace {

Box boxOf(const std::vector<Polyline>& paths, const Eigen::Matrix2d& M) {
  Box b;
  for (const auto& p : paths)
    for (const Vec2& q : p) b.add(M * q);
  return b;
}

// The rotation (degrees, in kTurnStepDeg steps) that gives the cut paths the smallest bounding box.
double bestRotation(const std::vector<Polyline>& cut) {
  double best = 0, bestArea = 1e300;
  for (int deg = 0; deg < 180; deg += kTurnStepDeg) {
    const Box b = boxOf(cut, flipRotate(deg));
    if (b.w() * b.h() < bestArea - 1e-9) {
      bestArea = b.w() * b.h();
      best = deg;
    }
  }
  return best;
}

}  // namespace

// A piece's extent on the sheet turned by `deg`: the box of its paths grown by `edge`, what sticks
// out of the outline (the ticks, kTickOut, or a printed bleed).
Box extentAt(const std::vector<Polyline>& paths, double deg, double edge) {
  Box b = boxOf(paths, flipRotate(deg));
  b.lo -= Vec2::Constant(edge);
  b.hi += Vec2::Constant(edge);
  return b;
}

namespace {

// Two pieces' extents side by side or stacked, `gap` apart: the arrangement's width and height.
Vec2 arranged(const Box& a, const Box& b, bool vertical, double gap) {
  return vertical ? Vec2(std::max(a.w(), b.w()), a.h() + gap + b.h())
                  : Vec2(a.w() + gap + b.w(), std::max(a.h(), b.h()));
}

// One arrangement of both pieces on a sheet: each piece's turn and extent, side by side or
// stacked, and the extent of the two.
struct Choice {
  double rot[2];
  bool vertical;
  Vec2 size;
  Box box[2];
};

// Each piece at its smallest-box turn or a quarter turn more, side by side or stacked.
std::vector<Choice> arrangementChoices(const std::vector<Polyline> cuts[2], double edge, double gap,
                                       int quarterTurns) {
  double baseRot[2];
  for (int p = 0; p < 2; ++p) baseRot[p] = bestRotation(cuts[p]);
  std::vector<Choice> choices;
  for (int ra = 0; ra < 2; ++ra)
    for (int rb = 0; rb < 2; ++rb)
      if (quarterTurns < 0 || (ra == quarterTurns && rb == quarterTurns))
        for (int v = 0; v < 2; ++v) {
          Choice c;
          c.rot[0] = baseRot[0] + 90 * ra;
          c.rot[1] = baseRot[1] + 90 * rb;
          c.vertical = v == 1;
          for (int p = 0; p < 2; ++p) c.box[p] = extentAt(cuts[p], c.rot[p], edge);
          c.size = arranged(c.box[0], c.box[1], c.vertical, gap);
          choices.push_back(c);
        }
  return choices;
}

// One way to put a sheet's pieces on it: the arrangement choice, the page turned or not, and its
// title block.
struct Candidate {
  const Choice* choice = nullptr;
  bool landscape = false;
  TitlePlace title;
};

// Whether candidate `c` of extent `size` is better than `best` of extent `bestSize`: a better
// title block (the full one before the mark, larger before smaller), then a page as it is before
// one turned, then the smaller extent.
bool better(const Candidate& c, const Vec2& size, const Candidate& best, const Vec2& bestSize) {
  if (!best.choice) return true;
  if (betterTitle(c.title, best.title)) return true;
  if (betterTitle(best.title, c.title)) return false;
  if (c.landscape != best.landscape) return !c.landscape;
  return size.prod() < bestSize.prod() - 1e-9;
}

// Both pieces on one sheet (a print page turned to landscape where that helps): every
// arrangement whose pieces fit with at least the mark beside them, the best title block first,
// then the page as it is, then the smallest; false when none does. The full title block never
// decides whether the pieces share a sheet.
bool arrangeTogether(const SheetFit& fit, const std::vector<Choice>& choices, const TitleText& text,
                     Arrangement& a) {
  Candidate best;
  for (bool landscape : {false, true}) {
    if (landscape && !fit.mayTurnPage) continue;
    const double W = landscape ? fit.pageH : fit.pageW, H = landscape ? fit.pageW : fit.pageH;
    const Box region = fit.artRegion(W, H);
    for (const Choice& c : choices) {
      if (!fit.fits(c.size, W, H)) continue;
      const Vec2 second =
          c.vertical ? Vec2(0, c.box[0].h() + fit.m) : Vec2(c.box[0].w() + fit.m, 0);
      const std::vector<Box> taken = {
          Box::spanning(region.lo, region.lo + Vec2(c.box[0].w(), c.box[0].h())),
          Box::spanning(region.lo + second, region.lo + second + Vec2(c.box[1].w(), c.box[1].h()))};
      const Candidate candidate{&c, landscape, placeTitle(region, taken, 0, 1, 0, fit, text)};
      if (candidate.title.placed &&
          better(candidate, c.size, best, best.choice ? best.choice->size : Vec2::Zero()))
        best = candidate;
    }
  }
  if (!best.choice) return false;
  const Choice& together = *best.choice;
  SheetPlan plan;
  plan.box = Box::spanning(
      Vec2::Zero(), best.landscape ? Vec2(fit.pageH, fit.pageW) : Vec2(fit.pageW, fit.pageH));
  plan.pieces = {0, 1};
  plan.size = together.size;
  plan.title = best.title;
  const Box region = fit.artRegion(plan.box.w(), plan.box.h());
  for (int p = 0; p < 2; ++p) {
    a.rot[p] = together.rot[p];
    a.box[p] = together.box[p];
  }
  a.corner[0] = region.lo;
  a.corner[1] = region.lo +
                (together.vertical ? Vec2(0, a.box[0].h() + fit.m) : Vec2(a.box[0].w() + fit.m, 0));
  a.plans.push_back(plan);
  return true;
}

// Piece p on a sheet of its own whose left edge is at x on the canvas: at the better of its two
// turns, on the page as it is or turned (print), with the best title block beside it; else
// (print) tiled across pages, else refused.
Status arrangeAlone(const SheetFit& fit, const std::vector<Choice>& choices, int p, double x,
                    const std::string& name, const TitleText& text, Arrangement& a) {
  SheetPlan plan;
  plan.pieces = {p};
  Candidate best;  // the rotations tried for this piece: its two in `choices`
  auto extent = [&](const Choice& c) { return Vec2(c.box[p].w(), c.box[p].h()); };
  for (bool landscape : {false, true}) {
    if (landscape && !fit.mayTurnPage) continue;
    const double W = landscape ? fit.pageH : fit.pageW, H = landscape ? fit.pageW : fit.pageH;
    const Box region = fit.artRegion(W, H);
    for (const Choice& c : choices) {
      if (!fit.fits(extent(c), W, H)) continue;
      const Candidate candidate{
          &c, landscape,
          placeTitle(region, {Box::spanning(region.lo, region.lo + extent(c))}, size_t(p), 2, p,
                     fit, text)};
      if (candidate.title.placed &&
          better(candidate, extent(c), best, best.choice ? extent(*best.choice) : Vec2::Zero()))
        best = candidate;
    }
  }
  if (best.choice) {
    a.rot[p] = best.choice->rot[p];
    a.box[p] = best.choice->box[p];
    plan.box = Box::spanning(
        Vec2(x, 0),
        Vec2(x, 0) + (best.landscape ? Vec2(fit.pageH, fit.pageW) : Vec2(fit.pageW, fit.pageH)));
    plan.title = best.title;
    // Placed on the sheet at the canvas's x: the block moves with it.
    plan.title.block.start += Vec2(x, 0);
  } else if (fit.mayTile) {  // its turn of the smaller largest side, tiled
    const Choice* tiled = &choices[0];
    for (const Choice& c : choices)
      if (std::max(c.box[p].w(), c.box[p].h()) < std::max(tiled->box[p].w(), tiled->box[p].h()))
        tiled = &c;
    a.rot[p] = tiled->rot[p];
    a.box[p] = tiled->box[p];
    plan.tiled = true;
    plan.box =
        Box::spanning(Vec2(x, 0), Vec2(x, 0) + fit.tiledExtent(Vec2(a.box[p].w(), a.box[p].h())));
    const auto [nx, ny] = fit.tileGrid(Vec2(a.box[p].w(), a.box[p].h()));
    plan.tilesX = nx;
    plan.tilesY = ny;
  } else {
    std::vector<Vec2> sizes;
    for (const Choice& c : choices)  // the mark under the piece or beside it
      for (const Vec2& room : {Vec2(0, fit.markRoom()), Vec2(fit.markRoom(), 0)})
        sizes.push_back(extent(c) + room);
    return fit.tooLarge("piece " + name, sizes,
                        fit.markRoom() > 0 ? "the piece with its tabs and the mark beside it"
                                           : "the piece with its tabs");
  }
  plan.size = Vec2(a.box[p].w(), a.box[p].h());
  a.corner[p] = fit.artRegion(plan.box.w(), plan.box.h(), plan.box.lo).lo;
  a.plans.push_back(plan);
  return Status::ok();
}

}  // namespace

// Pieces are packed on as few sheets (pages) as hold them with the mark: both on one where they
// fit together (side by side or stacked, each at its smallest-box turn or a quarter turn more; a
// print page may turn to landscape), else each on its own, else (print) tiled across pages.
Result<Arrangement> arrange(const SheetFit& fit, const std::vector<Polyline> cuts[2],
                            const std::string names[2], const TitleText& text,
                            std::vector<std::string>& messages, int quarterTurns) {
  const std::vector<Choice> choices = arrangementChoices(cuts, fit.edge, fit.m, quarterTurns);
  Arrangement a;
  if (!arrangeTogether(fit, choices, text, a)) {
    double x = 0;  // the sheets lie side by side on the canvas
    for (int p = 0; p < 2; ++p) {
      if (Status s = arrangeAlone(fit, choices, p, x, names[p], text, a); !s.isOk()) return s;
      x = a.plans.back().box.hi.x();
    }
    messages.push_back("the pieces do not fit one " +
                       (fit.pageName.empty() ? std::string("sheet") : fit.pageName + " page") +
                       " together: each is on its own, in pattern.pdf and in " +
                       sheetFileName(1, "svg") + " and " + sheetFileName(2, "svg") + " (and .dxf)");
  }
  long tiles = 0;
  for (const SheetPlan& plan : a.plans) tiles += plan.tilesX * plan.tilesY;
  if (tiles > kMaxTiles) return fit.tooManyTiles(tiles);
  return a;
}

// Piece p on the sheet: its outline, material, cut paths, tint and creases.
PieceInfo placedPiece(const FlatPieces& flat, int p, const std::vector<Polyline>& cuts,
                      const std::vector<Polyline>& holeCuts, const Placement& place,
                      const Arrangement& a, double bleedMm) {
  const Piece& piece = *flat.piece[p];
  PieceInfo info;
  info.name = flat.names[p];
  info.outline = place.map(flat.seams[p].P);
  for (const auto& loop : flat.material[p]) info.boundaries.push_back(place.map(loop));
  info.seamIsHole = flat.seams[p].hole;
  for (const auto& c : cuts) info.cut.push_back(place.map(c));
  for (const auto& c : holeCuts) info.holeCuts.push_back(place.map(c));
  if (bleedMm > 0)
    for (const auto& loop : bleedLoops(cuts, holeCuts, bleedMm))
      info.bleed.push_back(place.map(loop));
  const std::vector<CreaseFold> folds = creaseFolds(piece);
  for (size_t k = 0; k < folds.size(); ++k)
    info.creases.push_back({info.name + "-crease-" + std::to_string(k + 1) + "-" +
                                foldDirectionName(folds[k].direction),
                            folds[k], place.map(flatPolyline(piece.flat, piece.creases[k]))});
  info.perimeter = flat.seams[p].L;
  info.rotationDeg = a.rot[p];
  for (size_t k = 0; k < a.plans.size(); ++k)
    if (std::count(a.plans[k].pieces.begin(), a.plans[k].pieces.end(), p)) info.sheet = int(k);
  return info;
}

}  // namespace dform::fab
