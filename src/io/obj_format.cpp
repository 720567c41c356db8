// SPDX-License-Identifier: GPL-3.0-or-later
#include "obj_format.h"

#include <charconv>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>

#include "dform/core/message_text.h"
#include "io_util.h"

namespace dform::io_detail {
namespace {

/// The vertex part of an index token ("7", "-2", "7/3/1", "7//1"); nullopt if it is not a
/// non-zero integer.
std::optional<long> vertexIndex(const std::string& token) {
  const std::size_t slash = token.find('/');
  const char* first = token.data();
  const char* last = first + (slash == std::string::npos ? token.size() : slash);
  long value = 0;
  const auto [end, ec] = std::from_chars(first + (first != last && *first == '+'), last, value);
  if (ec != std::errc() || end != last || value == 0) return std::nullopt;
  return value;
}

// The whitespace-separated words of a line (what `>>` reads from a stream of it, in the "C"
// locale), without a stream per line: a result at resolution 1000 has 560k lines.
class Words {
 public:
  explicit Words(const std::string& line) : line_(line) {}
  bool next(std::string& word) {
    while (at_ < line_.size() && isSpace(line_[at_])) ++at_;
    if (at_ == line_.size()) return false;
    const std::size_t start = at_;
    while (at_ < line_.size() && !isSpace(line_[at_])) ++at_;
    word.assign(line_, start, at_ - start);
    return true;
  }

 private:
  static bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
  }
  const std::string& line_;
  std::size_t at_ = 0;
};

}  // namespace

Result<ObjData> parseObj(const std::string& path, const std::string& text,
                         std::size_t maxVertices) {
  ObjData obj;
  std::istringstream lines(text);
  std::string line;
  int lineNumber = 0;
  std::string group;
  auto malformed = [&](const std::string& what) {
    return Status{ErrorCode::InputUnreadable,
                  path + ": line " + std::to_string(lineNumber) + ": " + what};
  };
  auto tooMany = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, path + ": line " + std::to_string(lineNumber) +
                                               ": more than " + std::to_string(maxVertices) + " " +
                                               what + " (the limit)"};
  };
  while (std::getline(lines, line)) {
    ++lineNumber;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    Words tokens(line);
    std::string keyword, token;
    if (!tokens.next(keyword)) continue;
    if (keyword == "g") {
      if (!tokens.next(group)) group.clear();
    } else if (keyword == "v") {
      Eigen::Vector3d v;
      int count = 0;
      while (tokens.next(token)) {
        const std::optional<double> value = parseDouble(token);
        if (!value && isOutOfRangeNumber(token))  // "1e999", "1e-999": no double holds them
          return Status{ErrorCode::InputInvalid,
                        path + ": line " + std::to_string(lineNumber) + ": '" + printable(token) +
                            "' is out of range (" + outOfRangeReason(token) + ")"};
        if (!value) return malformed("'" + printable(token) + "' is not a number");
        if (count < 3) v(count) = *value;
        ++count;
      }
      if (count < 3 || count > 4) return malformed("a vertex needs x y z (and optionally w)");
      if (obj.vertices.size() == maxVertices) return tooMany("vertices");
      obj.vertices.push_back(v);
    } else if (keyword == "f" || keyword == "l") {
      ObjElement element;
      element.lineNumber = lineNumber;
      element.group = group;
      while (tokens.next(token)) {
        const std::optional<long> index = vertexIndex(token);
        if (!index)
          return malformed("'" + printable(token) + "' is not a vertex index (they start at 1)");
        // Negative indices count back from the newest vertex; positive ones are checked below,
        // once every vertex is known.
        const long resolved = *index < 0 ? long(obj.vertices.size()) + *index : *index - 1;
        if (resolved < 0) return malformed("index " + printable(token) + " refers to no vertex");
        if (resolved > std::numeric_limits<int>::max())
          return malformed("index " + printable(token) + " is too large");
        if (element.indices.size() > maxVertices) return tooMany("points in one element");
        element.indices.push_back(int(resolved));
      }
      const std::size_t needed = keyword == "f" ? 3 : 2;
      if (element.indices.size() < needed)
        return malformed(keyword == "f" ? "a face needs at least 3 vertices"
                                        : "a polyline needs at least 2 vertices");
      (keyword == "f" ? obj.faces : obj.lines).push_back(std::move(element));
    }
  }
  for (const auto* elements : {&obj.faces, &obj.lines})
    for (const ObjElement& e : *elements)
      for (int i : e.indices)
        if (std::size_t(i) >= obj.vertices.size()) {
          lineNumber = e.lineNumber;
          return malformed("vertex index " + std::to_string(std::int64_t(i) + 1) +
                           " is out of range (the file has " + std::to_string(obj.vertices.size()) +
                           " vertices)");
        }
  return obj;
}

}  // namespace dform::io_detail
