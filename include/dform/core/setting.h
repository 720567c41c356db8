// SPDX-License-Identifier: GPL-3.0-or-later
// The user settings by name. Each setting that job files, the command line, Python and the studio
// set has one value of `Setting` here and its job-file key; the rest of its row (its flag, keyword,
// type, default, range, unit and help) is the pipeline's settings table (pipeline/settings.h).
// A library message about a setting names it with mention(), never in a shell's words; each shell
// words the mentions its own way (the command line "--fit-perimeter", Python "fit_perimeter"),
// and Status::message() gives them as their job-file keys.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace dform {

enum class Setting {
  // forward runs
  Model,
  Join,
  StartA,
  StartB,
  InteriorEdge,
  Flip,
  FitPerimeter,
  PerimeterTolerance,
  // inverse runs
  Closed,
  // both
  Resolution,
  Weight,  ///< one term's weight: mention(Setting::Weight, name)
  MaxIterations,
  FunctionTolerance,
  GradientTolerance,
  // the pattern and previews, and the gate
  Profile,
  Sheet,
  Page,
  Scale,
  TabWidth,
  Tabs,
  TickSpacing,
  Joint,
  Material,
  Kerf,
  HoleSpacing,
  HoleDiameter,
  HoleEdge,
  SlotLength,
  ScoreFolds,
  Numbers,
  Hinge,
  Title,
  Gltf,
  CuttingFiles,
  ExportAnyway,
  Gate,
};

/// The setting's key in a job file ("fit_perimeter", "solver.max_iterations", "export.kerf"; for
/// Weight the object holding the weights, "weights").
const char* settingKey(Setting setting);

/// The setting whose key (or, for a weight, "weights.<name>") is `key`, or nullopt.
std::optional<Setting> settingOfKey(const std::string& key);

/// The setting as a message names it: a mention that each shell words its own way. `member` names
/// one of Weight's terms ("smooth_3d").
std::string mention(Setting setting, const std::string& member = "");

/// How a shell words a mentioned setting, from its key ("resolution", "weights.smooth_3d").
using SettingWords = std::function<std::string(const std::string& key)>;

/// `text` with each mention worded by `words`; a text without mentions is returned as it is.
std::string wordSettings(const std::string& text, const SettingWords& words);

/// `text` with each mention as its key: how the library's messages read outside a shell.
std::string plainSettings(const std::string& text);

/// The first setting `text` mentions, or nullopt.
std::optional<Setting> firstMention(const std::string& text);

}  // namespace dform
