// SPDX-License-Identifier: GPL-3.0-or-later
#include "plot.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

namespace {

const double width = 380, height = 260, left = 60, top = 30, gap = 90;

// Where v lies along the axis: 0 at its start, 1 at its end.
double along(const PlotAxis& axis, double v) {
  if (axis.logMin > 0) return std::log10(v / axis.logMin) / std::log10(axis.max / axis.logMin);
  return v / axis.max;
}

// The axis' grid lines and their labels.
std::vector<std::pair<double, std::string>> ticks(const PlotAxis& axis) {
  std::vector<std::pair<double, std::string>> out;
  if (axis.logMin > 0) {
    const long first = std::lround(std::log10(axis.logMin)),
               last = std::lround(std::log10(axis.max));
    for (long e = first; e <= last; ++e)
      out.emplace_back(std::pow(10.0, double(e)), "1e" + std::to_string(e));
    return out;
  }
  for (int k = 0; k <= 5; ++k) {
    std::ostringstream label;
    label << axis.max * k / 5 << axis.tickSuffix;
    out.emplace_back(axis.max * k / 5, label.str());
  }
  return out;
}

void writePanel(std::ostream& svg, double x0, const PlotPanel& p) {
  const double right = x0 + width, bottom = top + height;
  auto px = [&](double v) { return x0 + along(p.x, v) * width; };
  auto py = [&](double v) { return bottom - along(p.y, v) * height; };
  svg << "<text x='" << x0 + width / 2 << "' y='" << top - 10
      << "' text-anchor='middle' font-weight='bold'>" << p.title << "</text>\n";
  for (const auto& [v, label] : ticks(p.x))
    svg << "<line x1='" << px(v) << "' y1='" << bottom << "' x2='" << px(v) << "' y2='" << top
        << "' stroke='#eee'/><text x='" << px(v) << "' y='" << bottom + 16
        << "' text-anchor='middle'>" << label << "</text>\n";
  for (const auto& [v, label] : ticks(p.y))
    svg << "<line x1='" << x0 << "' y1='" << py(v) << "' x2='" << right << "' y2='" << py(v)
        << "' stroke='#eee'/><text x='" << x0 - 6 << "' y='" << py(v) + 4 << "' text-anchor='end'>"
        << label << "</text>\n";
  svg << "<text x='" << x0 + width / 2 << "' y='" << bottom + 34 << "' text-anchor='middle'>"
      << p.x.label << "</text><text x='" << x0 - 48 << "' y='" << top + height / 2
      << "' transform='rotate(-90 " << x0 - 48 << " " << top + height / 2
      << ")' text-anchor='middle'>" << p.y.label << "</text>\n";
  const char* goalStyle = "' stroke='#c00' stroke-dasharray='6 4'/>";
  if (p.goalY > 0 && along(p.y, p.goalY) <= 1)
    svg << "<line x1='" << x0 << "' y1='" << py(p.goalY) << "' x2='" << right << "' y2='"
        << py(p.goalY) << goalStyle << "<text x='" << right << "' y='" << py(p.goalY) - 4
        << "' text-anchor='end' fill='#c00'>goal</text>\n";
  if (p.goalX > 0 && along(p.x, p.goalX) <= 1)
    svg << "<line x1='" << px(p.goalX) << "' y1='" << bottom << "' x2='" << px(p.goalX) << "' y2='"
        << top << goalStyle << "<text x='" << px(p.goalX) + 4 << "' y='" << top + 14
        << "' fill='#c00'>goal</text>\n";
  for (const PlotSeries& s : p.series) {
    std::string points;
    for (std::size_t i = 0; i < s.x.size(); ++i)
      points += std::to_string(px(s.x[i])) + "," + std::to_string(py(s.y[i])) + " ";
    svg << "<polyline points='" << points << "' fill='none' stroke='" << s.colour
        << "' stroke-width='2'/>\n";
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      svg << "<circle cx='" << px(s.x[i]) << "' cy='" << py(s.y[i]) << "' r='3.5' fill='"
          << s.colour << "'/>\n";
      if (i < s.labels.size())
        svg << "<text x='" << px(s.x[i]) + 6 << "' y='" << py(s.y[i]) - 6
            << "' font-size='10' fill='" << s.colour << "'>" << s.labels[i] << "</text>\n";
    }
  }
  svg << "<rect x='" << x0 << "' y='" << top << "' width='" << width << "' height='" << height
      << "' fill='none' stroke='#333'/>\n";
}

}  // namespace

bool writePlot(const std::string& path, const std::vector<PlotPanel>& panels) {
  const double count = double(panels.size());
  std::ofstream svg(path);
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='"
      << count * width + (count - 1) * gap + 2 * left << "' height='" << height + 2 * top + 40
      << "' font-family='sans-serif' font-size='12'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";
  for (std::size_t i = 0; i < panels.size(); ++i)
    writePanel(svg, left + double(i) * (width + gap), panels[i]);
  double x = left;
  for (const PlotSeries& s : panels.front().series) {
    svg << "<text x='" << x << "' y='" << top + height + 54 << "' fill='" << s.colour << "'>"
        << s.legend << "</text>";
    x += 200;
  }
  svg << "\n</svg>\n";
  return bool(svg);
}
