// The flat pattern: seam ticks at matching seam points on both pieces, glue tabs, cut paths
// (outline with tabs merged, holes, kerf offset), crease fold lines, placement on the sheet (or a
// page per piece), single-stroke labels and the pages. Geometry is computed in each piece's flat frame (mm, y up), then mapped to
// the sheet (y down). A piece's seam may be its outer outline or a hole's loop (anti and demi
// D-Forms): ticks and tabs go along the seam only, on the side away from the material.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/piece_loops.h"
#include "core/polyline.h"
#include "export/internal.h"
#include "export/plane_geometry.h"

namespace dform::fab {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Cricut Print Then Cut: 6.75 x 9.25 in (the long-standing safe maximum on Letter).
constexpr double kCricutW = 6.75 * 25.4, kCricutH = 9.25 * 25.4;
// Silhouette type-1 marks: 10 mm from the edges, 5 mm square, 20 mm L arms, 0.3 mm lines (the
// artwork's clearance from them is the profile's registration_clear_mm).
constexpr double kRegInset = 10.0, kRegSquare = 5.0, kRegArm = 20.0, kRegLine = 0.3;
constexpr double kTickOut = 1.5;      // tick length outside the outline (mm)
constexpr double kTickIn = 3.0;       // tick length inside the outline (mm)
constexpr double kStartTickIn = 6.0;  // the start tick is longer (mm)
// Tiles: each page shows a window of the pattern inside a 10 mm margin, under a 12 mm header.
constexpr double kTileMargin = 10.0, kTileHeader = 12.0;
// More pages than this is no print job anyone assembles by hand (500 A4 pages are 31 m^2 of
// paper): such a pattern is refused before it is drawn, as one too large for its sheet is.
constexpr long kMaxTiles = 500;

Points2 toPoints(const Polyline& p) {
  Points2 P(Eigen::Index(p.size()), 2);
  for (size_t i = 0; i < p.size(); ++i) P.row(Eigen::Index(i)) = p[i].transpose();
  return P;
}

double polylineLength(const Polyline& p, bool closed) {
  double len = 0;
  for (size_t i = 0; i + 1 < p.size(); ++i) len += (p[i + 1] - p[i]).norm();
  if (closed && p.size() > 1) len += (p.front() - p.back()).norm();
  return len;
}

std::string formatMm(double x, int decimals = 1) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

// The rows of `flat` listed by `loop`, as a polyline.
Polyline flatPolyline(const Points2& flat, const std::vector<int>& loop) {
  Polyline P;
  for (int v : loop) P.emplace_back(flat(v, 0), flat(v, 1));
  return P;
}

// The closed polygon turned counter-clockwise (ccw) or clockwise.
Polyline oriented(const Polyline& P, bool ccw) {
  return (signedArea(toPoints(P)) >= 0) == ccw ? P : Polyline(P.rbegin(), P.rend());
}

// A piece's seam as a closed polyline in its flat frame, parameterised by arc length.
struct Seam {
  Polyline P;
  std::vector<double> cum;         // cum[i] = arc length at vertex i; cum[n] = L
  std::vector<double> turnPrefix;  // sum of |turning angle| at vertices 0..i-1
  double L = 0;
  double orient = 1;  // +1 counter-clockwise, -1 clockwise
  bool hole = false;  // the seam is a hole's loop: the material lies outside it

  int n() const { return int(P.size()); }

  explicit Seam(const Piece& piece)
      : P(flatPolyline(piece.flat, piece.seam)), hole(seamIsHole(piece)) {
    cum.assign(P.size() + 1, 0.0);
    for (int i = 0; i < n(); ++i)
      cum[size_t(i) + 1] = cum[size_t(i)] + (P[next(i)] - P[size_t(i)]).norm();
    L = cum.back();
    orient = signedArea(toPoints(P)) >= 0 ? 1.0 : -1.0;
    turnPrefix.assign(P.size() + 1, 0.0);
    for (int i = 0; i < n(); ++i) {
      const Vec2 a = dir((i - 1 + n()) % n()), b = dir(i);
      const double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
      turnPrefix[size_t(i) + 1] = turnPrefix[size_t(i)] + std::abs(turn);
    }
  }
  size_t next(int i) const { return size_t((i + 1) % n()); }
  // Unit direction of segment i (the next non-degenerate one if it has no length).
  Vec2 dir(int i) const {
    for (int k = 0; k < n(); ++k) {
      const int j = (i + k) % n();
      const Vec2 d = P[next(j)] - P[size_t(j)];
      if (d.norm() > 1e-12) return d.normalized();
    }
    return Vec2(1, 0);
  }
  // Unit normal of segment i away from the material: out of the piece, or into its hole.
  Vec2 outward(int i) const {
    const Vec2 t = dir(i);
    return orient * (hole ? -1 : 1) > 0 ? Vec2(t.y(), -t.x()) : Vec2(-t.y(), t.x());
  }
  // Offset direction at vertex i for an offset curve at constant distance (mitre, capped at 2x).
  Vec2 miter(int i) const {
    const Vec2 a = outward((i - 1 + n()) % n()), b = outward(i);
    Vec2 m = a + b;
    if (m.norm() < 1e-9) return b;
    m.normalize();
    return m / std::max(m.dot(b), 0.5);
  }
  int segmentAt(double s) const {
    s = std::fmod(std::fmod(s, L) + L, L);
    const auto it = std::upper_bound(cum.begin(), cum.end(), s);
    return std::clamp(int(it - cum.begin()) - 1, 0, n() - 1);
  }
  Vec2 at(double s, int* segment = nullptr) const {
    const int i = segmentAt(s);
    s = std::fmod(std::fmod(s, L) + L, L);
    const double len = cum[size_t(i) + 1] - cum[size_t(i)];
    const double f = len > 0 ? (s - cum[size_t(i)]) / len : 0.0;
    if (segment) *segment = i;
    return P[size_t(i)] + f * (P[next(i)] - P[size_t(i)]);
  }
  // Vertices strictly inside the arc-length interval (s0, s1), 0 <= s0 < s1 <= L.
  std::pair<int, int> innerVertices(double s0, double s1) const {
    const int first = int(std::upper_bound(cum.begin(), cum.begin() + n(), s0) - cum.begin());
    const int last = int(std::lower_bound(cum.begin(), cum.begin() + n(), s1) - cum.begin());
    return {first, last};  // [first, last)
  }
  double turning(double s0, double s1) const {
    const auto [first, last] = innerVertices(s0, s1);
    return last > first ? turnPrefix[size_t(last)] - turnPrefix[size_t(first)] : 0.0;
  }
  Polyline sub(double s0, double s1, double offset = 0) const {
    Polyline out;
    int seg = 0;
    Vec2 p = at(s0, &seg);
    out.push_back(p + offset * outward(seg));
    const auto [first, last] = innerVertices(s0, s1);
    for (int j = first; j < last; ++j) out.push_back(P[size_t(j)] + offset * miter(j));
    p = at(s1, &seg);
    if (s1 >= L) seg = n() - 1;
    out.push_back(p + offset * outward(seg));
    return out;
  }
};

// The arc length along `to` of the seam point at arc length s along `from`: the same seam pair
// index i and fraction along the edge i..i+1, so the same point of the 3D seam (a.seam[i] and
// b.seam[i] share one 3D position). The two flat seams may differ slightly in length; points at
// equal arc lengths would drift apart by up to that difference.
double matchingArc(const Seam& from, const Seam& to, double s) {
  const int i = from.segmentAt(s);
  const size_t k = size_t(i);
  const double len = from.cum[k + 1] - from.cum[k];
  const double f = len > 0 ? std::clamp((s - from.cum[k]) / len, 0.0, 1.0) : 0.0;
  return to.cum[k] + f * (to.cum[k + 1] - to.cum[k]);
}

struct FlatTab {
  int piece = 0;
  double s0 = 0, s1 = 0;      // seam parameter (A's arc length) of the fold line's ends
  double own0 = 0, own1 = 0;  // the same along the tab's own piece's seam
  double width = 0;
  Polyline polygon;  // flat frame, fold line first
  Polyline fold;
  Box box;  // of the polygon
};

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

// A piece's material in its flat frame: every boundary loop, the outer outline first (even-odd).
std::vector<Polyline> materialLoops(const Piece& piece) {
  const std::vector<std::vector<int>> loops = boundaryLoops(piece);
  const size_t outer = size_t(outerLoopIndex(piece));
  std::vector<Polyline> material{flatPolyline(piece.flat, loops[outer])};
  for (size_t k = 0; k < loops.size(); ++k)
    if (k != outer) material.push_back(flatPolyline(piece.flat, loops[k]));
  return material;
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

struct CutPaths {
  std::vector<Polyline> outer;  // counter-clockwise in the flat frame
  std::vector<Polyline> holes;  // clockwise
};

// `region` (outer loops positive, holes negative) grown by `mm`: the outer loops move out and the
// holes shrink, corners rounded within 5 um.
ClipperLib::Paths grownRegion(const ClipperLib::Paths& region, double mm) {
  ClipperLib::ClipperOffset offset(2.0, 0.005 * kClipScale);
  offset.AddPaths(region, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  ClipperLib::Paths grown;
  offset.Execute(grown, mm * kClipScale);
  return grown;
}

// The closed cut paths of one piece (flat frame): its outline, holes and tabs merged, offset by
// the kerf (outward from the material: the outline grows and the holes shrink). `freeLoops` are
// its free boundaries; `outer` is outerLoopIndex (0 the seam, k free loop k - 1).
CutPaths cutPaths(const Seam& seam, const std::vector<Polyline>& freeLoops, int outer,
                  const std::vector<FlatTab>& tabs, int piece, double kerf) {
  // The seam gets the tabs' fold ends as vertices, computed exactly as the tabs' own, so that
  // piece and tabs share their edges to the last bit and the union leaves no slivers.
  std::vector<double> ends;
  for (const FlatTab& t : tabs)
    if (t.piece == piece) ends.insert(ends.end(), {t.own0, t.own1});
  std::vector<Polyline> loops{seam.P};
  loops.insert(loops.end(), freeLoops.begin(), freeLoops.end());
  CutPaths out;
  if (ends.empty() && kerf <= 0) {
    for (size_t k = 0; k < loops.size(); ++k)
      (int(k) == outer ? out.outer : out.holes).push_back(oriented(loops[k], int(k) == outer));
    return out;
  }
  std::sort(ends.begin(), ends.end());
  Polyline& outline = loops[0];
  outline.clear();
  size_t e = 0;
  for (int i = 0; i < seam.n(); ++i) {
    for (; e < ends.size() && ends[e] <= seam.cum[size_t(i)]; ++e)
      if (ends[e] < seam.cum[size_t(i)]) outline.push_back(seam.at(ends[e]));
    outline.push_back(seam.P[size_t(i)]);
  }
  for (; e < ends.size(); ++e) outline.push_back(seam.at(ends[e]));
  // Non-zero winding: the outline counter-clockwise, holes clockwise, tabs (in a hole too)
  // counter-clockwise.
  ClipperLib::Paths shapes;
  for (size_t k = 0; k < loops.size(); ++k) {
    shapes.push_back(toClip(loops[k]));
    if (int(k) != outer) ClipperLib::ReversePath(shapes.back());
  }
  for (const FlatTab& t : tabs)
    if (t.piece == piece) shapes.push_back(toClip(t.polygon));
  ClipperLib::Paths merged;
  ClipperLib::Clipper c;
  c.AddPaths(shapes, ClipperLib::ptSubject, true);
  c.Execute(ClipperLib::ctUnion, merged, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  ClipperLib::CleanPolygons(merged);  // drops duplicate and collinear points left by rounding
  if (kerf > 0) merged = grownRegion(merged, kerf);
  for (const auto& p : merged)
    (ClipperLib::Orientation(p) ? out.outer : out.holes).push_back(fromClip(p));
  return out;
}

// A piece's printed tint (flat frame; holes wind against the outer loops): its cut region grown
// by `bleed`.
std::vector<Polyline> bleedLoops(const std::vector<Polyline>& outer,
                                 const std::vector<Polyline>& holes, double bleed) {
  ClipperLib::Paths region;
  for (const auto* loops : {&outer, &holes})
    for (const Polyline& loop : *loops) region.push_back(toClip(loop));
  std::vector<Polyline> out;
  for (const auto& p : grownRegion(region, bleed)) out.push_back(fromClip(p));
  return out;
}

// Flat frame -> sheet: flip y (the sheet's y points down), rotate, translate.
struct Placement {
  Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
  Vec2 t = Vec2::Zero();
  Vec2 point(const Vec2& p) const { return M * p + t; }
  Vec2 vector(const Vec2& v) const { return M * v; }
  Polyline map(const Polyline& p) const {
    Polyline out;
    out.reserve(p.size());
    for (const Vec2& q : p) out.push_back(point(q));
    return out;
  }
};

Eigen::Matrix2d flipRotate(double deg) {
  const double a = deg * kPi / 180.0;
  Eigen::Matrix2d R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R * Eigen::Vector2d(1, -1).asDiagonal();
}

Box boxOf(const std::vector<Polyline>& paths, const Eigen::Matrix2d& M) {
  Box b;
  for (const auto& p : paths)
    for (const Vec2& q : p) b.add(M * q);
  return b;
}

// The layout turns pieces in steps of this many degrees; 90 is a multiple, so a piece's turn plus
// a quarter turn is a step too.
constexpr int kTurnStepDeg = 2;

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

// A piece's extent on the sheet turned by `deg`: the box of its paths grown by `edge`, what sticks
// out of the outline (the ticks, kTickOut, or a printed bleed).
Box extentAt(const std::vector<Polyline>& paths, double deg, double edge) {
  Box b = boxOf(paths, flipRotate(deg));
  b.lo -= Vec2::Constant(edge);
  b.hi += Vec2::Constant(edge);
  return b;
}

// Two pieces' extents side by side or stacked, `gap` apart: the arrangement's width and height.
Vec2 arranged(const Box& a, const Box& b, bool vertical, double gap) {
  return vertical ? Vec2(std::max(a.w(), b.w()), a.h() + gap + b.h())
                  : Vec2(a.w() + gap + b.w(), std::max(a.h(), b.h()));
}

// Where a sheet's title block goes: under its pieces, in a column beside them, or nowhere (the
// pieces and the block do not fit).
enum class TitleAt { Below, Aside, None };

// One sheet (or page) of the layout and what is on it.
struct SheetPlan {
  Box box;                   // on the canvas (mm); the sheets lie side by side
  std::vector<int> pieces;   // the pieces on it (0 = A, 1 = B)
  Vec2 size = Vec2::Zero();  // the extent of those pieces, from the region's top-left corner (mm)
  TitleAt title = TitleAt::Below;
  bool tiled = false;        // a piece larger than the page, tiled across pages (print)
  long tilesX = 1, tilesY = 1;  // its pages: columns and rows
};

// The id of a page's copy of the sheet furniture (title lines, registration marks): the first
// page keeps the plain id.
std::string onPage(const std::string& id, size_t page) {
  return page == 0 ? id : id + "-page-" + std::to_string(page + 1);
}

// Builds the drawing's layers and routes each operation to its layer for the profile's kind.
class DrawingBuilder {
 public:
  DrawingBuilder(const Profile& p, double w, double h) {
    drawing_.width = w;
    drawing_.height = h;
    auto layer = [&](std::string name, std::string color, double width, bool printed) {
      Layer l;
      l.name = std::move(name);
      l.color = std::move(color);
      l.widthMm = width;
      l.dashMm = p.dashMm;
      l.printed = printed;
      drawing_.layers.push_back(std::move(l));
      return int(drawing_.layers.size()) - 1;
    };
    // The title block and notes have a layer of their own (first), so that a laser operator can
    // switch them off without losing the tick numbers and a printer can leave them out.
    title_ = layer("Title", p.engraveColor, p.engraveWidthMm, true);
    const bool printAndCut = p.kind == ProfileKind::PrintAndCut;
    if (printAndCut || p.registration != Registration::None)
      regmarks_ = layer("Regmarks", "#000000", kRegLine, true);
    switch (p.kind) {
      case ProfileKind::Laser:  // engrave, then score, then cut (inner cuts first, outer last)
        engrave_ = layer("Engrave", p.engraveColor, p.engraveWidthMm, true);
        score_ = layer("Score", p.scoreColor, p.scoreWidthMm, true);
        break;
      case ProfileKind::Print:
        engrave_ = layer("Labels", p.engraveColor, p.engraveWidthMm, true);
        score_ = layer("Fold", p.scoreColor, p.scoreWidthMm, true);
        break;
      case ProfileKind::PrintAndCut:
        // Printed: the marks, the pieces' tint (under the lines), the lines and labels. For the
        // cutter only: a score pass along the folds (a scoring tool, or off), then the cut.
        if (p.bleedMm > 0) bleed_ = layer("Bleed", p.fillColorA, p.engraveWidthMm, true);
        engrave_ = score_ = layer("Print", p.engraveColor, p.engraveWidthMm, true);
        cutterScore_ = layer("Score", p.scoreColor, p.scoreWidthMm, false);
        break;
    }
    cut_ = layer("Cut", p.cutColor, p.cutWidthMm, !printAndCut);
  }
  Layer& title() { return drawing_.layers[size_t(title_)]; }
  Layer& engrave() { return drawing_.layers[size_t(engrave_)]; }
  /// Tick marks and printed or scored folds.
  Layer& score() { return drawing_.layers[size_t(score_)]; }
  Layer& cut() { return drawing_.layers[size_t(cut_)]; }
  /// Null where the profile has none: the registration marks, the printed tint (print-and-cut
  /// with a bleed), the cutter's own score pass (print-and-cut).
  Layer* regmarks() { return layerAt(regmarks_); }
  Layer* bleed() { return layerAt(bleed_); }
  Layer* cutterScore() { return layerAt(cutterScore_); }
  Drawing& drawing() { return drawing_; }

 private:
  Layer* layerAt(int index) { return index < 0 ? nullptr : &drawing_.layers[size_t(index)]; }
  Drawing drawing_;
  int title_ = -1, engrave_ = -1, score_ = -1, cut_ = -1;
  int regmarks_ = -1, bleed_ = -1, cutterScore_ = -1;
};

// The cutter's score pass along a printed fold line: the whole line, its own id.
Path scorePass(const Path& fold) {
  Path pass = fold;
  pass.id += "-score";
  return pass;
}

std::string twoDigits(int k) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", k);
  return buf;
}

// A text direction along `t` that does not read upside down on the sheet (y down).
Vec2 readable(Vec2 t) {
  t.normalize();
  if (t.x() < -1e-9 || (std::abs(t.x()) <= 1e-9 && t.y() > 0)) t = -t;
  return t;
}

// Whether a text box centred at c (half-extents along d and its normal) sits inside the piece's
// material (`region`, even-odd) with `clear` mm to spare: its corners and long sides' midpoints
// inside and clear of every loop, no loop vertex (a small hole) inside it, and no crease (`lines`)
// through it.
bool boxFits(const std::vector<Polyline>& region, const std::vector<Polyline>& lines, const Vec2& c,
             const Vec2& d, double halfW, double halfH, double clear) {
  const Vec2 n(-d.y(), d.x());
  for (double a : {-1.0, 0.0, 1.0})
    for (double b : {-1.0, 1.0}) {
      const Vec2 q = c + a * halfW * d + b * halfH * n;
      if (!insideRegion(region, q) || distanceToPolylines(region, q, true) < clear) return false;
    }
  const Polyline box = {c - halfW * d - halfH * n, c + halfW * d - halfH * n,
                        c + halfW * d + halfH * n, c - halfW * d + halfH * n};
  for (const std::vector<Polyline>* set : {&region, &lines})
    for (const Polyline& line : *set)
      for (const Vec2& q : line)
        if (insidePolygon(box, q)) return false;
  for (const Polyline& line : lines)
    for (size_t i = 0; i + 1 < line.size(); ++i)
      for (size_t k = 0; k < box.size(); ++k)
        if (segmentsIntersect(line[i], line[i + 1], box[k], box[(k + 1) % box.size()]))
          return false;
  return true;
}

// The point of the material farthest from its loops, from the creases (`lines`) and from the
// labels already placed (`labels`, closed footprints) (grid search), and that distance.
std::pair<Vec2, double> roomiestPoint(const std::vector<Polyline>& region,
                                      const std::vector<Polyline>& lines,
                                      const std::vector<Polyline>& labels) {
  Box b;
  for (const Vec2& q : region.front()) b.add(q);
  const int steps = 40;
  Vec2 best = 0.5 * (b.lo + b.hi);
  double bestD = -1;
  for (int i = 1; i < steps; ++i)
    for (int j = 1; j < steps; ++j) {
      const Vec2 q(b.lo.x() + b.w() * i / steps, b.lo.y() + b.h() * j / steps);
      if (!insideRegion(region, q) || insideRegion(labels, q)) continue;
      const double d =
          std::min({distanceToPolylines(region, q, true), distanceToPolylines(lines, q, false),
                    distanceToPolylines(labels, q, true)});
      if (d > bestD) {
        bestD = d;
        best = q;
      }
    }
  return {best, std::max(bestD, 0.0)};
}

Path textPath(const StrokeFont& font, std::string id, const std::string& text, const Vec2& c,
              const Vec2& d, double h) {
  Path p;
  p.id = std::move(id);
  p.parts = font.layout(text, c, d, h);
  return p;
}

// Splits an open polyline into dashes `on` mm long separated by `off`, centred so that both
// ends are bridges (the tab stays attached at its ends).
std::vector<Polyline> perforate(const Polyline& line, double on, double off) {
  const double len = polylineLength(line, false);
  std::vector<Polyline> dashes;
  const int count = int(std::floor((len - off) / (on + off)));
  if (count < 1) return dashes;
  const double start = 0.5 * (len - (count * (on + off) - off));
  for (int k = 0; k < count; ++k) {
    const double a = start + k * (on + off), b = a + on;
    Polyline dash{pointAlong(line, a)};
    double acc = 0;
    for (size_t i = 0; i + 1 < line.size(); ++i) {
      acc += (line[i + 1] - line[i]).norm();
      if (acc > a && acc < b) dash.push_back(line[i + 1]);
    }
    dash.push_back(pointAlong(line, b));
    dashes.push_back(dash);
  }
  return dashes;
}

// How a printed crease is dashed (on, off, ... in mm), after the origami diagram convention
// (Yoshizawa-Randlett): a valley is dashed, a mountain dash-dot.
std::vector<double> creaseDash(FoldDirection direction, double dash) {
  if (direction == FoldDirection::Valley) return {dash, dash};
  return {dash, 0.5 * dash, dash / 6.0, 0.5 * dash};
}

Path cross(const std::string& id, const Vec2& c, double r) {
  Path p;
  p.id = id;
  p.parts = {{c - Vec2(r, 0), c + Vec2(r, 0)}, {c - Vec2(0, r), c + Vec2(0, r)}};
  return p;
}

}  // namespace

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

namespace {

// The pattern of `model` drawn at `scale` (its flat pieces already scaled by it). `tooLarge` is
// set when it fails because a piece does not fit its sheet or page.
Result<PatternBuild> buildAtScale(const DForm& model, const ExportOptions& o,
                                  const Profile& profile, const StrokeFont& font, double scale,
                                  BuildWork& work, bool& tooLargeOut) {
  PatternBuild out;
  out.scale = scale;
  out.profile = profile;
  out.tickSpacing = o.tickSpacingMm;
  out.failedGate = o.failedGateMark;
  const Seam seams[2] = {Seam(model.a), Seam(model.b)};
  const std::string names[2] = {model.a.name.empty() ? "A" : model.a.name,
                                model.b.name.empty() ? "B" : model.b.name};
  const Piece* piece[2] = {&model.a, &model.b};
  const std::vector<Polyline> material[2] = {materialLoops(model.a), materialLoops(model.b)};
  const bool creased = !model.a.creases.empty() || !model.b.creases.empty();

  // --- Sheet, page and the region where the pieces go -----------------------------------------
  const double m = profile.marginMm;
  const double edge = std::max(kTickOut, profile.bleedMm);  // drawn outside a piece's cut line
  const double textH = std::clamp(profile.labelHeightMm, 2.0, 4.0);
  const double lineH = 1.7 * textH;
  const double barH = profile.calibrationBar ? 9.0 : 0.0;
  const double failH = o.failedGateMark ? 2.0 * lineH : 0.0;
  // Tabs fold away from the printed (outer) side: a line says so on every sheet that has them.
  const bool tabbed = o.tabWidthMm > 0 && profile.tabs != TabSide::None;
  // The lines: title and note, a legend line for creases, the tab line (none with --no-title).
  const int titleLines = o.title ? 2 + int(creased) + int(tabbed) : 0;
  const double titleH = titleLines * lineH + barH + failH;
  const double titleBlock = titleH > 0 ? m + titleH : 0.0;  // with its margin from the pieces
  // The page: --page over the profile's. A page profile refuses a sheet size and a sheet profile
  // a page, rather than ignore them.
  const std::string pageName = o.page.empty() ? profile.page : o.page;
  if (!o.page.empty() && profile.page.empty())
    return Status{ErrorCode::Usage, "--page is for page profiles (print, print-and-cut); profile " +
                                        profile.name +
                                        " cuts a material sheet: give its size with --sheet WxHmm"};
  if (!profile.page.empty() && o.sheetGiven)
    return Status{ErrorCode::Usage,
                  "profile " + profile.name + " prints on " + pageName +
                      " pages, so --sheet does not apply; choose the paper with --page "
                      "A4|Letter|A3|Tabloid|WxHmm"};
  double pageW = o.sheetWidthMm, pageH = o.sheetHeightMm;
  if (!pageName.empty()) {
    const auto size = pageSizeMm(pageName);
    if (!size)
      return Status{ErrorCode::Usage, "unknown page \"" + pageName +
                                          "\": use A4, Letter, A3, Tabloid or a size such as "
                                          "200x300mm"};
    pageW = size->first;
    pageH = size->second;
  }
  const std::string sheetWord = pageName.empty() ? "sheet" : "page";
  // The area of a W x H sheet or page (its top-left corner at `at`) that the pieces and the title
  // lines may use.
  auto artRegion = [&](double W, double H, const Vec2& at = Vec2::Zero()) {
    double inset = m;
    if (profile.registration == Registration::Silhouette)  // clear of the square's far edge
      inset = kRegInset + kRegSquare + profile.registrationClearMm;
    Box r = Box::spanning(at + Vec2(inset, inset), at + Vec2(W - inset, H - inset));
    if (profile.registration == Registration::Cricut) {  // the Print Then Cut area, centred
      const Vec2 half(0.5 * std::min(kCricutW, W - 2 * m), 0.5 * std::min(kCricutH, H - 2 * m));
      const Vec2 centre = at + 0.5 * Vec2(W, H);
      r = Box::spanning(centre - half, centre + half);
    }
    return r;
  };
  // Where a sheet's title block goes when the pieces on it take `size` of its region `r`: under
  // them (a margin apart) where the region is tall enough, else in a column to their right, its
  // lines reading upwards; None when neither fits (or the pieces do not).
  auto titleAt = [&](const Vec2& size, const Box& r) {
    if (!(r.w() > 0 && size.x() <= r.w() + 1e-9 && size.y() <= r.h() + 1e-9)) return TitleAt::None;
    if (size.y() + titleBlock <= r.h() + 1e-9) return TitleAt::Below;
    if (size.x() + titleBlock <= r.w() + 1e-9) return TitleAt::Aside;
    return TitleAt::None;
  };
  // Whether pieces (and tabs) of extent `size` fit a W x H sheet with their title block.
  auto fits = [&](const Vec2& size, double W, double H) {
    return titleAt(size, artRegion(W, H)) != TitleAt::None;
  };
  // Only a print profile's page may turn to landscape or tile; a print-and-cut page keeps its
  // marks (the cutter reads one page's), and a laser sheet is the size it is.
  const bool mayTurnPage = profile.kind == ProfileKind::Print && !pageName.empty();
  const bool mayTile = profile.kind == ProfileKind::Print && profile.tile;
  auto fitsSomeWay = [&](const Vec2& size) {
    return fits(size, pageW, pageH) || (mayTurnPage && fits(size, pageH, pageW));
  };
  // `what` (`contents`) fits the sheet in none of the arrangements tried, of extents `sizes`:
  // the message gives the sheet size needed by the arrangement that needs the least enlargement.
  auto tooLarge = [&](const std::string& what, const std::vector<Vec2>& sizes,
                      const std::string& contents) {
    tooLargeOut = true;
    const Box r = artRegion(pageW, pageH);
    Vec2 need = Vec2::Zero(), size = Vec2::Zero();
    double least = std::numeric_limits<double>::infinity();
    for (const Vec2& candidate : sizes) {
      const Vec2 n(candidate.x() + (pageW - r.w()), candidate.y() + titleBlock + (pageH - r.h()));
      if (std::max(n.x() / pageW, n.y() / pageH) < least) {
        least = std::max(n.x() / pageW, n.y() / pageH);
        need = n;
        size = candidate;
      }
    }
    const std::string area = pageName.empty() ? "sheet" : pageName + " page's cutting area";
    return Status{ErrorCode::Usage, what + " does not fit the " + area + ": it needs at least " +
                                        formatMm(need.x()) + " x " + formatMm(need.y()) + " mm (" +
                                        formatMm(size.x()) + " x " + formatMm(size.y()) +
                                        " mm of " + contents +
                                        ", plus margins and the title lines); the " + sheetWord +
                                        " is " + formatMm(pageW) + " x " + formatMm(pageH) + " mm"};
  };
  // Tiling: the columns and rows of pages that show a piece of extent `size` with the margins and
  // its title block; neighbouring windows overlap by tileOverlapMm.
  const double tileW = pageW - 2 * kTileMargin, tileH = pageH - 2 * kTileMargin - kTileHeader;
  const double overlap = profile.tileOverlapMm;
  auto tiledExtent = [&](const Vec2& size) {
    return Vec2(size.x() + 2 * m, size.y() + titleBlock + 2 * m);
  };
  auto tileGrid = [&](const Vec2& size) {
    auto count = [&](double length, double window) {
      return std::max(1L, long(std::ceil((length - overlap) / (window - overlap) - 1e-9)));
    };
    const Vec2 extent = tiledExtent(size);
    return std::pair<long, long>(count(extent.x(), tileW), count(extent.y(), tileH));
  };
  auto tooManyTiles = [&](long tiles) {
    tooLargeOut = true;
    return Status{ErrorCode::Usage, "the pattern needs at least " + std::to_string(tiles) + " " +
                                        pageName + " pages when tiled, more than the " +
                                        std::to_string(kMaxTiles) +
                                        " a print profile makes; use a sheet profile"};
  };

  // --- Fit first: before any tick or tab is made ---------------------------------------------
  // A piece's cut path contains its outer outline (tabs and kerf only add to it), so at every turn
  // the layout may choose (2-degree steps; a half turn gives the same box) the outline's extent
  // bounds the cut path's from below. Each piece may get a sheet (or page) of its own, so the
  // pattern fits when each bare outline fits one alone, or, on a tiling profile, when its tiles
  // are not too many. When that fails, say so now, at a cost independent of the seam's length in
  // ticks and tabs.
  long fewestTiles = 0;
  for (int p = 0; p < 2; ++p) {
    std::vector<Vec2> sizes;
    for (int deg = 0; deg < 180; deg += kTurnStepDeg) {
      const Box b = extentAt({material[p].front()}, deg, edge);
      sizes.emplace_back(b.w(), b.h());
    }
    if (std::any_of(sizes.begin(), sizes.end(), fitsSomeWay)) continue;
    if (!mayTile) return tooLarge("piece " + names[p], sizes, "the piece");
    long fewest = std::numeric_limits<long>::max();
    for (const Vec2& size : sizes) {
      const auto [nx, ny] = tileGrid(size);
      fewest = std::min(fewest, nx * ny);
    }
    fewestTiles += fewest;
  }
  if (fewestTiles > kMaxTiles) return tooManyTiles(fewestTiles);
  // Seam lengths agree to the gate's tolerance on a solved model; ticks and tabs mark matching
  // seam points on both pieces whatever the difference, which a fabricator sees as a slightly
  // different tick spacing on B (0.1 mm is the accuracy the ticks are held to).
  if (std::abs(seams[0].L - seams[1].L) > 0.1) {
    out.messages.push_back("the seams differ in length by " +
                           formatMm(std::abs(seams[0].L - seams[1].L), 2) +
                           " mm; partner ticks mark the same seam point, so B's tick spacing "
                           "differs slightly from A's");
  }
  // Everything along the seam is placed by the seam parameter: A's arc length.
  const double L = seams[0].L;

  // Ticks: every spacing mm from the seam start; a last tick closer than half a spacing to the
  // start would crowd tick 0 and its arrow, so it is left out.
  std::vector<double> tickS;
  for (int k = 0; k * o.tickSpacingMm < L; ++k) {
    const double s = k * o.tickSpacingMm;
    if (k > 0 && L - s < 0.5 * o.tickSpacingMm) break;
    tickS.push_back(s);
    ++work.ticks;
  }

  const std::vector<FlatTab> tabs =
      makeTabs(seams, material, o, profile.tabs, L, out.messages, work);
  std::vector<Polyline> cuts[2], holeCuts[2];
  for (int p = 0; p < 2; ++p) {
    std::vector<Polyline> freeLoops;
    for (const auto& loop : piece[p]->freeBoundaries)
      freeLoops.push_back(flatPolyline(piece[p]->flat, loop));
    CutPaths c = cutPaths(seams[p], freeLoops, outerLoopIndex(*piece[p]), tabs, p, profile.kerfMm);
    cuts[p] = std::move(c.outer);
    holeCuts[p] = std::move(c.holes);
  }

  // --- Orientation and arrangement -------------------------------------------------------------
  // Pieces are packed on as few sheets (pages) as hold them: both on one where they fit together
  // (side by side or stacked, each at its smallest-box turn or a quarter turn more; a print page
  // may turn to landscape), else each on its own, at the smaller of its two turns that fits (a
  // print page turned where only that fits), else (print) tiled across pages.
  double baseRot[2];
  for (int p = 0; p < 2; ++p) baseRot[p] = bestRotation(cuts[p]);
  struct Choice {
    double rot[2];
    bool vertical;
    Vec2 size;
    Box box[2];
  };
  std::vector<Choice> choices;
  for (int ra = 0; ra < 2; ++ra)
    for (int rb = 0; rb < 2; ++rb)
      for (int v = 0; v < 2; ++v) {
        Choice c;
        c.rot[0] = baseRot[0] + 90 * ra;
        c.rot[1] = baseRot[1] + 90 * rb;
        c.vertical = v == 1;
        for (int p = 0; p < 2; ++p) c.box[p] = extentAt(cuts[p], c.rot[p], edge);
        c.size = arranged(c.box[0], c.box[1], c.vertical, m);
        choices.push_back(c);
      }
  auto pick = [&](double W, double H) -> const Choice* {
    const Choice* best = nullptr;
    for (const Choice& c : choices)
      if (fits(c.size, W, H) && (!best || c.size.prod() < best->size.prod() - 1e-9)) best = &c;
    return best;
  };
  // Where each piece goes: its turn, its extent, and the top-left corner of that extent.
  double rot[2];
  Box box[2];
  Vec2 corner[2];
  std::vector<SheetPlan> plans;
  const Choice* together = pick(pageW, pageH);
  bool landscape = false;
  if (!together && mayTurnPage) {
    together = pick(pageH, pageW);
    landscape = together != nullptr;
  }
  if (together) {
    SheetPlan plan;
    plan.box = Box::spanning(Vec2::Zero(), landscape ? Vec2(pageH, pageW) : Vec2(pageW, pageH));
    plan.pieces = {0, 1};
    plan.size = together->size;
    const Box region = artRegion(plan.box.w(), plan.box.h());
    plan.title = titleAt(plan.size, region);
    for (int p = 0; p < 2; ++p) {
      rot[p] = together->rot[p];
      box[p] = together->box[p];
    }
    corner[0] = region.lo;
    corner[1] = region.lo + (together->vertical ? Vec2(0, box[0].h() + m) : Vec2(box[0].w() + m, 0));
    plans.push_back(plan);
  } else {
    double x = 0;  // the sheets lie side by side on the canvas
    for (int p = 0; p < 2; ++p) {
      SheetPlan plan;
      plan.pieces = {p};
      const Choice* best = nullptr;  // the rotations tried for this piece: its two in `choices`
      bool turned = false;
      for (bool turn : {false, true}) {
        if (best || (turn && !mayTurnPage)) continue;
        const double W = turn ? pageH : pageW, H = turn ? pageW : pageH;
        for (const Choice& c : choices)
          if (fits(Vec2(c.box[p].w(), c.box[p].h()), W, H) &&
              (!best || c.box[p].w() * c.box[p].h() < best->box[p].w() * best->box[p].h() - 1e-9))
            best = &c;
        turned = turn;
      }
      if (best) {
        rot[p] = best->rot[p];
        box[p] = best->box[p];
        plan.box = Box::spanning(Vec2(x, 0), Vec2(x, 0) + (turned ? Vec2(pageH, pageW)
                                                                  : Vec2(pageW, pageH)));
      } else if (mayTile) {  // its turn of the smaller largest side, tiled
        best = &choices[0];
        for (const Choice& c : choices)
          if (std::max(c.box[p].w(), c.box[p].h()) < std::max(best->box[p].w(), best->box[p].h()))
            best = &c;
        rot[p] = best->rot[p];
        box[p] = best->box[p];
        plan.tiled = true;
        plan.box = Box::spanning(Vec2(x, 0),
                                 Vec2(x, 0) + tiledExtent(Vec2(box[p].w(), box[p].h())));
        const auto [nx, ny] = tileGrid(Vec2(box[p].w(), box[p].h()));
        plan.tilesX = nx;
        plan.tilesY = ny;
      } else {
        std::vector<Vec2> sizes;
        for (const Choice& c : choices) sizes.emplace_back(c.box[p].w(), c.box[p].h());
        return tooLarge("piece " + names[p], sizes, "the piece and its tabs");
      }
      plan.size = Vec2(box[p].w(), box[p].h());
      const Box region = artRegion(plan.box.w(), plan.box.h(), plan.box.lo);
      plan.title = titleAt(plan.size, region);
      corner[p] = region.lo;
      x = plan.box.hi.x();
      plans.push_back(plan);
    }
    out.messages.push_back("the pieces do not fit one " +
                           (pageName.empty() ? std::string("sheet") : pageName + " page") +
                           " together: each is on its own, in pattern.pdf and in " +
                           sheetFileName(1, "svg") + " and " + sheetFileName(2, "svg") +
                           " (and .dxf)");
  }
  long tiles = 0;
  for (const SheetPlan& plan : plans) tiles += plan.tilesX * plan.tilesY;
  if (tiles > kMaxTiles) return tooManyTiles(tiles);
  double canvasW = 0, canvasH = 0;
  for (const SheetPlan& plan : plans) {
    out.sheets.push_back(plan.box);
    canvasW = std::max(canvasW, plan.box.hi.x());
    canvasH = std::max(canvasH, plan.box.hi.y());
  }
  Placement place[2];
  for (int p = 0; p < 2; ++p) {
    place[p].M = flipRotate(rot[p]);
    place[p].t = corner[p] - box[p].lo;
  }

  // --- Pieces, ticks, tabs in sheet coordinates ------------------------------------------------
  for (int p = 0; p < 2; ++p) {
    PieceInfo info;
    info.name = names[p];
    info.outline = place[p].map(seams[p].P);
    for (const auto& loop : material[p]) info.boundaries.push_back(place[p].map(loop));
    info.seamIsHole = seams[p].hole;
    for (const auto& c : cuts[p]) info.cut.push_back(place[p].map(c));
    for (const auto& c : holeCuts[p]) info.holeCuts.push_back(place[p].map(c));
    if (profile.bleedMm > 0)
      for (const auto& loop : bleedLoops(cuts[p], holeCuts[p], profile.bleedMm))
        info.bleed.push_back(place[p].map(loop));
    const std::vector<CreaseFold> folds = creaseFolds(*piece[p]);
    for (size_t k = 0; k < folds.size(); ++k)
      info.creases.push_back({info.name + "-crease-" + std::to_string(k + 1) + "-" +
                                  foldDirectionName(folds[k].direction),
                              folds[k],
                              place[p].map(flatPolyline(piece[p]->flat, piece[p]->creases[k]))});
    info.perimeter = seams[p].L;
    info.rotationDeg = rot[p];
    for (size_t k = 0; k < plans.size(); ++k)
      if (std::count(plans[k].pieces.begin(), plans[k].pieces.end(), p)) info.sheet = int(k);
    out.pieces.push_back(info);
  }
  for (size_t k = 0; k < tickS.size(); ++k) {
    TickInfo t;
    t.id = int(k);
    t.s = tickS[k];
    t.sB = matchingArc(seams[0], seams[1], t.s);
    t.onA = place[0].point(seams[0].at(t.s));
    t.onB = place[1].point(seams[1].at(t.sB));
    out.ticks.push_back(t);
  }
  for (const FlatTab& t : tabs) {
    TabInfo info;
    info.piece = t.piece;
    info.s0 = t.s0;
    info.s1 = t.s1;
    info.width = t.width;
    info.polygon = place[t.piece].map(t.polygon);
    info.fold = place[t.piece].map(t.fold);
    out.tabs.push_back(info);
  }

  // --- The drawing -------------------------------------------------------------------------------
  DrawingBuilder b(profile, canvasW, canvasH);
  const std::string perimeterText = formatMm(seams[0].L, 1);
  // The scale as printed: "1:1" or the percentage of true size.
  char percent[32];
  std::snprintf(percent, sizeof percent, "%.0f%%", 100 * scale);
  const std::string scaleText =
      scale == 1.0 ? std::string("1:1, mm") : std::string("scale ") + percent + " of true size, mm";
  b.drawing().title = o.jobName + " - D-Form pattern (" + profile.name + ")";
  b.drawing().description = "job " + o.jobName + "; profile " + profile.name +
                            "; " + (scale == 1.0 ? std::string("true scale") : "scale " + std::string(percent)) +
                            ", 1 user unit = 1 mm; seam length " + perimeterText +
                            " mm; ticks every " + formatMm(o.tickSpacingMm) + " mm" +
                            (o.failedGateMark ? "; FAILED GATE: not for fabrication" : "");
  int skippedLabels = 0, thinnedLabels = 0, skippedCreaseLabels = 0;
  for (int p = 0; p < 2; ++p) {
    const PieceInfo& info = out.pieces[size_t(p)];
    const std::string& nm = info.name;
    const Seam& seam = seams[p];
    std::vector<Polyline> creaseLines;  // labels keep off them
    for (const CreaseInfo& crease : info.creases) creaseLines.push_back(crease.line);
    // Tick marks across the outline and their numbers inside the piece.
    std::vector<Polyline> tickLabelHulls;                               // the numbers placed
    BoxIndex tickLabelIndex(std::max(2.0 * profile.labelHeightMm, 1.0));  // about one number
    for (const TickInfo& t : out.ticks) {
      int seg = 0;
      seam.at(p == 0 ? t.s : t.sB, &seg);
      const Vec2 c = p == 0 ? t.onA : t.onB;
      const Vec2 nOut = place[p].vector(seam.outward(seg)).normalized();
      const Vec2 tan = place[p].vector(seam.dir(seg)).normalized();
      const double in = t.id == 0 ? kStartTickIn : kTickIn;
      Path tick;
      tick.id = nm + "-tick-" + twoDigits(t.id);
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
      if (!placed) ++(fitsSomewhere ? thinnedLabels : skippedLabels);
    }
    // Piece name (and the failed-gate mark) at the roomiest point inside the piece, clear of the
    // creases; and of the tick numbers where the roomiest point is near them (a ring-shaped piece).
    std::vector<Polyline> taken;  // footprints of the piece's labels so far
    for (const Path& path : b.engrave().paths)
      if (path.id.rfind(nm + "-", 0) == 0) taken.push_back(convexHull(path.parts));
    auto nameLabels = [&](const std::vector<Polyline>& avoid) {
      const auto [centre, room] = roomiestPoint(info.boundaries, creaseLines, avoid);
      std::vector<Path> labels;
      const double nameH = std::min(3 * profile.labelHeightMm, 0.9 * room);
      Vec2 nameAt = centre;
      if (o.failedGateMark) nameAt.y() -= 0.6 * nameH;
      if (nameH >= 1.0) labels.push_back(textPath(font, nm + "-name", nm, nameAt, {1, 0}, nameH));
      if (o.failedGateMark) {
        const std::string mark = "FAILED GATE";
        const double h = std::min(1.5 * profile.labelHeightMm,
                                  1.6 * room / std::max(1.0, font.width(mark, 1.0)));
        labels.push_back(textPath(font, nm + "-failed-gate", mark,
                                  centre + Vec2(0, 0.6 * nameH + 0.6 * h), {1, 0}, h));
      }
      return labels;
    };
    auto clashes = [&](const std::vector<Path>& labels) {
      return std::any_of(labels.begin(), labels.end(), [&](const Path& label) {
        return overlapsAny(convexHull(label.parts), taken, 0.0);
      });
    };
    std::vector<Path> names = nameLabels({});
    if (clashes(names)) names = nameLabels(taken);
    for (Path& label : names) {
      taken.push_back(convexHull(label.parts));
      b.engrave().paths.push_back(std::move(label));
    }
    // A small M or V beside each crease, where one fits clear of the piece's other labels.
    for (const CreaseInfo& crease : info.creases) {
      const std::string letter = crease.fold.direction == FoldDirection::Mountain ? "M" : "V";
      const double h = profile.labelHeightMm, halfW = 0.5 * font.width(letter, h), halfH = 0.5 * h;
      const double length = polylineLength(crease.line, false);
      bool placed = false;
      for (double f : {0.5, 0.3, 0.7, 0.15, 0.85})
        for (double side : {1.0, -1.0}) {
          Vec2 t;
          const Vec2 q = pointAlong(crease.line, f * length, &t);
          const Vec2 center = q + side * (halfH + 1.0) * Vec2(-t.y(), t.x());
          const Vec2 d = readable(t);
          if (placed || !boxFits(info.boundaries, creaseLines, center, d, halfW, halfH, 0.3))
            continue;
          const Vec2 n(-d.y(), d.x()), grow(halfW + 0.5, halfH + 0.5);  // 0.5 mm clear of others
          const Polyline box = {
              center - grow.x() * d - grow.y() * n, center + grow.x() * d - grow.y() * n,
              center + grow.x() * d + grow.y() * n, center - grow.x() * d + grow.y() * n};
          if (overlapsAny(box, taken, 0.0)) continue;
          Path label = textPath(font, crease.id + "-label", letter, center, d, h);
          taken.push_back(convexHull(label.parts));
          b.engrave().paths.push_back(std::move(label));
          placed = true;
        }
      skippedCreaseLabels += !placed;
    }
  }
  if (skippedLabels > 0)
    out.messages.push_back(std::to_string(skippedLabels) +
                           " tick number(s) left out where the piece is too narrow for them");
  if (thinnedLabels > 0)
    out.messages.push_back(std::to_string(thinnedLabels) +
                           " tick number(s) thinned out where the ticks are closer than the "
                           "numbers are wide; every tick is still marked");
  if (skippedCreaseLabels > 0)
    out.messages.push_back(std::to_string(skippedCreaseLabels) +
                           " crease M/V label(s) left out where there is no room; the crease ids "
                           "in pattern.svg and pattern.json name the fold");

  // Crease fold lines: the profile's fold style, dashed by the fold's direction.
  for (const PieceInfo& info : out.pieces)
    for (const CreaseInfo& crease : info.creases) {
      Path line;
      line.id = crease.id;
      if (profile.fold == FoldStyle::Perforated) {
        line.parts = perforate(crease.line, profile.perforationCutMm, profile.perforationGapMm);
        if (!line.parts.empty()) b.cut().paths.push_back(line);
        continue;
      }
      line.parts = {crease.line};
      if (Layer* cutter = b.cutterScore()) cutter->paths.push_back(scorePass(line));
      line.dashed = profile.fold == FoldStyle::Dashed;
      if (line.dashed) line.dash = creaseDash(crease.fold.direction, profile.dashMm);
      b.score().paths.push_back(line);
    }

  // Fold lines and perforations; then the cut paths (inner cuts before outer ones).
  int tabIndex[2] = {0, 0};
  for (const TabInfo& t : out.tabs) {
    const std::string id = names[t.piece] + "-fold-" + twoDigits(++tabIndex[t.piece]);
    if (profile.fold == FoldStyle::Perforated) {
      Path perf;
      perf.id = names[t.piece] + "-perf-" + twoDigits(tabIndex[t.piece]);
      perf.parts = perforate(t.fold, profile.perforationCutMm, profile.perforationGapMm);
      if (!perf.parts.empty()) b.cut().paths.push_back(perf);
    } else {
      Path fold;
      fold.id = id;
      fold.parts = {t.fold};
      if (Layer* cutter = b.cutterScore()) cutter->paths.push_back(scorePass(fold));
      fold.dashed = profile.fold == FoldStyle::Dashed;
      // A tab folds back, away from the printed face: a mountain fold seen from it, dashed as
      // the legend's mountain creases are.
      if (fold.dashed) fold.dash = creaseDash(FoldDirection::Mountain, profile.dashMm);
      b.score().paths.push_back(fold);
    }
  }
  for (bool holes : {true, false})  // every hole before any outer cut: inner cuts first
    for (int p = 0; p < 2; ++p) {
      const auto& cutList = holes ? out.pieces[size_t(p)].holeCuts : out.pieces[size_t(p)].cut;
      for (size_t k = 0; k < cutList.size(); ++k) {
        const std::string suffix =
            holes ? "-hole-" + std::to_string(k + 1) : (k == 0 ? "" : "-" + std::to_string(k + 1));
        Path cut;
        cut.id = names[p] + "-cut" + suffix;
        cut.parts = {cutList[k]};
        cut.closed = true;
        b.cut().paths.push_back(cut);
        // Print-and-cut prints the outline the cutter follows, unless a tint with a bleed stands
        // for it (a line on the cut would show wherever the cut is a little off).
        if (profile.kind == ProfileKind::PrintAndCut && !b.bleed()) {
          Path printed = cut;
          printed.id = names[p] + "-outline" + suffix;
          b.engrave().paths.push_back(printed);
        }
      }
    }
  if (Layer* tint = b.bleed())
    for (size_t p = 0; p < 2; ++p) {
      Path fill;
      fill.id = names[p] + "-bleed";
      fill.parts = out.pieces[p].bleed;
      fill.closed = fill.filled = true;
      fill.fill = p == 0 ? profile.fillColorA : profile.fillColorB;
      tint->paths.push_back(fill);
    }

  // Title lines (and the calibration bar) under each sheet's pieces or in a column beside them,
  // and the registration marks in each sheet's corners.
  for (size_t k = 0; k < plans.size(); ++k) {
    const SheetPlan& plan = plans[k];
    const Box& sheet = plan.box;
    const Box region = artRegion(sheet.w(), sheet.h(), sheet.lo);
    // The block's frame: lines run along `along` from `start`, each the next one across.
    const bool aside = plan.title == TitleAt::Aside;
    const Vec2 along = aside ? Vec2(0, -1) : Vec2(1, 0), across = aside ? Vec2(1, 0) : Vec2(0, 1);
    const Vec2 start = aside ? Vec2(region.lo.x() + plan.size.x() + m, region.hi.y())
                             : Vec2(region.lo.x(), region.lo.y() + plan.size.y() + m);
    const double length = aside ? region.h() : region.w();
    double v = 0;  // how far across the lines so far reach
    auto line = [&](const std::string& id, const std::string& text, double h) {
      const double w = font.width(text, h);
      if (w > length) h *= length / w;
      const Vec2 c = start + 0.5 * std::min(w, length) * along + (v + 0.5 * lineH * h / textH) * across;
      b.title().paths.push_back(textPath(font, onPage(id, k), text, c, along, h));
      v += lineH * h / textH;
    };
    std::string pieceNote;
    if (plans.size() > 1)
      pieceNote = " - " + sheetWord + " " + std::to_string(k + 1) + " of " +
                  std::to_string(plans.size()) + ": piece " + names[plan.pieces.front()];
    if (o.failedGateMark) line("failed-gate", "FAILED GATE - NOT FOR FABRICATION", 2 * textH);
    if (o.title) {
    line("title",
         o.jobName + " - D-Form " + names[0] + " + " + names[1] + pieceNote + " - " + scaleText + " - seam " +
             perimeterText + " mm - " + profile.name,
         textH);
    line("note",
         "tick 0 = start, arrow = zip direction; ticks every " + formatMm(o.tickSpacingMm, 0) +
             " mm; glue equal numbers together",
         textH);
    if (creased)
      line("crease-legend-label",
           profile.fold == FoldStyle::Dashed
               ? "creases seen from this side (the outside): M = mountain (dash-dot), V = valley "
                 "(dashed)"
               : "creases seen from this side (the outside): M = mountain, V = valley",
           textH);
    if (tabbed)
      line("tab-note",
           profile.kind == ProfileKind::Laser
               ? "engraved side out: fold the tabs back, away from the engraving, and glue them "
                 "inside"
               : "printed side out: fold the tabs back, away from the print (mountain folds, "
                 "dash-dot), and glue them inside",
           textH);
    }
    if (profile.calibrationBar) {
      auto at = [&](double u, double w) -> Vec2 { return start + u * along + w * across; };
      const double vb = v + 4.0;
      Path bar;
      bar.id = onPage("calibration-bar", k);
      bar.parts.push_back({at(0, vb), at(50, vb)});
      for (int j = 0; j <= 5; ++j) {
        const double tickLen = (j == 0 || j == 5) ? 3.0 : 1.5;
        bar.parts.push_back({at(10 * j, vb - tickLen), at(10 * j, vb)});
      }
      b.title().paths.push_back(bar);
      const std::string text = "50 mm - print at 100% (actual size)";
      // Smaller where the block is too short for it beside the bar (a narrow tiled piece).
      const double h = std::min(textH, (length - 54) / std::max(1.0, font.width(text, 1.0)));
      b.title().paths.push_back(textPath(font, onPage("calibration-label", k), text,
                                         at(54 + 0.5 * font.width(text, h), vb - 1.5), along, h));
    }
    if (profile.registration == Registration::Silhouette) {
      const double a = kRegInset, s = kRegSquare;
      const Vec2 lo = sheet.lo + Vec2(a, a), hi = sheet.hi - Vec2(a, a);
      Path square;
      square.id = onPage("regmark-square", k);
      square.filled = true;
      square.closed = true;
      square.parts = {{lo, lo + Vec2(s, 0), lo + Vec2(s, s), lo + Vec2(0, s)}};
      b.regmarks()->paths.push_back(square);
      Path tr;
      tr.id = onPage("regmark-top-right", k);
      tr.parts = {
          {Vec2(hi.x() - kRegArm, lo.y()), Vec2(hi.x(), lo.y()), Vec2(hi.x(), lo.y() + kRegArm)}};
      b.regmarks()->paths.push_back(tr);
      Path bl;
      bl.id = onPage("regmark-bottom-left", k);
      bl.parts = {
          {Vec2(lo.x(), hi.y() - kRegArm), Vec2(lo.x(), hi.y()), Vec2(lo.x() + kRegArm, hi.y())}};
      b.regmarks()->paths.push_back(bl);
    }
  }
  out.drawing = std::move(b.drawing());

  // --- Pages -------------------------------------------------------------------------------------
  // A page per sheet; a tiled piece gets a page map, then its tiles.
  for (size_t k = 0; k < plans.size(); ++k) {
    const SheetPlan& plan = plans[k];
    if (!plan.tiled) {
      PageView page;
      page.width = plan.box.w();
      page.height = plan.box.h();
      page.origin = plan.box.lo;
      page.clipX1 = plan.box.w();
      page.clipY1 = plan.box.h();
      out.pages.push_back(page);
      continue;
    }
    const std::string& nm = names[plan.pieces.front()];
    const PieceInfo& info = out.pieces[size_t(plan.pieces.front())];
    const double pm = kTileMargin, header = kTileHeader, ov = overlap, cw = tileW, ch = tileH;
    const long nx = plan.tilesX, ny = plan.tilesY;
    const size_t firstTilePage = out.pages.size() + 2;  // 1-based, after the map
    auto tileName = [&](long row, long col) {
      return nm + " " + std::to_string(row + 1) + "-" + std::to_string(col + 1);
    };
    auto furnitureLayer = [] {
      Layer l;
      l.name = "Tiling";
      l.color = "#000000";
      l.widthMm = 0.2;
      l.dashMm = 2.0;
      return l;
    };
    auto headerText = [&](Layer& furniture, const std::string& id, const std::string& head) {
      const double hh = std::min(3.0, cw / std::max(1.0, font.width(head, 1.0)));
      furniture.paths.push_back(
          textPath(font, id, head, Vec2(pm + 0.5 * font.width(head, hh), pm + 3.0), {1, 0}, hh));
    };
    // The page map: the piece's cut outline scaled onto one page under the grid of its tiles,
    // each named as its page's header names it.
    {
      PageView map;
      map.width = pageW;
      map.height = pageH;
      Layer furniture = furnitureLayer();
      // The grid of windows reaches past the piece's sheet (the last ones overhang it).
      const double gridW = double(nx) * (cw - ov) + ov, gridH = double(ny) * (ch - ov) + ov;
      const double mapScale = std::min(cw / gridW, ch / gridH);
      auto onMap = [&](const Vec2& q) -> Vec2 {
        return Vec2(pm, pm + header) + mapScale * (q - plan.box.lo);
      };
      Path outline;
      outline.id = "page-map-" + nm + "-outline";
      outline.closed = true;
      for (const Polyline& cut : info.cut) {
        Polyline mapped;
        for (const Vec2& q : cut) mapped.push_back(onMap(q));
        outline.parts.push_back(mapped);
      }
      furniture.paths.push_back(outline);
      for (long j = 0; j < ny; ++j)
        for (long i = 0; i < nx; ++i) {
          const Vec2 lo = plan.box.lo + Vec2(double(i) * (cw - ov), double(j) * (ch - ov));
          const Vec2 a = onMap(lo), c = onMap(lo + Vec2(cw, ch));
          Path cell;
          cell.id = "page-map-" + nm + "-tile-" + std::to_string(j + 1) + "-" + std::to_string(i + 1);
          cell.closed = true;
          cell.dashed = true;
          cell.parts = {{a, Vec2(c.x(), a.y()), c, Vec2(a.x(), c.y())}};
          furniture.paths.push_back(cell);
          const std::string text = tileName(j, i) + " (p. " +
                                   std::to_string(firstTilePage + size_t(j * nx + i)) + ")";
          const double th = std::min(4.0, 0.8 * (c.x() - a.x()) / std::max(1.0, font.width(text, 1.0)));
          furniture.paths.push_back(textPath(font, cell.id + "-name", text,
                                             Vec2(a.x() + 0.5 * (c.x() - a.x()), a.y() + th + 2.0),
                                             {1, 0}, th));
        }
      headerText(furniture, "page-map-header",
                 o.jobName + " - piece " + nm + ": page map, " + std::to_string(nx * ny) +
                     " tiles (" + std::to_string(ny) + " rows x " + std::to_string(nx) +
                     " cols) - not to scale - print the tiles at 100%");
      map.overlay.push_back(furniture);
      out.pages.push_back(map);
    }
    // Tiles, with alignment crosses in the middle of each overlap.
    std::vector<Vec2> marks;
    for (long i = 1; i < nx; ++i)
      for (long j = 0; j <= 2 * ny; ++j)
        marks.push_back(plan.box.lo + Vec2(double(i) * (cw - ov) + 0.5 * ov,
                                           double(j) * 0.5 * (ch - ov) + 0.5 * ov));
    for (long j = 1; j < ny; ++j)
      for (long i = 0; i <= 2 * nx; ++i)
        marks.push_back(plan.box.lo + Vec2(double(i) * 0.5 * (cw - ov) + 0.5 * ov,
                                           double(j) * (ch - ov) + 0.5 * ov));
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        PageView page;
        page.width = pageW;
        page.height = pageH;
        page.clipX0 = pm;
        page.clipY0 = pm + header;
        page.clipX1 = pm + cw;
        page.clipY1 = pm + header + ch;
        const Vec2 windowLo = plan.box.lo + Vec2(double(i) * (cw - ov), double(j) * (ch - ov));
        page.origin = windowLo - Vec2(page.clipX0, page.clipY0);
        Layer furniture = furnitureLayer();
        Path frame;
        frame.id = "tile-frame";
        frame.closed = true;
        frame.dashed = true;
        frame.parts = {{Vec2(page.clipX0, page.clipY0), Vec2(page.clipX1, page.clipY0),
                        Vec2(page.clipX1, page.clipY1), Vec2(page.clipX0, page.clipY1)}};
        furniture.paths.push_back(frame);
        int markId = 0;
        for (const Vec2& q : marks) {
          const Vec2 onPage = q - page.origin;
          if (onPage.x() < page.clipX0 || onPage.x() > page.clipX1 || onPage.y() < page.clipY0 ||
              onPage.y() > page.clipY1)
            continue;
          furniture.paths.push_back(cross("align-" + std::to_string(++markId), onPage, 4.0));
        }
        headerText(furniture, "tile-header",
                   o.jobName + " - piece " + nm + ", tile " + tileName(j, i) + " (row " +
                       std::to_string(j + 1) + " of " + std::to_string(ny) + ", col " +
                       std::to_string(i + 1) + " of " + std::to_string(nx) + ") - overlap " +
                       formatMm(ov, 0) + " mm, match the crosses - print at 100%");
        Path bar;
        bar.id = "tile-calibration-bar";
        const double yb = pm + 9.0;
        bar.parts.push_back({Vec2(pm, yb), Vec2(pm + 50, yb)});
        bar.parts.push_back({Vec2(pm, yb - 2.5), Vec2(pm, yb)});
        bar.parts.push_back({Vec2(pm + 50, yb - 2.5), Vec2(pm + 50, yb)});
        furniture.paths.push_back(bar);
        furniture.paths.push_back(textPath(font, "tile-bar-label", "50 mm",
                                           Vec2(pm + 56 + 0.5 * font.width("50 mm", 2.5), yb - 1.2),
                                           {1, 0}, 2.5));
        if (o.failedGateMark) {
          const std::string mark = "FAILED GATE";
          furniture.paths.push_back(
              textPath(font, "tile-failed-gate", mark,
                       Vec2(pageW - pm - 0.5 * font.width(mark, 4.0), pm + 8.0), {1, 0}, 4.0));
        }
        page.overlay.push_back(furniture);
        out.pages.push_back(page);
      }
    out.messages.push_back("piece " + nm + " is larger than a " + pageName + " page: it is tiled across " +
                           std::to_string(nx * ny) + " pages of pattern.pdf after a page map; print at 100% and match the crosses");
  }
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

}  // namespace

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
  Result<PatternBuild> built =
      buildAtScale(o.scale == 1.0 ? model : scaledFlat(model, o.scale), o, profile, font, o.scale,
                   work, tooLarge);
  if (built.isOk() || !tooLarge || !o.scaleToFit) return withAssembly(std::move(built));
  // Scaled to fit: the largest scale below the one asked for, in whole percent, at which every
  // piece fits, by bisection (a smaller scale never makes a piece's extent larger: its outline
  // shrinks and its tabs and ticks keep their size).
  const Status atFull = built.status();
  int fitsAt = 0, failsAt = int(std::lround(100 * o.scale));
  Result<PatternBuild> best = atFull;
  while (failsAt - fitsAt > 1) {
    const int mid = (fitsAt + failsAt) / 2;
    tooLarge = false;
    Result<PatternBuild> attempt = buildAtScale(scaledFlat(model, mid / 100.0), o, profile, font,
                                                mid / 100.0, work, tooLarge);
    if (attempt.isOk()) {
      fitsAt = mid;
      best = std::move(attempt);
    } else if (tooLarge) {
      failsAt = mid;
    } else {
      return attempt;
    }
  }
  if (fitsAt == 0) return atFull;
  best.value().messages.push_back("scaled to " + std::to_string(fitsAt) +
                                  "% to fit: at " + std::to_string(int(std::lround(100 * o.scale))) +
                                  "% " + atFull.message());
  return withAssembly(std::move(best));
}

}  // namespace dform::fab
