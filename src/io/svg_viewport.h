// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the outermost <svg> element's viewport (width, height, viewBox, preserveAspectRatio)
// as a map from user units to page millimetres, and the attribute and length readers it needs.
// Kept apart from svg_outline.cpp, the one translation unit that includes svgpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <rapidxml_ns/rapidxml_ns.hpp>
#include <string>
#include <string_view>

#include "dform/core/status.h"

namespace dform::io_detail {

using XmlNode = rapidxml_ns::xml_node<char>;

/// Maps user coordinates to page millimetres: p' = linear * p + offset.
struct Affine {
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();

  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const { return linear * p + offset; }
  /// The map that applies `inner` first, then this one.
  Affine then(const Affine& inner) const {
    return {linear * inner.linear, linear * inner.offset + offset};
  }
};

constexpr double kMillimetresPerPx = 25.4 / 96.0;  // CSS pixel: 96 per inch

/// `s` without leading and trailing white space.
std::string_view trim(std::string_view s);

/// The value of `node`'s attribute `localName` (any namespace prefix), if it has one.
std::optional<std::string_view> attributeValue(const XmlNode* node, std::string_view localName);

/// A length in mm ("210mm", "8.5in", "300" = px); nullopt when absent, a percentage or unknown.
std::optional<double> lengthInMillimetres(std::optional<std::string_view> text);

/// The four numbers of a viewBox attribute; nullopt when absent or malformed.
std::optional<std::array<double, 4>> parseViewBox(std::optional<std::string_view> text);

/// The first number in an attribute's text that reads as NaN or infinite ("NaN", "inf", or too
/// large for a double, like "1e999", with or without a unit), if any. SVG's number grammar
/// refuses them, but they are a non-finite coordinate (bad content), not a misspelt one (an
/// unreadable file).
std::optional<std::string> nonFiniteNumber(const std::string& text);

struct RootViewport {
  Affine userToPage;                               // user units to page mm, y down (as SVG draws)
  std::optional<double> pageHeight;                // mm, when the document says how tall it is
  Eigen::Vector2d userViewportSize{100.0, 100.0};  // user units, for percentage lengths
};

/// Implements SVG's viewport rules for the outermost <svg>: a viewBox maps user units onto
/// width x height (preserveAspectRatio honoured); without width/height a user unit is a px.
Result<RootViewport> rootViewport(const XmlNode* svg);

/// Nesting depth of elements, skipping comments, CDATA, processing instructions and quoted
/// attribute values. Conservative: it only has to bound what rapidxml will recurse into.
int elementDepth(const std::string& text);

}  // namespace dform::io_detail
