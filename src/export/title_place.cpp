// SPDX-License-Identifier: GPL-3.0-or-later
// Where each sheet's title block goes: in the free rectangles of its art region, around the
// pieces already placed, the full block at the largest text height that fits, else the mark every
// cut sheet carries (the job's name and the 50 mm bar), small if need be. The block never costs a
// sheet: an arrangement is judged with the mark, never with the full block.
#include <algorithm>

#include "pattern_layout.h"

namespace dform::fab {

namespace {

// Whether the block's lines (and the bar) fit `length` x `depth` mm at capital height h: every
// line no smaller than kMinTitleH where it is shrunk to the length, the bar and its label too.
bool blockFits(const std::vector<TitleLine>& lines, bool bar, const std::string& label, double h,
               double length, double depth, const StrokeFont& font) {
  if (double(lines.size()) * kTitlePitch * h + (bar ? kBarRow : 0.0) > depth + 1e-9) return false;
  for (const TitleLine& line : lines)
    if (font.width(line.words, kMinTitleH) > length + 1e-9) return false;
  return !bar || kBarLabelAt + font.width(label, kMinTitleH) <= length + 1e-9;
}

// Whether the open interiors of two boxes meet (touching boxes do not).
bool interiorsMeet(const Box& a, const Box& b) {
  const double eps = 1e-9;
  return a.lo.x() < b.hi.x() - eps && b.lo.x() < a.hi.x() - eps && a.lo.y() < b.hi.y() - eps &&
         b.lo.y() < a.hi.y() - eps;
}

}  // namespace

std::vector<Box> freeRectangles(const Box& region, const std::vector<Box>& taken, double gap) {
  std::vector<double> xs{region.lo.x(), region.hi.x()}, ys{region.lo.y(), region.hi.y()};
  Box all;
  std::vector<Box> grown;
  for (const Box& b : taken) {
    grown.push_back(Box::spanning(b.lo - Vec2::Constant(gap), b.hi + Vec2::Constant(gap)));
    all.add(b.lo);
    all.add(b.hi);
    for (double x : {grown.back().lo.x(), grown.back().hi.x()})
      if (x > region.lo.x() && x < region.hi.x()) xs.push_back(x);
    for (double y : {grown.back().lo.y(), grown.back().hi.y()})
      if (y > region.lo.y() && y < region.hi.y()) ys.push_back(y);
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  auto isFree = [&](const Box& r) {
    return r.w() > 0 && r.h() > 0 && std::none_of(grown.begin(), grown.end(), [&](const Box& g) {
             return interiorsMeet(r, g);
           });
  };
  std::vector<Box> out;
  if (!taken.empty())
    for (const Box& r : {Box::spanning(Vec2(region.lo.x(), all.hi.y() + gap), region.hi),
                         Box::spanning(Vec2(all.hi.x() + gap, region.lo.y()), region.hi)})
      if (isFree(r)) out.push_back(r);
  for (size_t x0 = 0; x0 < xs.size(); ++x0)
    for (size_t x1 = x0 + 1; x1 < xs.size(); ++x1)
      for (size_t y0 = 0; y0 < ys.size(); ++y0)
        for (size_t y1 = y0 + 1; y1 < ys.size(); ++y1) {
          const Box r = Box::spanning(Vec2(xs[x0], ys[y0]), Vec2(xs[x1], ys[y1]));
          if (isFree(r)) out.push_back(r);
        }
  return out;
}

TitlePlace placeTitle(const Box& region, const std::vector<Box>& taken, size_t k, size_t sheets,
                      int piece, const SheetFit& fit, const TitleText& text) {
  const std::vector<Box> rects = freeRectangles(region, taken, fit.m);
  const bool bar = fit.profile->calibrationBar;
  const std::vector<TitleLine> mark = titleLines(k, sheets, piece, false, fit, text);
  for (bool full : {true, false}) {
    if (full && !text.o.title) continue;
    const std::vector<TitleLine> lines = titleLines(k, sheets, piece, full, fit, text);
    const std::string label = barLabel(full, fit);
    for (int step = 0; fit.textH - 0.25 * step >= kMinTitleH - 1e-9; ++step) {
      const double h = fit.textH - 0.25 * step;
      for (const Box& r : rects)
        for (bool upwards : {false, true}) {
          const double length = upwards ? r.h() : r.w(), depth = upwards ? r.w() : r.h();
          // The full block only where the mark would fit too: with the title on or off, the
          // pieces are laid out alike.
          if (!blockFits(lines, bar, label, h, length, depth, text.font) ||
              !blockFits(mark, bar, barLabel(false, fit), kMinTitleH, length, depth, text.font))
            continue;
          TitlePlace place;
          place.placed = true;
          place.full = full;
          place.h = h;
          place.block.along = upwards ? Vec2(0, -1) : Vec2(1, 0);
          place.block.across = upwards ? Vec2(1, 0) : Vec2(0, 1);
          place.block.start = upwards ? Vec2(r.lo.x(), r.hi.y()) : r.lo;
          place.block.length = length;
          return place;
        }
    }
  }
  return TitlePlace{};
}

bool betterTitle(const TitlePlace& a, const TitlePlace& b) {
  if (a.placed != b.placed) return a.placed;
  if (a.full != b.full) return a.full;
  return a.h > b.h + 1e-9;
}

}  // namespace dform::fab
