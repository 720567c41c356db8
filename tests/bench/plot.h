// SPDX-License-Identifier: GPL-3.0-or-later
// The bench's SVG plots (--scale, --accuracy): panels side by side, each with series of points
// against a linear x axis and a linear or logarithmic y axis.
#pragma once

#include <string>
#include <vector>

struct PlotAxis {
  std::string label;
  double max = 1;          ///< the axis runs from 0 to max in five steps, or from logMin to max
  double logMin = 0;       ///< positive: a logarithmic axis, a grid line per decade from here
  std::string tickSuffix;  ///< after each linear tick's number ("k")
};

struct PlotSeries {
  std::string colour, legend;
  std::vector<double> x, y;
  std::vector<std::string> labels;  ///< beside each point; empty for none
};

struct PlotPanel {
  std::string title;
  PlotAxis x, y;
  std::vector<PlotSeries> series;
  double goalX = 0, goalY = 0;  ///< positive: a dashed red line marks the goal there
};

/// Writes the panels side by side into an SVG file at `path`, the first panel's series' legends
/// below them; false when the file cannot be written.
bool writePlot(const std::string& path, const std::vector<PlotPanel>& panels);
