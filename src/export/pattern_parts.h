// SPDX-License-Identifier: GPL-3.0-or-later
// Internals of the pattern builder, shared by its files (pattern_layout.h lists the layout's),
// seam_marks.cpp (the ticks across the seam) and glue_tabs.cpp (the tabs along it): a piece's
// seam parameterised by arc length, the flat-frame-to-sheet placement, the drawing's layers and
// the label and fold-line helpers they all use. Geometry is in each piece's flat frame (mm, y up)
// until a Placement maps it to the sheet (y down).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "dform/core/constants.h"
#include "dform/core/piece_loops.h"
#include "dform/core/polyline.h"
#include "internal.h"

namespace dform::fab {

constexpr double kTickOut = 1.5;  // tick length outside the outline (mm)

Points2 toPoints(const Polyline& p);
std::string formatMm(double x, int decimals = 1);
std::string twoDigits(int k);

// The rows of `flat` listed by `loop`, as a polyline.
Polyline flatPolyline(const Points2& flat, const std::vector<int>& loop);

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
  // Unit normal of the seam direction t away from the material: out of the piece, or into its
  // hole.
  Vec2 outwardOf(const Vec2& t) const {
    return orient * (hole ? -1 : 1) > 0 ? Vec2(t.y(), -t.x()) : Vec2(-t.y(), t.x());
  }
  Vec2 outward(int i) const { return outwardOf(dir(i)); }
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
double matchingArc(const Seam& from, const Seam& to, double s);

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

// Builds the drawing's layers and routes each operation to its layer for the profile's kind.
class DrawingBuilder {
 public:
  DrawingBuilder(const Profile& p, double w, double h);
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

// A text direction along `t` that does not read upside down on the sheet (y down).
Vec2 readable(Vec2 t);

// Whether a text box centred at c (half-extents along d and its normal) sits inside the piece's
// material (`region`, even-odd) with `clear` mm to spare: its centre inside and its whole outline
// at least `clear` from every loop (the outline, a hole, a joint slot; one inside the box counts
// as 0), and no crease (`lines`) through it or inside it.
bool boxFits(const std::vector<Polyline>& region, const std::vector<Polyline>& lines, const Vec2& c,
             const Vec2& d, double halfW, double halfH, double clear);

Path textPath(const StrokeFont& font, std::string id, const std::string& text, const Vec2& c,
              const Vec2& d, double h);

// Splits an open polyline into dashes `on` mm long separated by `off`, centred so that both
// ends are bridges (the tab stays attached at its ends).
std::vector<Polyline> perforate(const Polyline& line, double on, double off);

// How a printed crease is dashed (on, off, ... in mm), after the origami diagram convention
// (Yoshizawa-Randlett): a valley is dashed, a mountain dash-dot.
std::vector<double> creaseDash(FoldDirection direction, double dash);

// The cutter's score pass along a printed fold line: the whole line, its own id.
Path scorePass(const Path& fold);

// --- Seam marks (seam_marks.cpp) ---------------------------------------------------------------

// The seam parameters (A's arc length, up to L) of the ticks, `spacing` mm apart from the start.
std::vector<double> tickParameters(double L, double spacing, BuildWork& work);

// The ticks at the seam parameters `tickS`, where they cross each piece's outline on the sheet.
std::vector<TickInfo> placeTicks(const std::vector<double>& tickS, const Seam seams[2],
                                 const Placement place[2]);

// How many tick numbers were left out: `skipped` where the piece has no room for one, `thinned`
// where the numbers already placed leave none.
struct TickLabelCounts {
  int skipped = 0, thinned = 0;
};

// Piece p's tick marks across its outline (score layer) and their numbers inside it (engrave
// layer), clear of its creases (`creaseLines`); where the profile's `numbers` asks, a number goes
// on the glue tab of the piece over its tick (`tabs`: the piece's), "A-tick-07-tab-label".
TickLabelCounts drawTicks(int p, const PieceInfo& info, const Seam& seam, const Placement& place,
                          const std::vector<TickInfo>& ticks,
                          const std::vector<Polyline>& creaseLines,
                          const std::vector<const TabInfo*>& tabs, const Profile& profile,
                          const StrokeFont& font, DrawingBuilder& b, BuildWork& work);

// --- Glue tabs (glue_tabs.cpp) ------------------------------------------------------------------

struct FlatTab {
  int piece = 0;
  double s0 = 0, s1 = 0;      // seam parameter (A's arc length) of the fold line's ends
  double own0 = 0, own1 = 0;  // the same along the tab's own piece's seam
  double width = 0;
  Polyline polygon;  // flat frame, fold line first
  Polyline fold;
  Box box;  // of the polygon
};

// The tabs along the seam (A's arc length up to L) on the pieces `side` names, clear of their
// piece's material and of each other; a tab that cannot be made so is left out, with a message.
std::vector<FlatTab> makeTabs(const Seam seams[2], const std::vector<Polyline> material[2],
                              const ExportOptions& o, TabSide side, double L,
                              std::vector<std::string>& messages, BuildWork& work);

// The tabs on the sheet.
std::vector<TabInfo> placeTabs(const std::vector<FlatTab>& tabs, const Placement place[2]);

// The tabs' fold lines in the profile's fold style (or their perforations), with ids
// "<piece>-<kind>fold-NN" and "<piece>-<kind>perf-NN": `kind` "" for glue tabs, "tongue-" for
// slot tongues.
void drawTabFolds(const std::vector<TabInfo>& tabs, const std::string names[2],
                  const std::string& kind, const Profile& profile, DrawingBuilder& b);

// --- Joints (joints.cpp) ------------------------------------------------------------------------

struct FlatHole {
  int piece = 0;
  int index = 0;   // pair (holes) or place along the seam (lace)
  double s = 0;    // seam parameter (A's arc length)
  double own = 0;  // arc length along its own piece's seam
  Vec2 centre;     // flat frame
  double diameter = 0;
};

// A slot in B (flat frame) for the tongue of A with the same index.
struct FlatSlot {
  int index = 0;
  double s = 0;   // seam parameter (A's arc length) of its seam point
  Polyline loop;  // clockwise: a hole in the material
  Vec2 centre;
  double length = 0, width = 0;
};

// The joints of both pieces: holes (holes, lace, and slots where a tongue does not fit), and for
// slots the tongues on A (spliced into A's cut loop as glue tabs are) with slots[k] the slot of
// tongues[k].
struct FlatJoints {
  std::vector<FlatHole> holes;
  std::vector<FlatTab> tongues;
  std::vector<FlatSlot> slots;
};

// The joints of both pieces (flat frame) for `joint` (none for glue): placed along the seam
// clear of its corners, `edgeMm` inside each piece; a joint too close to a corner, another joint
// or an edge is left out (a tongue and slot become a hole pair first), with a message.
FlatJoints makeJoints(const Seam seams[2], const std::vector<Polyline> material[2],
                      const JointSettings& joint, std::vector<std::string>& messages);

// A hole's loop (flat frame, clockwise): a polygon whose edges stay within 5 um of the circle.
Polyline holeLoop(const FlatHole& hole);

}  // namespace dform::fab
