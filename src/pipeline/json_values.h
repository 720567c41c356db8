// SPDX-License-Identifier: GPL-3.0-or-later
// Pipeline-internal: the JSON values its files share (report.json, sweep.json, batch manifests).
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>

#include "dform/validate/metrics.h"

namespace dform {

/// `value` as a JSON number, or null when it is not finite (JSON has no NaN or infinity): a figure
/// that was not measured.
inline nlohmann::json numberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

/// The figures as report.json records them under "metrics" (NaN and infinity as null).
nlohmann::json metricsJson(const Metrics& metrics);

}  // namespace dform
