// SPDX-License-Identifier: GPL-3.0-or-later
// The FAILED GATE stamp: an overlay laid on a pattern that is already laid out. It moves nothing:
// the text goes into the free band above (or below) what each sheet, page, tile and the assembly
// page already show, in a colour of its own that no profile cuts or scores with.
#include <algorithm>
#include <cctype>

#include "internal.h"

namespace dform::fab {

namespace {

constexpr double kStampMaxH = 4.0;      // the stamp's capital height at most (mm)
constexpr double kStampMinH = 1.5;      // and at least, where the free band is thinner
constexpr double kStampWidthMm = 0.35;  // its stroke: visible, whatever the profile's hairline

std::string upperCase(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// A warning orange, light and none of the pure colours lasers map to operations (Epilog,
// LightBurn's first layers, every shipped profile's cut, score and engrave); where a profile
// uses it for an operation, another (a machine must never take the stamp for a cut or a score).
std::string stampColor(const Profile& p) {
  for (const char* color : {"#FF9933", "#999999", "#E0C060", "#66CCCC"})
    if (color != upperCase(p.cutColor) && color != upperCase(p.scoreColor) &&
        color != upperCase(p.engraveColor))
      return color;
  return "#FF9933";  // unreachable: three operations cannot take four colours
}

Layer stampLayer(const Profile& profile, bool printed) {
  Layer layer;
  layer.name = kFailedGateLayer;
  layer.color = stampColor(profile);
  layer.widthMm = kStampWidthMm;
  layer.printed = printed;
  return layer;
}

// What a sheet or page shows, as boxes in its own frame: everything drawn, and apart from it
// the registration marks (the stamp keeps beside them, `clear` mm away, not below them).
struct Shown {
  std::vector<Box> drawn, marks;
  void add(const Box& b, bool mark) { (mark ? marks : drawn).push_back(b); }
};

// The stamp in `frame`, around what is shown there: centred in the free band above everything,
// or in the one below where that is the wider and the band above is too thin for the smallest
// stamp; as tall as the band allows (at most 4 mm) and as wide as the frame less `side` mm each
// side and the marks.
Path stampIn(const Box& frame, const Shown& shown, double side, double clear,
             const StrokeFont& font, const std::string& id) {
  double top = frame.hi.y(), bottom = frame.lo.y();
  for (const Box& b : shown.drawn) {
    top = std::min(top, b.lo.y());
    bottom = std::max(bottom, b.hi.y());
  }
  const double above = top - frame.lo.y(), below = frame.hi.y() - bottom;
  const bool under = above < 2 * kStampMinH && below > above;
  const double y0 = under ? bottom : frame.lo.y(), y1 = under ? frame.hi.y() : top;
  double x0 = frame.lo.x() + side, x1 = frame.hi.x() - side;
  const double middle = 0.5 * (frame.lo.x() + frame.hi.x());
  for (const Box& m : shown.marks) {
    if (m.hi.y() < y0 || m.lo.y() > y1) continue;  // not beside the band
    if (0.5 * (m.lo.x() + m.hi.x()) < middle)
      x0 = std::max(x0, m.hi.x() + clear);
    else
      x1 = std::min(x1, m.lo.x() - clear);
  }
  if (!(x1 - x0 > 10)) x0 = frame.lo.x(), x1 = frame.hi.x();
  const std::string text = kFailedGateText;
  const double h = std::max(
      kStampMinH, std::min({kStampMaxH, 0.6 * (y1 - y0), (x1 - x0) / font.width(text, 1.0)}));
  const Vec2 centre(0.5 * (x0 + x1), 0.5 * (y0 + y1));
  Path stamp;
  stamp.id = id;
  stamp.parts = font.layout(text, centre, {1, 0}, h);
  return stamp;
}

std::vector<std::pair<Box, bool>> pathBoxes(const Drawing& drawing) {
  std::vector<std::pair<Box, bool>> boxes;
  for (const Layer& layer : drawing.layers) {
    if (layer.name == kFailedGateLayer) continue;
    for (const Path& path : layer.paths)
      boxes.emplace_back(boxOf(path.parts), layer.name == "Regmarks");
  }
  return boxes;
}

// The id of sheet or page k's stamp: the first keeps the plain id.
std::string stampId(const std::string& id, size_t k) {
  return k == 0 ? id : id + "-" + std::to_string(k + 1);
}

// Page `page`'s stamp, in page coordinates: around its furniture and the part of the canvas
// (`canvas`, the drawing's boxes) it shows.
Path pageStamp(const PageView& page, const std::vector<std::pair<Box, bool>>& canvas,
               const Profile& profile, const StrokeFont& font, size_t k) {
  Shown shown;
  for (const Layer& layer : page.overlay)
    for (const Path& path : layer.paths) shown.add(boxOf(path.parts), false);
  const Box window = Box::spanning(page.origin + Vec2(page.clipX0, page.clipY0),
                                   page.origin + Vec2(page.clipX1, page.clipY1));
  // Whether a box shares area with the window (a tile shows part of a piece).
  auto across = [&](const Box& b) {
    return b.lo.x() < window.hi.x() && window.lo.x() < b.hi.x() && b.lo.y() < window.hi.y() &&
           window.lo.y() < b.hi.y();
  };
  if (window.w() > 0 && window.h() > 0)
    for (const auto& [b, mark] : canvas) {
      if (!across(b) && !window.contains(b, 1e-6)) continue;  // not on this page
      shown.add(Box::spanning(b.lo.cwiseMax(window.lo) - page.origin,
                              b.hi.cwiseMin(window.hi) - page.origin),
                mark);
    }
  const double side = std::max(profile.marginMm, page.clipX0);
  return stampIn(Box::spanning(Vec2::Zero(), Vec2(page.width, page.height)), shown, side,
                 profile.registrationClearMm, font, stampId("page-failed-gate", k));
}

}  // namespace

void stampFailedGate(PatternBuild& pattern, const StrokeFont& font) {
  if (pattern.failedGate) return;
  pattern.failedGate = true;
  const Profile& profile = pattern.profile;
  const std::string note = "; FAILED GATE: not for fabrication";
  const std::vector<std::pair<Box, bool>> canvas = pathBoxes(pattern.drawing);
  // The drawing (pattern.svg and .dxf, each sheet's files): one stamp per sheet. Not printed:
  // the PDF's pages carry their own.
  Layer sheets = stampLayer(profile, false);
  for (size_t k = 0; k < pattern.sheets.size(); ++k) {
    const Box& sheet = pattern.sheets[k];
    Shown shown;
    for (const auto& [b, mark] : canvas)
      if (sheet.contains(b, 1e-6)) shown.add(b, mark);
    sheets.paths.push_back(stampIn(sheet, shown, profile.marginMm, profile.registrationClearMm,
                                   font, stampId("failed-gate", k)));
  }
  pattern.drawing.layers.insert(pattern.drawing.layers.begin(), std::move(sheets));
  pattern.drawing.description += note;
  // Every page of the PDF (a sheet, a tiled piece's page map and tiles).
  for (size_t k = 0; k < pattern.pages.size(); ++k) {
    Layer onPage = stampLayer(profile, true);
    onPage.paths.push_back(pageStamp(pattern.pages[k], canvas, profile, font, k));
    pattern.pages[k].overlay.push_back(std::move(onPage));
  }
  // The assembly page (the PDF's last page and assembly.svg).
  if (Drawing& assembly = pattern.assembly; assembly.width > 0) {
    Shown shown;
    for (const auto& [b, mark] : pathBoxes(assembly)) shown.add(b, mark);
    Layer onPage = stampLayer(profile, true);
    onPage.paths.push_back(
        stampIn(Box::spanning(Vec2::Zero(), Vec2(assembly.width, assembly.height)), shown,
                profile.marginMm, 0, font, "assembly-failed-gate"));
    assembly.layers.insert(assembly.layers.begin(), std::move(onPage));
    assembly.description += note;
  }
}

}  // namespace dform::fab
