// SPDX-License-Identifier: GPL-3.0-or-later
// Pipeline-internal: how the settings table's rows read and write a Job, and the rows made once
// (setting_rows.cpp) for settings.cpp's lookups and checks.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dform/pipeline/settings.h"

namespace dform {

/// How a row reads and writes its member: `get` the value as a job file writes it (null when an
/// optional setting is not set); `set` stores a value that passed the row's type and range check
/// and returns why it cannot ("" when stored): a Text row reads its text here.
struct SettingAccess {
  std::function<nlohmann::json(const Job&)> get;
  std::function<std::string(Job&, const nlohmann::json&)> set;
};

/// Every row of the table, in settingRows' order.
std::vector<SettingRow> makeSettingRows();

/// A number as the table's texts write it: its shortest form to ten digits ("0.05", "20000").
std::string numberText(double value);

}  // namespace dform
