// Each sheet's furniture: the title lines (title, note, crease and tab legends) under its pieces
// or in a column beside them, the 50 mm calibration bar, Silhouette registration marks in its
// corners; and the drawing's title and description.
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

}  // namespace

void drawTitleLines(size_t k, size_t sheets, const SheetPlan& plan, const SheetFit& fit,
                    const TitleText& text, Layer& layer, TitleBlock& block) {
  const FlatPieces& flat = text.flat;
  const ExportOptions& o = text.o;
  const StrokeFont& font = text.font;
  const Profile& profile = *fit.profile;
  const double textH = fit.textH, lineH = fit.lineH;
  auto line = [&](const std::string& id, const std::string& words, double h) {
    const double w = font.width(words, h);
    if (w > block.length) h *= block.length / w;
    const Vec2 c = block.start + 0.5 * std::min(w, block.length) * block.along +
                   (block.v + 0.5 * lineH * h / textH) * block.across;
    layer.paths.push_back(textPath(font, onPage(id, k), words, c, block.along, h));
    block.v += lineH * h / textH;
  };
  std::string pieceNote;
  if (sheets > 1)
    pieceNote = " - " + fit.sheetWord + " " + std::to_string(k + 1) + " of " +
                std::to_string(sheets) + ": piece " + flat.names[plan.pieces.front()];
  if (!o.title) {
    if (!fit.scaleNote.empty()) line("scale-note", fit.scaleNote, textH);
    return;
  }
  const std::optional<MaterialPreset> material = materialNamed(o.material);
  const std::string materialNote =
      material ? " - " + material->name + " " + formatMm(material->thicknessMm) + " mm" : "";
  line("title",
       o.jobName + " - D-Form " + flat.names[0] + " + " + flat.names[1] + pieceNote + " - " +
           text.scaleText + " - seam " + text.perimeterText + " mm - " + profile.name +
           materialNote,
       textH);
  const char* joinNote = profile.joint == Joint::Holes  ? "tie or stitch the hole pairs"
                         : profile.joint == Joint::Lace ? "lace the holes, A to B in turn"
                         : profile.joint == Joint::Slots
                             ? "fold A's tongues back and push each out through B's slot "
                               "at the same ticks; tie any hole pairs"
                             : "glue equal numbers together";
  line("note",
       "tick 0 = start, arrow = zip direction; ticks every " + formatMm(o.tickSpacingMm, 0) +
           " mm; " + joinNote,
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
  if (!fit.scaleNote.empty()) line("scale-note", fit.scaleNote, textH);
}

namespace {

// The 50 mm calibration bar of sheet k, after its title lines.
void drawCalibrationBar(size_t k, const TitleBlock& block, double textH, const StrokeFont& font,
                        Layer& layer) {
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
  const std::string text = "50 mm - print at 100% (actual size)";
  // Smaller where the block is too short for it beside the bar (a narrow tiled piece).
  const double h = std::min(textH, (block.length - 54) / std::max(1.0, font.width(text, 1.0)));
  layer.paths.push_back(textPath(font, onPage("calibration-label", k), text,
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

}  // namespace

// Title lines (and the calibration bar) under each sheet's pieces or in a column beside them,
// and the registration marks in each sheet's corners.
void drawTitleBlock(size_t k, size_t sheets, const SheetPlan& plan, const SheetFit& fit,
                    const TitleText& text, Layer& layer, TitleBlock& block) {
  drawTitleLines(k, sheets, plan, fit, text, layer, block);
  if (fit.profile->calibrationBar) drawCalibrationBar(k, block, fit.textH, text.font, layer);
}

void drawSheetFurniture(const std::vector<SheetPlan>& plans, const SheetFit& fit,
                        const TitleText& text, DrawingBuilder& b) {
  for (size_t k = 0; k < plans.size(); ++k) {
    if (!plans[k].tiled && plans[k].title != TitleAt::None) {
      TitleBlock block = titleBlockOf(plans[k], fit);
      drawTitleBlock(k, plans.size(), plans[k], fit, text, b.title(), block);
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
