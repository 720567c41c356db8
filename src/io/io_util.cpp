// SPDX-License-Identifier: GPL-3.0-or-later
#include "io_util.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace dform::io_detail {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

Eigen::Matrix<double, Eigen::Dynamic, 2> dropRepeatedPoints(
    const Eigen::Matrix<double, Eigen::Dynamic, 2>& P, bool closed) {
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    if (keep.empty() || (P.row(i) - P.row(keep.back())).norm() > kSamePointMm) keep.push_back(i);
  while (closed && keep.size() > 1 &&
         (P.row(keep.back()) - P.row(keep.front())).norm() <= kSamePointMm)
    keep.pop_back();
  Eigen::Matrix<double, Eigen::Dynamic, 2> out(Eigen::Index(keep.size()), 2);
  for (std::size_t k = 0; k < keep.size(); ++k) out.row(Eigen::Index(k)) = P.row(keep[k]);
  return out;
}

std::string fmt(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

std::string fmtPoint(const Eigen::Ref<const Eigen::RowVectorXd>& p) {
  std::string text = "(";
  for (Eigen::Index i = 0; i < p.size(); ++i) text += (i ? ", " : "") + fmt(p(i));
  return text + ")";
}

Status tooManyPoints(const std::string& path, const std::string& what, std::size_t limit) {
  return {ErrorCode::InputInvalid,
          path + ": " + what + " more than " + std::to_string(limit) + " points (the limit)"};
}

std::string exactDecimal(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::optional<double> parseDouble(const std::string& token) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+') ++begin;
  double value = 0.0;
  const auto result = std::from_chars(begin, end, value);
  if (result.ec != std::errc() || result.ptr != end) return std::nullopt;
  return value;
}

bool isOutOfRangeNumber(const std::string& token) {
  const char* begin = token.data() + (!token.empty() && token[0] == '+');
  double value = 0.0;
  const auto [end, ec] = std::from_chars(begin, token.data() + token.size(), value);
  return ec == std::errc::result_out_of_range && end == token.data() + token.size();
}

std::string outOfRangeReason(const std::string& token) {
  return std::isinf(std::strtod(token.c_str(), nullptr))
             ? "too large for a number: coordinates must be finite"
             : "too close to zero to be held as a number: write 0";
}

std::optional<double> millimetresPerUnit(const std::string& unit) {
  if (unit == "mm") return 1.0;
  if (unit == "cm") return 10.0;
  if (unit == "in") return 25.4;
  return std::nullopt;
}

std::optional<std::pair<Eigen::Index, Eigen::Index>> findBadCoordinate(const Eigen::MatrixXd& P,
                                                                       double maxCoordinate) {
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    for (Eigen::Index j = 0; j < P.cols(); ++j)
      if (!(std::abs(P(i, j)) <= maxCoordinate)) return std::make_pair(i, j);  // NaN fails too
  return std::nullopt;
}

std::string describeBadCoordinate(double value, double maxCoordinate) {
  if (std::isnan(value)) return "is not a number";
  if (std::isinf(value)) return "is infinite";
  return "is too large (" + fmt(value) + " mm; the limit is " + fmt(maxCoordinate) + " mm)";
}

}  // namespace dform::io_detail
