// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/setting.h"

namespace dform {

namespace {

// A mention: the key between two control characters that no message text holds otherwise (file
// names in messages are made printable first).
constexpr char kOpen = '\x02', kClose = '\x03';

}  // namespace

const char* settingKey(Setting setting) {
  switch (setting) {
    case Setting::Model: return "model";
    case Setting::Join: return "join";
    case Setting::StartA: return "start_a";
    case Setting::StartB: return "start_b";
    case Setting::InteriorEdge: return "interior_edge";
    case Setting::Flip: return "flip";
    case Setting::FitPerimeter: return "fit_perimeter";
    case Setting::PerimeterTolerance: return "perimeter_tolerance";
    case Setting::Closed: return "closed";
    case Setting::Resolution: return "resolution";
    case Setting::Weight: return "weights";
    case Setting::MaxIterations: return "solver.max_iterations";
    case Setting::FunctionTolerance: return "solver.function_tolerance";
    case Setting::GradientTolerance: return "solver.gradient_tolerance";
    case Setting::Profile: return "export.profile";
    case Setting::Sheet: return "export.sheet";
    case Setting::Page: return "export.page";
    case Setting::Scale: return "export.scale";
    case Setting::TabWidth: return "export.tab_width";
    case Setting::Tabs: return "export.tabs";
    case Setting::TickSpacing: return "export.tick_spacing";
    case Setting::Joint: return "export.joint";
    case Setting::Material: return "export.material";
    case Setting::Kerf: return "export.kerf";
    case Setting::HoleSpacing: return "export.hole_spacing";
    case Setting::HoleDiameter: return "export.hole_diameter";
    case Setting::HoleEdge: return "export.hole_edge";
    case Setting::SlotLength: return "export.slot_length";
    case Setting::ScoreFolds: return "export.score_folds";
    case Setting::Numbers: return "export.numbers";
    case Setting::Hinge: return "export.hinge";
    case Setting::Title: return "export.title";
    case Setting::Gltf: return "export.gltf";
    case Setting::CuttingFiles: return "export.cutting_files";
    case Setting::ExportAnyway: return "export.export_anyway";
    case Setting::Gate: return "gate";
  }
  return "";
}

std::optional<Setting> settingOfKey(const std::string& key) {
  const std::string weights = settingKey(Setting::Weight);
  if (key.compare(0, weights.size() + 1, weights + ".") == 0 && key.size() > weights.size() + 1)
    return Setting::Weight;
  for (int s = 0; s <= int(Setting::Gate); ++s)
    if (key == settingKey(Setting(s))) return Setting(s);
  return std::nullopt;
}

std::string mention(Setting setting, const std::string& member) {
  std::string key = settingKey(setting);
  if (!member.empty()) key += "." + member;
  return kOpen + key + kClose;
}

std::string wordSettings(const std::string& text, const SettingWords& words) {
  std::string out;
  std::size_t at = 0;
  while (true) {
    const std::size_t open = text.find(kOpen, at);
    const std::size_t close = open == std::string::npos ? open : text.find(kClose, open + 1);
    if (close == std::string::npos) return out + text.substr(at);
    const std::string key = text.substr(open + 1, close - open - 1);
    out += text.substr(at, open - at) + (settingOfKey(key) ? words(key) : key);
    at = close + 1;
  }
}

std::string plainSettings(const std::string& text) {
  return wordSettings(text, [](const std::string& key) { return key; });
}

std::optional<Setting> firstMention(const std::string& text) {
  const std::size_t open = text.find(kOpen);
  const std::size_t close = open == std::string::npos ? open : text.find(kClose, open + 1);
  if (close == std::string::npos) return std::nullopt;
  return settingOfKey(text.substr(open + 1, close - open - 1));
}

}  // namespace dform
