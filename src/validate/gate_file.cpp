// SPDX-License-Identifier: GPL-3.0-or-later
// Gate files: {"version": 1, "name": "...", "description": "...", "limits": {...}}. Every limit
// may be left out to keep its default (GateLimits); nothing unknown is accepted, so that a typo
// never silently keeps a default.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "dform/core/input_file.h"
#include "dform/core/message_text.h"
#include "dform/validate/gate.h"

namespace dform {

namespace {

using nlohmann::json;

Status invalid(const std::string& source, const std::string& problem) {
  return Status(ErrorCode::InputInvalid, source + ": " + problem);
}

// Every limit of a gate file, by its key: the reader and the writer walk the same table.
struct Real {
  const char* key;
  double GateLimits::*field;
};
constexpr Real kReals[] = {
    {"L_error", &GateLimits::lengthError},
    {"L_max", &GateLimits::lengthErrorMax},
    {"B_error", &GateLimits::seamError},
    {"D_error", &GateLimits::curveError},
    {"seam_gap_mm", &GateLimits::seamGapMm},
    {"gauss_max_rad", &GateLimits::gaussMaxRad},
    {"seam_length_rel", &GateLimits::seamLengthRel},
    {"hull_distance_rel", &GateLimits::hullDistanceRel},
    {"exact_distance_rel", &GateLimits::exactDistanceRel},
    {"roundtrip_rel", &GateLimits::roundtripRel},
};
struct Count {
  const char* key;
  int GateLimits::*field;
};
constexpr Count kCounts[] = {{"flipped", &GateLimits::flipped},
                             {"degenerate", &GateLimits::degenerate}};

}  // namespace

std::string gateLimitsJson(const GateLimits& limits) {
  json out = json::object();
  for (const Real& r : kReals) out[r.key] = limits.*r.field;
  for (const Count& c : kCounts) out[c.key] = limits.*c.field;
  return out.dump();
}

Result<GateLimits> parseGateJson(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    return Status(ErrorCode::InputUnreadable,
                  source + ": not JSON (" + parserReason(e.what()) + ")");
  }
  if (!doc.is_object()) return invalid(source, "a gate file is a JSON object");

  GateLimits limits;
  bool sawVersion = false;
  for (const auto& [key, value] : doc.items()) {
    if (key == "version") {
      if (!value.is_number_integer() || value.get<long long>() != 1)
        return invalid(source, "version must be 1 (got " + describeJsonValue(value) + ")");
      sawVersion = true;
    } else if (key == "name") {
      if (!value.is_string())
        return invalid(source, "name must be a string (got " + describeJsonValue(value) + ")");
      limits.name = value.get<std::string>();
    } else if (key == "description") {
      if (!value.is_string())
        return invalid(source,
                       "description must be a string (got " + describeJsonValue(value) + ")");
    } else if (key == "limits") {
      if (!value.is_object())
        return invalid(source, "limits must be an object (got " + describeJsonValue(value) + ")");
    } else {
      return invalid(source, "unknown field '" + printable(key) + "'");
    }
  }
  if (!sawVersion) return invalid(source, "missing field 'version' (1)");

  if (!doc.contains("limits")) return limits;
  for (const auto& [key, value] : doc["limits"].items()) {
    const std::string where = "limits." + printable(key);
    bool known = false;
    for (const Real& r : kReals) {
      if (key != r.key) continue;
      known = true;
      if (!value.is_number())
        return invalid(source, where + " must be a number (got " + describeJsonValue(value) + ")");
      const double x = value.get<double>();
      if (!(x >= 0.0) || !std::isfinite(x))
        return invalid(source, where + " must be a finite non-negative number (got " +
                                   describeJsonValue(value) + ")");
      limits.*r.field = x;
    }
    for (const Count& c : kCounts) {
      if (key != c.key) continue;
      known = true;
      if (!value.is_number_integer())
        return invalid(source,
                       where + " must be a whole number (got " + describeJsonValue(value) + ")");
      const long long x = value.get<long long>();
      if (x < 0 || x > 1000000000)
        return invalid(
            source, where + " must be a non-negative count (got " + describeJsonValue(value) + ")");
      limits.*c.field = int(x);
    }
    if (!known) return invalid(source, "unknown field '" + where + "'");
  }
  return limits;
}

Result<GateLimits> readGateFile(const std::string& path) {
  const Result<std::string> text = readInputFile(path, kMaxSettingsBytes);
  if (!text.isOk()) return text.status();
  return parseGateJson(text.value(), path);
}

}  // namespace dform
