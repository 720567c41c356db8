// SPDX-License-Identifier: GPL-3.0-or-later
// The glue tabs: along the seam, on one piece or alternating, each a trapezoid folded on the
// piece's outline, narrowed, split or left out where it would overlap its piece or a neighbour.
#include "pattern_parts.h"
#include "plane_geometry.h"

namespace dform::fab {

namespace {

// The tab on piece `piece` over the seam parameters [s0, s1]: the fold line, then the outer edge
// (offset by `width`, inset at both ends by width / tan(angle)) back to the start.
FlatTab makeTab(const Seam seams[2], int piece, double s0, double s1, double width,
                double angleRad) {
  const Seam& seam = seams[piece];
  FlatTab tab;
  tab.piece = piece;
  tab.s0 = s0;
  tab.s1 = s1;
  tab.own0 = piece == 0 ? s0 : matchingArc(seams[0], seam, s0);
  tab.own1 = piece == 0 ? s1 : matchingArc(seams[0], seam, s1);
  tab.width = width;
  tab.fold = seam.sub(tab.own0, tab.own1);
  const double inset = width / std::tan(angleRad);
  Polyline outer = seam.sub(tab.own0 + inset, tab.own1 - inset, width);
  tab.polygon = tab.fold;
  tab.polygon.insert(tab.polygon.end(), outer.rbegin(), outer.rend());
  tab.box = boxOf({tab.polygon});
  return tab;
}

// The tabs accepted so far, with a grid of their boxes per piece: a new tab is compared only with
// the tabs whose boxes meet its own (tabs whose boxes do not meet share no area), so the cost
// grows with the tab count, not with its square.
class TabSet {
 public:
  explicit TabSet(double cell) : index_{BoxIndex(cell), BoxIndex(cell)} {}
  const std::vector<FlatTab>& tabs() const { return tabs_; }
  void add(const FlatTab& tab) {
    index_[tab.piece].insert(int(tabs_.size()), tab.box);
    tabs_.push_back(tab);
  }
  // A simple polygon sharing no area with its piece's material nor with its piece's other tabs.
  bool isClean(const FlatTab& tab, const std::vector<Polyline>& material, BuildWork& work) const {
    ++work.tabCandidates;
    if (findSelfIntersection(toPoints(tab.polygon))) return false;
    ++work.pairTests;
    if (overlapArea({tab.polygon}, material) > kOverlapTolMm2) return false;
    for (int k : index_[tab.piece].overlapping(tab.box)) {
      ++work.pairTests;
      if (overlapArea(tab.polygon, tabs_[size_t(k)].polygon) > kOverlapTolMm2) return false;
    }
    return true;
  }

 private:
  BoxIndex index_[2];
  std::vector<FlatTab> tabs_;
};

}  // namespace

// Splits the seam into tab intervals no longer than maxLen whose seam turns by at most maxTurn on
// either piece, then builds each tab on the side's piece; a tab that would overlap its piece or a
// neighbour is made narrower, then split, then left out (with a message). Intervals are in the
// seam parameter (A's arc length, up to A's seam length L).
std::vector<FlatTab> makeTabs(const Seam seams[2], const std::vector<Polyline> material[2],
                              const ExportOptions& o, TabSide side, double L,
                              std::vector<std::string>& messages, BuildWork& work) {
  if (o.tabWidthMm <= 0 || side == TabSide::None) return {};
  const double angle = o.tabAngleDeg * kPi / 180.0;
  const double inset = o.tabWidthMm / std::tan(angle);
  const double minLen = 2 * inset + 1.0;  // the outer edge keeps at least 1 mm
  const double maxLen = std::max(o.tabMaxLengthMm, minLen);
  const double maxTurn = o.tabMaxTurnDeg * kPi / 180.0;
  const double step = std::min(1.0, L / 1000);  // growth step along the seam (mm)
  const double sEnd = L - 0.5 * o.tabGapMm;
  auto onB = [&](double s) { return matchingArc(seams[0], seams[1], s); };
  std::vector<std::pair<double, double>> intervals;
  for (double s = 0.5 * o.tabGapMm; s + minLen <= sEnd;) {
    double e = s + minLen;
    for (;;) {
      const double next = std::min(e + step, sEnd);
      if (next <= e || next - s > maxLen) break;
      if (std::max(seams[0].turning(s, next), seams[1].turning(onB(s), onB(next))) > maxTurn) break;
      e = next;
    }
    intervals.emplace_back(s, e);
    s = e + o.tabGapMm;
  }
  // A cell about one tab long: a tab's box meets the boxes of a few neighbours only.
  TabSet accepted(maxLen + 2 * o.tabWidthMm);
  int dropped = 0;
  for (size_t k = 0; k < intervals.size(); ++k) {
    const int piece = side == TabSide::Alternate ? int(k % 2) : side == TabSide::B ? 1 : 0;
    const auto [s0, s1] = intervals[k];
    FlatTab tab = makeTab(seams, piece, s0, s1, o.tabWidthMm, angle);
    if (accepted.isClean(tab, material[piece], work)) {
      accepted.add(tab);
      continue;
    }
    const double narrow = 0.5 * o.tabWidthMm;
    tab = makeTab(seams, piece, s0, s1, narrow, angle);
    if (accepted.isClean(tab, material[piece], work)) {
      accepted.add(tab);
      continue;
    }
    const double mid = 0.5 * (s0 + s1), halfGap = 0.5 * o.tabGapMm;
    bool any = false;
    for (const auto& [a, b] : {std::pair{s0, mid - halfGap}, std::pair{mid + halfGap, s1}}) {
      if (b - a < 2 * narrow / std::tan(angle) + 1.0) continue;
      FlatTab half = makeTab(seams, piece, a, b, narrow, angle);
      if (accepted.isClean(half, material[piece], work)) {
        accepted.add(half);
        any = true;
      }
    }
    if (!any) ++dropped;
  }
  if (dropped > 0) {
    messages.push_back(std::to_string(dropped) +
                       " glue tab(s) left out where the seam is too tightly curved for a " +
                       formatMm(o.tabWidthMm) + " mm tab; glue those stretches edge to edge");
  }
  return accepted.tabs();
}

std::vector<TabInfo> placeTabs(const std::vector<FlatTab>& tabs, const Placement place[2]) {
  std::vector<TabInfo> placed;
  for (const FlatTab& t : tabs) {
    TabInfo info;
    info.piece = t.piece;
    info.s0 = t.s0;
    info.s1 = t.s1;
    info.width = t.width;
    info.polygon = place[t.piece].map(t.polygon);
    info.fold = place[t.piece].map(t.fold);
    placed.push_back(info);
  }
  return placed;
}

void drawTabFolds(const std::vector<TabInfo>& tabs, const std::string names[2],
                  const std::string& kind, const Profile& profile, DrawingBuilder& b) {
  int tabIndex[2] = {0, 0};
  for (const TabInfo& t : tabs) {
    const std::string id = names[t.piece] + "-" + kind + "fold-" + twoDigits(++tabIndex[t.piece]);
    if (profile.fold == FoldStyle::Perforated) {
      Path perf;
      perf.id = names[t.piece] + "-" + kind + "perf-" + twoDigits(tabIndex[t.piece]);
      perf.parts = perforate(t.fold, profile.perforationCutMm, profile.perforationGapMm);
      if (!perf.parts.empty()) b.cut().paths.push_back(perf);
    } else {
      Path fold;
      fold.id = id;
      fold.parts = {t.fold};
      if (Layer* cutter = b.cutterScore()) cutter->paths.push_back(scorePass(fold));
      fold.dashed = profile.fold == FoldStyle::Dashed;
      // A tab (or tongue) folds back, away from the printed face: a mountain fold seen from it,
      // dashed as the legend's mountain creases are.
      if (fold.dashed) fold.dash = creaseDash(FoldDirection::Mountain, profile.dashMm);
      b.score().paths.push_back(fold);
    }
  }
}

}  // namespace dform::fab
