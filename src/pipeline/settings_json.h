// SPDX-License-Identifier: GPL-3.0-or-later
// Pipeline-internal: the settings table's values as JSON, for the job-file reader and writer.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "dform/pipeline/settings.h"

namespace dform {

/// The row's value in `job` (a job of the row's mode) as a job file writes it; null for an
/// optional setting that is not set.
nlohmann::json settingJson(const Job& job, const SettingRow& row);

/// Sets the row's value in `job` after the row's type and range check (null unsets an optional
/// setting); why not, without the setting's name ("must be between 8 and 20000, got 5"), or ""
/// when it is set.
std::string settingProblem(Job& job, const SettingRow& row, const nlohmann::json& value);

/// The value at a row's key ("resolution", "weights.isometry") in a JSON object shaped as a job
/// file, or null when it holds none.
const nlohmann::json* settingAt(const nlohmann::json& object, const std::string& key);

/// Sets each setting `object` holds on `job`, in the table's order: the first row refused and
/// why (settingProblem's words), or null and "" when every one was set.
std::pair<const SettingRow*, std::string> readSettingsObject(Job& job,
                                                             const nlohmann::json& object);

/// Every setting of `job`'s mode in a JSON object shaped as a job file (an optional setting only
/// when set).
nlohmann::json settingsObject(const Job& job);

}  // namespace dform
