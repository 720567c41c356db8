// SPDX-License-Identifier: GPL-3.0-or-later
// Professional print-and-cut: the RIP profile's cut line is the CutContour spot colour in
// pattern.pdf (a Separation colour space, named nowhere else, stroking each piece's cut loop and
// nothing else), its SVG cut layer named so; the Cricut profile's print as a 300 dpi PNG (the
// pieces at true size on the raster) with the cut line alone as an SVG of the same frame.
#include <cairo.h>
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>

#include "dform/export/exporter.h"
#include "export/internal.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

using nlohmann::json;

// Every object of the PDF as qpdf shows it, streams decoded.
std::string decodedPdf(const std::string& pdf) {
  const std::string qdf = pdf + ".qdf";
  std::string out;
  EXPECT_EQ(run("qpdf --qdf --object-streams=disable '" + pdf + "' '" + qdf + "'", &out), 0) << out;
  return readText(qdf);
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(ExportPrintAndCut, TheRipsCutLineIsTheCutContourSpotColourAndNothingElse) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = options("print-and-cut-rip");
  const Exported e = exportTo("rip", model, o);
  std::string out;
  ASSERT_EQ(run("qpdf --check '" + e.dir + "/pattern.pdf'", &out), 0) << out;
  // The name once, as a Separation colour space whose tint is drawn in magenta without the ink.
  const std::string decoded = decodedPdf(e.dir + "/pattern.pdf");
  EXPECT_EQ(count(decoded, "CutContour"), 1u) << "CutContour is named once";
  EXPECT_TRUE(std::regex_search(
      decoded, std::regex(R"(/Separation\s+/CutContour\s+/DeviceCMYK\s+(\d+ 0 R|<<))")))
      << "a Separation colour space";
  // In it: each piece's cut loop, and nothing else; no path stroked in its RGB stand-in.
  const std::vector<PdfPath> paths = readPdfPaths(e.dir + "/pattern.pdf");
  std::vector<PdfPath> spot;
  for (const PdfPath& p : paths) {
    if (!p.space.empty()) {
      spot.push_back(p);
      EXPECT_TRUE(p.closed) << "a cut loop is closed";
    } else {
      EXPECT_GT((p.color - Eigen::Vector3d(1, 0, 1)).norm(), 1e-6) << "a magenta RGB path";
    }
  }
  size_t loops = 0;
  for (const SvgPath& cut : e.svg.paths)
    if (cut.layer == "CutContour") {
      ++loops;
      for (const Polyline& loop : cut.parts)
        EXPECT_LT(closestDrawing(spot, loop), 0.01) << cut.id << " in the spot colour";
    }
  EXPECT_EQ(loops, 2u) << "the SVG's cut layer is named CutContour, one loop per piece";
  EXPECT_EQ(spot.size(), loops) << "the spot colour strokes the cut loops and nothing else";
  for (const PdfPath& p : spot) EXPECT_EQ(p.space, spot.front().space);
  // The print reaches the bleed past the cut: 2 mm.
  EXPECT_NEAR(e.sidecar["bleed_mm"].get<double>(), 2.0, 1e-12);
  ASSERT_NE(e.svg.find("A-bleed"), nullptr);
  // A profile without a spot colour writes none.
  const Exported plain = exportTo("plain", model, options("print-and-cut"));
  EXPECT_EQ(count(decodedPdf(plain.dir + "/pattern.pdf"), "Separation"), 0u);
}

// The pixels of `surface` (ARGB32) whose colour is `hex` (within 8 of 255 per channel) and at
// least half opaque: their bounding box in pixels (x0, y0, x1, y1, inclusive), or x0 > x1.
std::array<int, 4> tintBox(cairo_surface_t* surface, const std::string& hex) {
  const unsigned long v = std::stoul(hex.substr(1), nullptr, 16);
  const int r = int((v >> 16) & 0xFF), g = int((v >> 8) & 0xFF), b = int(v & 0xFF);
  const int w = cairo_image_surface_get_width(surface), h = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  std::array<int, 4> box{w, h, -1, -1};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint32_t px = *reinterpret_cast<const uint32_t*>(data + y * stride + 4 * x);
      const int a = int(px >> 24);
      if (a < 128) continue;
      // Premultiplied: the colour is the channel over alpha.
      const int pr = int((px >> 16) & 0xFF) * 255 / a, pg = int((px >> 8) & 0xFF) * 255 / a,
                pb = int(px & 0xFF) * 255 / a;
      if (std::abs(pr - r) > 8 || std::abs(pg - g) > 8 || std::abs(pb - b) > 8) continue;
      box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
    }
  return box;
}

TEST(ExportPrintAndCut, TheCricutsPrintIsA300DpiPngAtTrueSizeWithItsCutLineBeside) {
  const DForm model = ellipseCircleDForm(64, 8, 60, 40);
  const Exported e = exportTo("cricut", model, options("print-and-cut-cricut"));
  const json& pages = e.sidecar["pages"];
  const std::string png = e.dir + "/print-sheet-1.png", cut = e.dir + "/cut-sheet-1.svg";
  // The resolution is recorded: pHYs 11811 pixels per metre (300 dpi) both ways.
  const std::string bytes = readText(png);
  const size_t phys = bytes.find("pHYs");
  ASSERT_NE(phys, std::string::npos);
  auto be32 = [&](size_t at) {
    return (unsigned(uint8_t(bytes[at])) << 24) | (unsigned(uint8_t(bytes[at + 1])) << 16) |
           (unsigned(uint8_t(bytes[at + 2])) << 8) | unsigned(uint8_t(bytes[at + 3]));
  };
  EXPECT_EQ(be32(phys + 4), 11811u);
  EXPECT_EQ(be32(phys + 8), 11811u);
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> image(
      cairo_image_surface_create_from_png(png.c_str()), cairo_surface_destroy);
  ASSERT_EQ(cairo_surface_status(image.get()), CAIRO_STATUS_SUCCESS);
  // The frame: the Print Then Cut area, 6.75 x 9.25 in, and the cut SVG the same size.
  EXPECT_EQ(cairo_image_surface_get_width(image.get()), 2025);
  EXPECT_EQ(cairo_image_surface_get_height(image.get()), 2775);
  const SvgDoc cutDoc = readSvg(cut);
  EXPECT_NEAR(parseMm(cutDoc.width), 171.45, 1e-9);
  EXPECT_NEAR(parseMm(cutDoc.height), 234.95, 1e-9);
  const Vec2 frame((215.9 - 171.45) / 2, (279.4 - 234.95) / 2);  // the area's corner on Letter
  ASSERT_EQ(pages.size(), 1u);
  // Each piece's tint measured on the raster: its box within 0.1 mm of its cut line's (the print
  // stops at the cut line: Design Space cuts round the image and adds its own bleed).
  const double mmPerPixel = 25.4 / 300;
  for (int p = 0; p < 2; ++p) {
    fab::Box bleed;  // the piece as cut
    for (const auto& loop : e.sidecar["pieces"][p]["cut"]) bleed.add(toPolyline(loop));
    const std::array<int, 4> px =
        tintBox(image.get(), p == 0 ? std::string("#FFE6CC") : std::string("#CCE6FF"));
    ASSERT_LE(px[0], px[2]) << "piece " << p << "'s tint is on the print";
    const double measured[4] = {px[0] * mmPerPixel, px[1] * mmPerPixel, (px[2] + 1) * mmPerPixel,
                                (px[3] + 1) * mmPerPixel};
    const double expected[4] = {bleed.lo.x() - frame.x(), bleed.lo.y() - frame.y(),
                                bleed.hi.x() - frame.x(), bleed.hi.y() - frame.y()};
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(measured[k], expected[k], 0.1) << "piece " << p << " edge " << k;
    std::cout << "piece " << p << ": tint " << measured[2] - measured[0] << " x "
              << measured[3] - measured[1] << " mm on the raster, the cut " << bleed.w() << " x "
              << bleed.h() << " mm\n";
    // The cut line in the SVG: the piece's cut loop moved into the frame.
    const SvgPath* loop = cutDoc.find(p == 0 ? "A-cut" : "B-cut");
    ASSERT_NE(loop, nullptr);
    const Polyline drawn = toPolyline(e.sidecar["pieces"][p]["cut"][0]);
    ASSERT_EQ(loop->parts[0].size(), drawn.size());
    for (size_t i = 0; i < drawn.size(); ++i)
      EXPECT_LT((loop->parts[0][i] + frame - drawn[i]).norm(), 1e-3);
  }
  for (const SvgPath& path : cutDoc.paths) EXPECT_EQ(path.layer, "Cut") << path.id;
  // Nothing opaque outside the pieces (no title, no bar): the software cuts round what is.
  std::vector<fab::Box> pieces;
  for (int p = 0; p < 2; ++p) {
    fab::Box b;
    for (const auto& loop : e.sidecar["pieces"][p]["cut"]) b.add(toPolyline(loop));
    pieces.push_back(fab::Box::spanning((b.lo - frame) / mmPerPixel - Vec2::Constant(1),
                                        (b.hi - frame) / mmPerPixel + Vec2::Constant(1)));
  }
  const int stride = cairo_image_surface_get_stride(image.get());
  const unsigned char* data = cairo_image_surface_get_data(image.get());
  int outside = 0;
  for (int y = 0; y < 2775; ++y)
    for (int x = 0; x < 2025; ++x) {
      const uint32_t px = *reinterpret_cast<const uint32_t*>(data + y * stride + 4 * x);
      const Vec2 q(x + 0.5, y + 0.5);
      outside +=
          (px >> 24) > 0 && !std::any_of(pieces.begin(), pieces.end(), [&](const fab::Box& b) {
            return b.contains(fab::Box::spanning(q, q), 0);
          });
    }
  EXPECT_EQ(outside, 0) << "opaque pixels outside the pieces";
}

}  // namespace
}  // namespace dform::test

namespace dform::test {
namespace {

TEST(ExportPrintAndCut, TheSilhouetteMarksAreInPatternJsonAndTheirSettingsOnThePage) {
  const DForm model = ellipseCircleDForm();
  ExportOptions o = options("print-and-cut");
  o.page = "A3";
  const Exported e = exportTo("silhouette", model, o);
  const nlohmann::json& r = e.sidecar["registration"];
  EXPECT_EQ(r["type"], "silhouette");
  EXPECT_EQ(r["style"], "Type 1");
  EXPECT_EQ(r["inset_mm"].get<double>(), 10.0);
  EXPECT_EQ(r["square_mm"].get<double>(), 5.0);
  EXPECT_EQ(r["length_mm"].get<double>(), 20.0);
  EXPECT_EQ(r["thickness_mm"].get<double>(), 0.3);
  // Each mark as drawn in the SVG's Regmarks layer: the square 10 mm in from the top left, the
  // L-marks' corners 10 mm in from the top right and the bottom left.
  const double W = parseMm(e.svg.width), H = parseMm(e.svg.height);
  size_t marks = 0;
  for (const auto& mark : r["marks"]) {
    const SvgPath* drawn = e.svg.find(mark["id"].get<std::string>());
    ASSERT_NE(drawn, nullptr) << mark["id"];
    EXPECT_EQ(drawn->layer, "Regmarks");
    const Polyline lines = toPolyline(mark["lines"][0]);
    ASSERT_EQ(lines.size(), drawn->parts[0].size());
    for (size_t i = 0; i < lines.size(); ++i)
      EXPECT_LT((lines[i] - drawn->parts[0][i]).norm(), 1e-6);
    ++marks;
  }
  EXPECT_EQ(marks, 3u);
  const Polyline square = toPolyline(r["marks"][0]["lines"][0]);
  EXPECT_NEAR(square[0].x(), 10, 1e-9);
  EXPECT_NEAR(square[2].y(), 15, 1e-9);
  const Polyline topRight = toPolyline(r["marks"][1]["lines"][0]);
  EXPECT_NEAR(topRight[1].x(), W - 10, 1e-9);
  EXPECT_NEAR(topRight[1].y(), 10, 1e-9);
  const Polyline bottomLeft = toPolyline(r["marks"][2]["lines"][0]);
  EXPECT_NEAR(bottomLeft[1].x(), 10, 1e-9);
  EXPECT_NEAR(bottomLeft[1].y(), H - 10, 1e-9);
  // The page says how to set Silhouette Studio's marks.
  const fab::PatternBuild built = build(model, o);
  const Result<fab::StrokeFont> font = fab::StrokeFont::load(o.fontPath);
  ASSERT_TRUE(font.isOk());
  bool said = false;
  for (const fab::Layer& layer : built.drawing.layers)
    for (const fab::Path& path : layer.paths)
      said = said ||
             (path.id == "regmark-note" &&
              startsWithText(path, "Silhouette Studio: registration marks Type 1", font.value()));
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace dform::test
