// SPDX-License-Identifier: GPL-3.0-or-later
#include "json_util.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "dform/core/message_text.h"
#include "io_util.h"

namespace dform::io_detail {

namespace {

// The first number of a JSON text that no double holds ("1e999", "1e-999"), if any: nlohmann
// reads an underflow as 0 and refuses an overflow as a parse error, where OBJ refuses both as out
// of range. Strings are skipped.
std::optional<std::string> outOfRangeNumber(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      const std::size_t end = text.find_first_not_of("0123456789+-.eE", i);
      const std::string token = text.substr(i, end - i);
      if (isOutOfRangeNumber(token)) return token;
      i = std::min(end, text.size()) - 1;
    }
  }
  return std::nullopt;
}

}  // namespace

Result<nlohmann::json> parseJson(const std::string& path, const std::string& text,
                                 std::size_t maxPoints, int dimension) {
  if (const std::optional<std::string> token = outOfRangeNumber(text))
    return Status{
        ErrorCode::InputInvalid,
        path + ": '" + printable(*token) + "' is out of range (" + outOfRangeReason(*token) + ")"};
  // A point is a list of `dimension` numbers, and no other number belongs in the document: its
  // numbers are held to exactly what the limit's points have, while the parser reads them. Lists
  // and objects, one per point and a handful besides, are counted too ("[]" takes memory).
  using Event = nlohmann::json::parse_event_t;
  const std::size_t maxNumbers = std::size_t(dimension) * maxPoints,
                    maxContainers = maxPoints + 1024;
  struct TooManyValues {
    bool numbers;
  };
  struct RepeatedKey {
    std::string key;
  };
  std::size_t numbers = 0, containers = 0;
  std::vector<std::set<std::string>> keys;  // of each object being read, innermost last
  const auto count = [&](int, Event event, nlohmann::json& parsed) {
    if (event == Event::object_start) keys.emplace_back();
    if (event == Event::object_end && !keys.empty()) keys.pop_back();
    if (event == Event::key && !keys.empty() &&
        !keys.back().insert(parsed.get<std::string>()).second)
      throw RepeatedKey{parsed.get<std::string>()};
    if (event == Event::value && parsed.is_number() && ++numbers > maxNumbers)
      throw TooManyValues{true};
    if ((event == Event::array_start || event == Event::object_start) &&
        ++containers > maxContainers)
      throw TooManyValues{false};
    return true;
  };
  try {
    return nlohmann::json::parse(text, count);
  } catch (const nlohmann::json::exception& e) {
    return Status{ErrorCode::InputUnreadable,
                  path + ": not valid JSON (" + parserReason(e.what()) + ")"};
  } catch (const TooManyValues& many) {
    if (many.numbers) return io_detail::tooManyPoints(path, "the file has", maxPoints);
    return Status{ErrorCode::InputInvalid, path + ": more JSON values than " +
                                               std::to_string(maxPoints) +
                                               " points (the limit) can have"};
  } catch (const RepeatedKey& repeated) {
    return Status{ErrorCode::InputInvalid, path + ": \"" + printable(repeated.key, 100) +
                                               "\" is given twice in one object (which one is "
                                               "meant cannot be told)"};
  }
}

Status onlyKnownKeys(const std::string& path, const nlohmann::json& doc,
                     const std::vector<std::string>& allowed) {
  if (!doc.is_object()) return Status::ok();
  for (const auto& item : doc.items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
    std::string known;
    for (std::size_t k = 0; k < allowed.size(); ++k)
      known += (k == 0                    ? ""
                : k + 1 == allowed.size() ? " and "
                                          : ", ") +
               ("\"" + allowed[k] + "\"");
    return Status{ErrorCode::InputInvalid, path + ": \"" + printable(item.key(), 100) +
                                               "\": unknown key (the file may have " + known + ")"};
  }
  return Status::ok();
}

Result<double> jsonUnitScale(const std::string& path, const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("units")) return 1.0;
  const nlohmann::json& units = doc["units"];
  const std::optional<double> scale =
      units.is_string() ? millimetresPerUnit(units.get<std::string>()) : std::nullopt;
  if (!scale)
    return Status{ErrorCode::InputUnreadable,
                  path + ": \"units\" must be \"mm\", \"cm\" or \"in\" (found " +
                      describeJsonValue(units) + ")"};
  return *scale;
}

Result<Eigen::MatrixXd> jsonPointList(const std::string& path, const nlohmann::json& list,
                                      const std::string& what, int dimension, double scale) {
  const std::string shape = dimension == 2 ? "[x, y]" : "[x, y, z]";
  if (!list.is_array())
    return Status{ErrorCode::InputUnreadable,
                  path + ": " + what + " is not a list of " + shape + " points"};
  Eigen::MatrixXd P(Eigen::Index(list.size()), dimension);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& p = list[i];
    const bool ok =
        p.is_array() && p.size() == std::size_t(dimension) &&
        std::all_of(p.begin(), p.end(), [](const nlohmann::json& v) { return v.is_number(); });
    if (!ok)
      return Status{ErrorCode::InputUnreadable, path + ": " + what + " point " +
                                                    std::to_string(i + 1) + " is not " + shape +
                                                    " with numbers"};
    for (int k = 0; k < dimension; ++k)
      P(Eigen::Index(i), k) = scale * p[std::size_t(k)].get<double>();
  }
  return P;
}

}  // namespace dform::io_detail
