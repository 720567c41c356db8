// SPDX-License-Identifier: GPL-3.0-or-later
// The cutting SVG, written by hand: millimetre page (1 user unit = 1 mm), one Inkscape layer per
// operation, an id on every path, inline hex styles repeated as presentation attributes (VisiCut
// ignores CSS classes; early LaserGRBL read only style=""). Paths use absolute M/L/Z only.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <sstream>

#include "dform/core/message_text.h"
#include "internal.h"

namespace dform::fab {

namespace {

std::string num(double x) {
  char buf[48];  // 0.1 um: far below any cutter's resolution (to_chars: printf's "%.4f" digits)
  std::string s(buf, std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed, 4).ptr);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::string pathData(const Path& p) {
  std::string d;
  for (const Polyline& part : p.parts) {
    if (part.empty()) continue;
    for (size_t i = 0; i < part.size(); ++i) {
      d += (d.empty() ? "" : " ");
      d += (i == 0 ? "M " : "L ") + num(part[i].x()) + " " + num(part[i].y());
    }
    if (p.closed) d += " Z";
  }
  return d;
}

}  // namespace

std::string svgDocument(const Drawing& drawing) {
  std::ostringstream s;
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\"\n"
    << "     xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\"\n"
    << "     version=\"1.1\" width=\"" << num(drawing.width) << "mm\" height=\""
    << num(drawing.height) << "mm\" viewBox=\"0 0 " << num(drawing.width) << " "
    << num(drawing.height) << "\">\n"
    << "  <title>" << escapeXml(drawing.title) << "</title>\n"
    << "  <desc>" << escapeXml(drawing.description) << "</desc>\n";
  for (const Layer& layer : drawing.layers) {
    // A spot colour names its layer (a RIP's CutContour, in the cutter's layer list).
    const std::string& label = layer.spot.empty() ? layer.name : layer.spot;
    s << "  <g inkscape:groupmode=\"layer\" inkscape:label=\"" << escapeXml(label)
      << "\" id=\"layer-" << escapeXml(label) << "\">\n";
    for (const Path& p : layer.paths) {
      const std::string d = pathData(p);
      if (d.empty()) continue;
      std::string style, attributes;
      if (p.filled) {
        const std::string& color = p.fill.empty() ? layer.color : p.fill;
        const std::string stroke = p.sealed ? color : "none";
        style = "fill:" + color + ";stroke:" + stroke;
        attributes = "fill=\"" + color + "\" stroke=\"" + stroke + "\"";
        if (p.sealed) {
          style += ";stroke-width:" + num(layer.widthMm) + ";stroke-linejoin:round";
          attributes += " stroke-width=\"" + num(layer.widthMm) + "\"";
        }
      } else {
        style = "fill:none;stroke:" + layer.color + ";stroke-width:" + num(layer.widthMm) +
                ";stroke-linecap:round;stroke-linejoin:round";
        attributes = "fill=\"none\" stroke=\"" + layer.color + "\" stroke-width=\"" +
                     num(layer.widthMm) + "\"";
        if (p.dashed) {
          const std::vector<double> pattern =
              p.dash.empty() ? std::vector<double>{layer.dashMm, layer.dashMm} : p.dash;
          std::string dashes;
          for (double length : pattern) dashes += (dashes.empty() ? "" : ",") + num(length);
          style += ";stroke-dasharray:" + dashes;
          attributes += " stroke-dasharray=\"" + dashes + "\"";
        }
      }
      s << "    <path id=\"" << escapeXml(p.id) << "\" style=\"" << style << "\" " << attributes
        << " d=\"" << d << "\"/>\n";
    }
    s << "  </g>\n";
  }
  s << "</svg>\n";
  return s.str();
}

std::string cutSvg(const PatternBuild& pattern, int pageIndex) {
  const PageView& page = pattern.pages[size_t(pageIndex)];
  const Box area = Box::spanning(page.origin + page.printArea.lo, page.origin + page.printArea.hi);
  Drawing cut = pattern.drawing;
  cut.layers.erase(std::remove_if(cut.layers.begin(), cut.layers.end(),
                                  [](const Layer& layer) { return layer.name != "Cut"; }),
                   cut.layers.end());
  cut.description += "; the cut line alone, in the frame of the print's PNG";
  return svgDocument(sheetDrawing(cut, area));
}

Drawing sheetDrawing(const Drawing& drawing, const Box& sheet) {
  Drawing out = drawing;
  out.width = sheet.w();
  out.height = sheet.h();
  // Every path lies inside one sheet (the layout check counts any that does not); 1e-6 mm is
  // rounding on coordinates of a few metres.
  for (Layer& layer : out.layers) {
    std::vector<Path> kept;
    for (Path& path : layer.paths) {
      if (!sheet.contains(boxOf(path.parts), 1e-6)) continue;
      for (Polyline& part : path.parts)
        for (Vec2& q : part) q -= sheet.lo;
      kept.push_back(std::move(path));
    }
    layer.paths = std::move(kept);
  }
  return out;
}

}  // namespace dform::fab
