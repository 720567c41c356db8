// SPDX-License-Identifier: GPL-3.0-or-later
#include "setting_options.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "dform/core/message_text.h"

namespace dform::cli {

namespace {

// A JSON default as --help shows it: a text without its quotes, a number in its shortest form.
std::string shown(const std::string& json) {
  if (json.size() >= 2 && json.front() == '"') return json.substr(1, json.size() - 2);
  char* end = nullptr;
  const double number = std::strtod(json.c_str(), &end);
  if (end != json.c_str() && *end == '\0') {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", number);
    return text;
  }
  return json;
}

std::string typeName(const SettingRow& row) {
  switch (row.type) {
    case SettingType::Flag: return "";
    case SettingType::Integer: return "INT";
    case SettingType::Number:
      return row.unit == "mm" ? "MM" : row.unit == "degrees" ? "DEG" : "NUMBER";
    case SettingType::Choice: {
      std::string names;
      for (const SettingChoice& c : row.choices) names += (names.empty() ? "" : "|") + c.name;
      return names;
    }
    case SettingType::Text: return row.id == Setting::Sheet ? "WxHmm" : "TEXT";
    case SettingType::Start: return "FRACTION";
    case SettingType::Weight: return "NAME=VALUE";
  }
  return "";
}

const SettingRow* rowOfKey(const std::string& key) {
  for (const SettingRow& row : settingRows())
    if (row.key == key) return &row;
  return nullptr;
}

}  // namespace

std::string commandLineWords(const std::string& key) {
  const SettingRow* row = rowOfKey(key);
  if (!row || row->flag.empty()) return key;
  return row->type == SettingType::Weight ? row->flag + " " + row->weightName() : row->flag;
}

std::string inCommandLineTerms(const std::string& text) {
  return wordSettings(text, commandLineWords);
}

std::string helpLine(const SettingRow& row, bool forward) {
  std::string line = row.help;
  if (row.type == SettingType::Choice) {
    line += ": ";
    for (std::size_t k = 0; k < row.choices.size(); ++k) {
      const SettingChoice& c = row.choices[k];
      line += (k == 0                        ? ""
               : k + 1 == row.choices.size() ? " or "
                                             : ", ") +
              c.name + (c.help.empty() ? "" : " (" + c.help + ")");
    }
  } else if (row.type == SettingType::Integer || row.type == SettingType::Number) {
    line += ", " + row.rangeText();
  } else if (row.type == SettingType::Start) {
    line += ", in [0, 1)";
  }
  if (row.type == SettingType::Flag) return row.flagValue ? line : "turn off " + line;
  if (!row.unset.empty()) return line + " (default: " + row.unset + ")";
  return line + " (default " + shown(settingDefault(row, forward)) + ")";
}

void SettingOptions::add(CLI::App* command, const std::vector<const SettingRow*>& rows,
                         bool forward) {
  std::string weightHelp;
  for (const SettingRow* row : rows) {
    if (row->type == SettingType::Weight) {
      weightHelp += (weightHelp.empty() ? "" : ", ") + row->weightName() + " (default " +
                    shown(settingDefault(*row, forward)) + ")";
      continue;
    }
    if (row->type == SettingType::Flag) {
      CLI::Option* flag = command->add_flag(row->flag);
      flag->description(helpLine(*row, forward));
      bound_.push_back({row, row->flag, flag, nullptr});
      if (!row->offFlag.empty()) {
        CLI::Option* off = command->add_flag(row->offFlag);
        off->description("turn off " + row->help);
        off->excludes(flag);
        bound_.push_back({row, row->offFlag, off, nullptr});
      }
      continue;
    }
    texts_.emplace_back();
    CLI::Option* option = command->add_option(row->flag, texts_.back(), helpLine(*row, forward));
    option->type_name(typeName(*row));
    bound_.push_back({row, row->flag, option, &texts_.back()});
    if (!row->nearFlag.empty()) {
      texts_.emplace_back();
      CLI::Option* near = command->add_option(
          row->nearFlag, texts_.back(),
          "as " + row->flag + ", the outline point nearest X,Y (mm) instead of a fraction");
      near->type_name("X,Y");
      bound_.push_back({row, row->nearFlag, near, &texts_.back()});
    }
  }
  if (!weightHelp.empty()) {
    // One value per use ("--weight a=1 --weight b=2"), so that positionals after it stay such.
    weightOption_ =
        command
            ->add_option("--weight", weights_,
                         "a term's weight NAME=VALUE, one per use (repeatable): " + weightHelp)
            ->allow_extra_args(false)
            ->type_name("NAME=VALUE");
  }
}

bool SettingOptions::anyGiven() const {
  for (const Bound& b : bound_)
    if (b.option->count() > 0) return true;
  return !weights_.empty();
}

Status SettingOptions::apply(Job& job) const {
  // The table's order: a join sets the weights' defaults before a --weight sets one.
  for (const SettingRow* row : settingRows(job.isForward())) {
    for (const Bound& b : bound_) {
      if (b.row != row || b.option->count() == 0) continue;
      const bool flagValue = b.flag == row->offFlag ? !row->flagValue : row->flagValue;
      const Status set = b.text ? setSettingText(job, *row, b.flag, *b.text)
                                : setSetting(job, *row, flagValue ? "true" : "false");
      if (!set.isOk())
        return Status(ErrorCode::Usage, wordSettings(set.text(), [&](const std::string& key) {
                        return key == row->key ? b.flag : commandLineWords(key);
                      }));
    }
  }
  for (const std::string& assignment : weights_) {
    const std::size_t eq = assignment.find('=');
    const std::string name = assignment.substr(0, eq);
    const SettingRow* row =
        findSetting(std::string(settingKey(Setting::Weight)) + "." + name, job.isForward());
    if (eq == std::string::npos)
      return Status(ErrorCode::Usage,
                    "--weight must look like name=value, got '" + printable(assignment) + "'");
    if (!row) {
      std::string known;
      for (const SettingRow* r : settingRows(job.isForward()))
        if (r->type == SettingType::Weight) known += (known.empty() ? "" : ", ") + r->weightName();
      return Status(ErrorCode::Usage, "--weight: unknown weight '" + printable(name) + "' (the " +
                                          job.modeName() + " weights: " + known + ")");
    }
    if (Status set = setSettingText(job, *row, "--weight", assignment.substr(eq + 1)); !set.isOk())
      return Status(ErrorCode::Usage, inCommandLineTerms(set.text()));
  }
  return Status::ok();
}

}  // namespace dform::cli
