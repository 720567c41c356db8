// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table's lookups, its values as JSON and the one range check (pipeline/settings.h);
// the rows themselves are in setting_rows.cpp.
#include "dform/pipeline/settings.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "dform/core/message_text.h"
#include "setting_rows.h"
#include "settings_json.h"

namespace dform {

using nlohmann::json;

std::string SettingRow::weightName() const {
  return type == SettingType::Weight ? key.substr(key.find('.') + 1) : std::string();
}

namespace {

// "a, b or c"
std::string alternatives(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k)
    out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return out;
}

std::string rangeWords(const SettingRow& row) {
  // An integer's range up to the largest int is a range without an upper end, as it reads.
  const bool low = std::isfinite(row.min),
             high = std::isfinite(row.max) && row.max < std::numeric_limits<int>::max();
  const std::string unit = row.unit.empty() ? "" : " " + row.unit;
  if (low && high && !row.minExcluded && !row.maxExcluded)
    return "between " + numberText(row.min) + " and " + numberText(row.max) + unit;
  if (low && high)
    return std::string("in ") + (row.minExcluded ? "(" : "[") + numberText(row.min) + ", " +
           numberText(row.max) + (row.maxExcluded ? ")" : "]") + unit;
  if (low) return (row.minExcluded ? "above " : "at least ") + numberText(row.min) + unit;
  if (high) return (row.maxExcluded ? "below " : "at most ") + numberText(row.max) + unit;
  return "a number";
}

}  // namespace

std::string SettingRow::rangeText() const {
  switch (type) {
    case SettingType::Flag: return "true or false";
    case SettingType::Choice: {
      std::vector<std::string> list;
      for (const SettingChoice& c : choices) list.push_back(c.name);
      return alternatives(list);
    }
    case SettingType::Start: return "a fraction in [0, 1) or the point nearest X,Y (mm)";
    case SettingType::Text:
      return id == Setting::Scale ? rangeWords(*this) + ", a percentage or fit" : "text";
    case SettingType::Integer:
    case SettingType::Number:
    case SettingType::Weight: return rangeWords(*this);
  }
  return "";
}

namespace {

bool inRange(const SettingRow& row, double value) {
  return (row.minExcluded ? value > row.min : value >= row.min) &&
         (row.maxExcluded ? value < row.max : value <= row.max);
}

bool finitePoint(const json& p) {
  return p.is_array() && p.size() == 2 && p[0].is_number() && p[1].is_number() &&
         std::isfinite(p[0].get<double>()) && std::isfinite(p[1].get<double>());
}

// Why `v` is not a value of `row` (its type, range or choices), or "".
std::string valueProblem(const SettingRow& row, const json& v) {
  if (v.is_null()) return row.unset.empty() ? "must be " + row.rangeText() : "";
  switch (row.type) {
    case SettingType::Flag: return v.is_boolean() ? "" : "must be true or false";
    case SettingType::Integer: {
      // Compared before get<int>(), which would wrap a larger number silently.
      const bool whole = v.is_number_integer();
      const double d = !whole                   ? 0.0
                       : v.is_number_unsigned() ? double(v.get<std::uint64_t>())
                                                : double(v.get<std::int64_t>());
      if (!whole || !inRange(row, d))
        return "must be a whole number " + rangeWords(row) + ", got " + describeJsonValue(v);
      return "";
    }
    case SettingType::Number:
    case SettingType::Weight:
      if (!v.is_number() || !std::isfinite(v.get<double>()) || !inRange(row, v.get<double>()))
        return "must be " +
               (row.type == SettingType::Weight ? "a finite number >= 0"
                                                : "a number " + rangeWords(row)) +
               ", got " + describeJsonValue(v);
      return "";
    case SettingType::Choice:
      for (const SettingChoice& c : row.choices)
        if (v.is_string() && v.get<std::string>() == c.name) return "";
      return "must be " + row.rangeText() + ", got " + describeJsonValue(v);
    case SettingType::Text:
      if (row.id == Setting::Scale && v.is_number()) return "";
      if (!v.is_string() || v.get<std::string>().empty())
        return "must be non-empty text, got " + describeJsonValue(v);
      return "";
    case SettingType::Start:
      if (v.is_number())
        return v.get<double>() >= 0.0 && v.get<double>() < 1.0
                   ? ""
                   : "must be a fraction in [0, 1), got " + describeJsonValue(v);
      if (v.is_object() && v.size() == 1 && v.contains("fraction") && v["fraction"].is_number())
        return valueProblem(row, v["fraction"]);
      if (v.is_object() && v.size() == 1 && v.contains("near") && finitePoint(v["near"])) return "";
      return "must be a fraction, {\"fraction\": f} or {\"near\": [x, y]} with finite x and y";
  }
  return "";
}

bool ofMode(const SettingRow& row, bool forward) {
  return forward ? row.scope != SettingScope::Inverse : row.scope != SettingScope::Forward;
}

}  // namespace

const std::vector<SettingRow>& settingRows() {
  static const std::vector<SettingRow> rows = makeSettingRows();
  return rows;
}

std::vector<const SettingRow*> settingRows(bool forward) {
  std::vector<const SettingRow*> out;
  for (const SettingRow& row : settingRows())
    if (ofMode(row, forward)) out.push_back(&row);
  return out;
}

const SettingRow* findSetting(const std::string& key, bool forward) {
  for (const SettingRow& row : settingRows())
    if (row.key == key && ofMode(row, forward)) return &row;
  return nullptr;
}

json settingJson(const Job& job, const SettingRow& row) { return row.access->get(job); }

std::string settingProblem(Job& job, const SettingRow& row, const json& value) {
  if (std::string why = valueProblem(row, value); !why.empty()) return why;
  return row.access->set(job, value);
}

std::string settingValue(const Job& job, const SettingRow& row) {
  return settingJson(job, row).dump();
}

std::string settingDefault(const SettingRow& row) {
  return settingDefault(row, row.scope != SettingScope::Inverse);
}

std::string settingDefault(const SettingRow& row, bool forward) {
  const Job fresh = forward ? Job(ForwardJob()) : Job(InverseJob());
  return settingValue(fresh, row);
}

const json* settingAt(const json& object, const std::string& key) {
  const std::size_t dot = key.find('.');
  const std::string first = key.substr(0, dot);
  if (!object.is_object() || !object.contains(first)) return nullptr;
  if (dot == std::string::npos) return &object.at(first);
  const json& inner = object.at(first);
  const std::string rest = key.substr(dot + 1);
  return inner.is_object() && inner.contains(rest) ? &inner.at(rest) : nullptr;
}

std::pair<const SettingRow*, std::string> readSettingsObject(Job& job, const json& object) {
  for (const SettingRow* row : settingRows(job.isForward()))
    if (const json* value = settingAt(object, row->key))
      if (std::string why = settingProblem(job, *row, *value); !why.empty()) return {row, why};
  return {nullptr, ""};
}

json settingsObject(const Job& job) {
  json out = json::object();
  for (const SettingRow* row : settingRows(job.isForward())) {
    const json value = settingJson(job, *row);
    if (value.is_null()) continue;  // an optional setting not set: its row says what it is then
    const std::size_t dot = row->key.find('.');
    if (dot == std::string::npos)
      out[row->key] = value;
    else
      out[row->key.substr(0, dot)][row->key.substr(dot + 1)] = value;
  }
  return out;
}

Status readSettings(Job& job, const std::string& text) {
  const json object = json::parse(text, nullptr, false);
  if (!object.is_object()) return Status(ErrorCode::Usage, "the settings must be a JSON object");
  const auto [row, why] = readSettingsObject(job, object);
  if (row) return Status(ErrorCode::Usage, mention(row->id, row->weightName()) + " " + why);
  return Status::ok();
}

std::string settingsJson(const Job& job) {
  return settingsObject(job).dump(-1, ' ', false, json::error_handler_t::replace);
}

Status setSetting(Job& job, const SettingRow& row, const std::string& text) {
  const json value = json::parse(text, nullptr, false);
  if (value.is_discarded())
    return Status(ErrorCode::Usage, mention(row.id, row.weightName()) + " must be " +
                                        row.rangeText() + ", got '" + printable(text) + "'");
  if (std::string why = settingProblem(job, row, value); !why.empty())
    return Status(ErrorCode::Usage, mention(row.id, row.weightName()) + " " + why);
  return Status::ok();
}

Status setSettingText(Job& job, const SettingRow& row, const std::string& flag,
                      const std::string& text) {
  json value;
  switch (row.type) {
    case SettingType::Flag: value = text == "true" || text == "1" || text.empty(); break;
    case SettingType::Integer:
    case SettingType::Number:
    case SettingType::Weight:
      value = json::parse(text, nullptr, false);
      if (value.is_discarded() || !value.is_number()) value = text;  // refused as not a number
      break;
    case SettingType::Start:
      if (flag == row.nearFlag) {
        double x = 0, y = 0;
        char rest = 0;
        if (std::sscanf(text.c_str(), "%lf,%lf%c", &x, &y, &rest) != 2)
          return Status(ErrorCode::Usage, mention(row.id) + " must be a point X,Y (mm), got '" +
                                              printable(text) + "'");
        value = json{{"near", {x, y}}};
      } else {
        value = json::parse(text, nullptr, false);
        if (value.is_discarded() || !value.is_number()) value = text;
      }
      break;
    case SettingType::Choice:
    case SettingType::Text: value = text; break;
  }
  if (std::string why = settingProblem(job, row, value); !why.empty())
    return Status(ErrorCode::Usage, mention(row.id, row.weightName()) + " " + why);
  return Status::ok();
}

namespace {

// The rows of `scopes` in `job` checked, each by setting its own value again on a copy.
Status checkRows(const Job& job, std::initializer_list<SettingScope> scopes) {
  for (const SettingRow* row : settingRows(job.isForward())) {
    if (std::find(scopes.begin(), scopes.end(), row->scope) == scopes.end()) continue;
    Job copy = job;
    if (std::string why = settingProblem(copy, *row, settingJson(job, *row)); !why.empty())
      return Status(ErrorCode::Usage, mention(row->id, row->weightName()) + " " + why);
  }
  return Status::ok();
}

}  // namespace

Status checkSettings(const Job& job) {
  using S = SettingScope;
  return checkRows(job, {S::Forward, S::Inverse, S::Solve, S::Export, S::Output});
}

Status checkSettings(const ForwardSettings& settings) {
  return checkRows(Job(ForwardJob{settings, "", ""}), {SettingScope::Forward, SettingScope::Solve});
}

Status checkSettings(const InverseSettings& settings) {
  return checkRows(Job(InverseJob{settings, "", false}),
                   {SettingScope::Inverse, SettingScope::Solve});
}

Status checkExportSettings(const ExportSettings& settings) {
  Job job;
  job.exporting = settings;
  return checkRows(job, {SettingScope::Export, SettingScope::Output});
}

}  // namespace dform
