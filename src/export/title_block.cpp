// SPDX-License-Identifier: GPL-3.0-or-later
// Each sheet's furniture: the title lines (title, note, crease and tab legends, the scale in
// words) or, where they find no room, the mark (the job's name beside the bar), the 50 mm
// calibration bar, Silhouette registration marks in its corners; and the drawing's title and
// description.
#include <algorithm>
#include <cstdio>

#include "pattern_layout.h"

namespace dform::fab {

namespace {

// The id of a page's copy of the sheet furniture (title lines, registration marks): the first
// page keeps the plain id.
std::string onPage(const std::string& id, size_t page) {
  return page == 0 ? id : id + "-page-" + std::to_string(page + 1);
}

}  // namespace

// The scale as a percentage of true size, to a tenth ("73.4 %").
std::string percentText(double scale) {
  char percent[32];
  std::snprintf(percent, sizeof percent, "%.1f %%", 100 * scale);
  return percent;
}

namespace {

// What the bar asks: print (or cut) at 100 %, so that it measures 50 mm.
const char* checkWords(const SheetFit& fit) {
  return fit.profile->kind == ProfileKind::Laser ? "cut at 100% (actual size)"
                                                 : "print at 100% (actual size)";
}

}  // namespace

std::string barLabel(bool full, const SheetFit& fit) {
  return full ? std::string("50 mm - ") + checkWords(fit) : std::string("50 mm");
}

std::vector<TitleLine> titleLines(size_t k, size_t sheets, int piece, bool full,
                                  const SheetFit& fit, const TitleText& text) {
  const ExportOptions& o = text.o;
  const Profile& profile = *fit.profile;
  std::vector<TitleLine> lines;
  if (!full) {  // the mark: the job's name (over the bar), the scale where it is not 1
    lines.push_back(
        {"job-name", profile.calibrationBar ? o.jobName + " - " + checkWords(fit) : o.jobName});
    if (!fit.scaleNote.empty())
      lines.push_back({"scale-note", "printed at " + percentText(fit.scale) +
                                         " of the designed size (ticks, tabs, labels: 100 %)"});
    return lines;
  }
  std::string pieceNote;
  if (sheets > 1)
    pieceNote = " - " + fit.sheetWord + " " + std::to_string(k + 1) + " of " +
                std::to_string(sheets) +
                (piece >= 0 ? ": piece " + text.names[size_t(piece)] : std::string());
  const std::optional<MaterialPreset> material = materialNamed(o.material);
  const std::string materialNote =
      material ? " - " + material->name + " " + formatMm(material->thicknessMm) + " mm" : "";
  lines.push_back({"title", o.jobName + " - " + text.what + pieceNote + " - " + text.scaleText +
                                " - " + text.perimeterText + " - " + profile.name + materialNote});
  const char* joinNote = profile.joint == Joint::Holes  ? "tie or stitch the hole pairs"
                         : profile.joint == Joint::Lace ? "lace the holes, A to B in turn"
                         : profile.joint == Joint::Slots
                             ? "fold A's tongues back and push each out through B's slot "
                               "at the same ticks; tie any hole pairs"
                             : "glue equal numbers together";
  lines.push_back({"note", "tick 0 = start, arrow = zip direction; ticks every " +
                               formatMm(o.tickSpacingMm, 0) + " mm; " + joinNote});
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
  if (text.creased) lines.push_back({"crease-legend-label", creaseLegend});
  if (fit.tabbed) lines.push_back({"tab-note", tabNote});
  if (profile.registration == Registration::Silhouette)  // what Silhouette Studio is set to
    lines.push_back({"regmark-note", "Silhouette Studio: registration marks Type 1, length " +
                                         formatMm(kRegArm, 0) + " mm, thickness " +
                                         formatMm(kRegLine, 1) + " mm, inset " +
                                         formatMm(kRegInset, 0) + " mm"});
  if (!fit.scaleNote.empty()) lines.push_back({"scale-note", fit.scaleNote});
  return lines;
}

namespace {

void drawLines(size_t k, const std::vector<TitleLine>& lines, double textH, const StrokeFont& font,
               Layer& layer, TitleBlock& block) {
  for (const TitleLine& line : lines) {
    double h = textH;
    const double w = font.width(line.words, h);
    if (w > block.length) h *= block.length / w;
    const Vec2 c = block.start + 0.5 * std::min(w, block.length) * block.along +
                   (block.v + 0.5 * kTitlePitch * h) * block.across;
    layer.paths.push_back(textPath(font, onPage(line.id, k), line.words, c, block.along, h));
    block.v += kTitlePitch * h;
  }
}

// The 50 mm calibration bar of sheet k, after its title lines, and its label beside it.
void drawCalibrationBar(size_t k, const TitleBlock& block, double textH, const std::string& text,
                        const StrokeFont& font, Layer& layer) {
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
  layer.paths.push_back(bar);
  // Smaller where the block is too short for it beside the bar.
  const double h =
      std::min(textH, (block.length - kBarLabelAt) / std::max(1.0, font.width(text, 1.0)));
  layer.paths.push_back(textPath(font, onPage("calibration-label", k), text,
                                 at(kBarLabelAt + 0.5 * font.width(text, h), vb - 1.5), block.along,
                                 h));
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

}  // namespace

void drawTitleBlock(size_t k, size_t sheets, int piece, bool full, double h, const SheetFit& fit,
                    const TitleText& text, Layer& layer, TitleBlock& block) {
  drawLines(k, titleLines(k, sheets, piece, full, fit, text), h, text.font, layer, block);
  if (fit.profile->calibrationBar)
    drawCalibrationBar(k, block, h, barLabel(full, fit), text.font, layer);
}

void drawSheetFurniture(const std::vector<SheetPlan>& plans, const SheetFit& fit,
                        const TitleText& text, DrawingBuilder& b) {
  for (size_t k = 0; k < plans.size(); ++k) {
    const TitlePlace& title = plans[k].title;
    if (!plans[k].tiled && title.placed) {
      TitleBlock block = title.block;
      const int piece = plans[k].pieces.size() == 1 ? plans[k].pieces.front() : -1;
      drawTitleBlock(k, plans.size(), piece, title.full, title.h, fit, text, b.title(), block);
    }
    if (fit.profile->registration == Registration::Silhouette)
      drawRegistrationMarks(k, plans[k].box, *b.regmarks());
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

}  // namespace dform::fab
