// SPDX-License-Identifier: GPL-3.0-or-later
#include "run_steps.h"

#include <dlfcn.h>
#include <signal.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "dform/core/atomic_file.h"
#include "dform/core/constants.h"
#include "dform/core/message_text.h"
#include "dform/io/model_files.h"
#include "dform/report/html_report.h"
#include "dform/validate/metrics.h"

namespace dform {

namespace fs = std::filesystem;

namespace {

// Holds SIGINT and SIGTERM back for its lifetime; one that came meanwhile is delivered when it
// ends (a first one sets the run's flag, a second one ends the program: see main.cpp).
class StopSignalsHeld {
 public:
  StopSignalsHeld() {
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigprocmask(SIG_BLOCK, &stop, &previous_);
  }
  ~StopSignalsHeld() { sigprocmask(SIG_SETMASK, &previous_, nullptr); }
  StopSignalsHeld(const StopSignalsHeld&) = delete;
  StopSignalsHeld& operator=(const StopSignalsHeld&) = delete;

 private:
  sigset_t previous_;
};

}  // namespace

namespace {

// A dform templates folder holds the gate presets, the export profiles and the report page.
bool isTemplatesFolder(const fs::path& dir) {
  std::error_code ec;
  for (const char* part : {"gates", "profiles", "report"})
    if (!fs::is_directory(dir / part, ec)) return false;
  return true;
}

}  // namespace

Result<std::string> templatesDir() {
  if (const char* env = std::getenv("DFORM_TEMPLATES"); env && *env) {
    if (isTemplatesFolder(env)) return std::string(env);
    return Status(ErrorCode::InputUnreadable,
                  std::string("DFORM_TEMPLATES=") + env +
                      " is not a dform templates folder (it has no gates/, profiles/ or report/)");
  }
  // The folder `templates` beside the file that holds this code when that is a shared object (a
  // pip-installed Python module carries it), then the running program's own prefix (an
  // installed or relocated dform, the Debian package), then the source tree it was built from
  // when the program or module runs from the build folder (never for an installed copy: a
  // packager's tree is no place to look), then the configured install prefix.
  std::vector<fs::path> candidates;
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  fs::path code = program;
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&templatesDir), &self) != 0 && self.dli_fname &&
      fs::path(self.dli_fname).extension() == ".so") {
    code = fs::absolute(self.dli_fname, ec);
    candidates.push_back(code.parent_path() / "templates");
  }
  if (!program.empty())
    candidates.push_back(program.parent_path().parent_path() / "share/dform/templates");
  const std::string build = DFORM_BUILD_DIR "/";
  if (code.string().rfind(build, 0) == 0) candidates.push_back(DFORM_TEMPLATES_DIR);
  candidates.push_back(DFORM_INSTALLED_TEMPLATES_DIR);
  for (const fs::path& dir : candidates)
    if (isTemplatesFolder(dir)) return dir.string();
  std::string tried;
  for (const fs::path& dir : candidates) tried += (tried.empty() ? "" : ", ") + dir.string();
  return Status(ErrorCode::InputUnreadable, "no dform templates folder found (tried " + tried +
                                                "): set DFORM_TEMPLATES to one");
}

std::vector<std::string> exportProfileNames() {
  const Result<std::string> dir = templatesDir();
  return dir.isOk() ? listProfiles(dir.value()) : std::vector<std::string>{};
}

Result<GateLimits> loadGate(const std::string& nameOrPath) {
  const bool preset =
      nameOrPath.find('/') == std::string::npos && nameOrPath.find(".json") == std::string::npos;
  if (preset) {
    // A preset name that is not one is a usage mistake (2), as an unknown export profile is; a
    // gate file that cannot be read is unreadable input (3).
    const Result<std::string> templates = templatesDir();
    if (!templates.isOk()) return templates.status();
    const fs::path file = fs::path(templates.value()) / "gates" / (nameOrPath + ".json");
    std::error_code missing;
    if (!fs::exists(file, missing)) {
      std::set<std::string> names;
      for (const auto& entry : fs::directory_iterator(file.parent_path(), missing))
        if (entry.path().extension() == ".json") names.insert(entry.path().stem().string());
      std::string known;
      for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
      return Status(ErrorCode::Usage, mention(Setting::Gate) + ": unknown gate \"" + nameOrPath +
                                          "\" (known: " + known + ", or a gate .json file)");
    }
    return readGateFile(file.string());
  }
  // "gates/strict.json" as the docs write it: a path relative to templates/ when not one here.
  std::error_code ec;
  if (!fs::exists(nameOrPath, ec) && fs::path(nameOrPath).is_relative()) {
    const Result<std::string> templates = templatesDir();
    const std::string inTemplates = templates.isOk() ? templates.value() + "/" + nameOrPath : "";
    if (templates.isOk() && fs::exists(inTemplates, ec)) return readGateFile(inTemplates);
  }
  return readGateFile(nameOrPath);
}

// The export options of `settings` completed: the templates folder, the profile read once, now,
// not after the solve (when cutting files are written), and the options checked against each
// other. Each setting alone is in its range (checkOutput checks the table's rows first).
Result<ExportOptions> exportOptions(const ExportSettings& settings) {
  ExportOptions options = settings.pattern;
  const Result<std::string> templates = templatesDir();
  if (!templates.isOk()) return templates.status();
  options.templatesDir = templates.value();
  if (Status s = checkExportOptions(options); !s.isOk()) return s;
  if (settings.cuttingFiles) {
    Result<Profile> profile = loadProfile(options.profile, options.templatesDir);
    if (!profile.isOk()) return profile.status();
    options.profileOverride = profile.value();
    options.useProfileOverride = true;
    // The options against the profile (a kerf for scissors, tabs where slots go), before a solve.
    if (Status s = checkProfileOptions(options); !s.isOk()) return s;
  }
  return options;
}

std::vector<FoldToScore> foldsToScore(const ModelUsed& used, const DForm& model) {
  std::vector<FoldToScore> out;
  for (const BodyFold& f : used.folds) {
    const Points2& flat = f.piece == 0 ? model.a.flat : model.b.flat;
    // A crease is drawn already, as the piece's crease line: hinged, never scored.
    out.push_back({f.piece, flat.row(f.from).transpose(), flat.row(f.to).transpose(),
                   f.radians / kDegree, f.crease >= 0});
  }
  return out;
}

ExportOptions withFolds(ExportOptions options, std::vector<FoldToScore> folds,
                        const std::string& modelName, MessageSink& sink) {
  const std::optional<MaterialPreset> material = materialNamed(options.material);
  const bool hinged = options.hinge.value_or(material && material->hinge);
  if (!options.scoreFoldsDeg && !hinged) return options;
  const std::string whose = modelName.empty() ? std::string("saved") : modelName + " model's";
  if (folds.empty() && options.scoreFoldsDeg)
    sink.warning(mention(Setting::ScoreFolds) + ": no folds known: the " + whose +
                 " result has none; no score lines added");
  if (folds.empty() && hinged)
    sink.warning("hinge: no folds known: the " + whose +
                 " result has none; no kerf-bending cuts (the exact and ruled models' results "
                 "have them)");
  options.folds = std::move(folds);
  return options;
}

// Lays out the cutting patterns of `model` once, not yet rendered. The glTF preview will carry
// the curvature map the report shows (COLOR_0).
Result<LaidOutExport> layOut(const DForm& model, ExportOptions options,
                             const std::string& jobName) {
  options.jobName = utf8Text(jobName);  // Cairo's PDF metadata and the SVG title take UTF-8 only
  options.failedGateMark = false;       // stamped, if at all, once the gate is known (render)
  const Eigen::VectorXd curvature[2] = {curvatureMap(model.a), curvatureMap(model.b)};
  options.curvatureA.assign(curvature[0].data(), curvature[0].data() + curvature[0].size());
  options.curvatureB.assign(curvature[1].data(), curvature[1].data() + curvature[1].size());
  return layOutExport(model, options);
}

// Renders a laid-out pattern, stamped FAILED GATE when the gate failed.
Result<PreparedExport> render(const DForm& model, const LaidOutExport& laidOut, bool failedGate) {
  return renderExport(model, failedGate ? markFailedGate(laidOut) : laidOut);
}

// A run's job name: its first input's file name.
std::string jobName(const Job& job) { return fs::path(job.inputs().front()).stem().string(); }

// The gate's fabrication check: the laid-out pattern fits the sheet and nothing on it overlaps.
CheckResult layoutCheck(const LayoutFindings& f) {
  const std::string detail =
      f.problems() == 0
          ? "every path on the sheet; tabs, pieces and labels clear of each other"
          : std::to_string(f.outsideSheet) + " off the sheet, " +
                std::to_string(f.overlappingTabs) + " overlapping tab pairs, " +
                std::to_string(f.tabsOverPieces) + " tabs over a piece, " +
                std::to_string(f.overlappingPieces) + " overlapping pieces, " +
                std::to_string(f.labelsOutside) + " labels outside their piece, " +
                std::to_string(f.overlappingLabels) + " overlapping label pairs, " +
                std::to_string(f.titleOverlaps) + " title lines over a piece or mark, " +
                std::to_string(f.extraCutLoops) +
                " cut loops cut free of their piece; first: " + f.example;
  return judgeCheck("pattern_layout", f.problems(), 0, detail);
}

// Says what a prepared export holds, before it is written (so that the report has it).
void noteExport(const PreparedExport& prepared, MessageSink& sink) {
  for (const std::string& note : prepared.summary.messages) sink.info("export: " + note);
  for (const std::string& w : prepared.summary.warnings) sink.warning("export: " + w);
  sink.info("export (" + prepared.summary.profile + "): " + std::to_string(prepared.files.size()) +
            " files");
}

Status writeReportPage(const std::string& dir, const std::string& reportJson,
                       const std::string& reportPath, const PreparedExport* exported,
                       const DForm& model) {
  ReportSources sources;
  sources.reportJson = reportJson;
  sources.reportPath = reportPath;
  if (exported) {
    for (const auto& [name, content] : exported->files) {
      if (name == "pattern.svg") sources.patternSvg = content;
      if (name == "assembly.svg") sources.assemblySvg = content;
    }
    sources.seamTicks = exported->ticks;
  }
  const Result<std::string> templates = templatesDir();
  if (!templates.isOk()) return templates.status();
  const Result<std::string> html = renderReportHtml(sources, model, templates.value());
  if (!html.isOk()) return html.status();
  return writeFileAtomically((fs::path(dir) / "report.html").string(), html.value());
}

// Every file a run or an export writes into a result folder: the only files a folder that is
// replaced as a whole may hold.
std::set<std::string> resultFileNames() {
  std::set<std::string> names = {
      ModelFileNames::aFlat,       ModelFileNames::a3d, ModelFileNames::bFlat, ModelFileNames::b3d,
      ModelFileNames::targetCurve, "report.json",       "report.html"};
  for (const std::string& name : exportFileNames()) names.insert(name);
  return names;
}

// An interrupt that stops a command before its result is in place, naming the folder.
Status leftAsItWas(const std::string& dir, const std::string& what) {
  return {ErrorCode::Interrupted, dir + ": " + what + "; the folder was left as it was"};
}

// Swaps the staged result in with SIGINT and SIGTERM held back, so that a signal cannot cut the
// swap short; one that came before it leaves the folder as it was.
Status commitUnlessInterrupted(ResultFolder& folder, const std::string& dir,
                               const std::atomic<bool>& interrupted, MessageSink* sink) {
  const StopSignalsHeld held;
  if (interrupted) return leftAsItWas(dir, "interrupted");
  return folder.commit(sink);
}

}  // namespace dform
