// SPDX-License-Identifier: GPL-3.0-or-later
// Values of the settings table's rows for tests that walk it (pipeline/settings.h): one in each
// row's range or choices other than its default, and one each row must refuse.
#pragma once

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "dform/pipeline/settings.h"

namespace dform::test {

// A value of `row` in its range or choices other than its default in a job of the mode (forward:
// `forward`), as JSON text.
inline std::string otherValue(const SettingRow& row, bool forward) {
  const nlohmann::json fallback = nlohmann::json::parse(settingDefault(row, forward));
  switch (row.type) {
    case SettingType::Flag:  // an optional flag unset: "false", valid with every other setting
      return fallback.is_null() || fallback.get<bool>() ? "false" : "true";
    case SettingType::Integer: return std::to_string(int(row.min) + 1);
    case SettingType::Number:
    case SettingType::Weight: {
      const double low = std::isfinite(row.min) ? row.min : -1.0;
      const double high = std::isfinite(row.max) ? row.max : low + 10.0;
      const double inside = low + 0.375 * (high - low);
      const bool same = fallback.is_number() && inside == fallback.get<double>();
      return nlohmann::json(same ? low + 0.625 * (high - low) : inside).dump();
    }
    case SettingType::Choice:
      for (const SettingChoice& c : row.choices)
        if (fallback.is_null() || c.name != fallback.get<std::string>())
          return nlohmann::json(c.name).dump();
      return "";
    case SettingType::Start: return R"({"near": [12.5, -3]})";
    case SettingType::Text: {
      // Every text setting has its example here: a new one fails until it is given one.
      const std::map<Setting, std::string> examples = {{Setting::Profile, "\"print\""},
                                                       {Setting::Sheet, "\"300x200mm\""},
                                                       {Setting::Page, "\"A3\""},
                                                       {Setting::Scale, "0.5"},
                                                       {Setting::Gate, "\"strict\""}};
      const auto found = examples.find(row.id);
      return found == examples.end() ? "" : found->second;
    }
  }
  return "";
}

// A value `row` must refuse (out of its range, not one of its choices, not of its kind), as
// JSON text, and the same as the command line would give it ("" where a flag takes no value).
inline std::pair<std::string, std::string> badValue(const SettingRow& row) {
  switch (row.type) {
    case SettingType::Flag: return {"\"yes\"", ""};
    case SettingType::Integer: {
      const long long bad =
          std::isfinite(row.max) && row.max < 2e9 ? (long long)row.max + 1 : (long long)row.min - 1;
      return {std::to_string(bad), std::to_string(bad)};
    }
    case SettingType::Number:
    case SettingType::Weight: {
      const double bad =
          std::isfinite(row.min) ? (row.minExcluded ? row.min : row.min - 1) : row.max + 1;
      return {nlohmann::json(bad).dump(), nlohmann::json(bad).dump()};
    }
    case SettingType::Choice: return {"\"no-such-choice\"", "no-such-choice"};
    case SettingType::Start: return {"1.5", "1.5"};
    case SettingType::Text: {
      const std::map<Setting, std::string> bad = {{Setting::Sheet, "big"},
                                                  {Setting::Page, "B9"},
                                                  {Setting::Scale, "huge"},
                                                  {Setting::Profile, ""},
                                                  {Setting::Gate, ""}};
      const std::string text = bad.at(row.id);
      return {nlohmann::json(text).dump(), text};
    }
  }
  return {"", ""};
}

}  // namespace dform::test
