// SPDX-License-Identifier: GPL-3.0-or-later
// Machine profiles: templates/profiles/<name>.json, read strictly (an unknown or mistyped field is
// an error naming the file and the field, so that a typo never silently falls back to a default).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "dform/core/input_file.h"
#include "dform/core/message_text.h"
#include "internal.h"

namespace dform {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Status invalid(const std::string& source, const std::string& what) {
  return {ErrorCode::InputInvalid, source + ": " + what};
}

bool isHexColor(const std::string& s) {
  if (s.size() != 7 || s[0] != '#') return false;
  return std::all_of(s.begin() + 1, s.end(), [](char c) { return std::isxdigit(uint8_t(c)); });
}

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(uint8_t(c)));
  return s;
}

// Reads one field into `out` if present; returns a non-ok Status naming the field when mistyped.
struct FieldReader {
  const json& j;
  const std::string& source;
  Status status;

  const json* get(const char* key) {
    auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
  }
  void number(const char* key, double& out, double lo, double hi) {
    const json* v = get(key);
    if (!v || !status.isOk()) return;
    if (!v->is_number()) {
      status = invalid(source, std::string("field \"") + key + "\" must be a number");
      return;
    }
    const double x = v->get<double>();
    if (!(x >= lo && x <= hi)) {
      std::ostringstream msg;
      msg << "field \"" << key << "\" = " << x << " is out of range [" << lo << ", " << hi << "]";
      status = invalid(source, msg.str());
      return;
    }
    out = x;
  }
  void text(const char* key, std::string& out) {
    const json* v = get(key);
    if (!v || !status.isOk()) return;
    if (!v->is_string()) {
      status = invalid(source, std::string("field \"") + key + "\" must be a string");
      return;
    }
    out = v->get<std::string>();
  }
  void flag(const char* key, bool& out) {
    const json* v = get(key);
    if (!v || !status.isOk()) return;
    if (!v->is_boolean()) {
      status = invalid(source, std::string("field \"") + key + "\" must be true or false");
      return;
    }
    out = v->get<bool>();
  }
  void color(const char* key, std::string& out) {
    std::string value = out;
    text(key, value);
    if (!status.isOk()) return;
    if (!isHexColor(value)) {
      status = invalid(source, std::string("field \"") + key + "\" = \"" + printable(value) +
                                   "\" is not a #RRGGBB colour");
      return;
    }
    out = upper(value);
  }
  template <typename E>
  void choice(const char* key, E& out, const std::vector<std::pair<std::string, E>>& options) {
    const json* v = get(key);
    if (!v || !status.isOk()) return;
    std::string allowed;
    for (const auto& [name, value] : options) {
      allowed += (allowed.empty() ? "" : ", ") + name;
      if (v->is_string() && v->get<std::string>() == name) {
        out = value;
        return;
      }
    }
    status = invalid(source, std::string("field \"") + key + "\" must be one of " + allowed);
  }
};

constexpr TabSide kTabSides[] = {TabSide::A, TabSide::B, TabSide::Alternate, TabSide::None};
constexpr Joint kJoints[] = {Joint::Glue, Joint::Holes, Joint::Lace, Joint::Slots};
constexpr TickNumbers kNumbers[] = {TickNumbers::Face, TickNumbers::Tabs, TickNumbers::Both};

// The sheet materials: paper and card are glued with tabs; polypropylene (0.5 mm) is laced, its
// holes a little larger for a 2 mm cord; 3 mm plywood is joined with cable ties or bolts through
// hole pairs kept well in from the edge, where a thin edge of plywood would split.
// Plywood bends with a hinge: a lattice of cuts whose links (about as wide as the sheet is thick)
// twist. A 90-degree bend of 3 mm plywood with 3 mm links and a 0.2 mm kerf takes 23 rows (a
// 44 mm inner radius; the torsional-link sums of deferredprocrastination.co.uk's lattice hinge
// notes): rows 3.2 mm apart, 90/23 degrees each.
const MaterialPreset kMaterials[] = {
    {"paper", 0.1, Joint::Glue, 15, 2, 3},
    {"card", 0.3, Joint::Glue, 15, 2, 3},
    {"polypropylene", 0.5, Joint::Lace, 15, 3, 4},
    {"plywood", 3.0, Joint::Holes, 25, 4, 6, true, 3.2, 90.0 / 23},
};

const char* kKnownFields[] = {"version",
                              "name",
                              "description",
                              "kind",
                              "cut_color",
                              "score_color",
                              "engrave_color",
                              "cut_width_mm",
                              "score_width_mm",
                              "engrave_width_mm",
                              "fold",
                              "perforation_cut_mm",
                              "perforation_gap_mm",
                              "dash_mm",
                              "margin_mm",
                              "page",
                              "tile",
                              "tile_overlap_mm",
                              "registration",
                              "registration_clear_mm",
                              "calibration_bar",
                              "label_height_mm",
                              "kerf_mm",
                              "tabs",
                              "joint",
                              "numbers",
                              "bleed_mm",
                              "fill_color_a",
                              "fill_color_b",
                              "cut_spot_color",
                              "print_png_dpi"};

}  // namespace

Result<Profile> parseProfileJson(const std::string& text, const std::string& source) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    return Status{ErrorCode::InputUnreadable,
                  source + ": not JSON (" + parserReason(e.what()) + ")"};
  }
  if (!j.is_object()) return invalid(source, "a profile must be a JSON object");
  for (const auto& item : j.items()) {
    const auto& key = item.key();
    if (std::find(std::begin(kKnownFields), std::end(kKnownFields), key) == std::end(kKnownFields))
      return invalid(source, "unknown field \"" + printable(key) + "\" (see docs/export.md)");
  }
  Profile p;
  p.source = source;
  FieldReader r{j, source, Status::ok()};
  double version = 1;
  r.number("version", version, 1, 1);
  r.text("name", p.name);
  r.text("description", p.description);
  r.choice<ProfileKind>("kind", p.kind,
                        {{"laser", ProfileKind::Laser},
                         {"print", ProfileKind::Print},
                         {"print-and-cut", ProfileKind::PrintAndCut}});
  r.color("cut_color", p.cutColor);
  r.color("score_color", p.scoreColor);
  r.color("engrave_color", p.engraveColor);
  // Strokes: a laser wants hairlines (shops ask 0.01-0.025 mm; Cairo drops width 0), paper wants
  // lines a person can follow with scissors; 2 mm is far past either.
  const double maxWidth = p.kind == ProfileKind::Laser ? 0.1 : 2.0;
  r.number("cut_width_mm", p.cutWidthMm, 0.001, maxWidth);
  r.number("score_width_mm", p.scoreWidthMm, 0.001, maxWidth);
  r.number("engrave_width_mm", p.engraveWidthMm, 0.001, maxWidth);
  r.choice<FoldStyle>("fold", p.fold,
                      {{"score", FoldStyle::Score},
                       {"dashed", FoldStyle::Dashed},
                       {"perforated", FoldStyle::Perforated}});
  r.number("perforation_cut_mm", p.perforationCutMm, 0.05, 50);
  r.number("perforation_gap_mm", p.perforationGapMm, 0.05, 50);
  r.number("dash_mm", p.dashMm, 0.1, 50);
  r.number("margin_mm", p.marginMm, 0, 100);
  r.text("page", p.page);
  r.flag("tile", p.tile);
  r.number("tile_overlap_mm", p.tileOverlapMm, 0, 50);
  r.choice<Registration>("registration", p.registration,
                         {{"none", Registration::None},
                          {"silhouette", Registration::Silhouette},
                          {"cricut", Registration::Cricut}});
  r.number("registration_clear_mm", p.registrationClearMm, 0, 50);
  r.flag("calibration_bar", p.calibrationBar);
  r.number("label_height_mm", p.labelHeightMm, 0.5, 50);
  r.number("kerf_mm", p.kerfMm, 0, kMaxKerfMm);
  // Print shops ask for up to 3 mm of bleed; a cutter's registration is off by far less.
  r.number("bleed_mm", p.bleedMm, 0, 3);
  r.color("fill_color_a", p.fillColorA);
  r.color("fill_color_b", p.fillColorB);
  r.text("cut_spot_color", p.cutSpotColor);
  r.number("print_png_dpi", p.printPngDpi, 0, 1200);
  std::vector<std::pair<std::string, TabSide>> sides;
  for (TabSide side : kTabSides) sides.emplace_back(tabSideName(side), side);
  r.choice<TabSide>("tabs", p.tabs, sides);
  std::vector<std::pair<std::string, Joint>> joints;
  for (Joint joint : kJoints) joints.emplace_back(jointName(joint), joint);
  r.choice<Joint>("joint", p.joint, joints);
  std::vector<std::pair<std::string, TickNumbers>> numbers;
  for (TickNumbers n : kNumbers) numbers.emplace_back(tickNumbersName(n), n);
  r.choice<TickNumbers>("numbers", p.numbers, numbers);
  if (!r.status.isOk()) return r.status;
  if (!p.page.empty() && !pageSizeMm(p.page))
    return invalid(source,
                   "field \"page\" must be A4, Letter, A3, Tabloid, a size such as 200x300mm, or "
                   "absent");
  if (p.kind == ProfileKind::PrintAndCut && p.page.empty())
    return invalid(source, "a print-and-cut profile needs \"page\" (A4 or Letter)");
  if (p.tile && p.page.empty()) return invalid(source, "\"tile\" needs a \"page\"");
  const bool spotName = std::all_of(p.cutSpotColor.begin(), p.cutSpotColor.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (!spotName || p.cutSpotColor.size() > 64)
    return invalid(source,
                   "field \"cut_spot_color\" must be a name of letters, digits, '_' and '-' "
                   "(such as CutContour), at most 64 characters");
  if (p.kind != ProfileKind::PrintAndCut && (!p.cutSpotColor.empty() || p.printPngDpi > 0))
    return invalid(source,
                   "fields \"cut_spot_color\" and \"print_png_dpi\" are for print-and-cut "
                   "profiles: they split a print from its cut line");
  if (p.printPngDpi > 0 && p.printPngDpi < 72)
    return invalid(source, "field \"print_png_dpi\" must be 0 (none) or from 72 to 1200");
  if (p.kind != ProfileKind::PrintAndCut && p.bleedMm > 0)
    return invalid(source,
                   "field \"bleed_mm\" is for print-and-cut profiles: scissors follow the printed "
                   "line, which a bleed leaves out, and a laser prints nothing");
  return p;
}

std::string pageName(const std::string& name) {
  std::string lower;
  for (char c : name) lower += char(std::tolower(static_cast<unsigned char>(c)));
  for (const char* named : {"A4", "A3", "Letter", "Tabloid"}) {
    std::string n = named;
    for (char& c : n) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (lower == n) return named;
  }
  return lower;
}

std::optional<std::pair<double, double>> pageSizeMm(const std::string& given) {
  const std::string name = pageName(given);
  if (name == "A4") return std::pair{210.0, 297.0};
  if (name == "A3") return std::pair{297.0, 420.0};
  if (name == "Letter") return std::pair{8.5 * 25.4, 11.0 * 25.4};
  if (name == "Tabloid") return std::pair{11.0 * 25.4, 17.0 * 25.4};
  double w = 0, h = 0;
  char unit[8] = "";
  char rest = 0;
  if (std::sscanf(name.c_str(), "%lfx%lf%7[a-z]%c", &w, &h, unit, &rest) != 3) return std::nullopt;
  const std::string u = unit;
  const double scale = u == "mm" ? 1.0 : u == "cm" ? 10.0 : u == "in" ? 25.4 : 0.0;
  // A page smaller than 50 mm holds no piece with its marks; over 2 m is a sheet, not a page.
  if (scale == 0.0 ||
      !(w * scale >= 50 && h * scale >= 50 && w * scale <= 2000 && h * scale <= 2000))
    return std::nullopt;
  return std::pair{w * scale, h * scale};
}

std::string sheetFileName(int sheet, const std::string& extension) {
  return "pattern-sheet-" + std::to_string(sheet) + "." + extension;
}

std::string printSheetFileName(int sheet, const std::string& extension) {
  return (extension == "png" ? "print-sheet-" : "cut-sheet-") + std::to_string(sheet) + "." +
         extension;
}

const char* tabSideName(TabSide side) {
  switch (side) {
    case TabSide::A: return "a";
    case TabSide::B: return "b";
    case TabSide::Alternate: return "alternate";
    case TabSide::None: return "none";
  }
  return "?";
}

std::optional<TabSide> tabSideNamed(const std::string& name) {
  for (TabSide side : kTabSides)
    if (name == tabSideName(side)) return side;
  return std::nullopt;
}

const char* tickNumbersName(TickNumbers numbers) {
  switch (numbers) {
    case TickNumbers::Face: return "face";
    case TickNumbers::Tabs: return "tabs";
    case TickNumbers::Both: return "both";
  }
  return "?";
}

std::optional<TickNumbers> tickNumbersNamed(const std::string& name) {
  for (TickNumbers n : kNumbers)
    if (name == tickNumbersName(n)) return n;
  return std::nullopt;
}

const char* jointName(Joint joint) {
  switch (joint) {
    case Joint::Glue: return "glue";
    case Joint::Holes: return "holes";
    case Joint::Lace: return "lace";
    case Joint::Slots: return "slots";
  }
  return "?";
}

std::optional<Joint> jointNamed(const std::string& name) {
  for (Joint joint : kJoints)
    if (name == jointName(joint)) return joint;
  return std::nullopt;
}

std::optional<MaterialPreset> materialNamed(const std::string& name) {
  for (const MaterialPreset& m : kMaterials)
    if (name == m.name) return m;
  return std::nullopt;
}

std::vector<std::string> tabSideNames() {
  std::vector<std::string> names;
  for (TabSide side : kTabSides) names.push_back(tabSideName(side));
  return names;
}

std::vector<std::string> tickNumbersNames() {
  std::vector<std::string> names;
  for (TickNumbers n : kNumbers) names.push_back(tickNumbersName(n));
  return names;
}

std::vector<std::string> jointNames() {
  std::vector<std::string> names;
  for (Joint joint : kJoints) names.push_back(jointName(joint));
  return names;
}

std::vector<std::string> materialPresetNames() {
  std::vector<std::string> names;
  for (const MaterialPreset& m : kMaterials) names.push_back(m.name);
  return names;
}

std::string materialNames() {
  std::string names;
  for (const MaterialPreset& m : kMaterials) names += (names.empty() ? "" : ", ") + m.name;
  return names;
}

std::string rigidMaterials() {
  std::string names;
  for (const MaterialPreset& m : kMaterials)
    if (m.hinge) names += (names.empty() ? "" : ", ") + m.name;
  return names;
}

std::vector<std::string> listProfiles(const std::string& templatesDir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::path(templatesDir) / "profiles", ec)) {
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

Result<Profile> loadProfile(const std::string& nameOrPath, const std::string& templatesDir) {
  std::string path = nameOrPath;
  const bool looksLikePath =
      nameOrPath.find('/') != std::string::npos || fs::path(nameOrPath).extension() == ".json";
  if (!looksLikePath) {
    path = (fs::path(templatesDir) / "profiles" / (nameOrPath + ".json")).string();
    if (!fs::exists(path)) {
      std::string known;
      for (const auto& n : listProfiles(templatesDir)) known += (known.empty() ? "" : ", ") + n;
      return Status{ErrorCode::Usage,
                    "unknown profile \"" + nameOrPath + "\" (known: " +
                        (known.empty() ? "none found in " + templatesDir + "/profiles" : known) +
                        ")"};
    }
  }
  const Result<std::string> text = readInputFile(path, kMaxSettingsBytes);
  if (!text.isOk()) return text.status();
  Result<Profile> profile = parseProfileJson(text.value(), path);
  if (profile.isOk() && profile.value().name.empty())
    profile.value().name = fs::path(path).stem().string();
  return profile;
}

namespace fab {

Result<Profile> resolveProfile(const ExportOptions& options) {
  Result<Profile> loaded = options.useProfileOverride
                               ? Result<Profile>(options.profileOverride)
                               : loadProfile(options.profile, options.templatesDir);
  if (!loaded.isOk()) return loaded;
  Profile p = loaded.value();
  // Scissors follow the printed line: a kerf would move the line off the pattern's true size.
  if (options.kerfMm && *options.kerfMm > 0 && p.kind == ProfileKind::Print)
    return Status{ErrorCode::Usage, "kerf: profile " + p.name +
                                        " is cut by hand along its printed line, which has no "
                                        "kerf; a laser or print-and-cut profile takes one"};
  if (options.kerfMm) p.kerfMm = *options.kerfMm;
  if (options.numbers) p.numbers = *options.numbers;
  const std::optional<MaterialPreset> material = materialNamed(options.material);
  if (options.joint)
    p.joint = *options.joint;
  else if (material)
    p.joint = material->joint;
  // Holes, lace and slots join the pieces: glue tabs only where asked for.
  if (p.joint != Joint::Glue) p.tabs = TabSide::None;
  if (options.tabSide) p.tabs = *options.tabSide;
  if (p.joint == Joint::Slots && (p.tabs == TabSide::A || p.tabs == TabSide::Alternate))
    return Status{ErrorCode::Usage, mention(Setting::Joint) +
                                        " slots puts its tongues on A's seam: glue tabs go on B (" +
                                        mention(Setting::Tabs) + " b) or none, not on " +
                                        tabSideName(p.tabs)};
  return p;
}

JointSettings jointSettings(const ExportOptions& o, const Profile& profile) {
  JointSettings j;
  j.joint = profile.joint;
  if (const std::optional<MaterialPreset> m = materialNamed(o.material)) {
    j.material = m->name;
    j.thicknessMm = m->thicknessMm;
    j.spacingMm = m->holeSpacingMm;
    j.diameterMm = m->holeDiameterMm;
    j.edgeMm = m->holeEdgeMm;
  }
  j.spacingMm = o.holeSpacingMm.value_or(j.spacingMm);
  j.diameterMm = o.holeDiameterMm.value_or(j.diameterMm);
  j.edgeMm = o.holeEdgeMm.value_or(j.edgeMm);
  j.slotLengthMm = o.slotLengthMm.value_or(0.5 * j.spacingMm);
  j.slotWidthMm = std::max((j.thicknessMm > 0 ? j.thicknessMm : 0.3) + 0.2, profile.kerfMm + 0.1);
  return j;
}

}  // namespace fab

}  // namespace dform
