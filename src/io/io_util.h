// SPDX-License-Identifier: GPL-3.0-or-later
// Internal helpers shared by the io readers and writers: number formatting for messages and files,
// unit names. Not part of the public io API.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "dform/core/status.h"

namespace dform::io_detail {

/// Consecutive points closer than this (mm) are one point: a nanometre is far below any cutting
/// precision and far above double rounding of coordinates up to the readers' coordinate limit.
constexpr double kSamePointMm = 1e-9;

/// P (#P by 2) without points within kSamePointMm of the previous one (and, when `closed`, without
/// last points that repeat the first).
Eigen::Matrix<double, Eigen::Dynamic, 2> dropRepeatedPoints(
    const Eigen::Matrix<double, Eigen::Dynamic, 2>& P, bool closed);
/// Lower-case extension without the dot ("svg"), empty when there is none.
std::string lowerExtension(const std::string& path);

/// Short human-readable number for messages: "3.2", "0.00012", "1.5e+07".
std::string fmt(double value);

/// "(x, y)" or "(x, y, z)" with fmt() numbers.
std::string fmtPoint(const Eigen::Ref<const Eigen::RowVectorXd>& p);

/// The smallest outline, hole or seam curve read, as the diagonal of its bounding box (mm). A
/// smaller one is nothing a sheet can be cut to (a seam curve 0.2 um across would give a pattern
/// of tabs wider than its pieces), and at the closing tolerance (0.01 mm) its drawn shape is no
/// longer kept (a 0.01 mm square closes into a triangle): refused, not reshaped.
constexpr double kMinShapeSizeMm = 1.0;

/// InputInvalid for a file over its point limit (OutlineReadOptions::maxPoints,
/// CurveReadOptions::maxPoints): "<path>: <what> more than <limit> points (the limit)".
Status tooManyPoints(const std::string& path, const std::string& what, std::size_t limit);

/// Shortest decimal text that reads back to exactly `value` (locale-independent).
std::string exactDecimal(double value);

/// Parses a whole token as a double, locale-independently (accepts a leading '+').
std::optional<double> parseDouble(const std::string& token);

/// Whether `token` is a whole number that no double holds: too large ("1e999") or too small to
/// be told from zero ("1e-999"). OBJ and JSON files refuse both alike (InputInvalid).
bool isOutOfRangeNumber(const std::string& token);

/// Why an out-of-range number (isOutOfRangeNumber) is refused, for the message "'TOKEN' is out of
/// range (REASON)": too large for a double ("1e999": coordinates must be finite) or too close to
/// zero to hold ("1e-999").
std::string outOfRangeReason(const std::string& token);

/// Millimetres per unit for the unit names accepted in JSON files ("mm", "cm", "in"); nullopt if
/// the name is unknown.
std::optional<double> millimetresPerUnit(const std::string& unit);

/// The first coordinate of P (#P by d) that is NaN, infinite or larger than `maxCoordinate` in
/// magnitude, as (row, column); nullopt if all are fine.
std::optional<std::pair<Eigen::Index, Eigen::Index>> findBadCoordinate(const Eigen::MatrixXd& P,
                                                                       double maxCoordinate);

/// Message text for a coordinate found by findBadCoordinate: "is not a number" / "is too large
/// (...)".
std::string describeBadCoordinate(double value, double maxCoordinate);

}  // namespace dform::io_detail
