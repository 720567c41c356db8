// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table: one row per user setting of forward, inverse and export runs, with its
// job-file key, command-line flag, Python keyword, type, range or choices, unit and help; its
// default is its value in a new job (the settings structs' member initialisers). Every shell
// reads it: the job-file reader and writer (pipeline/job_file.h), the command line's options,
// --help, man page and completion, Python's keyword arguments and docstrings, and the studio's
// requests and saved jobs. setSetting is the one range check. A message about a setting names it
// by mention() (core/setting.h); each shell words it its own way.
//
// To add a setting: a member with its default in the settings struct it belongs to, its value of
// Setting and its key (core/setting.h), and its row here (settings.cpp). A choice's values come
// from the module that owns them (forward's modelChoices(), export's jointNames(), ...), so that a
// new value is one line there.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "dform/core/setting.h"
#include "dform/core/status.h"
#include "dform/pipeline/job.h"

namespace dform {

/// Which jobs a setting belongs to.
enum class SettingScope {
  Forward,  ///< forward jobs (ForwardJob)
  Inverse,  ///< inverse jobs (InverseJob)
  Solve,    ///< both modes, each its own member (the resolution, the solver's stops)
  Export,   ///< every job: its pattern and previews (ExportSettings::pattern)
  Output,   ///< every job: the gate and what is released (ExportSettings)
};

/// How a setting's value is written: in a job file (and the studio's requests, and Python) as a
/// JSON value, on the command line as text.
enum class SettingType {
  Flag,     ///< true or false; the command line's flag sets `flagValue`
  Integer,  ///< a whole number in [min, max]
  Number,   ///< a number in [min, max] (either end excluded where the row says)
  Choice,   ///< one of the row's choices
  Text,     ///< text the row reads: a sheet size, a page, a scale, a profile, a gate
  Start,    ///< an arc-length fraction in [0, 1), or the outline point nearest {"near": [x, y]}
  Weight,   ///< a term's weight: a number >= 0 (one row per term of the mode's table)
};

/// One value of a Choice row and what it means.
struct SettingChoice {
  std::string name;  ///< as job files, the command line and Python write it
  std::string help;  ///< what it means, one line
};

struct SettingAccess;  ///< how a row reads and writes its member of a Job (settings.cpp)

/// One user setting.
struct SettingRow {
  Setting id;           ///< which setting (core/setting.h), as messages name it
  std::string key;      ///< in job files: "resolution", "weights.smooth_3d", "export.kerf"
  std::string flag;     ///< on the command line: "--resolution"; "--weight" for every weight
  std::string keyword;  ///< in Python: "resolution"; a weight is an entry of the dict "weights"
  SettingScope scope = SettingScope::Forward;  ///< which mode and stage reads it
  SettingType type = SettingType::Number;      ///< the form of its value
  std::string unit;  ///< "mm", "degrees"; empty for a count, a ratio or a name
  std::string help;  ///< one line, without the default or the range (those are columns)
  double min = -std::numeric_limits<double>::infinity();  ///< Integer, Number: the range
  double max = std::numeric_limits<double>::infinity();   ///< see min
  bool minExcluded = false;                               ///< min itself is out of range
  bool maxExcluded = false;                               ///< max itself is out of range
  std::vector<SettingChoice> choices;                     ///< Choice rows
  bool flagValue = true;  ///< Flag rows: what the command line's flag sets (--no-title: false)
  std::string nearFlag;   ///< Start rows: the flag of the point form, "--start-a-near X,Y"
  std::string offFlag;    ///< optional Flag rows: a flag setting the other value, "--no-hinge"
  /// An optional setting: what it is when not set ("the profile's"); empty: always set.
  std::string unset;
  const SettingAccess* access = nullptr;  ///< how it reads and writes its member of a Job

  /// The weight's term name ("smooth_3d") of a Weight row, else empty.
  std::string weightName() const;
  /// The row's range, choices or form in words: "8 to 20000", "auto, exact, paper or general".
  std::string rangeText() const;
};

/// Every row, in the order the readers apply them (a join before the weights it sets the
/// defaults of): forward's, inverse's, both modes', the export's and the output's; each mode's
/// weights from its term table (model/term_table.h).
const std::vector<SettingRow>& settingRows();

/// The rows of a job of one mode (forward or inverse): its own, the solve's, the export's and the
/// output's.
std::vector<const SettingRow*> settingRows(bool forward);

/// The row of `key` among a mode's rows, or null.
const SettingRow* findSetting(const std::string& key, bool forward);

/// The row's value in `job` (a job of the row's mode) as JSON text: 100, true, "auto",
/// {"near": [150, 50]}; null for an optional setting that is not set.
std::string settingValue(const Job& job, const SettingRow& row);

/// The row's default: its value in a new job of its mode (forward for a row of both modes), as
/// JSON text.
std::string settingDefault(const SettingRow& row);
/// The same in a new job of one mode: a row of both modes has each mode's own default (the
/// inverse solve's stops are not the forward solve's).
std::string settingDefault(const SettingRow& row, bool forward);

/// Sets the row's value in `job` from JSON text (null unsets an optional setting): the one range
/// check. Usage naming the setting (a mention) with what it must be when refused.
Status setSetting(Job& job, const SettingRow& row, const std::string& json);

/// The same from the command line's text after `flag` (the row's flag or nearFlag): a number, a
/// name, "X,Y" for a start point, "NAME=VALUE" for a weight.
Status setSettingText(Job& job, const SettingRow& row, const std::string& flag,
                      const std::string& text);

/// Sets every setting the JSON object `json` (text shaped as a job file: "resolution",
/// "weights": {"smooth_3d": 0.02}, "export": {"kerf": 0.2}) holds on `job`, in the table's order
/// (a join before the weights it sets the defaults of); its other keys are left alone. Usage
/// naming the first setting refused, or saying that `json` is not a JSON object.
Status readSettings(Job& job, const std::string& json);

/// Every setting of `job`'s mode as a JSON object's text shaped as a job file (an optional one
/// only when set): what readSettings reads back into an equal job.
std::string settingsJson(const Job& job);

/// Every setting of `job` checked against its row: Usage naming the first one out of range. A
/// job made in code (not through setSetting) is checked by this before it runs.
Status checkSettings(const Job& job);
/// The same for one mode's settings (makeDForm and makePieces check theirs first), and for the
/// export's (checkOutput checks them first).
Status checkSettings(const ForwardSettings& settings);
Status checkSettings(const InverseSettings& settings);
Status checkExportSettings(const ExportSettings& settings);

}  // namespace dform
