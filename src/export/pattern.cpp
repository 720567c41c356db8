// The flat pattern: ticks and tabs along the seam (seam_marks.cpp, glue_tabs.cpp), cut paths
// (outline with tabs merged, holes, kerf offset), crease fold lines, placement on the sheet (or a
// page per piece, or tiles), single-stroke labels, the title block and the pages. Geometry is
// computed in each piece's flat frame (mm, y up), then mapped to the sheet (y down). A piece's
// seam may be its outer outline or a hole's loop (anti and demi D-Forms): ticks and tabs go along
// the seam only, on the side away from the material.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "export/pattern_parts.h"
#include "export/plane_geometry.h"

namespace dform::fab {

namespace {

// Cricut Print Then Cut: 6.75 x 9.25 in (the long-standing safe maximum on Letter).
constexpr double kCricutW = 6.75 * 25.4, kCricutH = 9.25 * 25.4;
// Silhouette type-1 marks: 10 mm from the edges, 5 mm square, 20 mm L arms, 0.3 mm lines (the
// artwork's clearance from them is the profile's registration_clear_mm).
constexpr double kRegInset = 10.0, kRegSquare = 5.0, kRegArm = 20.0, kRegLine = 0.3;
// Tiles: each page shows a window of the pattern inside a 10 mm margin, under a 12 mm header.
constexpr double kTileMargin = 10.0, kTileHeader = 12.0;
// More pages than this is no print job anyone assembles by hand (500 A4 pages are 31 m^2 of
// paper): such a pattern is refused before it is drawn, as one too large for its sheet is.
constexpr long kMaxTiles = 500;

// The closed polygon turned counter-clockwise (ccw) or clockwise.
Polyline oriented(const Polyline& P, bool ccw) {
  return (signedArea(toPoints(P)) >= 0) == ccw ? P : Polyline(P.rbegin(), P.rend());
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
  bool tiled = false;           // a piece larger than the page, tiled across pages (print)
  long tilesX = 1, tilesY = 1;  // its pages: columns and rows
};

// The id of a page's copy of the sheet furniture (title lines, registration marks): the first
// page keeps the plain id.
std::string onPage(const std::string& id, size_t page) {
  return page == 0 ? id : id + "-page-" + std::to_string(page + 1);
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

Path cross(const std::string& id, const Vec2& c, double r) {
  Path p;
  p.id = id;
  p.parts = {{c - Vec2(r, 0), c + Vec2(r, 0)}, {c - Vec2(0, r), c + Vec2(0, r)}};
  return p;
}

}  // namespace

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

DrawingBuilder::DrawingBuilder(const Profile& p, double w, double h) {
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

Vec2 readable(Vec2 t) {
  t.normalize();
  if (t.x() < -1e-9 || (std::abs(t.x()) <= 1e-9 && t.y() > 0)) t = -t;
  return t;
}

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

Path textPath(const StrokeFont& font, std::string id, const std::string& text, const Vec2& c,
              const Vec2& d, double h) {
  Path p;
  p.id = std::move(id);
  p.parts = font.layout(text, c, d, h);
  return p;
}

std::vector<Polyline> perforate(const Polyline& line, double on, double off) {
  const double len = openLength(toPoints(line));
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

std::vector<double> creaseDash(FoldDirection direction, double dash) {
  if (direction == FoldDirection::Valley) return {dash, dash};
  return {dash, 0.5 * dash, dash / 6.0, 0.5 * dash};
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

namespace {
// The model's two pieces in their flat frames, as every stage of a build reads them.
struct FlatPieces {
  const Piece* piece[2];
  const Seam seams[2];
  const std::string names[2];
  const std::vector<Polyline> material[2];
  bool creased = false;

  explicit FlatPieces(const DForm& model)
      : piece{&model.a, &model.b},
        seams{Seam(model.a), Seam(model.b)},
        names{model.a.name.empty() ? "A" : model.a.name, model.b.name.empty() ? "B" : model.b.name},
        material{materialLoops(model.a), materialLoops(model.b)},
        creased(!model.a.creases.empty() || !model.b.creases.empty()) {}
};

// The sheet or page the pattern is laid out on and what fits on it: the region a sheet's pieces
// and title lines may use, where the title block goes, and the tiles of a piece too large for a
// page.
struct SheetFit {
  const Profile* profile = nullptr;
  bool* tooLargeOut = nullptr;  // set when the pattern fails because a piece does not fit
  double m = 0;                 // the profile's margin (mm)
  double edge = 0;              // drawn outside a piece's cut line
  double textH = 0, lineH = 0;  // the title lines' capital height and line pitch (mm)
  bool tabbed = false;          // the pattern has tabs: a title line says how they fold
  double titleBlock = 0;        // the title block's height with its margin from the pieces
  std::string pageName;         // empty for a material sheet
  std::string sheetWord;        // "sheet" or "page"
  double pageW = 0, pageH = 0;
  bool mayTurnPage = false, mayTile = false;
  double tileW = 0, tileH = 0, overlap = 0;  // a tile's window and the windows' overlap (mm)

  // The area of a W x H sheet or page (its top-left corner at `at`) that the pieces and the title
  // lines may use.
  Box artRegion(double W, double H, const Vec2& at = Vec2::Zero()) const {
    double inset = m;
    if (profile->registration == Registration::Silhouette)  // clear of the square's far edge
      inset = kRegInset + kRegSquare + profile->registrationClearMm;
    Box r = Box::spanning(at + Vec2(inset, inset), at + Vec2(W - inset, H - inset));
    if (profile->registration == Registration::Cricut) {  // the Print Then Cut area, centred
      const Vec2 half(0.5 * std::min(kCricutW, W - 2 * m), 0.5 * std::min(kCricutH, H - 2 * m));
      const Vec2 centre = at + 0.5 * Vec2(W, H);
      r = Box::spanning(centre - half, centre + half);
    }
    return r;
  }
  // Where a sheet's title block goes when the pieces on it take `size` of its region `r`: under
  // them (a margin apart) where the region is tall enough, else in a column to their right, its
  // lines reading upwards; None when neither fits (or the pieces do not).
  TitleAt titleAt(const Vec2& size, const Box& r) const {
    if (!(r.w() > 0 && size.x() <= r.w() + 1e-9 && size.y() <= r.h() + 1e-9)) return TitleAt::None;
    if (size.y() + titleBlock <= r.h() + 1e-9) return TitleAt::Below;
    if (size.x() + titleBlock <= r.w() + 1e-9) return TitleAt::Aside;
    return TitleAt::None;
  }
  // Whether pieces (and tabs) of extent `size` fit a W x H sheet with their title block.
  bool fits(const Vec2& size, double W, double H) const {
    return titleAt(size, artRegion(W, H)) != TitleAt::None;
  }
  bool fitsSomeWay(const Vec2& size) const {
    return fits(size, pageW, pageH) || (mayTurnPage && fits(size, pageH, pageW));
  }
  // `what` (`contents`) fits the sheet in none of the arrangements tried, of extents `sizes`:
  // the message gives the sheet size needed by the arrangement that needs the least enlargement.
  Status tooLarge(const std::string& what, const std::vector<Vec2>& sizes,
                  const std::string& contents) const {
    *tooLargeOut = true;
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
  }
  // Tiling: the columns and rows of pages that show a piece of extent `size` with the margins and
  // its title block; neighbouring windows overlap by tileOverlapMm.
  Vec2 tiledExtent(const Vec2& size) const {
    return Vec2(size.x() + 2 * m, size.y() + titleBlock + 2 * m);
  }
  std::pair<long, long> tileGrid(const Vec2& size) const {
    auto count = [&](double length, double window) {
      return std::max(1L, long(std::ceil((length - overlap) / (window - overlap) - 1e-9)));
    };
    const Vec2 extent = tiledExtent(size);
    return std::pair<long, long>(count(extent.x(), tileW), count(extent.y(), tileH));
  }
  Status tooManyTiles(long tiles) const {
    *tooLargeOut = true;
    return Status{ErrorCode::Usage, "the pattern needs at least " + std::to_string(tiles) + " " +
                                        pageName + " pages when tiled, more than the " +
                                        std::to_string(kMaxTiles) +
                                        " a print profile makes; use a sheet profile"};
  }
};

// The sheet or page for the options and profile, and its title block's height. `tooLargeOut` is
// the build's flag for failing because a piece does not fit.
Result<SheetFit> sheetFit(const ExportOptions& o, const Profile& profile, bool creased,
                          bool& tooLargeOut) {
  SheetFit fit;
  fit.profile = &profile;
  fit.tooLargeOut = &tooLargeOut;
  fit.m = profile.marginMm;
  fit.edge = std::max(kTickOut, profile.bleedMm);
  fit.textH = std::clamp(profile.labelHeightMm, 2.0, 4.0);
  fit.lineH = 1.7 * fit.textH;
  const double barH = profile.calibrationBar ? 9.0 : 0.0;
  // Tabs fold away from the printed (outer) side: a line says so on every sheet that has them.
  fit.tabbed = o.tabWidthMm > 0 && profile.tabs != TabSide::None;
  // The lines: title and note, a legend line for creases, the tab line (none with --no-title).
  const int titleLines = o.title ? 2 + int(creased) + int(fit.tabbed) : 0;
  const double titleH = titleLines * fit.lineH + barH;
  fit.titleBlock = titleH > 0 ? fit.m + titleH : 0.0;
  // The page: --page over the profile's. A page profile refuses a sheet size and a sheet profile
  // a page, rather than ignore them.
  fit.pageName = o.page.empty() ? profile.page : o.page;
  if (!o.page.empty() && profile.page.empty())
    return Status{ErrorCode::Usage, "--page is for page profiles (print, print-and-cut); profile " +
                                        profile.name +
                                        " cuts a material sheet: give its size with --sheet WxHmm"};
  if (!profile.page.empty() && o.sheetGiven)
    return Status{ErrorCode::Usage,
                  "profile " + profile.name + " prints on " + fit.pageName +
                      " pages, so --sheet does not apply; choose the paper with --page "
                      "A4|Letter|A3|Tabloid|WxHmm"};
  fit.pageW = o.sheetWidthMm;
  fit.pageH = o.sheetHeightMm;
  if (!fit.pageName.empty()) {
    const auto size = pageSizeMm(fit.pageName);
    if (!size)
      return Status{ErrorCode::Usage, "unknown page \"" + fit.pageName +
                                          "\": use A4, Letter, A3, Tabloid or a size such as "
                                          "200x300mm"};
    fit.pageW = size->first;
    fit.pageH = size->second;
  }
  fit.sheetWord = fit.pageName.empty() ? "sheet" : "page";
  // Only a print profile's page may turn to landscape or tile; a print-and-cut page keeps its
  // marks (the cutter reads one page's), and a laser sheet is the size it is.
  fit.mayTurnPage = profile.kind == ProfileKind::Print && !fit.pageName.empty();
  fit.mayTile = profile.kind == ProfileKind::Print && profile.tile;
  fit.tileW = fit.pageW - 2 * kTileMargin;
  fit.tileH = fit.pageH - 2 * kTileMargin - kTileHeader;
  fit.overlap = profile.tileOverlapMm;
  return fit;
}

// Fit first, before any tick or tab is made. A piece's cut path contains its outer outline (tabs
// and kerf only add to it), so at every turn the layout may choose (2-degree steps; a half turn
// gives the same box) the outline's extent bounds the cut path's from below. Each piece may get a
// sheet (or page) of its own, so the pattern fits when each bare outline fits one alone, or, on a
// tiling profile, when its tiles are not too many. When that fails, say so now, at a cost
// independent of the seam's length in ticks and tabs.
Status checkOutlinesFit(const SheetFit& fit, const FlatPieces& flat) {
  long fewestTiles = 0;
  for (int p = 0; p < 2; ++p) {
    std::vector<Vec2> sizes;
    for (int deg = 0; deg < 180; deg += kTurnStepDeg) {
      const Box b = extentAt({flat.material[p].front()}, deg, fit.edge);
      sizes.emplace_back(b.w(), b.h());
    }
    if (std::any_of(sizes.begin(), sizes.end(),
                    [&](const Vec2& size) { return fit.fitsSomeWay(size); }))
      continue;
    if (!fit.mayTile) return fit.tooLarge("piece " + flat.names[p], sizes, "the piece");
    long fewest = std::numeric_limits<long>::max();
    for (const Vec2& size : sizes) {
      const auto [nx, ny] = fit.tileGrid(size);
      fewest = std::min(fewest, nx * ny);
    }
    fewestTiles += fewest;
  }
  if (fewestTiles > kMaxTiles) return fit.tooManyTiles(fewestTiles);
  return Status::ok();
}

// Piece p's closed cut paths (flat frame): its seam and free boundaries with its tabs merged in.
CutPaths pieceCutPaths(const FlatPieces& flat, int p, const std::vector<FlatTab>& tabs,
                       double kerf) {
  const Piece& piece = *flat.piece[p];
  std::vector<Polyline> freeLoops;
  for (const auto& loop : piece.freeBoundaries) freeLoops.push_back(flatPolyline(piece.flat, loop));
  return cutPaths(flat.seams[p], freeLoops, outerLoopIndex(piece), tabs, p, kerf);
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

// Where each piece goes: its turn, its extent, the top-left corner of that extent, and the
// sheets (pages) they are on.
struct Arrangement {
  double rot[2] = {0, 0};
  Box box[2];
  Vec2 corner[2];
  std::vector<SheetPlan> plans;
};

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
// turns that fits (a print page turned where only that fits), else (print) tiled across pages.
Status arrangeAlone(const SheetFit& fit, const std::vector<Choice>& choices, int p, double x,
                    const std::string& name, Arrangement& a) {
  SheetPlan plan;
  plan.pieces = {p};
  const Choice* best = nullptr;  // the rotations tried for this piece: its two in `choices`
  bool turned = false;
  for (bool turn : {false, true}) {
    if (best || (turn && !fit.mayTurnPage)) continue;
    const double W = turn ? fit.pageH : fit.pageW, H = turn ? fit.pageW : fit.pageH;
    for (const Choice& c : choices)
      if (fit.fits(Vec2(c.box[p].w(), c.box[p].h()), W, H) &&
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
    return fit.tooLarge("piece " + name, sizes, "the piece and its tabs");
  }
  plan.size = Vec2(a.box[p].w(), a.box[p].h());
  const Box region = fit.artRegion(plan.box.w(), plan.box.h(), plan.box.lo);
  plan.title = fit.titleAt(plan.size, region);
  a.corner[p] = region.lo;
  a.plans.push_back(plan);
  return Status::ok();
}

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

// The scale as a percentage of true size ("80%").
std::string percentText(double scale) {
  char percent[32];
  std::snprintf(percent, sizeof percent, "%.0f%%", 100 * scale);
  return percent;
}

// The piece's name at the roomiest point inside it, clear of the creases; and of the labels
// already placed (`taken`) where the roomiest point is near them (a ring-shaped piece). The label
// placed joins `taken`.
void drawPieceName(const PieceInfo& info, const std::vector<Polyline>& creaseLines,
                   const Profile& profile, const StrokeFont& font, DrawingBuilder& b,
                   std::vector<Polyline>& taken) {
  const std::string& nm = info.name;
  auto nameLabels = [&](const std::vector<Polyline>& avoid) {
    const auto [centre, room] = roomiestPoint(info.boundaries, creaseLines, avoid);
    std::vector<Path> labels;
    const double nameH = std::min(3 * profile.labelHeightMm, 0.9 * room);
    if (nameH >= 1.0) labels.push_back(textPath(font, nm + "-name", nm, centre, {1, 0}, nameH));
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
}

// A small M or V beside each of the piece's creases, where one fits clear of its other labels
// (`taken`, which the letters placed join). Returns how many were left out.
int drawCreaseLetters(const PieceInfo& info, const std::vector<Polyline>& creaseLines,
                      const Profile& profile, const StrokeFont& font, DrawingBuilder& b,
                      std::vector<Polyline>& taken) {
  int skipped = 0;
  for (const CreaseInfo& crease : info.creases) {
    const std::string letter = crease.fold.direction == FoldDirection::Mountain ? "M" : "V";
    const double h = profile.labelHeightMm, halfW = 0.5 * font.width(letter, h), halfH = 0.5 * h;
    const double length = openLength(toPoints(crease.line));
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
    skipped += !placed;
  }
  return skipped;
}

// Each piece's ticks and tick numbers, name and crease letters, and messages for the labels left
// out.
void drawPieceLabels(const FlatPieces& flat, const Placement place[2], const Profile& profile,
                     const StrokeFont& font, DrawingBuilder& b, PatternBuild& out,
                     BuildWork& work) {
  int skippedLabels = 0, thinnedLabels = 0, skippedCreaseLabels = 0;
  for (int p = 0; p < 2; ++p) {
    const PieceInfo& info = out.pieces[size_t(p)];
    std::vector<Polyline> creaseLines;  // labels keep off them
    for (const CreaseInfo& crease : info.creases) creaseLines.push_back(crease.line);
    const TickLabelCounts ticks =
        drawTicks(p, info, flat.seams[p], place[p], out.ticks, creaseLines, profile, font, b, work);
    skippedLabels += ticks.skipped;
    thinnedLabels += ticks.thinned;
    std::vector<Polyline> taken;  // footprints of the piece's labels so far
    for (const Path& path : b.engrave().paths)
      if (path.id.rfind(info.name + "-", 0) == 0) taken.push_back(convexHull(path.parts));
    drawPieceName(info, creaseLines, profile, font, b, taken);
    skippedCreaseLabels += drawCreaseLetters(info, creaseLines, profile, font, b, taken);
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
}

// Crease fold lines: the profile's fold style, dashed by the fold's direction.
void drawCreases(const std::vector<PieceInfo>& pieces, const Profile& profile, DrawingBuilder& b) {
  for (const PieceInfo& info : pieces)
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
}

// The cut paths, every hole before any outer cut (inner cuts first); then the printed tint.
void drawCuts(const std::vector<PieceInfo>& pieces, const std::string names[2],
              const Profile& profile, DrawingBuilder& b) {
  for (bool holes : {true, false})
    for (int p = 0; p < 2; ++p) {
      const auto& cutList = holes ? pieces[size_t(p)].holeCuts : pieces[size_t(p)].cut;
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
      fill.parts = pieces[p].bleed;
      fill.closed = fill.filled = true;
      fill.fill = p == 0 ? profile.fillColorA : profile.fillColorB;
      tint->paths.push_back(fill);
    }
}

// A sheet's title block: its lines run along `along` from `start`, each the next one across,
// in `length` mm; `v` is how far across the lines so far reach.
struct TitleBlock {
  Vec2 along, across, start;
  double length = 0;
  double v = 0;
};

// Where a sheet's title lines go: under its pieces or in a column beside them.
TitleBlock titleBlockOf(const SheetPlan& plan, const SheetFit& fit) {
  const Box region = fit.artRegion(plan.box.w(), plan.box.h(), plan.box.lo);
  const bool aside = plan.title == TitleAt::Aside;
  TitleBlock block;
  block.along = aside ? Vec2(0, -1) : Vec2(1, 0);
  block.across = aside ? Vec2(1, 0) : Vec2(0, 1);
  block.start = aside ? Vec2(region.lo.x() + plan.size.x() + fit.m, region.hi.y())
                      : Vec2(region.lo.x(), region.lo.y() + plan.size.y() + fit.m);
  block.length = aside ? region.h() : region.w();
  return block;
}

// The title lines of sheet k (of `sheets`), unless --no-title: the title, the note and the
// legends for creases and tabs.
void drawTitleLines(size_t k, size_t sheets, const SheetPlan& plan, const SheetFit& fit,
                    const FlatPieces& flat, const ExportOptions& o, const std::string& scaleText,
                    const std::string& perimeterText, const StrokeFont& font, DrawingBuilder& b,
                    TitleBlock& block) {
  const Profile& profile = *fit.profile;
  const double textH = fit.textH, lineH = fit.lineH;
  auto line = [&](const std::string& id, const std::string& text, double h) {
    const double w = font.width(text, h);
    if (w > block.length) h *= block.length / w;
    const Vec2 c = block.start + 0.5 * std::min(w, block.length) * block.along +
                   (block.v + 0.5 * lineH * h / textH) * block.across;
    b.title().paths.push_back(textPath(font, onPage(id, k), text, c, block.along, h));
    block.v += lineH * h / textH;
  };
  std::string pieceNote;
  if (sheets > 1)
    pieceNote = " - " + fit.sheetWord + " " + std::to_string(k + 1) + " of " +
                std::to_string(sheets) + ": piece " + flat.names[plan.pieces.front()];
  if (!o.title) return;
  line("title",
       o.jobName + " - D-Form " + flat.names[0] + " + " + flat.names[1] + pieceNote + " - " +
           scaleText + " - seam " + perimeterText + " mm - " + profile.name,
       textH);
  line("note",
       "tick 0 = start, arrow = zip direction; ticks every " + formatMm(o.tickSpacingMm, 0) +
           " mm; glue equal numbers together",
       textH);
  const char* creaseLegend =
      profile.fold == FoldStyle::Dashed
          ? "creases seen from this side (the outside): M = mountain (dash-dot), V = valley "
            "(dashed)"
          : "creases seen from this side (the outside): M = mountain, V = valley";
  const char* tabNote =
      profile.kind == ProfileKind::Laser
          ? "engraved side out: fold the tabs back, away from the engraving, and glue them inside"
          : "printed side out: fold the tabs back, away from the print (mountain folds, "
            "dash-dot), and glue them inside";
  if (flat.creased) line("crease-legend-label", creaseLegend, textH);
  if (fit.tabbed) line("tab-note", tabNote, textH);
}

// The 50 mm calibration bar of sheet k, after its title lines.
void drawCalibrationBar(size_t k, const TitleBlock& block, double textH, const StrokeFont& font,
                        DrawingBuilder& b) {
  auto at = [&](double u, double w) -> Vec2 {
    return block.start + u * block.along + w * block.across;
  };
  const double vb = block.v + 4.0;
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
  const double h = std::min(textH, (block.length - 54) / std::max(1.0, font.width(text, 1.0)));
  b.title().paths.push_back(textPath(font, onPage("calibration-label", k), text,
                                     at(54 + 0.5 * font.width(text, h), vb - 1.5), block.along, h));
}

// Silhouette type-1 registration marks in the corners of sheet k.
void drawRegistrationMarks(size_t k, const Box& sheet, Layer& regmarks) {
  const double a = kRegInset, s = kRegSquare;
  const Vec2 lo = sheet.lo + Vec2(a, a), hi = sheet.hi - Vec2(a, a);
  Path square;
  square.id = onPage("regmark-square", k);
  square.filled = true;
  square.closed = true;
  square.parts = {{lo, lo + Vec2(s, 0), lo + Vec2(s, s), lo + Vec2(0, s)}};
  regmarks.paths.push_back(square);
  Path tr;
  tr.id = onPage("regmark-top-right", k);
  tr.parts = {
      {Vec2(hi.x() - kRegArm, lo.y()), Vec2(hi.x(), lo.y()), Vec2(hi.x(), lo.y() + kRegArm)}};
  regmarks.paths.push_back(tr);
  Path bl;
  bl.id = onPage("regmark-bottom-left", k);
  bl.parts = {
      {Vec2(lo.x(), hi.y() - kRegArm), Vec2(lo.x(), hi.y()), Vec2(lo.x() + kRegArm, hi.y())}};
  regmarks.paths.push_back(bl);
}

// Title lines (and the calibration bar) under each sheet's pieces or in a column beside them,
// and the registration marks in each sheet's corners.
void drawSheetFurniture(const std::vector<SheetPlan>& plans, const SheetFit& fit,
                        const FlatPieces& flat, const ExportOptions& o,
                        const std::string& scaleText, const std::string& perimeterText,
                        const StrokeFont& font, DrawingBuilder& b) {
  for (size_t k = 0; k < plans.size(); ++k) {
    TitleBlock block = titleBlockOf(plans[k], fit);
    drawTitleLines(k, plans.size(), plans[k], fit, flat, o, scaleText, perimeterText, font, b,
                   block);
    if (fit.profile->calibrationBar) drawCalibrationBar(k, block, fit.textH, font, b);
    if (fit.profile->registration == Registration::Silhouette)
      drawRegistrationMarks(k, plans[k].box, *b.regmarks());
  }
}

// The page of an untiled sheet: the whole sheet.
PageView sheetPage(const SheetPlan& plan) {
  PageView page;
  page.width = plan.box.w();
  page.height = plan.box.h();
  page.origin = plan.box.lo;
  page.clipX1 = plan.box.w();
  page.clipY1 = plan.box.h();
  return page;
}

// The layer of a tiled piece's page furniture: frames, crosses, headers.
Layer tilingLayer() {
  Layer l;
  l.name = "Tiling";
  l.color = "#000000";
  l.widthMm = 0.2;
  l.dashMm = 2.0;
  return l;
}

// A tile as its page's header and the page map name it: the piece, its row and column.
std::string tileName(const std::string& piece, long row, long col) {
  return piece + " " + std::to_string(row + 1) + "-" + std::to_string(col + 1);
}

// A page of a tiled piece, before its window and furniture are set.
PageView blankPage(const SheetFit& fit) {
  PageView page;
  page.width = fit.pageW;
  page.height = fit.pageH;
  return page;
}

// A page header at the top left of a tiled piece's page, no wider than a tile.
void addHeader(Layer& furniture, const std::string& id, const std::string& head,
               const SheetFit& fit, const StrokeFont& font) {
  const double pm = kTileMargin, cw = fit.tileW;
  const double hh = std::min(3.0, cw / std::max(1.0, font.width(head, 1.0)));
  furniture.paths.push_back(
      textPath(font, id, head, Vec2(pm + 0.5 * font.width(head, hh), pm + 3.0), {1, 0}, hh));
}

// The page map of a tiled piece: its cut outline scaled onto one page under the grid of its
// tiles, each named as its page's header names it (its tiles are pages firstTilePage on).
PageView pageMap(const SheetPlan& plan, const PieceInfo& info, const SheetFit& fit,
                 size_t firstTilePage, const ExportOptions& o, const StrokeFont& font) {
  const std::string& nm = info.name;
  const double pm = kTileMargin, header = kTileHeader, ov = fit.overlap, cw = fit.tileW,
               ch = fit.tileH;
  const long nx = plan.tilesX, ny = plan.tilesY;
  PageView map = blankPage(fit);
  Layer furniture = tilingLayer();
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
      const std::string text =
          tileName(nm, j, i) + " (p. " + std::to_string(firstTilePage + size_t(j * nx + i)) + ")";
      const double th = std::min(4.0, 0.8 * (c.x() - a.x()) / std::max(1.0, font.width(text, 1.0)));
      furniture.paths.push_back(textPath(font, cell.id + "-name", text,
                                         Vec2(a.x() + 0.5 * (c.x() - a.x()), a.y() + th + 2.0),
                                         {1, 0}, th));
    }
  addHeader(furniture, "page-map-header",
            o.jobName + " - piece " + nm + ": page map, " + std::to_string(nx * ny) + " tiles (" +
                std::to_string(ny) + " rows x " + std::to_string(nx) +
                " cols) - not to scale - print the tiles at 100%",
            fit, font);
  map.overlay.push_back(furniture);
  return map;
}

// The alignment crosses of a tiled sheet (canvas mm): in the middle of each overlap.
std::vector<Vec2> alignmentMarks(const SheetPlan& plan, const SheetFit& fit) {
  const double ov = fit.overlap, cw = fit.tileW, ch = fit.tileH;
  const long nx = plan.tilesX, ny = plan.tilesY;
  std::vector<Vec2> marks;
  for (long i = 1; i < nx; ++i)
    for (long j = 0; j <= 2 * ny; ++j)
      marks.push_back(plan.box.lo + Vec2(double(i) * (cw - ov) + 0.5 * ov,
                                         double(j) * 0.5 * (ch - ov) + 0.5 * ov));
  for (long j = 1; j < ny; ++j)
    for (long i = 0; i <= 2 * nx; ++i)
      marks.push_back(plan.box.lo + Vec2(double(i) * 0.5 * (cw - ov) + 0.5 * ov,
                                         double(j) * (ch - ov) + 0.5 * ov));
  return marks;
}

// The tile in row j, column i of a tiled piece's sheet: its window of the sheet, framed, with the
// alignment crosses in it, a header and a calibration bar.
PageView tilePage(const SheetPlan& plan, const std::string& nm, long j, long i,
                  const std::vector<Vec2>& marks, const SheetFit& fit, const ExportOptions& o,
                  const StrokeFont& font) {
  const double pm = kTileMargin, header = kTileHeader, ov = fit.overlap, cw = fit.tileW,
               ch = fit.tileH;
  const long nx = plan.tilesX, ny = plan.tilesY;
  PageView page = blankPage(fit);
  page.clipX0 = pm;
  page.clipY0 = pm + header;
  page.clipX1 = pm + cw;
  page.clipY1 = pm + header + ch;
  const Vec2 windowLo = plan.box.lo + Vec2(double(i) * (cw - ov), double(j) * (ch - ov));
  page.origin = windowLo - Vec2(page.clipX0, page.clipY0);
  Layer furniture = tilingLayer();
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
  addHeader(furniture, "tile-header",
            o.jobName + " - piece " + nm + ", tile " + tileName(nm, j, i) + " (row " +
                std::to_string(j + 1) + " of " + std::to_string(ny) + ", col " +
                std::to_string(i + 1) + " of " + std::to_string(nx) + ") - overlap " +
                formatMm(ov, 0) + " mm, match the crosses - print at 100%",
            fit, font);
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
  page.overlay.push_back(furniture);
  return page;
}

// The pages: one per sheet; a tiled piece gets a page map, then its tiles.
void addPages(const std::vector<SheetPlan>& plans, const SheetFit& fit, const ExportOptions& o,
              const StrokeFont& font, PatternBuild& out) {
  for (const SheetPlan& plan : plans) {
    if (!plan.tiled) {
      out.pages.push_back(sheetPage(plan));
      continue;
    }
    const PieceInfo& info = out.pieces[size_t(plan.pieces.front())];
    const size_t firstTilePage = out.pages.size() + 2;  // 1-based, after the map
    out.pages.push_back(pageMap(plan, info, fit, firstTilePage, o, font));
    const std::vector<Vec2> marks = alignmentMarks(plan, fit);
    for (long j = 0; j < plan.tilesY; ++j)
      for (long i = 0; i < plan.tilesX; ++i)
        out.pages.push_back(tilePage(plan, info.name, j, i, marks, fit, o, font));
    out.messages.push_back("piece " + info.name + " is larger than a " + fit.pageName +
                           " page: it is tiled across " +
                           std::to_string(plan.tilesX * plan.tilesY) +
                           " pages of pattern.pdf after a page map; print at 100% and match the "
                           "crosses");
  }
}

// The drawing's title and description (SVG <title> and <desc>, PDF title).
void describe(Drawing& drawing, const ExportOptions& o, const Profile& profile, double scale,
              const std::string& perimeterText) {
  drawing.title = o.jobName + " - D-Form pattern (" + profile.name + ")";
  drawing.description = "job " + o.jobName + "; profile " + profile.name + "; " +
                        (scale == 1.0 ? std::string("true scale") : "scale " + percentText(scale)) +
                        ", 1 user unit = 1 mm; seam length " + perimeterText + " mm; ticks every " +
                        formatMm(o.tickSpacingMm) + " mm";
}

// The pattern of `model` drawn at `scale` (its flat pieces already scaled by it). `tooLargeOut`
// is set when it fails because a piece does not fit its sheet or page.
Result<PatternBuild> buildAtScale(const DForm& model, const ExportOptions& o,
                                  const Profile& profile, const StrokeFont& font, double scale,
                                  BuildWork& work, bool& tooLargeOut) {
  PatternBuild out;
  out.scale = scale;
  out.profile = profile;
  out.tickSpacing = o.tickSpacingMm;
  const FlatPieces flat(model);
  Result<SheetFit> fitResult = sheetFit(o, profile, flat.creased, tooLargeOut);
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
  std::vector<Polyline> cuts[2], holeCuts[2];
  for (int p = 0; p < 2; ++p) {
    CutPaths c = pieceCutPaths(flat, p, tabs, profile.kerfMm);
    cuts[p] = std::move(c.outer);
    holeCuts[p] = std::move(c.holes);
  }
  Result<Arrangement> arranged = arrange(fit, cuts, flat.names, out.messages);
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
  }
  out.ticks = placeTicks(tickS, seams, place);
  out.tabs = placeTabs(tabs, place);

  DrawingBuilder b(profile, canvasW, canvasH);
  const std::string perimeterText = formatMm(seams[0].L, 1);
  const std::string scaleText =
      scale == 1.0 ? std::string("1:1, mm") : "scale " + percentText(scale) + " of true size, mm";
  describe(b.drawing(), o, profile, scale, perimeterText);
  drawPieceLabels(flat, place, profile, font, b, out, work);
  drawCreases(out.pieces, profile, b);
  drawTabFolds(out.tabs, flat.names, profile, b);
  drawCuts(out.pieces, flat.names, profile, b);
  drawSheetFurniture(a.plans, fit, flat, o, scaleText, perimeterText, font, b);
  out.drawing = std::move(b.drawing());
  addPages(a.plans, fit, o, font, out);
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
  Result<PatternBuild> built = buildAtScale(o.scale == 1.0 ? model : scaledFlat(model, o.scale), o,
                                            profile, font, o.scale, work, tooLarge);
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
    Result<PatternBuild> attempt =
        buildAtScale(scaledFlat(model, mid / 100.0), o, profile, font, mid / 100.0, work, tooLarge);
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
  best.value().messages.push_back("scaled to " + std::to_string(fitsAt) + "% to fit: at " +
                                  std::to_string(int(std::lround(100 * o.scale))) + "% " +
                                  atFull.message());
  return withAssembly(std::move(best));
}

}  // namespace dform::fab
