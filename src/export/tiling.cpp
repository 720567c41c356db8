// SPDX-License-Identifier: GPL-3.0-or-later
// The pattern's pages: one per sheet, and for a print piece larger than its page a page map then
// its tiles, each a window of the piece's sheet with a frame, alignment crosses in the overlaps, a
// header naming the tile and a calibration bar.
#include <algorithm>

#include "pattern_layout.h"

namespace dform::fab {

namespace {

Path cross(const std::string& id, const Vec2& c, double r) {
  Path p;
  p.id = id;
  p.parts = {{c - Vec2(r, 0), c + Vec2(r, 0)}, {c - Vec2(0, r), c + Vec2(0, r)}};
  return p;
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

// "1 row", "2 columns".
std::string counted(long n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
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
PageView pageMap(size_t k, size_t sheets, const SheetPlan& plan, const PieceInfo& info,
                 const SheetFit& fit, size_t firstTilePage, const TitleText& title) {
  const ExportOptions& o = title.o;
  const StrokeFont& font = title.font;
  const std::string& nm = info.name;
  const double pm = kTileMargin, header = kTileHeader, ov = fit.overlap, cw = fit.tileW,
               ch = fit.tileH;
  const long nx = plan.tilesX, ny = plan.tilesY;
  PageView map = blankPage(fit);
  map.kind = "map";
  Layer furniture = tilingLayer();
  // The grid of windows reaches past the piece's sheet (the last ones overhang it). The sheet's
  // title lines go under it, on this page: never on a tile, where they would be cut at its edge.
  const double gridW = double(nx) * (cw - ov) + ov, gridH = double(ny) * (ch - ov) + ov;
  const double mapScale = std::min(cw / gridW, std::max(ch - fit.titleBlock, 0.5 * ch) / gridH);
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
                counted(ny, "row") + " x " + counted(nx, "column") +
                ") - not to scale - print the tiles at 100%",
            fit, font);
  TitleBlock block;
  block.along = Vec2(1, 0);
  block.across = Vec2(0, 1);
  block.start = Vec2(pm, pm + header + mapScale * gridH + fit.m);
  block.length = cw;
  Layer titleLines = tilingLayer();
  titleLines.name = "Title";
  drawTitleBlock(k, sheets, plan.pieces.front(), o.title, fit.textH, fit, title, titleLines, block);
  map.overlay.push_back(titleLines);
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
  page.kind = "tile";
  page.clipX0 = pm;
  page.clipY0 = pm + header;
  const Vec2 windowLo = plan.box.lo + Vec2(double(i) * (cw - ov), double(j) * (ch - ov));
  page.origin = windowLo - Vec2(page.clipX0, page.clipY0);
  // The window ends where the piece's sheet does: the last row and column of tiles overhang it,
  // and what lies beyond (the other piece's sheet) is not this piece's.
  page.clipX1 = std::min(pm + cw, plan.box.hi.x() - page.origin.x());
  page.clipY1 = std::min(pm + header + ch, plan.box.hi.y() - page.origin.y());
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

}  // namespace

std::string aPage(const std::string& pageName) {
  // A4, A3 ... read "ay-four": an; Letter, Tabloid and sizes (200x300mm): a.
  return (pageName.rfind('A', 0) == 0 ? "an " : "a ") + pageName;
}

void addPages(const std::vector<SheetPlan>& plans, const SheetFit& fit, const TitleText& text,
              PatternBuild& out) {
  for (size_t k = 0; k < plans.size(); ++k) {
    const SheetPlan& plan = plans[k];
    if (!plan.tiled) {
      if (text.o.title && !plan.title.full)
        out.messages.push_back("the title lines do not fit beside the pieces on " + fit.sheetWord +
                               " " + std::to_string(k + 1) + ": it carries the job's name" +
                               (fit.profile->calibrationBar ? " and the 50 mm bar" : "") +
                               " alone");
      out.pages.push_back(sheetPage(plan));
      out.pages.back().printArea = fit.artRegion(plan.box.w(), plan.box.h());
      continue;
    }
    const PieceInfo& info = out.pieces[size_t(plan.pieces.front())];
    const size_t firstTilePage = out.pages.size() + 2;  // 1-based, after the map
    out.pages.push_back(pageMap(k, plans.size(), plan, info, fit, firstTilePage, text));
    const std::vector<Vec2> marks = alignmentMarks(plan, fit);
    for (long j = 0; j < plan.tilesY; ++j)
      for (long i = 0; i < plan.tilesX; ++i)
        out.pages.push_back(tilePage(plan, info.name, j, i, marks, fit, text.o, text.font));
    out.messages.push_back("piece " + info.name + " is larger than " + aPage(fit.pageName) +
                           " page: it is tiled across " +
                           std::to_string(plan.tilesX * plan.tilesY) +
                           " pages of pattern.pdf after a page map; print at 100% and match the "
                           "crosses");
  }
}

}  // namespace dform::fab
