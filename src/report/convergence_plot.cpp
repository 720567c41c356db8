// SPDX-License-Identifier: GPL-3.0-or-later
#include "convergence_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "svg_text.h"

namespace dform {

std::string convergencePlotSvg(const std::vector<PlotSeries>& series, double widthPx,
                               double heightPx) {
  // Colour-blind-safe palette (Okabe & Ito) for the terms; the total is black.
  static const char* const kPalette[] = {"#E69F00", "#56B4E9", "#009E73", "#D55E00",
                                         "#0072B2", "#CC79A7", "#999999", "#F0E442"};
  double xMax = 1.0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const PlotSeries& s : series)
    for (const auto& [x, y] : s.points) {
      xMax = std::max(xMax, x);
      if (y > 0 && std::isfinite(y)) {
        lo = std::min(lo, std::log10(y));
        hi = std::max(hi, std::log10(y));
      }
    }
  std::string out =
      svg::open(widthPx, heightPx) + "<rect width='100%' height='100%' fill='white'/>";
  if (!std::isfinite(lo))
    return out +
           "<text x='10' y='20' font-size='12' fill='#555'>no positive objective to "
           "plot</text></svg>";
  const double decadeLo = std::floor(lo), decadeHi = std::max(std::ceil(hi), decadeLo + 1);
  const double left = 56, right = widthPx - 120, top = 10, bottom = heightPx - 34;
  auto px = [&](double x) { return left + (right - left) * x / xMax; };
  auto py = [&](double y) {
    return bottom - (bottom - top) * (std::log10(y) - decadeLo) / (decadeHi - decadeLo);
  };

  // Decades: a grid line and a label each (at most ~8 labels, so long spans step by more).
  const int step = std::max(1, int(std::ceil((decadeHi - decadeLo) / 8)));
  for (int d = int(decadeLo); d <= int(decadeHi); d += step) {
    const std::string y = svg::number(py(std::pow(10.0, d)));
    out += "<line x1='" + svg::number(left) + "' x2='" + svg::number(right) + "' y1='" + y +
           "' y2='" + y + "' stroke='#e0e0e0'/><text x='" + svg::number(left - 6) + "' y='" + y +
           "' font-size='11' text-anchor='end' dominant-baseline='middle' fill='#444'>1e" +
           std::to_string(d) + "</text>";
  }
  const int xStep = std::max(1, int(std::ceil(xMax / 10)));
  for (int i = 0; i <= int(xMax); i += xStep)
    out += "<text x='" + svg::number(px(i)) + "' y='" + svg::number(bottom + 16) +
           "' font-size='11' text-anchor='middle' fill='#444'>" + std::to_string(i) + "</text>";
  out += "<rect x='" + svg::number(left) + "' y='" + svg::number(top) + "' width='" +
         svg::number(right - left) + "' height='" + svg::number(bottom - top) +
         "' fill='none' stroke='#888'/>";
  out += "<text x='" + svg::number((left + right) / 2) + "' y='" + svg::number(heightPx - 4) +
         "' font-size='12' text-anchor='middle' fill='#222'>iteration</text>";

  for (std::size_t k = 0; k < series.size(); ++k) {
    const std::string colour = k == 0 ? "#000000" : kPalette[(k - 1) % std::size(kPalette)];
    std::string line;
    for (const auto& [x, y] : series[k].points)
      if (y > 0 && std::isfinite(y)) line += svg::number(px(x)) + "," + svg::number(py(y)) + " ";
    if (!line.empty())
      out += "<polyline points='" + line + "' fill='none' stroke='" + colour + "' stroke-width='" +
             (k == 0 ? "2.5" : "1.5") + "'/>";
    const std::string ly = svg::number(top + 8 + 16 * double(k));
    out += "<line x1='" + svg::number(right + 10) + "' x2='" + svg::number(right + 28) + "' y1='" +
           ly + "' y2='" + ly + "' stroke='" + colour + "' stroke-width='2'/><text x='" +
           svg::number(right + 32) + "' y='" + ly +
           "' font-size='11' dominant-baseline='middle' fill='#222'>" + series[k].name + "</text>";
  }
  return out + "</svg>";
}

}  // namespace dform
