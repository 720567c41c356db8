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
std::vector<Choice> arrangementChoices(const std::vector<Polyline> cuts[2], double edge,
                                       double gap) {
  double baseRot[2];
  for (int p = 0; p < 2; ++p) baseRot[p] = bestRotation(cuts[p]);
  std::vector<Choice> choices;
  for (int ra = 0; ra < 2; ++ra)
    for (int rb = 0; rb < 2; ++rb)
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

// Both pieces on one sheet (a print page turned to landscape where only that fits), in the
// smallest arrangement that fits; false when none does.
bool arrangeTogether(const SheetFit& fit, const std::vector<Choice>& choices, Arrangement& a) {
  auto pick = [&](double W, double H) -> const Choice* {
    const Choice* best = nullptr;
    for (const Choice& c : choices)
      if (fit.fits(c.size, W, H) && (!best || c.size.prod() < best->size.prod() - 1e-9)) best = &c;
    return best;
  };
  const Choice* together = pick(fit.pageW, fit.pageH);
  bool landscape = false;
  if (!together && fit.mayTurnPage) {
    together = pick(fit.pageH, fit.pageW);
    landscape = together != nullptr;
  }
  if (!together) return false;
  SheetPlan plan;
  plan.box = Box::spanning(Vec2::Zero(),
                           landscape ? Vec2(fit.pageH, fit.pageW) : Vec2(fit.pageW, fit.pageH));
  plan.pieces = {0, 1};
  plan.size = together->size;
  const Box region = fit.artRegion(plan.box.w(), plan.box.h());
  plan.title = fit.titleAt(plan.size, region);
  for (int p = 0; p < 2; ++p) {
    a.rot[p] = together->rot[p];
    a.box[p] = together->box[p];
  }
  a.corner[0] = region.lo;
  a.corner[1] = region.lo + (together->vertical ? Vec2(0, a.box[0].h() + fit.m)
                                                : Vec2(a.box[0].w() + fit.m, 0));
  a.plans.push_back(plan);
  return true;
}

// Piece p on a sheet of its own whose left edge is at x on the canvas: at the smaller of its two
// turns that fits (a print page turned where only that fits), with its title block, else
// without, else (print) tiled across pages.
Status arrangeAlone(const SheetFit& fit, const std::vector<Choice>& choices, int p, double x,
                    const std::string& name, Arrangement& a) {
  SheetPlan plan;
  plan.pieces = {p};
  const Choice* best = nullptr;  // the rotations tried for this piece: its two in `choices`
  bool turned = false;
  // With its title block beside it where one fits, else bare (the title lines on a page of
  // their own): the title never makes a piece tiled or refused.
  for (bool withTitle : {true, false})
    for (bool turn : {false, true}) {
      if (best || (turn && !fit.mayTurnPage)) continue;
      const double W = turn ? fit.pageH : fit.pageW, H = turn ? fit.pageW : fit.pageH;
      for (const Choice& c : choices)
        if (fit.fits(Vec2(c.box[p].w(), c.box[p].h()), W, H, withTitle) &&
            (!best || c.box[p].w() * c.box[p].h() < best->box[p].w() * best->box[p].h() - 1e-9))
          best = &c;
      turned = turn;
    }
  if (best) {
    a.rot[p] = best->rot[p];
    a.box[p] = best->box[p];
    plan.box = Box::spanning(Vec2(x, 0), Vec2(x, 0) + (turned ? Vec2(fit.pageH, fit.pageW)
                                                              : Vec2(fit.pageW, fit.pageH)));
  } else if (fit.mayTile) {  // its turn of the smaller largest side, tiled
    best = &choices[0];
    for (const Choice& c : choices)
      if (std::max(c.box[p].w(), c.box[p].h()) < std::max(best->box[p].w(), best->box[p].h()))
        best = &c;
    a.rot[p] = best->rot[p];
    a.box[p] = best->box[p];
    plan.tiled = true;
    plan.box =
        Box::spanning(Vec2(x, 0), Vec2(x, 0) + fit.tiledExtent(Vec2(a.box[p].w(), a.box[p].h())));
    const auto [nx, ny] = fit.tileGrid(Vec2(a.box[p].w(), a.box[p].h()));
    plan.tilesX = nx;
    plan.tilesY = ny;
  } else {
    std::vector<Vec2> sizes;
    for (const Choice& c : choices) sizes.emplace_back(c.box[p].w(), c.box[p].h());
    return fit.tooLarge("piece " + name, sizes, "the piece with its tabs");
  }
  plan.size = Vec2(a.box[p].w(), a.box[p].h());
  const Box region = fit.artRegion(plan.box.w(), plan.box.h(), plan.box.lo);
  plan.title = fit.titleAt(plan.size, region);
  a.corner[p] = region.lo;
  a.plans.push_back(plan);
  return Status::ok();
}

}  // namespace

// Pieces are packed on as few sheets (pages) as hold them: both on one where they fit together
// (side by side or stacked, each at its smallest-box turn or a quarter turn more; a print page
// may turn to landscape), else each on its own, at the smaller of its two turns that fits (a
// print page turned where only that fits), else (print) tiled across pages.
Result<Arrangement> arrange(const SheetFit& fit, const std::vector<Polyline> cuts[2],
                            const std::string names[2], std::vector<std::string>& messages) {
  const std::vector<Choice> choices = arrangementChoices(cuts, fit.edge, fit.m);
  Arrangement a;
  if (!arrangeTogether(fit, choices, a)) {
    double x = 0;  // the sheets lie side by side on the canvas
    for (int p = 0; p < 2; ++p) {
      if (Status s = arrangeAlone(fit, choices, p, x, names[p], a); !s.isOk()) return s;
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
