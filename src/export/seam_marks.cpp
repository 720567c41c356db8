// SPDX-License-Identifier: GPL-3.0-or-later
// The seam marks: numbered ticks at matching seam points on both pieces, across each piece's
// outline, the start tick longer with an arrow along the zip direction; a tick stops short of a
// joint hole or slot in its way.
#include "pattern_parts.h"
#include "plane_geometry.h"

namespace dform::fab {

namespace {

constexpr double kTickIn = 3.0;       // tick length inside the outline (mm)
constexpr double kStartTickIn = 6.0;  // the start tick is longer (mm)
constexpr double kTickClear = 0.5;    // a tick stops this far before a hole or slot (mm)

// How far a tick may run from its seam point c along unit direction d, up to `length`, keeping
// kTickClear from every joint hole and slot (`joints`, convex loops): the distance to each is
// convex along the tick, so stepping 0.02 mm finds where it first comes too close, and a
// bisection puts the end there to a micrometre.
double tickReach(const Vec2& c, const Vec2& d, double length, const std::vector<Polyline>& joints) {
  const Vec2 r = Vec2::Constant(length + kTickClear);
  const Box reach = Box::spanning(c - r, c + r);  // the tick and its clearance lie in it
  std::vector<Polyline> near;
  for (const Polyline& loop : joints)
    if (boxOf({loop}).overlaps(reach)) near.push_back(loop);
  if (near.empty()) return length;
  auto clear = [&](double t) { return distanceToPolylines(near, c + t * d, true) >= kTickClear; };
  if (!clear(0)) return 0;
  for (double lo = 0;;) {
    const double hi = std::min(lo + 0.02, length);
    if (!clear(hi)) {
      for (double top = hi; top - lo > 1e-6;)
        (clear(0.5 * (lo + top)) ? lo : top) = 0.5 * (lo + top);
      return lo;
    }
    if (hi >= length) return length;
    lo = hi;
  }
}

// Tick t's number on the glue tab of its piece over it (`tabs`: the piece's), centred across the
// tab, up to the tab's half width tall: at the tick, else slid along the tab by up to 8 mm (off a
// slanted end), where it fits inside the tab 0.3 mm clear of its edges and of the numbers already
// on tabs (`placed`, their hulls, which it joins). Whether it was placed.
bool drawTabNumber(const TickInfo& t, const std::string& id, const std::string& label,
                   const Vec2& c, const Vec2& nOut, const Vec2& tan,
                   const std::vector<const TabInfo*>& tabs, const Profile& profile,
                   const StrokeFont& font, DrawingBuilder& b, std::vector<Polyline>& placed) {
  const Vec2 d = readable(tan);
  for (const TabInfo* tab : tabs) {
    if (!(t.s > tab->s0 && t.s < tab->s1)) continue;
    const double h = std::min(profile.labelHeightMm, 0.5 * tab->width);
    const double halfW = 0.5 * font.width(label, h), halfH = 0.5 * h;
    for (int k = 0; k <= 16; ++k) {
      const double slide = (k % 2 == 0 ? 1 : -1) * double((k + 1) / 2);  // 0, -1, 1, -2, 2, ...
      const Vec2 center = c + 0.5 * tab->width * nOut + slide * tan;
      if (!boxFits({tab->polygon}, {}, center, d, halfW, halfH, 0.3)) continue;
      Path text = textPath(font, id + "-tab-label", label, center, d, h);
      Polyline hull = convexHull(text.parts);
      if (overlapsAny(hull, placed, 0.0)) continue;
      placed.push_back(std::move(hull));
      b.engrave().paths.push_back(std::move(text));
      return true;
    }
    return false;
  }
  return false;
}

}  // namespace

double matchingArc(const Seam& from, const Seam& to, double s) {
  const int i = from.segmentAt(s);
  const size_t k = size_t(i);
  const double len = from.cum[k + 1] - from.cum[k];
  const double f = len > 0 ? std::clamp((s - from.cum[k]) / len, 0.0, 1.0) : 0.0;
  return to.cum[k] + f * (to.cum[k + 1] - to.cum[k]);
}

std::vector<double> tickParameters(double L, double spacing, BuildWork& work) {
  // A last tick closer than half a spacing to the start would crowd tick 0 and its arrow, so it
  // is left out.
  std::vector<double> tickS;
  for (int k = 0; k * spacing < L; ++k) {
    const double s = k * spacing;
    if (k > 0 && L - s < 0.5 * spacing) break;
    tickS.push_back(s);
    ++work.ticks;
  }
  return tickS;
}

std::vector<TickInfo> placeTicks(const std::vector<double>& tickS, const Seam seams[2],
                                 const Placement place[2]) {
  std::vector<TickInfo> ticks;
  for (size_t k = 0; k < tickS.size(); ++k) {
    TickInfo t;
    t.id = int(k);
    t.s = tickS[k];
    t.sB = matchingArc(seams[0], seams[1], t.s);
    t.onA = place[0].point(seams[0].at(t.s));
    t.onB = place[1].point(seams[1].at(t.sB));
    ticks.push_back(t);
  }
  return ticks;
}

TickLabelCounts drawTicks(int p, const PieceInfo& info, const Seam& seam, const Placement& place,
                          const std::vector<TickInfo>& ticks,
                          const std::vector<Polyline>& creaseLines,
                          const std::vector<const TabInfo*>& tabs, const Profile& profile,
                          const StrokeFont& font, DrawingBuilder& b, BuildWork& work) {
  TickLabelCounts counts;
  std::vector<Polyline> tabLabelHulls;                                  // the numbers on tabs
  std::vector<Polyline> tickLabelHulls;                                 // the numbers placed
  BoxIndex tickLabelIndex(std::max(2.0 * profile.labelHeightMm, 1.0));  // about one number
  for (const TickInfo& t : ticks) {
    int seg = 0;
    seam.at(p == 0 ? t.s : t.sB, &seg);
    const Vec2 c = p == 0 ? t.onA : t.onB;
    const Vec2 nOut = place.vector(seam.outward(seg)).normalized();
    const Vec2 tan = place.vector(seam.dir(seg)).normalized();
    const double in = tickReach(c, -nOut, t.id == 0 ? kStartTickIn : kTickIn, info.jointLoops);
    Path tick;
    tick.id = info.name + "-tick-" + twoDigits(t.id);
    tick.parts.push_back({c + kTickOut * nOut, c - in * nOut});
    if (t.id == 0) {  // the start: a longer tick with an arrow pointing along the seam
      const Vec2 a0 = c - in * nOut, a1 = a0 + 4.0 * tan;
      tick.parts.push_back({a0, a1});
      tick.parts.push_back({a1 - 1.5 * tan + 1.0 * nOut, a1, a1 - 1.5 * tan - 1.0 * nOut});
    }
    b.score().paths.push_back(tick);
    const std::string label = tickLabel(t.id);
    const double h = profile.labelHeightMm;
    const Vec2 d = readable(tan);
    // On the tab over the tick where the profile asks (hidden once glued), and on the face
    // unless the tab took it alone.
    const bool onTab =
        profile.numbers != TickNumbers::Face &&
        drawTabNumber(t, tick.id, label, c, nOut, tan, tabs, profile, font, b, tabLabelHulls);
    if (onTab && profile.numbers == TickNumbers::Tabs) continue;
    const double halfW = 0.5 * font.width(label, h), halfH = 0.5 * h;
    // Next to the tick, else deeper into the piece, else slid along the seam (at a corner the
    // tick's own normal points past the corner): moved inward, not dropped. A number that fits
    // nowhere clear of the numbers already placed is thinned out (the spacing is tighter than
    // the numbers are wide); one that fits nowhere at all is too narrow a piece.
    bool fitsSomewhere = false, placed = false;
    for (int attempt = 0; attempt < 6 && !placed; ++attempt)
      for (double slide : {0.0, 1.0, -1.0, 2.0, -2.0}) {
        if (placed) break;
        const double depth = in + 1.0 + (t.id == 0 ? 1.5 : 0.0) + halfH + attempt * h;
        const Vec2 center = c - depth * nOut + slide * (halfW + 1.0) * tan;
        if (!boxFits(info.boundaries, creaseLines, center, d, halfW, halfH, 0.3)) continue;
        fitsSomewhere = true;
        Path text = textPath(font, tick.id + "-label", label, center, d, h);
        Polyline hull = convexHull(text.parts);
        const Box hullBox = fab::boxOf({hull});
        bool clear = true;  // sharing no area with a number placed (as the layout check sees it)
        for (int k : tickLabelIndex.overlapping(hullBox)) {
          ++work.pairTests;
          clear = clear && overlapArea(hull, tickLabelHulls[size_t(k)]) <= kOverlapTolMm2;
        }
        if (!clear) continue;
        tickLabelIndex.insert(int(tickLabelHulls.size()), hullBox);
        tickLabelHulls.push_back(std::move(hull));
        b.engrave().paths.push_back(std::move(text));
        placed = true;
      }
    if (!placed) ++(fitsSomewhere ? counts.thinned : counts.skipped);
  }
  return counts;
}

}  // namespace dform::fab
