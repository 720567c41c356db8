// SPDX-License-Identifier: GPL-3.0-or-later
// The solver's convergence plot for report.html: each objective term and the total against the
// iteration, on a logarithmic scale, as inline SVG.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace dform {

struct PlotSeries {
  std::string name;
  std::vector<std::pair<double, double>> points;  ///< (iteration, value); values <= 0 are skipped
};

/// A line plot of `series` (the first drawn thick and black: the total) with a log10 y axis of
/// whole decades, a linear x axis and a legend on the right.
std::string convergencePlotSvg(const std::vector<PlotSeries>& series, double widthPx,
                               double heightPx);

}  // namespace dform
