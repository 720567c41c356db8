#include "io/io_util.h"

#include <vector>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

namespace dform::io_detail {

Result<std::string> readInputFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  // A missing file (or a path through a regular file) is no error here, only not found; anything
  // else (a symbolic-link loop, a folder that may not be searched) is said as the system says it.
  if (ec) return Status{ErrorCode::InputUnreadable, path + ": cannot be read (" + ec.message() + ")"};
  if (!fs::exists(status)) return Status{ErrorCode::InputUnreadable, path + ": no such file"};
  if (fs::is_directory(status))
    return Status{ErrorCode::InputUnreadable, path + ": is a folder, not a file"};
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxInputBytes) {
    return Status{ErrorCode::InputUnreadable,
                  path + ": file is too large (" + std::to_string(size >> 20) +
                      " MiB; the limit is " + std::to_string(kMaxInputBytes >> 20) + " MiB)"};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status{ErrorCode::InputUnreadable, path + ": cannot be opened for reading"};
  std::string text;
  // Read at most one byte past the limit so a file that grows (or a pipe) cannot exhaust memory.
  text.reserve(ec ? 0 : std::size_t(size));
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, std::size_t(in.gcount()));
    if (text.size() > kMaxInputBytes) {
      return Status{ErrorCode::InputUnreadable,
                    path + ": file is too large (the limit is " +
                        std::to_string(kMaxInputBytes >> 20) + " MiB)"};
    }
  }
  if (in.bad()) return Status{ErrorCode::InputUnreadable, path + ": read error"};
  return text;
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

Eigen::Matrix<double, Eigen::Dynamic, 2> dropRepeatedPoints(const Eigen::Matrix<double, Eigen::Dynamic, 2>& P,
                                                            bool closed) {
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    if (keep.empty() || (P.row(i) - P.row(keep.back())).norm() > kSamePointMm) keep.push_back(i);
  while (closed && keep.size() > 1 && (P.row(keep.back()) - P.row(keep.front())).norm() <= kSamePointMm)
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
