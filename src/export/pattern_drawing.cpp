// SPDX-License-Identifier: GPL-3.0-or-later
// Drawing the laid-out pattern: the drawing's layers per profile kind, the label helpers (text,
// readable directions, boxes clear of the material's edges and creases), perforated and dashed fold
// lines, each piece's ticks, name and crease letters, the creases, and the cut paths with their
// printed tint.
#include <algorithm>
#include <cmath>

#include "pattern_layout.h"
#include "plane_geometry.h"

namespace dform::fab {

namespace {

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

}  // namespace

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
  drawing_.layers[size_t(cut_)].spot = p.cutSpotColor;
}

Path scorePass(const Path& fold) {
  Path pass = fold;
  pass.id += "-score";
  return pass;
}

Vec2 readable(Vec2 t) {
  t.normalize();
  if (t.x() < -1e-9 || (std::abs(t.x()) <= 1e-9 && t.y() > 0)) t = -t;
  return t;
}

namespace {

// The distance from segment [a, b] to the convex quadrilateral `box` (its inside included): 0
// where they meet.
double segmentToBox(const Vec2& a, const Vec2& b, const Polyline& box) {
  if (insidePolygon(box, a) || insidePolygon(box, b)) return 0;
  double best = 1e300;
  for (size_t k = 0; k < box.size(); ++k) {
    const Vec2& p = box[k];
    const Vec2& q = box[(k + 1) % box.size()];
    if (segmentsIntersect(a, b, p, q)) return 0;
    best = std::min(
        {best, distanceToSegment(a, p, q), distanceToSegment(b, p, q), distanceToSegment(p, a, b)});
  }
  return best;
}

// Whether every segment of `line` (closed or open) lies at least `clear` from the box (`near`
// bounds the points that could be nearer).
bool clearOf(const Polyline& line, bool closed, const Polyline& box, const Box& near,
             double clear) {
  const size_t n = line.size(), segments = closed ? n : n - 1;
  for (size_t i = 0; n > 1 && i < segments; ++i) {
    const Vec2& a = line[i];
    const Vec2& b = line[(i + 1) % n];
    if (std::max(a.x(), b.x()) < near.lo.x() || std::min(a.x(), b.x()) > near.hi.x() ||
        std::max(a.y(), b.y()) < near.lo.y() || std::min(a.y(), b.y()) > near.hi.y())
      continue;
    const double d = segmentToBox(a, b, box);
    if (clear > 0 ? d < clear : d <= 0) return false;
  }
  return true;
}

}  // namespace

bool boxFits(const std::vector<Polyline>& region, const std::vector<Polyline>& lines, const Vec2& c,
             const Vec2& d, double halfW, double halfH, double clear) {
  // Its centre in the material and its whole outline `clear` from every loop (the outline, a
  // hole, a joint slot): then all of it is material, with that much to spare. No crease through
  // it or inside it.
  if (!insideRegion(region, c)) return false;
  const Vec2 n(-d.y(), d.x());
  const Polyline box = {c - halfW * d - halfH * n, c + halfW * d - halfH * n,
                        c + halfW * d + halfH * n, c - halfW * d + halfH * n};
  Box near = boxOf({box});
  near.lo -= Vec2::Constant(clear);
  near.hi += Vec2::Constant(clear);
  for (const Polyline& loop : region)
    if (!clearOf(loop, true, box, near, clear)) return false;
  for (const Polyline& line : lines)
    if (!clearOf(line, false, box, near, 0)) return false;
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

namespace {

// The piece's name at the roomiest point inside it, clear of the creases; and of the labels
// already placed (`taken`) where the roomiest point is near them (a ring-shaped piece). The label
// placed joins `taken`.
void drawPieceName(const PieceInfo& info, const std::vector<Polyline>& creaseLines,
                   const Profile& profile, const StrokeFont& font, DrawingBuilder& b,
                   std::vector<Polyline>& taken, bool fitNames) {
  const std::string& nm = info.name;
  auto nameLabels = [&](const std::vector<Polyline>& avoid) {
    const auto [centre, room] = roomiestPoint(info.boundaries, creaseLines, avoid);
    std::vector<Path> labels;
    double nameH = std::min(3 * profile.labelHeightMm, 0.9 * room);
    if (fitNames) {  // the name's box within the free disc of radius `room` about the centre
      const double aspect = font.width(nm, 1.0);
      nameH = std::min(nameH, 0.9 * 2 * room / std::sqrt(aspect * aspect + 1));
    }
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

}  // namespace

// Each piece's ticks and tick numbers, name and crease letters, and messages for the labels left
// out.
void drawPieceLabels(const FlatPieces& flat, const Placement place[2], const Profile& profile,
                     const StrokeFont& font, DrawingBuilder& b, PatternBuild& out, BuildWork& work,
                     bool fitNames) {
  int skippedLabels = 0, thinnedLabels = 0, skippedCreaseLabels = 0;
  for (int p = 0; p < 2; ++p) {
    const PieceInfo& info = out.pieces[size_t(p)];
    std::vector<Polyline> creaseLines;  // labels keep off them
    for (const CreaseInfo& crease : info.creases) creaseLines.push_back(crease.line);
    std::vector<const TabInfo*> tabs;  // the piece's, for numbers on them
    for (const TabInfo& tab : out.tabs)
      if (tab.piece == p) tabs.push_back(&tab);
    const TickLabelCounts ticks = drawTicks(p, info, flat.seams[p], place[p], out.ticks,
                                            creaseLines, tabs, profile, font, b, work);
    skippedLabels += ticks.skipped;
    thinnedLabels += ticks.thinned;
    std::vector<Polyline> taken;  // footprints of the piece's labels so far
    for (const Path& path : b.engrave().paths)
      if (path.id.rfind(info.name + "-", 0) == 0) taken.push_back(convexHull(path.parts));
    drawPieceName(info, creaseLines, profile, font, b, taken, fitNames);
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

std::vector<ScoredFoldInfo> scoredFolds(const ExportOptions& o, int p, const Placement& place,
                                        double scale, const PieceInfo& info) {
  std::vector<ScoredFoldInfo> out;
  if (!o.scoreFoldsDeg) return out;
  for (const FoldToScore& fold : o.folds) {
    if (fold.piece != p || fold.crease || !(fold.angleDeg >= *o.scoreFoldsDeg)) continue;
    std::vector<Polyline> lines =
        clipToRegion(place.map(Polyline{scale * fold.from, scale * fold.to}), info.boundaries);
    if (lines.empty()) continue;
    out.push_back({info.name + "-body-fold-" + std::to_string(out.size() + 1), fold.angleDeg,
                   std::move(lines)});
  }
  return out;
}

void drawScoredFolds(const std::vector<PieceInfo>& pieces, DrawingBuilder& b) {
  for (const PieceInfo& info : pieces)
    for (const ScoredFoldInfo& fold : info.scoredFolds) {
      Path line;
      line.id = fold.id;
      line.parts = fold.lines;
      if (Layer* cutter = b.cutterScore()) cutter->paths.push_back(scorePass(line));
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

}  // namespace dform::fab
