// SPDX-License-Identifier: GPL-3.0-or-later
#include "svg_viewport.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>
#include <utility>

#include "dform/core/message_text.h"
#include "io_util.h"

namespace dform::io_detail {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

std::optional<std::string_view> attributeValue(const XmlNode* node, std::string_view localName) {
  for (auto* a = node->first_attribute(); a; a = a->next_attribute())
    if (std::string_view(a->local_name(), a->local_name_size()) == localName)
      return std::string_view(a->value(), a->value_size());
  return std::nullopt;
}

std::optional<double> lengthInMillimetres(std::optional<std::string_view> text) {
  if (!text) return std::nullopt;
  std::string_view s = trim(*text);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double number = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), number);
  if (ec != std::errc()) return std::nullopt;
  const std::string_view unit = trim(std::string_view(end, std::size_t(s.data() + s.size() - end)));
  static const std::map<std::string_view, double> kMillimetresPer = {
      {"", kMillimetresPerPx}, {"px", kMillimetresPerPx}, {"mm", 1.0}, {"cm", 10.0}, {"in", 25.4},
      {"pt", 25.4 / 72.0},     {"pc", 25.4 / 6.0}};
  const auto it = kMillimetresPer.find(unit);
  if (it == kMillimetresPer.end() || !std::isfinite(number)) return std::nullopt;
  return number * it->second;
}

std::optional<std::array<double, 4>> parseViewBox(std::optional<std::string_view> text) {
  if (!text) return std::nullopt;
  std::array<double, 4> box{};
  const char* p = text->data();
  const char* end = p + text->size();
  for (double& value : box) {
    while (p != end && (*p == ' ' || *p == ',' || *p == '\t' || *p == '\r' || *p == '\n')) ++p;
    if (p != end && *p == '+') ++p;
    const auto result = std::from_chars(p, end, value);
    if (result.ec != std::errc() || !std::isfinite(value)) return std::nullopt;
    p = result.ptr;
  }
  return box;
}

std::optional<std::string> nonFiniteNumber(const std::string& text) {
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t start = text.find_first_not_of(" \t\r\n,()", at);
    if (start == std::string::npos) break;
    at = std::min(text.find_first_of(" \t\r\n,()", start), text.size());
    const std::string token = text.substr(start, at - start);
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    // A unit may follow ("1e999mm").
    const bool unitOnly =
        std::all_of(static_cast<const char*>(end), token.c_str() + token.size(),
                    [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '%'; });
    if (end != token.c_str() && unitOnly && !std::isfinite(value)) return token;
  }
  return std::nullopt;
}

Result<RootViewport> rootViewport(const XmlNode* svg) {
  for (const char* name : {"width", "height", "viewBox"})
    if (const auto text = attributeValue(svg, name))
      if (const auto token = nonFiniteNumber(std::string(*text)))
        return Status{ErrorCode::InputInvalid,
                      "has a non-finite number '" + *token + "' in its '" + name + "' attribute"};
  // A root size in a unit that is not a length (a typo, "300furlong", or a percentage of a
  // viewport the file does not have) gives no size in mm: refused like an element's unknown unit,
  // not read as px.
  for (const char* name : {"width", "height"})
    if (const auto text = attributeValue(svg, name); text && !lengthInMillimetres(text))
      return Status{ErrorCode::InputUnreadable,
                    "has an unknown unit in its '" + std::string(name) + "' attribute '" +
                        printable(*text) + "' (units: mm, cm, in, pt, pc, px or none for px)"};
  const std::optional<double> width = lengthInMillimetres(attributeValue(svg, "width"));
  const std::optional<double> height = lengthInMillimetres(attributeValue(svg, "height"));
  // SVG gives a negative root size no meaning (a drawing would be mirrored) and a zero one
  // disables rendering: refused by name rather than drawn mirrored or read as no shape.
  for (const auto& [name, size] : {std::pair{"width", width}, std::pair{"height", height}})
    if (size && !(*size > 0.0))
      return Status{ErrorCode::InputInvalid,
                    "has a root '" + std::string(name) + "' of " +
                        printable(std::string(*attributeValue(svg, name))) +
                        ": a drawing's size must be positive"};
  const auto viewBoxText = attributeValue(svg, "viewBox");
  const auto box = parseViewBox(viewBoxText);
  RootViewport vp;
  if (viewBoxText && !box) return Status{ErrorCode::InputUnreadable, "has a malformed viewBox"};
  if (!box) {
    vp.userToPage.linear *= kMillimetresPerPx;
    vp.pageHeight = height;
    if (width && height)
      vp.userViewportSize = {*width / kMillimetresPerPx, *height / kMillimetresPerPx};
    return vp;
  }
  const double bx = (*box)[0], by = (*box)[1], bw = (*box)[2], bh = (*box)[3];
  if (!(bw > 0.0 && bh > 0.0))
    return Status{ErrorCode::InputInvalid, "has a viewBox of zero or negative size"};
  vp.userViewportSize = {bw, bh};
  double sx = kMillimetresPerPx, sy = kMillimetresPerPx, dx = 0.0, dy = 0.0;
  if (width && height) {
    sx = *width / bw;
    sy = *height / bh;
    const std::string_view aspect = trim(attributeValue(svg, "preserveAspectRatio").value_or(""));
    if (aspect.find("none") == std::string_view::npos) {
      const double s =
          aspect.find("slice") != std::string_view::npos ? std::max(sx, sy) : std::min(sx, sy);
      auto align = [&](std::string_view minName, std::string_view maxName) {
        if (aspect.find(minName) != std::string_view::npos) return 0.0;
        if (aspect.find(maxName) != std::string_view::npos) return 1.0;
        return 0.5;  // xMidYMid is the default
      };
      dx = align("xMin", "xMax") * (*width - s * bw);
      dy = align("YMin", "YMax") * (*height - s * bh);
      sx = sy = s;
    }
  } else if (width) {
    sx = sy = *width / bw;  // the missing height follows the viewBox aspect ratio
  } else if (height) {
    sx = sy = *height / bh;
  }
  vp.userToPage.linear = Eigen::Vector2d(sx, sy).asDiagonal();
  vp.userToPage.offset = {dx - sx * bx, dy - sy * by};
  vp.pageHeight = height ? *height : sy * bh;
  return vp;
}

int elementDepth(const std::string& text) {
  int depth = 0, deepest = 0;
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (text[i] != '<') continue;
    auto skipTo = [&](const char* terminator) {
      const std::size_t end = text.find(terminator, i);
      i = end == std::string::npos ? n : end;
    };
    if (text.compare(i, 4, "<!--") == 0) {
      skipTo("-->");
      continue;
    }
    if (text.compare(i, 9, "<![CDATA[") == 0) {
      skipTo("]]>");
      continue;
    }
    if (i + 1 < n && (text[i + 1] == '?' || text[i + 1] == '!')) {
      skipTo(">");
      continue;
    }
    if (i + 1 < n && text[i + 1] == '/') {
      --depth;
      skipTo(">");
      continue;
    }
    char quote = 0;  // inside a start tag: find its end outside quoted values
    std::size_t j = i + 1;
    for (; j < n; ++j) {
      if (quote) {
        if (text[j] == quote) quote = 0;
      } else if (text[j] == '"' || text[j] == '\'')
        quote = text[j];
      else if (text[j] == '>')
        break;
    }
    const bool selfClosing = j < n && text[j - 1] == '/';
    if (!selfClosing) deepest = std::max(deepest, ++depth);
    i = j;
  }
  return deepest;
}

}  // namespace dform::io_detail
