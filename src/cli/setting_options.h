// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table's rows as command-line options (pipeline/settings.h): each row's flag (and a
// start's point form, and one repeatable --weight NAME=VALUE for a mode's weights) with its help,
// range and default from the row. The values given are set on a job after the parse, in the
// table's order, through the table's one range check; a refusal names the flag.
#pragma once

#include <CLI/CLI.hpp>
#include <deque>
#include <string>
#include <vector>

#include "dform/pipeline/settings.h"

namespace dform::cli {

/// How the command line names a setting a message mentions (core/setting.h): its flag
/// ("--fit-perimeter"), a weight as "--weight smooth_3d"; a setting without a flag by its key.
std::string commandLineWords(const std::string& key);

/// `text` (a library message) with the settings it mentions as the command line names them.
std::string inCommandLineTerms(const std::string& text);

/// The --help line of a row in a command of one mode: its help, range and default (or what it is
/// when unset).
std::string helpLine(const SettingRow& row, bool forward);

class SettingOptions {
 public:
  /// Adds the options of `rows` to `command`, a command of one mode (forward: `forward`; an
  /// export's rows are alike in both), their defaults that mode's.
  void add(CLI::App* command, const std::vector<const SettingRow*>& rows, bool forward = true);

  /// Sets every setting given on the command line in `job` (of a mode the rows belong to; rows
  /// of the other mode are skipped), in the table's order: Usage naming the flag when a value is
  /// refused.
  Status apply(Job& job) const;

  /// Whether a value was given for any of the rows.
  bool anyGiven() const;

 private:
  struct Bound {
    const SettingRow* row;
    std::string flag;  ///< the row's flag, or a start's point form
    CLI::Option* option;
    std::string* text;  ///< the value given (not for flags)
  };
  std::vector<Bound> bound_;
  std::deque<std::string> texts_;
  std::vector<std::string> weights_;  ///< --weight NAME=VALUE, each use
  CLI::Option* weightOption_ = nullptr;
};

}  // namespace dform::cli
