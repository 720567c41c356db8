// SPDX-License-Identifier: GPL-3.0-or-later
// PDF pages and PNG previews of the pattern through Cairo. Cairo draws in points (PDF) or pixels
// (PNG); the drawing is in mm, so each page is scaled by 72/25.4 or dpi/25.4. Cairo 1.16 drops
// strokes of width 0, so every width is explicit; PNG previews draw hairlines one pixel wide.
#include <cairo-pdf.h>
#include <cairo.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "internal.h"

namespace dform::fab {

namespace {

constexpr double kMmPerInch = 25.4;
constexpr double kPointsPerInch = 72.0;

cairo_status_t appendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void setColor(cairo_t* cr, const std::string& hex) {
  const unsigned long v = std::stoul(hex.substr(1), nullptr, 16);
  cairo_set_source_rgb(cr, double((v >> 16) & 0xFF) / 255.0, double((v >> 8) & 0xFF) / 255.0,
                       double(v & 0xFF) / 255.0);
}

// Draws the layer's paths that meet `visible` (all of them when it is null): a tile or a piece's
// page leaves out what it does not show, so that a document of many pages stays the size of the
// drawing rather than pages times it.
void drawLayer(cairo_t* cr, const Layer& layer, double minWidthMm, const Box* visible = nullptr) {
  setColor(cr, layer.color);
  cairo_set_line_width(cr, std::max(layer.widthMm, minWidthMm));
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const Path& p : layer.paths) {
    if (visible && !visible->overlaps(boxOf(p.parts))) continue;
    cairo_new_path(cr);
    for (const Polyline& part : p.parts) {
      if (part.empty()) continue;
      cairo_move_to(cr, part[0].x(), part[0].y());
      for (size_t i = 1; i < part.size(); ++i) cairo_line_to(cr, part[i].x(), part[i].y());
      if (p.closed) cairo_close_path(cr);
    }
    if (p.filled) {
      if (!p.fill.empty()) setColor(cr, p.fill);
      if (p.sealed) {
        cairo_fill_preserve(cr);
        cairo_stroke(cr);
      } else {
        cairo_fill(cr);
      }
      setColor(cr, layer.color);
      continue;
    }
    if (p.dashed) {
      const std::vector<double> dash =
          p.dash.empty() ? std::vector<double>{layer.dashMm, layer.dashMm} : p.dash;
      cairo_set_dash(cr, dash.data(), int(dash.size()), 0);
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
  }
}

// Draws one page; the context is already scaled so that 1 unit = 1 mm.
void drawPage(cairo_t* cr, const PatternBuild& pattern, const PageView& page, double minWidthMm) {
  cairo_save(cr);
  cairo_rectangle(cr, page.clipX0, page.clipY0, page.clipX1 - page.clipX0,
                  page.clipY1 - page.clipY0);
  cairo_clip(cr);
  cairo_translate(cr, -page.origin.x(), -page.origin.y());
  // The window of the canvas the page shows, widened by the widest stroke (round caps).
  double halfStroke = minWidthMm;
  for (const Layer& layer : pattern.drawing.layers)
    halfStroke = std::max(halfStroke, layer.widthMm);
  const Box visible =
      Box::spanning(page.origin + Vec2(page.clipX0, page.clipY0) - Vec2::Constant(halfStroke),
                    page.origin + Vec2(page.clipX1, page.clipY1) + Vec2::Constant(halfStroke));
  for (const Layer& layer : pattern.drawing.layers)
    if (layer.printed) drawLayer(cr, layer, minWidthMm, &visible);
  cairo_restore(cr);
  for (const Layer& layer : page.overlay) drawLayer(cr, layer, minWidthMm);
}

// Draws a whole drawing (every printed layer) at its own origin; 1 unit = 1 mm.
void drawDrawing(cairo_t* cr, const Drawing& drawing, double minWidthMm) {
  for (const Layer& layer : drawing.layers)
    if (layer.printed) drawLayer(cr, layer, minWidthMm);
}

Status cairoError(cairo_status_t status, const std::string& what) {
  return {ErrorCode::OutputFailed,
          what + ": Cairo failed (" + cairo_status_to_string(status) + ")"};
}

}  // namespace

Result<std::string> pdfDocument(const PatternBuild& pattern) {
  std::string bytes;
  const double k = kPointsPerInch / kMmPerInch;
  const PageView& first = pattern.pages.front();
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_pdf_surface_create_for_stream(appendToString, &bytes, first.width * k,
                                          first.height * k),
      cairo_surface_destroy);
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE,
                                 pattern.drawing.title.c_str());
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_SUBJECT,
                                 pattern.drawing.description.c_str());
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "dform export");
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), cairo_destroy);
  for (const PageView& page : pattern.pages) {
    cairo_pdf_surface_set_size(surface.get(), page.width * k, page.height * k);
    cairo_save(cr.get());
    cairo_scale(cr.get(), k, k);
    drawPage(cr.get(), pattern, page, 0.0);
    cairo_restore(cr.get());
    cairo_show_page(cr.get());
  }
  if (const Drawing& assembly = pattern.assembly; assembly.width > 0) {  // the last page
    cairo_pdf_surface_set_size(surface.get(), assembly.width * k, assembly.height * k);
    cairo_save(cr.get());
    cairo_scale(cr.get(), k, k);
    drawDrawing(cr.get(), assembly, 0.0);
    cairo_restore(cr.get());
    cairo_show_page(cr.get());
  }
  cr.reset();
  cairo_surface_finish(surface.get());
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    return cairoError(cairo_surface_status(surface.get()), "pattern.pdf");
  Result<std::string> scaled = withPrintScalingNone(std::move(bytes));
  if (!scaled.isOk()) return scaled;
  return withSpotLayers(std::move(scaled.value()), pattern);
}

namespace {

// The PNG `png` with a pHYs chunk recording `dpi` (as pixels per metre) after its header.
std::string withResolution(std::string png, double dpi) {
  auto crc32 = [](const std::string& bytes) {
    unsigned long crc = 0xFFFFFFFFul;
    for (unsigned char c : bytes) {
      crc ^= c;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320ul & (0ul - (crc & 1ul)));
    }
    return crc ^ 0xFFFFFFFFul;
  };
  auto be32 = [](unsigned long v) {
    return std::string{char((v >> 24) & 0xFF), char((v >> 16) & 0xFF), char((v >> 8) & 0xFF),
                       char(v & 0xFF)};
  };
  const unsigned long perMetre = static_cast<unsigned long>(std::lround(dpi / 0.0254));
  const std::string chunk = "pHYs" + be32(perMetre) + be32(perMetre) + std::string(1, '\1');
  constexpr std::size_t kAfterHeader = 8 + 4 + 4 + 13 + 4;  // signature, IHDR chunk
  png.insert(kAfterHeader, be32(9) + chunk + be32(crc32(chunk)));
  return png;
}

}  // namespace

Result<std::string> printPng(const PatternBuild& pattern, int pageIndex, double dpi) {
  const PageView& page = pattern.pages[size_t(pageIndex)];
  const Box area = page.printArea;
  const double k = dpi / kMmPerInch;
  const int w = int(std::lround(area.w() * k)), h = int(std::lround(area.h() * k));
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h), cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), cairo_destroy);
  cairo_scale(cr.get(), k, k);
  cairo_translate(cr.get(), -area.lo.x(), -area.lo.y());
  // Only the pieces, each clipped to its cut line (ticks and tint stop there): the software cuts
  // round the image's opaque pixels, and adds its own bleed. A pattern stamped FAILED GATE keeps
  // the stamp, outside the pieces.
  if (!pattern.failedGate) {
    cairo_new_path(cr.get());
    for (const PieceInfo& piece : pattern.pieces)
      for (const auto* loops : {&piece.cut, &piece.holeCuts})
        for (const Polyline& loop : *loops) {
          if (loop.empty()) continue;
          cairo_move_to(cr.get(), loop[0].x() - page.origin.x(), loop[0].y() - page.origin.y());
          for (const Vec2& q : loop)
            cairo_line_to(cr.get(), q.x() - page.origin.x(), q.y() - page.origin.y());
          cairo_close_path(cr.get());
        }
    cairo_set_fill_rule(cr.get(), CAIRO_FILL_RULE_EVEN_ODD);
    cairo_clip(cr.get());
  }
  drawPage(cr.get(), pattern, page, 1.0 / k);
  cr.reset();
  std::string bytes;
  const cairo_status_t status =
      cairo_surface_write_to_png_stream(surface.get(), appendToString, &bytes);
  if (status != CAIRO_STATUS_SUCCESS) return cairoError(status, "the print's PNG");
  return withResolution(std::move(bytes), dpi);
}

Result<std::string> pngImage(const PatternBuild& pattern, int pageIndex, double dpi) {
  const bool assembly = pageIndex == int(pattern.pages.size()) && pattern.assembly.width > 0;
  const int pages = int(pattern.pages.size()) + (pattern.assembly.width > 0 ? 1 : 0);
  if (pageIndex < 0 || pageIndex >= pages)
    return Status{ErrorCode::Usage, "page " + std::to_string(pageIndex + 1) + " does not exist (" +
                                        std::to_string(pages) + " pages)"};
  if (!(dpi >= 10 && dpi <= 1200)) return Status{ErrorCode::Usage, "dpi must be in 10..1200"};
  const double pageW = assembly ? pattern.assembly.width : pattern.pages[size_t(pageIndex)].width;
  const double pageH = assembly ? pattern.assembly.height : pattern.pages[size_t(pageIndex)].height;
  const double k = dpi / kMmPerInch;
  const int w = int(std::ceil(pageW * k)), h = int(std::ceil(pageH * k));
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h), cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  cairo_scale(cr.get(), k, k);
  if (assembly)  // hairlines: one pixel
    drawDrawing(cr.get(), pattern.assembly, 1.0 / k);
  else
    drawPage(cr.get(), pattern, pattern.pages[size_t(pageIndex)], 1.0 / k);
  cr.reset();
  std::string bytes;
  const cairo_status_t status =
      cairo_surface_write_to_png_stream(surface.get(), appendToString, &bytes);
  if (status != CAIRO_STATUS_SUCCESS) return cairoError(status, "PNG preview");
  return bytes;
}

}  // namespace dform::fab
