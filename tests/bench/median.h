// SPDX-License-Identifier: GPL-3.0-or-later
// The figure a bench row reports for a time: the median of its repeats, so that a neighbour's
// load on the shared machine shows up as spread, not as the figure.
#pragma once

#include <algorithm>
#include <vector>

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
