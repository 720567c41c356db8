// SPDX-License-Identifier: GPL-3.0-or-later
// Packing a nest's parts on sheets: rectangles (each part's extent at either of its two turns) on
// as few sheets as hold them. Several greedy packings are made (MaxRects, Jylänki 2010, with three
// rules for the free rectangle, and shelves), each with the parts in three orders, and the one on
// the fewest sheets wins, then the one that fills its earlier sheets most. Everything is
// deterministic: ties go to the earlier candidate.
#include "nest_pack.h"

#include <algorithm>
#include <numeric>

namespace dform::fab {

namespace {

struct Rect {
  double x = 0, y = 0, w = 0, h = 0;
  double right() const { return x + w; }
  double bottom() const { return y + h; }
  bool contains(const Rect& o) const {
    const double eps = 1e-9;
    return o.x >= x - eps && o.y >= y - eps && o.right() <= right() + eps &&
           o.bottom() <= bottom() + eps;
  }
  bool meets(const Rect& o) const {
    const double eps = 1e-9;
    return o.x < right() - eps && x < o.right() - eps && o.y < bottom() - eps &&
           y < o.bottom() - eps;
  }
};

enum class Rule { ShortSide, Area, BottomLeft };

// One sheet's free rectangles (MaxRects): the maximal rectangles no placed part meets.
class Bin {
 public:
  Bin(double w, double h) { free_.push_back({0, 0, w, h}); }
  // Where a w x h rectangle goes by `rule` (its score, lower is better), or false.
  bool find(double w, double h, Rule rule, Rect& at, double& score) const {
    bool found = false;
    for (const Rect& f : free_) {
      if (w > f.w + 1e-9 || h > f.h + 1e-9) continue;
      const double s = rule == Rule::ShortSide
                           ? std::min(f.w - w, f.h - h) * 1e6 + std::max(f.w - w, f.h - h)
                       : rule == Rule::Area ? f.w * f.h - w * h
                                            : (f.y + h) * 1e6 + f.x;
      if (!found || s < score - 1e-9) {
        found = true;
        score = s;
        at = {f.x, f.y, w, h};
      }
    }
    return found;
  }
  void place(const Rect& r) {
    std::vector<Rect> next;
    for (const Rect& f : free_) {
      if (!f.meets(r)) {
        next.push_back(f);
        continue;
      }
      if (r.x > f.x) next.push_back({f.x, f.y, r.x - f.x, f.h});
      if (r.right() < f.right()) next.push_back({r.right(), f.y, f.right() - r.right(), f.h});
      if (r.y > f.y) next.push_back({f.x, f.y, f.w, r.y - f.y});
      if (r.bottom() < f.bottom()) next.push_back({f.x, r.bottom(), f.w, f.bottom() - r.bottom()});
    }
    free_.clear();
    for (size_t i = 0; i < next.size(); ++i) {
      bool inside = false;
      for (size_t j = 0; j < next.size() && !inside; ++j)
        inside = j != i && next[j].contains(next[i]) && !(next[i].contains(next[j]) && j > i);
      if (!inside) free_.push_back(next[i]);
    }
    used_ += r.w * r.h;
  }
  double used() const { return used_; }

 private:
  std::vector<Rect> free_;
  double used_ = 0;
};

// The parts in `order` packed by MaxRects with `rule`: each part on the first sheet where one of
// its turns fits (the better turn there), else on a new sheet; every sheet starts with `reserved`
// taken at its bottom left. Parts and the reserved box are grown by `gap` on their right and
// bottom sides, the sheet by `gap` too, so that neighbours keep `gap` apart.
Packing maxRects(const std::vector<PackItem>& items, const std::vector<int>& order,
                 const Vec2& region, double gap, const Vec2& reserved, Rule rule) {
  Packing out;
  std::vector<Bin> bins;
  auto newBin = [&]() {
    bins.emplace_back(region.x() + gap, region.y() + gap);
    if (reserved.x() > 0 && reserved.y() > 0)
      bins.back().place({0, region.y() - reserved.y(), reserved.x() + gap, reserved.y() + gap});
  };
  // Part i on sheet b, at the better of its turns that fits there.
  auto tryPlace = [&](int i, size_t b) {
    Rect best;
    double bestScore = 0;
    int bestTurn = -1;
    for (int turn = 0; turn < 2; ++turn) {
      const Vec2& s = items[size_t(i)].size[turn];
      Rect at;
      double score = 0;
      if (bins[b].find(s.x() + gap, s.y() + gap, rule, at, score) &&
          (bestTurn < 0 || score < bestScore - 1e-9)) {
        best = at;
        bestScore = score;
        bestTurn = turn;
      }
    }
    if (bestTurn < 0) return false;
    bins[b].place(best);
    out.placed.push_back({i, bestTurn, int(b), Vec2(best.x, best.y)});
    return true;
  };
  for (int i : order) {
    bool placed = false;
    for (size_t b = 0; b < bins.size() && !placed; ++b) placed = tryPlace(i, b);
    if (placed) continue;
    newBin();
    if (!tryPlace(i, bins.size() - 1)) return Packing{};  // it fits no sheet
  }
  out.sheets = int(bins.size());
  return out;
}

// The parts in `order` on shelves: each turned so that it is no taller than wide, in rows along
// the sheet as long as they fit, a new row under the tallest of the last, a new sheet when a row
// does not fit under the last one.
Packing shelves(const std::vector<PackItem>& items, const std::vector<int>& order,
                const Vec2& region, double gap, const Vec2& reserved) {
  Packing out;
  int sheet = -1;
  double x = 0, y = 0, rowH = 0;
  const double bottom = region.y() - (reserved.y() > 0 ? reserved.y() + gap : 0);
  for (int i : order) {
    const PackItem& item = items[size_t(i)];
    const int turn = item.size[0].y() <= item.size[0].x() ? 0 : 1;
    const Vec2 s = item.size[turn];
    if (s.x() > region.x() + 1e-9 || s.y() > bottom + 1e-9) return Packing{};
    if (sheet >= 0 && x + s.x() > region.x() + 1e-9) {
      x = 0;
      y += rowH + gap;
      rowH = 0;
    }
    if (sheet < 0 || y + s.y() > bottom + 1e-9) {
      ++sheet;
      x = y = rowH = 0;
    }
    out.placed.push_back({i, turn, sheet, Vec2(x, y)});
    x += s.x() + gap;
    rowH = std::max(rowH, s.y());
  }
  out.sheets = sheet + 1;
  return out;
}

// The area each sheet of `p` holds, sheet by sheet.
std::vector<double> filled(const std::vector<PackItem>& items, const Packing& p) {
  std::vector<double> area(size_t(p.sheets), 0.0);
  for (const PackPlacement& q : p.placed)
    area[size_t(q.sheet)] += items[size_t(q.item)].size[q.turn].prod();
  return area;
}

// Whether packing `a` is better than `b`: fewer sheets, then its sheets filled more in order
// (the last sheet holding least: offcuts stay whole).
bool betterPacking(const std::vector<PackItem>& items, const Packing& a, const Packing& b) {
  if (a.sheets != b.sheets) return a.sheets < b.sheets;
  const std::vector<double> fa = filled(items, a), fb = filled(items, b);
  for (size_t k = 0; k + 1 < fa.size(); ++k)
    if (std::abs(fa[k] - fb[k]) > 1e-6) return fa[k] > fb[k];
  return false;
}

}  // namespace

Packing packParts(const std::vector<PackItem>& items, const Vec2& region, double gap,
                  const Vec2& reserved) {
  std::vector<std::vector<int>> orders;
  std::vector<int> base(items.size());
  std::iota(base.begin(), base.end(), 0);
  for (int key = 0; key < 3; ++key) {
    std::vector<int> order = base;
    auto measure = [&](int i) {
      const Vec2& s = items[size_t(i)].size[0];
      return key == 0 ? s.prod() : key == 1 ? std::max(s.x(), s.y()) : std::min(s.x(), s.y());
    };
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return measure(a) > measure(b) + 1e-9; });
    orders.push_back(order);
  }
  Packing best;
  for (const std::vector<int>& order : orders) {
    for (Rule rule : {Rule::ShortSide, Rule::Area, Rule::BottomLeft}) {
      const Packing p = maxRects(items, order, region, gap, reserved, rule);
      if (p.sheets > 0 && (best.sheets == 0 || betterPacking(items, p, best))) best = p;
    }
    const Packing p = shelves(items, order, region, gap, reserved);
    if (p.sheets > 0 && (best.sheets == 0 || betterPacking(items, p, best))) best = p;
  }
  return best;
}

}  // namespace dform::fab
