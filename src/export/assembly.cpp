// SPDX-License-Identifier: GPL-3.0-or-later
// The assembly page: how the two cut pieces become the D-Form. A person gluing paper wants to see
// the shape they are making with the tick numbers where they end up, where to start and which
// way to zip on each piece, and a few numbered steps; the page is drawn once, as a Drawing, and
// goes into pattern.pdf (last page), assembly.svg and report.html alike.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "dform/core/constants.h"
#include "dform/core/shape_projection.h"
#include "internal.h"
#include "plane_geometry.h"

namespace dform::fab {

namespace {

constexpr double kMargin = 15.0;    // page margin (mm)
constexpr double kTextH = 3.2;      // cap height of the steps (mm)
constexpr double kLineH = 1.7;      // line pitch, in cap heights
constexpr double kShadeSteps = 16;  // shades per piece: runs of one colour merge into one path
// The 3D picture's candidate views: the report's first (30, 25) first, then azimuths 120 degrees
// apart at 25 and 60 degrees above and below the shape (each costs a painter's sort of the faces).
constexpr double kViewAzimuth = 30;
constexpr double kViewElevations[] = {25, 60, -25, -60};
// Seam points the view choice tests for sight, at most (every k-th of a longer seam).
constexpr size_t kViewSeamSamples = 48;

std::string hex(const Eigen::Vector3d& rgb) {
  char text[8];
  auto c = [](double v) { return int(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); };
  std::snprintf(text, sizeof text, "#%02X%02X%02X", c(rgb.x()), c(rgb.y()), c(rgb.z()));
  return text;
}

Layer makeLayer(std::string name, std::string color, double width) {
  Layer l;
  l.name = std::move(name);
  l.color = std::move(color);
  l.widthMm = width;
  return l;
}

// A small filled disc (mm), as a polygon.
Polyline disc(const Vec2& c, double r) {
  Polyline p;
  for (int k = 0; k < 16; ++k) {
    const double a = 2 * kPi * k / 16;
    p.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
  }
  return p;
}

// `text` broken into lines no wider than `width` at cap height `h`, at spaces.
std::vector<std::string> wrapped(const StrokeFont& font, const std::string& text, double width,
                                 double h) {
  std::vector<std::string> lines;
  std::string line, word;
  auto flush = [&]() {
    if (word.empty()) return;
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && font.width(longer, h) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
    word.clear();
  };
  for (char c : text) {
    if (c == ' ') {
      flush();
    } else {
      word += c;
    }
  }
  flush();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

// Maps a box of points onto a page box, uniformly scaled and centred; `flipY` for the screen's
// y-up frame.
struct Fit {
  double scale = 1;
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  bool flipY = false;
  Fit(const Box& content, const Box& area, bool flip) : flipY(flip) {
    scale =
        std::min(area.w() / std::max(content.w(), 1e-9), area.h() / std::max(content.h(), 1e-9));
    from = 0.5 * (content.lo + content.hi);
    to = 0.5 * (area.lo + area.hi);
  }
  Vec2 operator()(const Vec2& p) const {
    const Vec2 d = scale * (p - from);
    return to + Vec2(d.x(), flipY ? -d.y() : d.y());
  }
  Polyline operator()(const Polyline& line) const {
    Polyline out;
    for (const Vec2& p : line) out.push_back((*this)(p));
    return out;
  }
};

// The index of the seam edge and the fraction along it at arc length `s` of the closed loop.
std::pair<size_t, double> edgeAt(const Polyline& loop, double s) {
  double acc = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const double seg = (loop[(i + 1) % loop.size()] - loop[i]).norm();
    if (seg > 0 && acc + seg >= s) return {i, (s - acc) / seg};
    acc += seg;
  }
  return {loop.size() - 1, 1.0};
}

// `s` in `font`, centred on c at capital height h, as one path of `layer`.
void write(Layer& layer, const StrokeFont& font, const std::string& id, const std::string& s,
           const Vec2& c, double h) {
  Path p;
  p.id = id;
  p.parts = font.layout(s, c, Vec2(1, 0), h);
  layer.paths.push_back(std::move(p));
}

// Where the page's labels are, so that a new one goes where it overlaps none: each label takes the
// first of its candidate spots that is free and inside the region it may use.
class LabelSpots {
 public:
  explicit LabelSpots(const StrokeFont& font) : font_(font) {}
  // The footprint of `s` centred on c at capital height h, with a clearance of 0.3 mm.
  Box footprint(const std::string& s, const Vec2& c, double h) const {
    const Vec2 half(0.5 * font_.width(s, h) + 0.3, 0.5 * h + 0.3);
    return Box::spanning(c - half, c + half);
  }
  bool isFree(const Box& b, const Box& region) const {
    if (!region.contains(b, 0)) return false;
    return std::none_of(taken_.begin(), taken_.end(), [&](const Box& t) { return t.overlaps(b); });
  }
  void take(const Box& b) { taken_.push_back(b); }
  // The first of `centres` where `s` fits, taken; nullopt when none is free.
  std::optional<Vec2> firstFree(const std::string& s, const std::vector<Vec2>& centres, double h,
                                const Box& region) {
    for (const Vec2& c : centres)
      if (isFree(footprint(s, c, h), region)) {
        take(footprint(s, c, h));
        return c;
      }
    return std::nullopt;
  }

 private:
  const StrokeFont& font_;
  std::vector<Box> taken_;
};

// Spots around a mark at `at` pointing away along `out`: at each distance in turn, straight out,
// then turned by 20, 40, 60 and 90 degrees either way.
std::vector<Vec2> spotsAround(const Vec2& at, const Vec2& out,
                              const std::vector<double>& distances) {
  std::vector<Vec2> spots;
  for (double d : distances)
    for (double deg : {0.0, 20.0, -20.0, 40.0, -40.0, 60.0, -60.0, 90.0, -90.0}) {
      const double r = deg * kPi / 180;
      spots.push_back(at + d * Vec2(std::cos(r) * out.x() - std::sin(r) * out.y(),
                                    std::sin(r) * out.x() + std::cos(r) * out.y()));
    }
  return spots;
}

// The numbered steps at the foot of a W x H page, laid out from the bottom up so that the
// pictures take the room that is left. Returns the top of the steps (mm).
double drawSteps(const PatternBuild& pattern, const StrokeFont& font, double W, double H,
                 Layer& text) {
  std::vector<std::vector<std::string>> stepLines;
  double stepsH = 0;
  const double indent = 8.0, textW = W - 2 * kMargin - indent;
  for (const std::string& step : assemblySteps(pattern)) {
    stepLines.push_back(wrapped(font, step, textW, kTextH));
    stepsH += (double(stepLines.back().size()) + 0.4) * kLineH * kTextH;
  }
  double y = H - kMargin - stepsH;
  const double stepsTop = y;
  for (size_t k = 0; k < stepLines.size(); ++k) {
    const std::string number = std::to_string(k + 1) + ".";
    write(text, font, "step-" + std::to_string(k + 1) + "-number", number,
          Vec2(kMargin + 0.5 * font.width(number, kTextH), y + 0.5 * kTextH), kTextH);
    for (size_t i = 0; i < stepLines[k].size(); ++i) {
      const std::string& line = stepLines[k][i];
      write(text, font, "step-" + std::to_string(k + 1) + "-line-" + std::to_string(i + 1), line,
            Vec2(kMargin + indent + 0.5 * font.width(line, kTextH), y + 0.5 * kTextH), kTextH);
      y += kLineH * kTextH;
    }
    y += 0.4 * kLineH * kTextH;
  }
  return stepsTop;
}

// The page's layers, in drawing order.
struct AssemblyLayers {
  Layer& shape;
  Layer& hidden;
  Layer& seam;
  Layer& pieces;
  Layer& marks;
  Layer& text;
};

// Piece p small in its half of the strip [thumbsTop, thumbsTop + thumbsH] whose left edge is at
// x0: outline and tabs, tick 0 and the zip.
void drawThumbnail(const PatternBuild& pattern, size_t p, double x0, double half, double thumbsTop,
                   double thumbsH, const StrokeFont& font, LabelSpots& labels,
                   AssemblyLayers& layers) {
  const PieceInfo& piece = pattern.pieces[p];
  const std::string& name = piece.name;
  Box content = boxOf(piece.cut);
  content.add(piece.outline);
  const Box area =
      Box::spanning(Vec2(x0 + 6, thumbsTop + 2), Vec2(x0 + half - 6, thumbsTop + thumbsH - 8));
  const Fit fit(content, area, false);
  Path cut;
  cut.id = "thumb-" + name + "-cut";
  cut.closed = true;
  for (const Polyline& loop : piece.cut) cut.parts.push_back(fit(loop));
  for (const Polyline& loop : piece.holeCuts) cut.parts.push_back(fit(loop));
  layers.pieces.paths.push_back(cut);
  // The zip: the seam from tick 0 to tick 1 (or a tenth of the way round), arrowed.
  Polyline loop = piece.outline;
  loop.push_back(loop.front());
  const TickInfo& t0 = pattern.ticks.front();
  const double s0 = p == 0 ? t0.s : t0.sB;
  const double step = pattern.ticks.size() > 1
                          ? (p == 0 ? pattern.ticks[1].s : pattern.ticks[1].sB) - s0
                          : 0.1 * piece.perimeter;
  Path zip;
  zip.id = "thumb-" + name + "-zip";
  Polyline arc;
  const int pieces = 24;
  for (int k = 0; k <= pieces; ++k) arc.push_back(fit(pointAlong(loop, s0 + step * k / pieces)));
  Vec2 along = (arc.back() - arc[arc.size() - 2]);
  along = along.norm() > 0 ? along.normalized() : Vec2(1, 0);
  const Vec2 side(-along.y(), along.x()), tip = arc.back();
  zip.parts = {arc, {tip - 2.5 * along + 1.3 * side, tip, tip - 2.5 * along - 1.3 * side}};
  layers.marks.paths.push_back(zip);
  Path start;
  start.id = "thumb-" + name + "-start";
  start.filled = start.closed = true;
  const Vec2 at = fit(p == 0 ? t0.onA : t0.onB);
  start.parts = {disc(at, 1.2)};
  layers.marks.paths.push_back(start);
  // The name under the piece; "0" just outside the start, away from the piece's centre, turned or
  // further out where it would overlap another label, and left out (the disc marks the start)
  // where no spot near it is free.
  const Vec2 nameAt(x0 + 0.5 * half, thumbsTop + thumbsH - 3);
  labels.take(labels.footprint(name, nameAt, 4.0));
  write(layers.text, font, "thumb-" + name + "-name", name, nameAt, 4.0);
  Vec2 out = at - 0.5 * (area.lo + area.hi);
  out = out.norm() > 0 ? out.normalized() : Vec2(0, -1);
  const Box strip = Box::spanning(Vec2(x0, thumbsTop), Vec2(x0 + half, thumbsTop + thumbsH));
  const std::optional<Vec2> zeroAt =
      labels.firstFree("0", spotsAround(at, out, {3.5, 5.5, 7.5, 10.0, 13.0}), kTextH, strip);
  if (zeroAt) write(layers.text, font, "thumb-" + name + "-start-label", "0", *zeroAt, kTextH);
}

// The faces, shaded. Each face's shade is quantised; a run of faces of one colour in painter's
// order is one path.
void drawShadedFaces(const std::vector<SeenFace>& faces, const Fit& view, Layer& shapeLayer) {
  std::vector<std::string> colours;
  for (const SeenFace& f : faces)
    colours.push_back(
        hex(shadedPieceColour(f.piece, std::round(f.shade * kShadeSteps) / kShadeSteps)));
  for (size_t i = 0; i < faces.size();) {
    Path run;
    run.id = "view-faces-" + std::to_string(shapeLayer.paths.size() + 1);
    run.filled = run.closed = run.sealed = true;
    run.fill = colours[i];
    for (; i < faces.size() && colours[i] == run.fill; ++i) {
      const SeenFace& f = faces[i];
      // A hundredth of a millimetre is finer than any printer: shorter numbers, a smaller file.
      auto at = [&](const Vec2& c) { return Vec2((100 * view(c)).array().round() / 100); };
      Polyline tri{at(f.corners[0]), at(f.corners[1]), at(f.corners[2])};
      const double twiceArea = (tri[1] - tri[0]).x() * (tri[2] - tri[0]).y() -
                               (tri[1] - tri[0]).y() * (tri[2] - tri[0]).x();
      if (twiceArea < 0) std::swap(tri[1], tri[2]);  // one winding: the run's triangles add up
      run.parts.push_back(tri);
    }
    shapeLayer.paths.push_back(std::move(run));
  }
}

// Which screen points the surface hides. A point (screen x, y, depth) is hidden where a face
// covers it that is nearer there by more than a hundredth of the shape's size (the faces beside
// a seam point are at its depth). The faces are bucketed in a grid over their screen box, so a
// point is tested against the faces whose boxes reach its cell only: the same answer as testing
// every face, at a small part of the cost.
class SurfaceDepth {
 public:
  explicit SurfaceDepth(const std::vector<SeenFace>& faces) : faces_(faces) {
    for (const SeenFace& f : faces)
      for (const Vec2& c : f.corners) box_.add(c);
    size_ = std::max(box_.w(), box_.h());
    cells_.resize(kCells * kCells);
    for (size_t k = 0; k < faces.size(); ++k) {
      Box b;
      for (const Vec2& c : faces[k].corners) b.add(c);
      const auto [i0, j0] = cell(b.lo);
      const auto [i1, j1] = cell(b.hi);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) cells_[size_t(j * kCells + i)].push_back(k);
    }
  }

  bool hides(const Eigen::Vector3d& s) const {
    const Vec2 p(s.head<2>());
    if (faces_.empty() || !box_.contains(Box::spanning(p, p), 0)) return false;
    const auto [i, j] = cell(p);
    for (size_t k : cells_[size_t(j * kCells + i)]) {
      const SeenFace& f = faces_[k];
      const Vec2 u = f.corners[1] - f.corners[0], v = f.corners[2] - f.corners[0];
      const Vec2 w = p - f.corners[0];
      const double det = u.x() * v.y() - u.y() * v.x();
      if (std::abs(det) < 1e-12) continue;
      const double b1 = (w.x() * v.y() - w.y() * v.x()) / det;
      const double b2 = (u.x() * w.y() - u.y() * w.x()) / det;
      if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
      const double there =
          (1 - b1 - b2) * f.cornerDepths[0] + b1 * f.cornerDepths[1] + b2 * f.cornerDepths[2];
      if (there < s.z() - 0.01 * size_) return true;
    }
    return false;
  }

 private:
  static constexpr int kCells = 64;  // per side
  // The cell of a point of the box, clamped (a box's own corners fall in its last cells).
  std::pair<int, int> cell(const Vec2& p) const {
    auto index = [](double x, double lo, double span) {
      const int k = span > 0 ? int(std::floor((x - lo) / span * kCells)) : 0;
      return std::clamp(k, 0, kCells - 1);
    };
    return {index(p.x(), box_.lo.x(), box_.w()), index(p.y(), box_.lo.y(), box_.h())};
  }

  const std::vector<SeenFace>& faces_;
  Box box_;
  double size_ = 0;
  std::vector<std::vector<size_t>> cells_;
};

// A view of the shape and its faces in painter's order.
struct ShapeView {
  ShapeCamera camera;
  std::vector<SeenFace> faces;
};

// The candidate view that shows the most of the seam: the 3D length of the seam edges (between
// every k-th seam point, at most kViewSeamSamples) with both ends in sight (SurfaceDepth),
// preferring views with tick 0 (`start`) in sight. A later view replaces the best only when it
// shows more by over 1 % of the seam, so that rounding never decides and a tie keeps the
// report's view.
ShapeView mostSeamInSight(const DForm& model, const Eigen::Vector3d& start) {
  const Piece& a = model.a;
  const size_t n = a.seam.size(), step = std::max<size_t>(1, n / kViewSeamSamples);
  std::vector<Eigen::Vector3d> points;
  for (size_t i = 0; i < n; i += step) points.push_back(a.shape.row(a.seam[i]).transpose());
  double seamLength = 0;
  for (size_t i = 0; i < points.size(); ++i)
    seamLength += (points[(i + 1) % points.size()] - points[i]).norm();
  std::optional<ShapeView> best;
  double bestScore = 0;
  const PointClusters drawn = drawnShapeClusters(model);  // the same on every view
  for (double elevation : kViewElevations)
    for (int k = 0; k < 3; ++k) {
      ShapeView v{ShapeCamera(kViewAzimuth + 120.0 * k, elevation), {}};
      v.faces = paintersFaces(model, v.camera, drawn);
      const SurfaceDepth surface(v.faces);
      auto inSight = [&](const Eigen::Vector3d& p) { return !surface.hides(v.camera.screen(p)); };
      std::vector<bool> seenAt;
      for (const Eigen::Vector3d& p : points) seenAt.push_back(inSight(p));
      double length = 0;
      for (size_t i = 0; i < points.size(); ++i)
        if (seenAt[i] && seenAt[(i + 1) % points.size()])
          length += (points[(i + 1) % points.size()] - points[i]).norm();
      // Tick 0 in sight counts as more than any seam length.
      const double score = length + (inSight(start) ? 2 * seamLength : 0);
      if (!best || score > bestScore + 0.01 * seamLength) {
        best = std::move(v);
        bestScore = score;
      }
    }
  return std::move(*best);
}

// The seam on the 3D shape: all of it dashed grey, then the stretches in sight over it; and the
// tick numbers where the ticks meet. A tick's 3D point is the same seam edge and fraction as on
// the flat outline of A; its number goes outside the shape's picture, grey where the surface
// hides the point, at the first spot near it that no other label takes (within `region`), with a
// leader line where that is not the nearest; a number with no free spot is left out. Returns how
// many were.
int drawSeamAndTicks(const DForm& model, const PatternBuild& pattern, const ShapeCamera& camera,
                     const std::vector<SeenFace>& faces, const Box& seen, const Fit& view,
                     const StrokeFont& font, LabelSpots& labels, const Box& region,
                     AssemblyLayers& layers) {
  const SurfaceDepth surface(faces);
  const Piece& a = model.a;
  const size_t n = a.seam.size();
  auto seam3 = [&](size_t i) { return Eigen::Vector3d(a.shape.row(a.seam[i % n]).transpose()); };
  Path seamPath;
  seamPath.id = "view-seam";
  seamPath.closed = seamPath.dashed = true;
  seamPath.dash = {1.5, 1.0};
  seamPath.parts.emplace_back();
  Path inSight;
  inSight.id = "view-seam-in-sight";
  std::vector<bool> seenAt(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d s = camera.screen(seam3(i));
    seamPath.parts[0].push_back(view(Vec2(s.head<2>())));
    seenAt[i] = !surface.hides(s);
  }
  for (size_t i = 0; i < n; ++i) {  // each edge with both ends in sight, runs joined
    if (!seenAt[i] || !seenAt[(i + 1) % n]) continue;
    const Vec2& from = seamPath.parts[0][i];
    if (inSight.parts.empty() || (inSight.parts.back().back() - from).norm() > 0)
      inSight.parts.push_back({from});
    inSight.parts.back().push_back(seamPath.parts[0][(i + 1) % n]);
  }
  layers.hidden.paths.push_back(seamPath);
  if (!inSight.parts.empty()) layers.seam.paths.push_back(inSight);
  // A tick's number goes outside the shape's picture; grey where the surface hides its point.
  const Vec2 middle = view(0.5 * (seen.lo + seen.hi));
  int dropped = 0;
  for (const SeamTick& t : seamTicks(model, pattern)) {
    const Eigen::Vector3d s = camera.screen(t.at);
    const Vec2 at = view(Vec2(s.head<2>()));
    const bool covered = surface.hides(s);
    Path dot;
    dot.id = "view-tick-" + std::to_string(t.id);
    dot.filled = dot.closed = true;
    dot.parts = {disc(at, t.id == 0 ? 1.2 : 0.7)};
    (covered ? layers.hidden : layers.marks).paths.push_back(dot);
    Vec2 out = at - middle;
    out = out.norm() > 0 ? out.normalized() : Vec2(0, -1);
    const double h = t.id == 0 ? 3.2 : 2.6;
    const std::optional<Vec2> c =
        labels.firstFree(t.label, spotsAround(at, out, {4.0, 7.0, 10.0, 13.0}), h, region);
    if (!c) {
      ++dropped;
      continue;
    }
    Layer& layer = covered ? layers.hidden : layers.text;
    write(layer, font, "view-tick-" + std::to_string(t.id) + "-label", t.label, *c, h);
    const Vec2 to = *c - at;
    if (to.norm() > 4.0 + 1e-9) {  // a leader from the dot to the number's near side
      Path leader;
      leader.id = "view-tick-" + std::to_string(t.id) + "-leader";
      leader.parts = {{at + 1.0 * to.normalized(), *c - (0.5 * h + 0.8) * to.normalized()}};
      layer.paths.push_back(leader);
    }
  }
  return dropped;
}

}  // namespace

std::vector<std::string> assemblySteps(const PatternBuild& pattern) {
  const std::string& a = pattern.pieces[0].name;
  const std::string& b = pattern.pieces[1].name;
  bool tabsOn[2] = {false, false};
  for (const TabInfo& t : pattern.tabs) tabsOn[t.piece] = true;
  const bool tabs = tabsOn[0] || tabsOn[1];
  const Joint joint = pattern.joint.joint;
  const bool laser = pattern.profile.kind == ProfileKind::Laser;
  const std::string face = laser ? "engraved" : "printed";
  std::string cut = "Cut out both pieces on their cut lines";
  if (joint != Joint::Glue)
    cut += joint == Joint::Slots ? ", their slots and holes first" : ", their joint holes first";
  if (tabs)
    cut += "; crease each tab's fold line and fold the tab back, away from the " + face + " side.";
  else if (joint == Joint::Glue)
    cut += ". There are no glue tabs: join the edges with tape on the inside.";
  else
    cut += ".";
  if (!pattern.jointSlots.empty())
    cut += " Crease each tongue of " + a + " on its fold line and fold it back, away from the " +
           face + " side.";
  std::string join =
      "Join " + a + "'s tick 0 to " + b + "'s tick 0, edge to edge, " + face + " sides out";
  if (tabsOn[0] && tabsOn[1])
    join += "; the tabs alternate between the pieces and go inside, under the other edge.";
  else if (tabs)
    join += "; " + (tabsOn[0] ? a : b) + "'s tabs go inside, under " + (tabsOn[0] ? b : a) +
            "'s edge. Glue one tab at a time.";
  else
    join += ".";
  // How each stretch of the seam is closed as the zip goes along.
  const std::string holePairs = "tie each hole pair (a hole of " + a + " facing one of " + b +
                                ") with a cable tie, rivet or stitch";
  std::string zip = "Zip along the arrows: tick 1 to 1, 2 to 2, and on";
  switch (joint) {
    case Joint::Glue: zip += "."; break;
    case Joint::Holes: zip += ", and " + holePairs + " as you go."; break;
    case Joint::Lace:
      zip += ", lacing as you go: from a hole of " + a + " to the next hole along, on " + b +
             ", and back, so the lace zigzags across the seam and pulls the edges together.";
      break;
    case Joint::Slots:
      zip += ", and push each tongue of " + a + " from the inside out through the slot of " + b +
             " beside it, pressing its barbed head flat" +
             (pattern.jointHoles.empty() ? std::string(".") : "; " + holePairs + ".");
      break;
  }
  zip += " The sheet bends by itself; do not crease it anywhere but on drawn fold lines.";
  const std::string last = tickLabel(int(pattern.ticks.size()) - 1);
  return {cut,
          "Find tick 0 on each piece: the long tick with the arrow, which points the way to zip "
          "(shown on the small pieces above).",
          join, zip,
          "Close the last gap, from tick " + last + " back to 0, from the outside" +
              (tabs ? " (tweezers help with the last tabs)" : "") +
              ", and compare the shape with the picture above."};
}

Drawing assemblyPage(const DForm& model, const PatternBuild& pattern, const ExportOptions& o,
                     const StrokeFont& font) {
  Drawing d;
  // The job's paper (--page over the profile's), portrait, so that a printer prints the whole job
  // on one paper size; A4 for a sheet profile, which has none.
  const std::string page = o.page.empty() ? pattern.profile.page : o.page;
  const auto size = pageSizeMm(page.empty() ? "A4" : page);
  d.width = size ? size->first : 210.0;
  d.height = size ? size->second : 297.0;
  d.title = o.jobName + " - assembly";
  d.description = "How to glue the pieces: dform assembly page, mm";
  d.layers = {makeLayer("Shape", "#000000", 0.1), makeLayer("Hidden", "#999999", 0.25),
              makeLayer("Seam", "#C2185B", 0.5),  makeLayer("Pieces", "#333333", 0.3),
              makeLayer("Marks", "#C2185B", 0.6), makeLayer("Text", "#000000", 0.3)};
  AssemblyLayers layers{d.layers[0], d.layers[1], d.layers[2],
                        d.layers[3], d.layers[4], d.layers[5]};
  const double W = d.width, H = d.height;
  write(layers.text, font, "assembly-title",
        "How to assemble " + o.jobName + ": D-Form " + pattern.pieces[0].name + " + " +
            pattern.pieces[1].name,
        Vec2(0.5 * W, kMargin + 2.5), 5.0);
  // The steps first, so that the pictures take the room that is left.
  const double stepsTop = drawSteps(pattern, font, W, H, layers.text);
  // The two pieces, small, side by side above the steps.
  const double top = kMargin + 10.0, gap = 8.0;
  const double thumbsH = std::min(60.0, 0.35 * (stepsTop - top));
  const double thumbsTop = stepsTop - gap - thumbsH;
  const double half = 0.5 * (W - 2 * kMargin - gap);
  LabelSpots labels(font);
  for (size_t p = 0; p < 2; ++p)
    drawThumbnail(pattern, p, kMargin + double(p) * (half + gap), half, thumbsTop, thumbsH, font,
                  labels, layers);
  // The 3D shape, shaded, with its seam and the tick numbers where the ticks meet.
  const std::vector<SeamTick> ticks = seamTicks(model, pattern);
  const ShapeView chosen =
      mostSeamInSight(model, ticks.empty() ? Eigen::Vector3d(model.a.shape.row(model.a.seam[0]))
                                           : ticks.front().at);
  const ShapeCamera& camera = chosen.camera;
  const std::vector<SeenFace>& faces = chosen.faces;
  Box seen;
  for (const SeenFace& f : faces)
    for (const Vec2& c : f.corners) seen.add(c);
  const Box viewArea =
      Box::spanning(Vec2(kMargin + 8, top + 6), Vec2(W - kMargin - 8, thumbsTop - gap - 6));
  const Fit view(seen, viewArea, true);
  drawShadedFaces(faces, view, layers.shape);
  // The tick numbers keep between the title and the thumbnails, above a note's line under the
  // picture, which says how many had no room (each is numbered on the pieces).
  const Box tickRegion = Box::spanning(Vec2(kMargin, top), Vec2(W - kMargin, thumbsTop - gap));
  const int dropped =
      drawSeamAndTicks(model, pattern, camera, faces, seen, view, font, labels, tickRegion, layers);
  if (dropped > 0)
    write(layers.text, font, "view-dropped-note",
          std::to_string(dropped) + " tick number" + (dropped > 1 ? "s" : "") +
              " left out of this picture for lack of room: every tick is numbered on the pieces",
          Vec2(0.5 * W, thumbsTop - 0.5 * gap), 2.4);
  return d;
}

std::vector<SeamTick> seamTicks(const DForm& model, const PatternBuild& pattern) {
  const Piece& a = model.a;
  const size_t n = a.seam.size();
  const Polyline& flatSeam = pattern.pieces[0].outline;
  if (flatSeam.size() != n) return {};
  auto seam3 = [&](size_t i) { return Eigen::Vector3d(a.shape.row(a.seam[i % n]).transpose()); };
  std::vector<SeamTick> ticks;
  for (const TickInfo& t : pattern.ticks) {
    const auto [i, frac] = edgeAt(flatSeam, t.s);
    ticks.push_back({t.id, tickLabel(t.id), (1 - frac) * seam3(i) + frac * seam3(i + 1)});
  }
  return ticks;
}

}  // namespace dform::fab
