// SPDX-License-Identifier: GPL-3.0-or-later
// Small helpers shared by the report's SVG pictures (inline SVG, pixel units).
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

namespace dform::svg {

/// A coordinate with one decimal: a tenth of a pixel is below what a screen shows.
inline std::string number(double v) {
  char text[32];  // to_chars: printf's "%.1f" digits, without its locale and format parsing
  const auto end = std::to_chars(text, text + sizeof text, v, std::chars_format::fixed, 1).ptr;
  return std::string(text, end);
}

/// "#rrggbb" from components in [0, 1].
inline std::string hexColour(double r, double g, double b) {
  char text[8];
  auto c = [](double v) { return int(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); };
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c(r), c(g), c(b));
  return text;
}

/// The opening tag of a picture `width` x `height` pixels, its user units the pixels.
inline std::string open(double width, double height) {
  return "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 " + number(width) + " " +
         number(height) + "' width='" + number(width) + "' height='" + number(height) + "'>";
}

}  // namespace dform::svg
