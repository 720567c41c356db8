// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table's rows: each setting's names, type, range or choices, unit, help, and how it
// reads and writes its member of a Job (pipeline/settings.h, setting_rows.h).
#include "setting_rows.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "dform/core/constants.h"
#include "dform/core/message_text.h"
#include "dform/model/term_table.h"

namespace dform {

using nlohmann::json;

std::string numberText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

ForwardJob& forwardOf(Job& job) { return std::get<ForwardJob>(job.run); }
const ForwardJob& forwardOf(const Job& job) { return std::get<ForwardJob>(job.run); }
InverseJob& inverseOf(Job& job) { return std::get<InverseJob>(job.run); }
const InverseJob& inverseOf(const Job& job) { return std::get<InverseJob>(job.run); }

// The accessors are made once, with the rows, and live as long as the table.
std::vector<std::unique_ptr<SettingAccess>>& accessors() {
  static std::vector<std::unique_ptr<SettingAccess>> made;
  return made;
}

const SettingAccess* access(std::function<json(const Job&)> get,
                            std::function<std::string(Job&, const json&)> set) {
  accessors().push_back(std::make_unique<SettingAccess>(SettingAccess{get, set}));
  return accessors().back().get();
}

// A member of the mode's job (ForwardJob or InverseJob, or a struct it derives from) stored as the
// JSON value's own type.
template <typename Mode, typename Owner, typename T>
const SettingAccess* member(T Owner::*field) {
  return access([field](const Job& job) { return json(std::get<Mode>(job.run).*field); },
                [field](Job& job, const json& v) {
                  std::get<Mode>(job.run).*field = v.get<T>();
                  return std::string();
                });
}

// A member both modes have, each its own: the resolution.
template <typename T>
const SettingAccess* solveMember(T ForwardSettings::*forward, T InverseSettings::*inverse) {
  return access(
      [=](const Job& job) {
        return json(job.isForward() ? forwardOf(job).*forward : inverseOf(job).*inverse);
      },
      [=](Job& job, const json& v) {
        (job.isForward() ? forwardOf(job).*forward : inverseOf(job).*inverse) = v.get<T>();
        return std::string();
      });
}

// One of Levenberg-Marquardt's options, in either mode's solver.
template <typename T>
const SettingAccess* solverMember(T SolverOptions::*field) {
  return access(
      [=](const Job& job) {
        return json((job.isForward() ? forwardOf(job).solver : inverseOf(job).solver).*field);
      },
      [=](Job& job, const json& v) {
        (job.isForward() ? forwardOf(job).solver : inverseOf(job).solver).*field = v.get<T>();
        return std::string();
      });
}

// A member of the export options or of the export settings around them.
template <typename T>
const SettingAccess* exportMember(T ExportOptions::*field) {
  return access([field](const Job& job) { return json(job.exporting.pattern.*field); },
                [field](Job& job, const json& v) {
                  job.exporting.pattern.*field = v.get<T>();
                  return std::string();
                });
}

template <typename T>
const SettingAccess* optionalExportMember(std::optional<T> ExportOptions::*field) {
  return access(
      [field](const Job& job) {
        const std::optional<T>& value = job.exporting.pattern.*field;
        return value ? json(*value) : json(nullptr);
      },
      [field](Job& job, const json& v) {
        job.exporting.pattern.*field = v.is_null() ? std::optional<T>() : v.get<T>();
        return std::string();
      });
}

template <typename T>
const SettingAccess* outputMember(T ExportSettings::*field) {
  return access([field](const Job& job) { return json(job.exporting.*field); },
                [field](Job& job, const json& v) {
                  job.exporting.*field = v.get<T>();
                  return std::string();
                });
}

// An optional member holding an enum named by `name`, read back by `named`.
template <typename E>
const SettingAccess* optionalNamedMember(std::optional<E> ExportOptions::*field,
                                         const char* (*name)(E),
                                         std::optional<E> (*named)(const std::string&)) {
  return access(
      [=](const Job& job) {
        const std::optional<E>& value = job.exporting.pattern.*field;
        return value ? json(name(*value)) : json(nullptr);
      },
      [=](Job& job, const json& v) {
        job.exporting.pattern.*field =
            v.is_null() ? std::optional<E>() : named(v.get<std::string>());
        return std::string();
      });
}

json startJson(const StartPoint& s) {
  if (s.nearestToPoint) return json{{"near", {s.point.x(), s.point.y()}}};
  return s.fraction;
}

StartPoint startPoint(const json& v) {
  StartPoint s;
  if (v.is_number()) {
    s.fraction = v.get<double>();
  } else if (v.contains("fraction")) {
    s.fraction = v["fraction"].get<double>();
  } else {
    s.nearestToPoint = true;
    s.point = {v["near"][0].get<double>(), v["near"][1].get<double>()};
  }
  return s;
}

const SettingAccess* startMember(StartPoint ForwardSettings::*field) {
  return access([field](const Job& job) { return startJson(forwardOf(job).*field); },
                [field](Job& job, const json& v) {
                  forwardOf(job).*field = startPoint(v);
                  return std::string();
                });
}

// The join: A's joined boundary then B's. Setting it sets the weights to the join's defaults
// (defaultWeights): the table applies the weights after it.
const SettingAccess* joinMember() {
  return access(
      [](const Job& job) {
        const ForwardJob& f = forwardOf(job);
        return json(std::string(joinedBoundaryName(f.joinA)) + "," + joinedBoundaryName(f.joinB));
      },
      [](Job& job, const json& v) {
        ForwardJob& f = forwardOf(job);
        parseJoin(v.get<std::string>(), f.joinA, f.joinB);  // a choice: checked already
        f.weights = defaultWeights(f.joinA, f.joinB);
        return std::string();
      });
}

const SettingAccess* modelMember() {
  return access([](const Job& job) { return json(modelChoiceName(forwardOf(job).model)); },
                [](Job& job, const json& v) {
                  parseModelChoice(v.get<std::string>(), forwardOf(job).model);
                  return std::string();
                });
}

template <typename Weights, typename Mode>
const SettingAccess* weightMember(double Weights::*weight) {
  return access([weight](const Job& job) { return json(std::get<Mode>(job.run).weights.*weight); },
                [weight](Job& job, const json& v) {
                  std::get<Mode>(job.run).weights.*weight = v.get<double>();
                  return std::string();
                });
}

// "600x400mm", "60x40cm", "23.6x15.7in" -> millimetres; "" when it is of that form. The unit is
// needed, as the page's is: a bare 24x16 may be inches.
std::string sheetProblem(const std::string& text, double& w, double& h) {
  char unit[8] = "";
  const int n = std::sscanf(text.c_str(), "%lfx%lf%7s", &w, &h, unit);
  std::string u = unit;
  for (char& c : u) c = char(std::tolower(static_cast<unsigned char>(c)));
  const double scale = u == "mm" ? 1.0 : u == "cm" ? 10.0 : u == "in" ? 25.4 : 0.0;
  if (n == 2)
    return "needs a unit (mm, cm or in), as in " + printable(text) + "mm, got '" + printable(text) +
           "'";
  if (n < 2 || scale == 0.0 || !(w > 0 && h > 0 && std::isfinite(w) && std::isfinite(h)))
    return "must look like 600x400mm (units mm, cm or in), got '" + printable(text) + "'";
  w *= scale;
  h *= scale;
  return "";
}

const SettingAccess* sheetMember() {
  return access(
      [](const Job& job) {
        const ExportOptions& o = job.exporting.pattern;
        return o.sheetGiven
                   ? json(numberText(o.sheetWidthMm) + "x" + numberText(o.sheetHeightMm) + "mm")
                   : json(nullptr);
      },
      [](Job& job, const json& v) {
        ExportOptions& o = job.exporting.pattern;
        if (v.is_null()) {
          const ExportOptions fresh;
          o.sheetWidthMm = fresh.sheetWidthMm;
          o.sheetHeightMm = fresh.sheetHeightMm;
          o.sheetGiven = false;
          return std::string();
        }
        double w = 0, h = 0;
        if (std::string why = sheetProblem(v.get<std::string>(), w, h); !why.empty()) return why;
        o.sheetWidthMm = w;
        o.sheetHeightMm = h;
        o.sheetGiven = true;
        return std::string();
      });
}

const SettingAccess* pageMember() {
  return access(
      [](const Job& job) {
        const std::string& page = job.exporting.pattern.page;
        return page.empty() ? json(nullptr) : json(page);
      },
      [](Job& job, const json& v) {
        const std::string page = v.is_null() ? "" : v.get<std::string>();
        if (!page.empty() && !pageSizeMm(page))
          return "must be A4, Letter, A3, Tabloid or a size such as 200x300mm, got '" +
                 printable(page) + "'";
        job.exporting.pattern.page = page.empty() ? "" : pageName(page);
        return std::string();
      });
}

// The scale: a number (0.8), a percentage ("80%") or "fit", within the row's range.
const SettingAccess* scaleMember(double min, double max) {
  return access(
      [](const Job& job) {
        const ExportOptions& o = job.exporting.pattern;
        return o.scaleToFit ? json("fit") : json(o.scale);
      },
      [min, max](Job& job, const json& v) {
        ExportOptions& o = job.exporting.pattern;
        double value = 0;
        if (v.is_string() && v.get<std::string>() == "fit") {
          o.scaleToFit = true;
          o.scale = ExportOptions().scale;
          return std::string();
        }
        if (v.is_number()) {
          value = v.get<double>();
        } else {
          char rest[4] = "";
          const std::string text = v.get<std::string>();
          const int n = std::sscanf(text.c_str(), "%lf%3s", &value, rest);
          const std::string unit = rest;
          if (n < 1 || !(unit.empty() || unit == "%"))
            return "must be a number (0.8), a percentage (80%) or fit, got '" + printable(text) +
                   "'";
          if (unit == "%") value /= 100;
        }
        if (!(value >= min && value <= max))
          return "must be between " + numberText(min) + " (" + numberText(100 * min) + "%) and " +
                 numberText(max);
        o.scale = value;
        o.scaleToFit = false;
        return std::string();
      });
}

const SettingAccess* textOutputMember(std::string ExportSettings::*field) {
  return outputMember(field);
}

const SettingAccess* materialMember() {
  return access(
      [](const Job& job) {
        const std::string& m = job.exporting.pattern.material;
        return m.empty() ? json(nullptr) : json(m);
      },
      [](Job& job, const json& v) {
        job.exporting.pattern.material = v.is_null() ? "" : v.get<std::string>();
        return std::string();
      });
}

const SettingAccess* gltfMember() {
  return access([](const Job& job) { return json(!job.exporting.pattern.gltfBinary); },
                [](Job& job, const json& v) {
                  job.exporting.pattern.gltfBinary = !v.get<bool>();
                  return std::string();
                });
}

std::vector<SettingChoice> names(const std::vector<std::string>& list) {
  std::vector<SettingChoice> out;
  for (const std::string& name : list) out.push_back({name, ""});
  return out;
}

std::vector<SettingChoice> modelChoiceList() {
  std::vector<SettingChoice> out;
  for (const ModelChoiceInfo& m : modelChoices()) out.push_back({m.name, m.help});
  return out;
}

std::vector<SettingChoice> joinChoiceList() {
  std::vector<SettingChoice> out;
  for (const JoinChoiceInfo& j : joinChoices()) out.push_back({j.name, j.help});
  return out;
}

// Each mode's weights, one row per term of its table, keyed "weights.<term>".
template <typename Weights, typename Mode>
void addWeights(std::vector<SettingRow>& rows, const TermTable<Weights>& table,
                SettingScope scope) {
  for (const TermRow<Weights>& term : table) {
    SettingRow row;
    row.id = Setting::Weight;
    row.key = std::string(settingKey(Setting::Weight)) + "." + term.name;
    row.flag = "--weight";
    row.keyword = "weights";
    row.scope = scope;
    row.type = SettingType::Weight;
    row.help = term.help;
    row.min = 0;
    row.access = weightMember<Weights, Mode>(term.weight);
    rows.push_back(row);
  }
}

// A row: its setting (whose key is its job-file key), command-line flag, Python keyword, scope,
// type and help; the rest set by the caller.
SettingRow row(Setting id, const char* flag, const char* keyword, SettingScope scope,
               SettingType type, const char* help, const SettingAccess* how) {
  SettingRow r;
  r.id = id;
  r.key = settingKey(id);
  r.flag = flag;
  r.keyword = keyword;
  r.scope = scope;
  r.type = type;
  r.help = help;
  r.access = how;
  return r;
}

SettingRow ranged(SettingRow r, double min, double max, const char* unit = "") {
  r.min = min;
  r.max = max;
  r.unit = unit;
  return r;
}

SettingRow optional(SettingRow r, const std::string& unset) {
  r.unset = unset;
  return r;
}

void addForwardRows(std::vector<SettingRow>& rows) {
  using S = SettingScope;
  using T = SettingType;
  SettingRow model = row(Setting::Model, "--model", "model", S::Forward, T::Choice,
                         "which model makes the 3D shape", modelMember());
  model.choices = modelChoiceList();
  SettingRow join = row(Setting::Join, "--join", "join", S::Forward, T::Choice,
                        "the boundaries zipped, A's then B's", joinMember());
  join.choices = joinChoiceList();
  SettingRow startA = row(Setting::StartA, "--start-a", "start_a", S::Forward, T::Start,
                          "where A's seam starts: an arc-length fraction from the outline's "
                          "first point, or the outline point nearest a point",
                          startMember(&ForwardSettings::startA));
  startA.nearFlag = "--start-a-near";
  SettingRow startB = row(Setting::StartB, "--start-b", "start_b", S::Forward, T::Start,
                          "where B's seam starts: an arc-length fraction from the outline's first "
                          "point, or the outline point nearest a point",
                          startMember(&ForwardSettings::startB));
  startB.nearFlag = "--start-b-near";
  rows.push_back(model);
  rows.push_back(join);
  rows.push_back(startA);
  rows.push_back(startB);
  rows.push_back(ranged(
      row(Setting::InteriorEdge, "--interior-edge", "interior_edge", S::Forward, T::Number,
          "interior edge length over the seam's edge length: above 1 a coarser, faster mesh at "
          "the same seam resolution",
          member<ForwardJob>(&ForwardJob::interiorEdgeFactor)),
      kMinInteriorEdgeFactor, kMaxInteriorEdgeFactor));
  rows.push_back(row(Setting::Flip, "--flip", "flip", S::Forward, T::Flag,
                     "zip piece B turned over (its mirror image)",
                     member<ForwardJob>(&ForwardJob::flip)));
  rows.push_back(row(Setting::FitPerimeter, "--fit-perimeter", "fit_perimeter", S::Forward, T::Flag,
                     "scale piece B uniformly to A's perimeter",
                     member<ForwardJob>(&ForwardJob::fitPerimeter)));
  SettingRow tolerance = ranged(
      row(Setting::PerimeterTolerance, "--perimeter-tolerance", "perimeter_tolerance", S::Forward,
          T::Number, "the largest relative difference of the joined lengths accepted as equal",
          member<ForwardJob>(&ForwardJob::perimeterTolerance)),
      0, 1);
  tolerance.minExcluded = tolerance.maxExcluded = true;
  rows.push_back(tolerance);
  addWeights<ForwardWeights, ForwardJob>(rows, forwardTerms(), S::Forward);
}

void addInverseRows(std::vector<SettingRow>& rows) {
  rows.push_back(row(Setting::Closed, "--closed", "closed", SettingScope::Inverse,
                     SettingType::Flag, "close an open OBJ polyline",
                     member<InverseJob>(&InverseJob::forceClosed)));
  addWeights<InverseWeights, InverseJob>(rows, inverseTerms(), SettingScope::Inverse);
}

void addSolveRows(std::vector<SettingRow>& rows) {
  using S = SettingScope;
  using T = SettingType;
  rows.push_back(
      ranged(row(Setting::Resolution, "--resolution", "resolution", S::Solve, T::Integer,
                 "seam vertices per piece (forward) or points of the curve (inverse)",
                 solveMember(&ForwardSettings::resolution, &InverseSettings::resolution)),
             kMinResolution, kMaxResolution));
  rows.push_back(
      ranged(row(Setting::MaxIterations, "--max-iterations", "max_iterations", S::Solve, T::Integer,
                 "Levenberg-Marquardt's iteration cap (0: the relaxation alone)",
                 solverMember(&SolverOptions::maxIterations)),
             0, std::numeric_limits<int>::max()));
  rows.push_back(ranged(
      row(Setting::FunctionTolerance, "--function-tolerance", "function_tolerance", S::Solve,
          T::Number,
          "Levenberg-Marquardt stops once a step lowers the objective by less than this part of it",
          solverMember(&SolverOptions::functionTolerance)),
      0, kInfinity));
  rows.push_back(ranged(
      row(Setting::GradientTolerance, "--gradient-tolerance", "gradient_tolerance", S::Solve,
          T::Number, "Levenberg-Marquardt stops once the gradient's largest entry is below this",
          solverMember(&SolverOptions::gradientTolerance)),
      0, kInfinity));
}

void addExportRows(std::vector<SettingRow>& rows) {
  using S = SettingScope;
  using T = SettingType;
  const ExportOptions fresh;
  rows.push_back(row(Setting::Profile, "--profile", "profile", S::Export, T::Text,
                     "export profile: the name of one in templates/profiles/, or a .json file",
                     exportMember(&ExportOptions::profile)));
  rows.push_back(optional(
      row(Setting::Sheet, "--sheet", "sheet", S::Export, T::Text,
          "material sheet of a laser profile, WxH with a unit mm, cm or in", sheetMember()),
      numberText(fresh.sheetWidthMm) + "x" + numberText(fresh.sheetHeightMm) + "mm"));
  rows.push_back(
      optional(row(Setting::Page, "--page", "page", S::Export, T::Text,
                   "paper of a print profile: A4, Letter, A3, Tabloid or WxHmm", pageMember()),
               "the profile's"));
  rows.push_back(ranged(
      row(Setting::Scale, "--scale", "scale", S::Export, T::Text,
          "pattern scale: a number (0.8), a percentage (80%), or fit (the largest scale up to 1 "
          "at which every piece fits its page or sheet)",
          scaleMember(kMinPatternScale, kMaxPatternScale)),
      kMinPatternScale, kMaxPatternScale));
  rows.push_back(ranged(row(Setting::TabWidth, "--tab-width", "tab_width", S::Export, T::Number,
                            "glue tab width, 0 for none", exportMember(&ExportOptions::tabWidthMm)),
                        0, kMaxTabWidthMm, "mm"));
  SettingRow tabs = optional(
      row(Setting::Tabs, "--tabs", "tabs", S::Export, T::Choice, "which piece gets the glue tabs",
          optionalNamedMember<TabSide>(&ExportOptions::tabSide, tabSideName, tabSideNamed)),
      "the profile's");
  tabs.choices = names(tabSideNames());
  rows.push_back(tabs);
  rows.push_back(
      ranged(row(Setting::TickSpacing, "--tick-spacing", "tick_spacing", S::Export, T::Number,
                 "seam length between numbered ticks", exportMember(&ExportOptions::tickSpacingMm)),
             kMinTickSpacingMm, kInfinity, "mm"));
  SettingRow joint =
      optional(row(Setting::Joint, "--joint", "joint", S::Export, T::Choice,
                   "how the pieces are joined (glue: tabs; holes: matched hole pairs for ties or "
                   "stitches; lace; slots: tongues on A through slots in B)",
                   optionalNamedMember<Joint>(&ExportOptions::joint, jointName, jointNamed)),
               "the material's, else the profile's");
  joint.choices = names(jointNames());
  rows.push_back(joint);
  SettingRow material =
      optional(row(Setting::Material, "--material", "material", S::Export, T::Choice,
                   "sheet material, setting the joint and the hole sizes", materialMember()),
               "none");
  material.choices = names(materialPresetNames());
  rows.push_back(material);
  rows.push_back(
      optional(ranged(row(Setting::Kerf, "--kerf", "kerf", S::Export, T::Number,
                          "the cutter's kerf: cut paths move half of it away from the material",
                          optionalExportMember(&ExportOptions::kerfMm)),
                      0, kMaxKerfMm, "mm"),
               "the profile's"));
  rows.push_back(
      optional(ranged(row(Setting::HoleSpacing, "--hole-spacing", "hole_spacing", S::Export,
                          T::Number, "joint holes: largest distance between neighbouring holes",
                          optionalExportMember(&ExportOptions::holeSpacingMm)),
                      0, kMaxHoleSpacingMm, "mm"),
               "the material's, else " + numberText(MaterialPreset().holeSpacingMm) + " mm"));
  rows.push_back(optional(
      ranged(row(Setting::HoleDiameter, "--hole-diameter", "hole_diameter", S::Export, T::Number,
                 "joint holes: diameter", optionalExportMember(&ExportOptions::holeDiameterMm)),
             kMinHoleDiameterMm, kMaxHoleDiameterMm, "mm"),
      "the material's, else " + numberText(MaterialPreset().holeDiameterMm) + " mm"));
  rows.push_back(
      optional(ranged(row(Setting::HoleEdge, "--hole-edge", "hole_edge", S::Export, T::Number,
                          "joint holes: distance from the seam to the hole centres",
                          optionalExportMember(&ExportOptions::holeEdgeMm)),
                      0, kMaxHoleEdgeMm, "mm"),
               "the material's, else " + numberText(MaterialPreset().holeEdgeMm) + " mm"));
  rows.push_back(optional(ranged(row(Setting::SlotLength, "--slot-length", "slot_length", S::Export,
                                     T::Number, "slots: a tongue's width along the seam",
                                     optionalExportMember(&ExportOptions::slotLengthMm)),
                                 kMinSlotLengthMm, kInfinity, "mm"),
                          "half the hole spacing"));
  rows.push_back(
      optional(ranged(row(Setting::ScoreFolds, "--score-folds", "score_folds", S::Export, T::Number,
                          "score every fold of the solved body of at least this angle on its piece",
                          optionalExportMember(&ExportOptions::scoreFoldsDeg)),
                      0, 180, "degrees"),
               "no folds scored"));
  SettingRow numbers = optional(
      row(Setting::Numbers, "--numbers", "numbers", S::Export, T::Choice,
          "where the ticks' numbers are printed (tabs: on the glue tabs, hidden once glued)",
          optionalNamedMember<TickNumbers>(&ExportOptions::numbers, tickNumbersName,
                                           tickNumbersNamed)),
      "the profile's");
  numbers.choices = names(tickNumbersNames());
  rows.push_back(numbers);
  SettingRow hinge = optional(row(Setting::Hinge, "--hinge", "hinge", S::Export, T::Flag,
                                  "kerf-bending cuts where the shape bends (a rigid sheet)",
                                  optionalExportMember(&ExportOptions::hinge)),
                              "the material's: on for " + rigidMaterials());
  hinge.offFlag = "--no-hinge";
  rows.push_back(hinge);
  SettingRow title =
      row(Setting::Title, "--no-title", "title", S::Export, T::Flag,
          "the title block and notes on the pattern sheets", exportMember(&ExportOptions::title));
  title.flagValue = false;
  rows.push_back(title);
  rows.push_back(row(Setting::Gltf, "--gltf", "gltf", S::Export, T::Flag,
                     "write the 3D preview as text dform.gltf instead of dform.glb", gltfMember()));
}

void addOutputRows(std::vector<SettingRow>& rows) {
  using S = SettingScope;
  using T = SettingType;
  SettingRow cutting =
      row(Setting::CuttingFiles, "--no-export", "cutting_files", S::Output, T::Flag,
          "the cutting patterns and 3D previews", outputMember(&ExportSettings::cuttingFiles));
  cutting.flagValue = false;
  rows.push_back(cutting);
  rows.push_back(row(Setting::ExportAnyway, "--export-anyway", "export_anyway", S::Output, T::Flag,
                     "release the cutting files even when the gate fails (marked FAILED "
                     "GATE)",
                     outputMember(&ExportSettings::exportAnyway)));
  rows.push_back(row(Setting::Gate, "--gate", "gate", S::Output, T::Text,
                     "quality gate: default, strict, lenient, a .json file, or none",
                     textOutputMember(&ExportSettings::gate)));
}

}  // namespace

std::vector<SettingRow> makeSettingRows() {
  std::vector<SettingRow> rows;
  addForwardRows(rows);
  addInverseRows(rows);
  addSolveRows(rows);
  addExportRows(rows);
  addOutputRows(rows);
  return rows;
}

}  // namespace dform
