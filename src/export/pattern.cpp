// The flat pattern: seam ticks at equal arc length on both pieces, glue tabs, cut paths (outline
// with tabs merged, holes, kerf offset), crease fold lines, placement on the sheet, single-stroke
// labels and the pages. Geometry is computed in each piece's flat frame (mm, y up), then mapped to
// the sheet (y down). A piece's seam may be its outer outline or a hole's loop (anti and demi
// D-Forms): ticks and tabs go along the seam only, on the side away from the material.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/piece_loops.h"
#include "core/polyline.h"
#include "export/internal.h"
#include "export/plane_geometry.h"

namespace dform::fab {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kA4W = 210.0, kA4H = 297.0;
constexpr double kLetterW = 215.9, kLetterH = 279.4;
// Cricut Print Then Cut: 6.75 x 9.25 in (the long-standing safe maximum on Letter).
constexpr double kCricutW = 6.75 * 25.4, kCricutH = 9.25 * 25.4;
// Silhouette type-1 marks: 10 mm from the edges, 5 mm square, 20 mm L arms, 0.3 mm lines,
// 20 mm kept clear of artwork around them.
constexpr double kRegInset = 10.0, kRegSquare = 5.0, kRegArm = 20.0, kRegLine = 0.3,
                 kRegClear = 20.0;
constexpr double kTickOut = 1.5;      // tick length outside the outline (mm)
constexpr double kTickIn = 3.0;       // tick length inside the outline (mm)
constexpr double kStartTickIn = 6.0;  // the start tick is longer (mm)

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

struct FlatTab {
  int piece = 0;
  double s0 = 0, s1 = 0, width = 0;
  Polyline polygon;  // flat frame, fold line first
  Polyline fold;
};

// The tab on `seam` over [s0, s1]: the fold line, then the outer edge (offset by `width`, inset
// at both ends by width / tan(angle)) back to the start.
FlatTab makeTab(const Seam& seam, int piece, double s0, double s1, double width, double angleRad) {
  FlatTab tab;
  tab.piece = piece;
  tab.s0 = s0;
  tab.s1 = s1;
  tab.width = width;
  tab.fold = seam.sub(s0, s1);
  const double inset = width / std::tan(angleRad);
  Polyline outer = seam.sub(s0 + inset, s1 - inset, width);
  tab.polygon = tab.fold;
  tab.polygon.insert(tab.polygon.end(), outer.rbegin(), outer.rend());
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

bool tabIsClean(const FlatTab& tab, const std::vector<Polyline>& material,
                const std::vector<FlatTab>& accepted) {
  if (findSelfIntersection(toPoints(tab.polygon))) return false;
  if (overlapArea({tab.polygon}, material) > kOverlapTolMm2) return false;
  for (const FlatTab& other : accepted) {
    if (other.piece == tab.piece && overlapArea(tab.polygon, other.polygon) > kOverlapTolMm2)
      return false;
  }
  return true;
}

// Splits the seam into tab intervals no longer than maxLen whose seam turns by at most maxTurn on
// either piece, then builds each tab; a tab that would overlap its piece or a neighbour is made
// narrower, then split, then left out (with a message).
std::vector<FlatTab> makeTabs(const Seam seams[2], const std::vector<Polyline> material[2],
                              const ExportOptions& o, double L,
                              std::vector<std::string>& messages) {
  std::vector<FlatTab> tabs;
  if (o.tabWidthMm <= 0) return tabs;
  const double angle = o.tabAngleDeg * kPi / 180.0;
  const double inset = o.tabWidthMm / std::tan(angle);
  const double minLen = 2 * inset + 1.0;  // the outer edge keeps at least 1 mm
  const double maxLen = std::max(o.tabMaxLengthMm, minLen);
  const double maxTurn = o.tabMaxTurnDeg * kPi / 180.0;
  const double step = std::min(1.0, L / 1000);  // growth step along the seam (mm)
  const double sEnd = L - 0.5 * o.tabGapMm;
  std::vector<std::pair<double, double>> intervals;
  for (double s = 0.5 * o.tabGapMm; s + minLen <= sEnd;) {
    double e = s + minLen;
    for (;;) {
      const double next = std::min(e + step, sEnd);
      if (next <= e || next - s > maxLen) break;
      if (std::max(seams[0].turning(s, next), seams[1].turning(s, next)) > maxTurn) break;
      e = next;
    }
    intervals.emplace_back(s, e);
    s = e + o.tabGapMm;
  }
  int dropped = 0;
  for (size_t k = 0; k < intervals.size(); ++k) {
    const int piece = o.alternateTabs ? int(k % 2) : 0;
    const Seam& seam = seams[piece];
    const auto [s0, s1] = intervals[k];
    FlatTab tab = makeTab(seam, piece, s0, s1, o.tabWidthMm, angle);
    if (tabIsClean(tab, material[piece], tabs)) {
      tabs.push_back(tab);
      continue;
    }
    const double narrow = 0.5 * o.tabWidthMm;
    tab = makeTab(seam, piece, s0, s1, narrow, angle);
    if (tabIsClean(tab, material[piece], tabs)) {
      tabs.push_back(tab);
      continue;
    }
    const double mid = 0.5 * (s0 + s1), halfGap = 0.5 * o.tabGapMm;
    bool any = false;
    for (const auto& [a, b] : {std::pair{s0, mid - halfGap}, std::pair{mid + halfGap, s1}}) {
      if (b - a < 2 * narrow / std::tan(angle) + 1.0) continue;
      FlatTab half = makeTab(seam, piece, a, b, narrow, angle);
      if (tabIsClean(half, material[piece], tabs)) {
        tabs.push_back(half);
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
  return tabs;
}

struct CutPaths {
  std::vector<Polyline> outer;  // counter-clockwise in the flat frame
  std::vector<Polyline> holes;  // clockwise
};

// The closed cut paths of one piece (flat frame): its outline, holes and tabs merged, offset by
// the kerf (outward from the material: the outline grows and the holes shrink). `freeLoops` are
// its free boundaries; `outer` is outerLoopIndex (0 the seam, k free loop k - 1).
CutPaths cutPaths(const Seam& seam, const std::vector<Polyline>& freeLoops, int outer,
                  const std::vector<FlatTab>& tabs, int piece, double kerf) {
  // The seam gets the tabs' fold ends as vertices, computed exactly as the tabs' own, so that
  // piece and tabs share their edges to the last bit and the union leaves no slivers.
  std::vector<double> ends;
  for (const FlatTab& t : tabs)
    if (t.piece == piece) ends.insert(ends.end(), {t.s0, t.s1});
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
  if (kerf > 0) {
    ClipperLib::ClipperOffset offset(2.0, 0.005 * kClipScale);  // arcs within 5 um
    offset.AddPaths(merged, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
    ClipperLib::Paths grown;
    offset.Execute(grown, kerf * kClipScale);
    merged = grown;
  }
  for (const auto& p : merged)
    (ClipperLib::Orientation(p) ? out.outer : out.holes).push_back(fromClip(p));
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

struct Box {
  Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  double w() const { return hi.x() - lo.x(); }
  double h() const { return hi.y() - lo.y(); }
};

Box boxOf(const std::vector<Polyline>& paths, const Eigen::Matrix2d& M) {
  Box b;
  for (const auto& p : paths)
    for (const Vec2& q : p) b.add(M * q);
  return b;
}

// The rotation (degrees, in 2-degree steps) that gives the cut paths the smallest bounding box.
double bestRotation(const std::vector<Polyline>& cut) {
  double best = 0, bestArea = 1e300;
  for (int deg = 0; deg < 180; deg += 2) {
    const Box b = boxOf(cut, flipRotate(deg));
    if (b.w() * b.h() < bestArea - 1e-9) {
      bestArea = b.w() * b.h();
      best = deg;
    }
  }
  return best;
}

struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double w() const { return x1 - x0; }
  double h() const { return y1 - y0; }
};

// Builds the drawing's layers and routes each operation to its layer for the profile's kind.
class DrawingBuilder {
 public:
  DrawingBuilder(const Profile& p, double w, double h) : kind_(p.kind) {
    drawing_.width = w;
    drawing_.height = h;
    auto layer = [](std::string name, std::string color, double width, double dash, bool printed) {
      Layer l;
      l.name = std::move(name);
      l.color = std::move(color);
      l.widthMm = width;
      l.dashMm = dash;
      l.printed = printed;
      return l;
    };
    switch (p.kind) {
      case ProfileKind::Laser:  // engrave, then score, then cut (inner cuts first, outer last)
        drawing_.layers = {layer("Engrave", p.engraveColor, p.engraveWidthMm, p.dashMm, true),
                           layer("Score", p.scoreColor, p.scoreWidthMm, p.dashMm, true),
                           layer("Cut", p.cutColor, p.cutWidthMm, p.dashMm, true)};
        break;
      case ProfileKind::Print:
        drawing_.layers = {layer("Labels", p.engraveColor, p.engraveWidthMm, p.dashMm, true),
                           layer("Fold", p.scoreColor, p.scoreWidthMm, p.dashMm, true),
                           layer("Cut", p.cutColor, p.cutWidthMm, p.dashMm, true)};
        break;
      case ProfileKind::PrintAndCut:  // the Cut layer goes to the cutter, not the printer
        drawing_.layers = {layer("Regmarks", "#000000", kRegLine, p.dashMm, true),
                           layer("Print", p.engraveColor, p.engraveWidthMm, p.dashMm, true),
                           layer("Cut", p.cutColor, p.cutWidthMm, p.dashMm, false)};
        break;
    }
  }
  Layer& engrave() { return drawing_.layers[kind_ == ProfileKind::PrintAndCut ? 1 : 0]; }
  Layer& score() { return drawing_.layers[1]; }
  Layer& cut() { return drawing_.layers[2]; }
  Layer& regmarks() { return drawing_.layers[0]; }
  Drawing& drawing() { return drawing_; }

 private:
  ProfileKind kind_;
  Drawing drawing_;
};

std::string twoDigits(int k) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", k);
  return buf;
}

// Tick numbers that read as another number upside down (6, 9, 16, 68, ...) get a trailing dot.
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

// The point at arc length s along the open polyline, and the unit direction of the segment it is
// on.
Vec2 pointAlong(const Polyline& line, double s, Vec2* tangent = nullptr) {
  double acc = 0;
  Vec2 dir(1, 0);
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const double seg = (line[i + 1] - line[i]).norm();
    if (seg <= 0) continue;
    dir = (line[i + 1] - line[i]) / seg;
    if (acc + seg >= s) {
      if (tangent) *tangent = dir;
      return line[i] + (s - acc) * dir;
    }
    acc += seg;
  }
  if (tangent) *tangent = dir;
  return line.back();
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

Result<PatternBuild> buildPattern(const DForm& model, const ExportOptions& o,
                                  const Profile& profile) {
  if (Status s = checkModel(model); !s.isOk()) return s;
  if (!(o.tickSpacingMm >= 1.0))
    return Status{ErrorCode::Usage, "tick spacing must be at least 1 mm"};
  if (!(o.tabWidthMm >= 0 && o.tabWidthMm <= 50))
    return Status{ErrorCode::Usage, "tab width must be between 0 and 50 mm"};
  if (!(o.tabAngleDeg >= 15 && o.tabAngleDeg <= 90))
    return Status{ErrorCode::Usage, "tab angle must be between 15 and 90 degrees"};
  if (!(o.tabGapMm >= 0) || !(o.tabMaxLengthMm > 0) || !(o.tabMaxTurnDeg > 0))
    return Status{ErrorCode::Usage, "tab gap, length and turn limits must be positive"};
  if (profile.page.empty() && !(o.sheetWidthMm > 0 && o.sheetHeightMm > 0))
    return Status{ErrorCode::Usage, "the sheet size must be positive (e.g. 600x400mm)"};
  auto fontResult = StrokeFont::load(o.fontPath);
  if (!fontResult.isOk()) return fontResult.status();
  const StrokeFont& font = fontResult.value();

  PatternBuild out;
  out.profile = profile;
  out.tickSpacing = o.tickSpacingMm;
  const Seam seams[2] = {Seam(model.a), Seam(model.b)};
  const std::string names[2] = {model.a.name.empty() ? "A" : model.a.name,
                                model.b.name.empty() ? "B" : model.b.name};
  // Seam lengths agree to the gate's tolerance on a solved model; warn where a fabricator would
  // see it (0.1 mm is the accuracy the ticks are held to).
  if (std::abs(seams[0].L - seams[1].L) > 0.1) {
    out.messages.push_back("the seams differ in length by " +
                           formatMm(std::abs(seams[0].L - seams[1].L), 2) +
                           " mm; the last ticks will not meet exactly");
  }
  const double L = std::min(seams[0].L, seams[1].L);

  // Ticks: every spacing mm from the seam start; a last tick closer than half a spacing to the
  // start would crowd tick 0 and its arrow, so it is left out.
  std::vector<double> tickS;
  for (int k = 0; k * o.tickSpacingMm < L; ++k) {
    const double s = k * o.tickSpacingMm;
    if (k > 0 && L - s < 0.5 * o.tickSpacingMm) break;
    tickS.push_back(s);
  }

  const Piece* piece[2] = {&model.a, &model.b};
  const std::vector<Polyline> material[2] = {materialLoops(model.a), materialLoops(model.b)};
  const std::vector<FlatTab> tabs = makeTabs(seams, material, o, L, out.messages);
  std::vector<Polyline> cuts[2], holeCuts[2];
  for (int p = 0; p < 2; ++p) {
    std::vector<Polyline> freeLoops;
    for (const auto& loop : piece[p]->freeBoundaries)
      freeLoops.push_back(flatPolyline(piece[p]->flat, loop));
    CutPaths c = cutPaths(seams[p], freeLoops, outerLoopIndex(*piece[p]), tabs, p, profile.kerfMm);
    cuts[p] = std::move(c.outer);
    holeCuts[p] = std::move(c.holes);
  }
  const bool creased = !model.a.creases.empty() || !model.b.creases.empty();

  // --- Sheet, page and the region where the pieces go -----------------------------------------
  const double m = profile.marginMm;
  const double textH = std::clamp(profile.labelHeightMm, 2.0, 4.0);
  const double lineH = 1.7 * textH;
  const double barH = profile.calibrationBar ? 9.0 : 0.0;
  const double failH = o.failedGateMark ? 2.0 * lineH : 0.0;
  const double titleH = (creased ? 3 : 2) * lineH + barH + failH;  // a legend line for creases
  double pageW = o.sheetWidthMm, pageH = o.sheetHeightMm;
  if (profile.page == "A4") {
    pageW = kA4W;
    pageH = kA4H;
  } else if (profile.page == "Letter") {
    pageW = kLetterW;
    pageH = kLetterH;
  }
  auto artRegion = [&](double W, double H) {
    Rect r{m, m, W - m, H - m};
    if (profile.registration == Registration::Silhouette) {
      const double inset = kRegInset + kRegSquare + kRegClear;  // clear of the square's far edge
      r = {inset, inset, W - inset, H - inset};
    } else if (profile.registration == Registration::Cricut) {
      r = {0.5 * (W - kCricutW), 0.5 * (H - kCricutH), 0.5 * (W + kCricutW), 0.5 * (H + kCricutH)};
    }
    return r;
  };

  // --- Orientation and arrangement -------------------------------------------------------------
  double baseRot[2];
  for (int p = 0; p < 2; ++p) baseRot[p] = bestRotation(cuts[p]);
  struct Choice {
    double rot[2];
    bool vertical;
    double w, h;
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
        for (int p = 0; p < 2; ++p) {  // ticks stick out of the outline by kTickOut
          c.box[p] = boxOf(cuts[p], flipRotate(c.rot[p]));
          c.box[p].lo -= Vec2::Constant(kTickOut);
          c.box[p].hi += Vec2::Constant(kTickOut);
        }
        c.w = c.vertical ? std::max(c.box[0].w(), c.box[1].w()) : c.box[0].w() + m + c.box[1].w();
        c.h = c.vertical ? c.box[0].h() + m + c.box[1].h() : std::max(c.box[0].h(), c.box[1].h());
        choices.push_back(c);
      }
  auto fits = [&](const Choice& c, double W, double H) {
    const Rect r = artRegion(W, H);
    return c.w <= r.w() + 1e-9 && c.h + titleH <= r.h() + 1e-9 && r.w() > 0;
  };
  const Choice* chosen = nullptr;
  bool landscape = false, tiled = false;
  auto pick = [&](double W, double H) -> const Choice* {
    const Choice* best = nullptr;
    for (const Choice& c : choices)
      if (fits(c, W, H) && (!best || c.w * c.h < best->w * best->h - 1e-9)) best = &c;
    return best;
  };
  chosen = pick(pageW, pageH);
  if (!chosen && profile.kind == ProfileKind::Print && !profile.page.empty()) {
    chosen = pick(pageH, pageW);
    landscape = chosen != nullptr;
  }
  const Choice* smallest = &choices[0];
  for (const Choice& c : choices)
    if (std::max(c.w, c.h) < std::max(smallest->w, smallest->h)) smallest = &c;
  double canvasW = landscape ? pageH : pageW, canvasH = landscape ? pageW : pageH;
  if (!chosen && profile.tile) {
    chosen = smallest;
    tiled = true;
    canvasW = chosen->w + 2 * m;
    canvasH = chosen->h + titleH + 2 * m;
  }
  if (!chosen) {
    const Rect r = artRegion(pageW, pageH);
    const double needW = smallest->w + (pageW - r.w()),
                 needH = smallest->h + titleH + (pageH - r.h());
    std::string what = profile.page.empty() ? "sheet" : profile.page + " page's cutting area";
    return Status{ErrorCode::Usage,
                  "the pattern does not fit the " + what + ": it needs at least " +
                      formatMm(needW) + " x " + formatMm(needH) + " mm (" + formatMm(smallest->w) +
                      " x " + formatMm(smallest->h) +
                      " mm of pieces and tabs, plus margins and the title line); the " +
                      (profile.page.empty() ? "sheet" : "page") + " is " + formatMm(pageW) + " x " +
                      formatMm(pageH) + " mm"};
  }
  const Rect region = artRegion(canvasW, canvasH);
  Placement place[2];
  for (int p = 0; p < 2; ++p) {
    place[p].M = flipRotate(chosen->rot[p]);
    Vec2 corner(region.x0, region.y0);
    if (p == 1) {
      corner +=
          chosen->vertical ? Vec2(0, chosen->box[0].h() + m) : Vec2(chosen->box[0].w() + m, 0);
    }
    place[p].t = corner - chosen->box[p].lo;
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
    const std::vector<CreaseFold> folds = creaseFolds(*piece[p]);
    for (size_t k = 0; k < folds.size(); ++k)
      info.creases.push_back({info.name + "-crease-" + std::to_string(k + 1) + "-" +
                                  foldDirectionName(folds[k].direction),
                              folds[k],
                              place[p].map(flatPolyline(piece[p]->flat, piece[p]->creases[k]))});
    info.perimeter = seams[p].L;
    info.rotationDeg = chosen->rot[p];
    out.pieces.push_back(info);
  }
  for (size_t k = 0; k < tickS.size(); ++k) {
    TickInfo t;
    t.id = int(k);
    t.s = tickS[k];
    t.onA = place[0].point(seams[0].at(t.s));
    t.onB = place[1].point(seams[1].at(t.s));
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
  b.drawing().title = o.jobName + " - D-Form pattern (" + profile.name + ")";
  b.drawing().description = "job " + o.jobName + "; profile " + profile.name +
                            "; true scale, 1 user unit = 1 mm; seam length " + perimeterText +
                            " mm; ticks every " + formatMm(o.tickSpacingMm) + " mm" +
                            (o.failedGateMark ? "; FAILED GATE: not for fabrication" : "");
  int skippedLabels = 0, skippedCreaseLabels = 0;
  for (int p = 0; p < 2; ++p) {
    const PieceInfo& info = out.pieces[size_t(p)];
    const std::string& nm = info.name;
    const Seam& seam = seams[p];
    std::vector<Polyline> creaseLines;  // labels keep off them
    for (const CreaseInfo& crease : info.creases) creaseLines.push_back(crease.line);
    // Tick marks across the outline and their numbers inside the piece.
    for (const TickInfo& t : out.ticks) {
      int seg = 0;
      seam.at(t.s, &seg);
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
      bool placed = false;
      for (int attempt = 0; attempt < 3 && !placed; ++attempt) {
        const double depth = in + 1.0 + (t.id == 0 ? 1.5 : 0.0) + halfH + attempt * h;
        const Vec2 center = c - depth * nOut;
        if (!boxFits(info.boundaries, creaseLines, center, d, halfW, halfH, 0.3)) continue;
        b.engrave().paths.push_back(textPath(font, tick.id + "-label", label, center, d, h));
        placed = true;
      }
      if (!placed) ++skippedLabels;
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
      for (const Path& label : labels) {
        const Polyline hull = convexHull(label.parts);
        const Box box = boxOf({hull}, Eigen::Matrix2d::Identity());
        for (const Polyline& other : taken) {
          const Box near = boxOf({other}, Eigen::Matrix2d::Identity());
          const bool apart = near.lo.x() > box.hi.x() || box.lo.x() > near.hi.x() ||
                             near.lo.y() > box.hi.y() || box.lo.y() > near.hi.y();
          if (!apart && overlapArea(hull, other) > 0.0) return true;
        }
      }
      return false;
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
          if (std::any_of(taken.begin(), taken.end(),
                          [&](const Polyline& other) { return overlapArea(box, other) > 0.0; }))
            continue;
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
      fold.dashed = profile.fold == FoldStyle::Dashed;
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
        if (profile.kind == ProfileKind::PrintAndCut) {  // the printed outline the cutter follows
          Path printed = cut;
          printed.id = names[p] + "-outline" + suffix;
          b.engrave().paths.push_back(printed);
        }
      }
    }

  // Title lines (and the calibration bar) at the bottom of the region.
  {
    double y = region.y1 - titleH;
    const double x0 = region.x0, width = region.w();
    auto line = [&](const std::string& id, const std::string& text, double h) {
      const double w = font.width(text, h);
      if (w > width) h *= width / w;
      const Vec2 c(x0 + 0.5 * std::min(w, width), y + 0.5 * lineH * h / textH);
      b.engrave().paths.push_back(textPath(font, id, text, c, {1, 0}, h));
      y += lineH * h / textH;
    };
    if (o.failedGateMark) line("failed-gate", "FAILED GATE - NOT FOR FABRICATION", 2 * textH);
    line("title",
         o.jobName + " - D-Form " + names[0] + " + " + names[1] + " - 1:1, mm - seam " +
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
    if (profile.calibrationBar) {
      const double yb = y + 4.0;
      Path bar;
      bar.id = "calibration-bar";
      bar.parts.push_back({Vec2(x0, yb), Vec2(x0 + 50, yb)});
      for (int k = 0; k <= 5; ++k) {
        const double tickLen = (k == 0 || k == 5) ? 3.0 : 1.5;
        bar.parts.push_back({Vec2(x0 + 10 * k, yb - tickLen), Vec2(x0 + 10 * k, yb)});
      }
      b.engrave().paths.push_back(bar);
      const std::string text = "50 mm - print at 100% (actual size)";
      b.engrave().paths.push_back(textPath(font, "calibration-label", text,
                                           Vec2(x0 + 54 + 0.5 * font.width(text, textH), yb - 1.5),
                                           {1, 0}, textH));
    }
  }

  // Registration marks.
  if (profile.registration == Registration::Silhouette) {
    Path square;
    square.id = "regmark-square";
    square.filled = true;
    square.closed = true;
    const double a = kRegInset, s = kRegSquare;
    square.parts = {{Vec2(a, a), Vec2(a + s, a), Vec2(a + s, a + s), Vec2(a, a + s)}};
    b.regmarks().paths.push_back(square);
    Path tr;
    tr.id = "regmark-top-right";
    tr.parts = {
        {Vec2(canvasW - a - kRegArm, a), Vec2(canvasW - a, a), Vec2(canvasW - a, a + kRegArm)}};
    b.regmarks().paths.push_back(tr);
    Path bl;
    bl.id = "regmark-bottom-left";
    bl.parts = {
        {Vec2(a, canvasH - a - kRegArm), Vec2(a, canvasH - a), Vec2(a + kRegArm, canvasH - a)}};
    b.regmarks().paths.push_back(bl);
  }
  out.drawing = std::move(b.drawing());

  // --- Pages -------------------------------------------------------------------------------------
  if (!tiled) {
    PageView page;
    page.width = canvasW;
    page.height = canvasH;
    page.clipX1 = canvasW;
    page.clipY1 = canvasH;
    out.pages.push_back(page);
  } else {
    // Tiles: each page shows a window of the canvas inside a 10 mm margin, under an 8 mm header;
    // neighbours overlap by tileOverlapMm, with alignment crosses in the middle of each overlap.
    const double pm = 10.0, header = 12.0, ov = profile.tileOverlapMm;
    const double cw = pageW - 2 * pm, ch = pageH - 2 * pm - header;
    const int nx = std::max(1, int(std::ceil((canvasW - ov) / (cw - ov) - 1e-9)));
    const int ny = std::max(1, int(std::ceil((canvasH - ov) / (ch - ov) - 1e-9)));
    std::vector<Vec2> marks;
    for (int i = 1; i < nx; ++i)
      for (int j = 0; j <= 2 * ny; ++j)
        marks.emplace_back(i * (cw - ov) + 0.5 * ov, j * 0.5 * (ch - ov) + 0.5 * ov);
    for (int j = 1; j < ny; ++j)
      for (int i = 0; i <= 2 * nx; ++i)
        marks.emplace_back(i * 0.5 * (cw - ov) + 0.5 * ov, j * (ch - ov) + 0.5 * ov);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        PageView page;
        page.width = pageW;
        page.height = pageH;
        page.clipX0 = pm;
        page.clipY0 = pm + header;
        page.clipX1 = pm + cw;
        page.clipY1 = pm + header + ch;
        const Vec2 windowLo(i * (cw - ov), j * (ch - ov));
        page.origin = windowLo - Vec2(page.clipX0, page.clipY0);
        Layer furniture;
        furniture.name = "Tiling";
        furniture.color = "#000000";
        furniture.widthMm = 0.2;
        Path frame;
        frame.id = "tile-frame";
        frame.closed = true;
        frame.dashed = true;
        frame.parts = {{Vec2(page.clipX0, page.clipY0), Vec2(page.clipX1, page.clipY0),
                        Vec2(page.clipX1, page.clipY1), Vec2(page.clipX0, page.clipY1)}};
        furniture.dashMm = 2.0;
        furniture.paths.push_back(frame);
        int markId = 0;
        for (const Vec2& q : marks) {
          const Vec2 onPage = q - page.origin;
          if (onPage.x() < page.clipX0 || onPage.x() > page.clipX1 || onPage.y() < page.clipY0 ||
              onPage.y() > page.clipY1)
            continue;
          furniture.paths.push_back(cross("align-" + std::to_string(++markId), onPage, 4.0));
        }
        const std::string head = o.jobName + " - tile row " + std::to_string(j + 1) + " col " +
                                 std::to_string(i + 1) + " of " + std::to_string(ny) + " rows x " +
                                 std::to_string(nx) + " cols - overlap " + formatMm(ov, 0) +
                                 " mm, match the crosses - print at 100%";
        const double hh = std::min(3.0, cw / std::max(1.0, font.width(head, 1.0)));
        furniture.paths.push_back(textPath(font, "tile-header", head,
                                           Vec2(pm + 0.5 * font.width(head, hh), pm + 3.0), {1, 0},
                                           hh));
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
  }
  return out;
}

}  // namespace dform::fab
