// One result from a job to its folder, and many at once (a sweep's starts, a batch's jobs): the
// run's policy (solve, gate, lay out, release or hold back the cutting files, write as one
// transaction) in one place, so that a front end only parses, prints and maps errors to exit
// codes. Also the export and the validation of a saved result (pipeline/saved_result.h).
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/pipeline/batch.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/job_file.h"
#include "dform/pipeline/sweep.h"
#include "dform/validate/gate.h"
#include "dform/validate/metrics.h"

namespace dform {

struct ExportOptions;

/// The documented exit code of an error kind (README "Exit codes"); batch manifests record it.
int exitCode(ErrorCode code);

/// The templates folder (export profiles, gate presets, the report page and the studio's page):
/// $DFORM_TEMPLATES, else share/dform/templates under the running program's prefix (an installed
/// or moved dform), else the source tree's templates/, else the one `cmake --install` put under
/// the configured prefix. A folder counts when it has gates/, profiles/ and report/.
/// InputUnreadable when $DFORM_TEMPLATES is set to anything else, or no folder is found.
Result<std::string> templatesDir();

/// The export profiles a run can name (templates/profiles/*.json), sorted; none without a
/// templates folder.
std::vector<std::string> exportProfileNames();

/// What to do with a run's result.
struct OutputOptions {
  std::string outDir;
  bool exportFiles = true;        ///< write the cutting patterns and previews
  std::string profile = "laser";  ///< export profile name or file
  std::string sheet;              ///< "WxH" in mm (e.g. 600x400mm); empty: the exporter's default
  std::string page;               ///< --page A4|Letter|A3|Tabloid|WxHmm; empty: the profile's
  std::string scale;              ///< --scale 0.8 | 80% | fit; empty: true size
  std::optional<double> tabWidthMm;     ///< --tab-width (mm; 0 = no tabs); unset: the default
  std::string tabs;                     ///< --tabs a|b|alternate|none; empty: the profile's
  std::optional<double> tickSpacingMm;  ///< --tick-spacing (mm); unset: the default
  std::string joint;  ///< --joint glue|holes|lace|slots; empty: the material's, else the profile's
  std::string material;          ///< --material paper|card|polypropylene|plywood; empty: none
  std::optional<double> kerfMm;  ///< --kerf: the cutter's kerf (mm); unset: the profile's
  /// --hole-spacing, --hole-diameter, --hole-edge (mm); unset: the material's or the defaults
  std::optional<double> holeSpacingMm, holeDiameterMm, holeEdgeMm;
  std::optional<double> slotLengthMm;   ///< --slot-length (mm); unset: half the hole spacing
  bool gltfText = false;                ///< --gltf: dform.gltf (text) instead of dform.glb
  bool title = true;                    ///< the title block on the sheets (--no-title: none)
  std::optional<double> scoreFoldsDeg;  ///< --score-folds (degrees); unset: no folds scored
  std::string numbers;  ///< --numbers face|tabs|both: where tick numbers go; empty: the profile's
  /// --hinge / --no-hinge: kerf-bending cuts where the shape bends; unset: the material's
  std::optional<bool> hinge;
  std::string gate = "default";  ///< gate name or file; "none" skips the gate
  bool exportAnyway = false;     ///< export even when the gate fails (files marked FAILED GATE)
  /// `dform export`: measure and judge the saved result again even where report.json's verdict
  /// still holds (its meshes unchanged, the same gate and dform)
  bool regate = false;
  bool quiet = false;
};

/// A gate preset's name (templates/gates/NAME.json: Usage when there is none) or a gate file.
Result<GateLimits> loadGate(const std::string& nameOrPath);

/// A run's settings, checked before anything is solved: the gate's limits (none: no gate) and
/// the export's options with its profile read.
struct RunSettings {
  std::optional<GateLimits> limits;
  std::shared_ptr<const ExportOptions> exporting;
};

/// Checks `output`'s gate, profile, sheet, page, scale and tabs: Usage (or the profile's read
/// error) naming the option, before any work is done.
Result<RunSettings> checkOutput(const OutputOptions& output);

/// What a result written into its folder shows afterwards. `exported` is the export's error
/// when the result was saved without its cutting files.
struct WrittenResult {
  Metrics metrics;
  std::optional<CurveMatch> curve;
  Timings timings;
  std::optional<GateReport> gate;
  Status exported = Status::ok();
};

/// Solves `job`, gates it, lays out its pattern and writes the whole result into output.outDir
/// as one transaction (locked, staged, swapped in). hooks.interrupted stops it with the folder
/// left as it was; an allocation that fails past the solve is reported with a resolution.
Result<WrittenResult> runAndWrite(const Job& job, const OutputOptions& output,
                                  const RunSettings& settings, MessageSink& sink,
                                  const RunHooks& hooks);

/// A result made in memory (makeDForm, makePieces) written into output.outDir as runAndWrite
/// writes one; `job` (its settings, and names for its inputs) is what report.json records.
Result<WrittenResult> writeResult(const ForwardJob& job, const ForwardRun& run,
                                  const OutputOptions& output, const RunSettings& settings,
                                  MessageSink& sink);
Result<WrittenResult> writeResult(const InverseJob& job, const InverseRun& run,
                                  const OutputOptions& output, const RunSettings& settings,
                                  MessageSink& sink);

/// `base` from every start of `options`, each written as runAndWrite writes one into
/// output.outDir/<start>/, with sweep.json and gallery.html (docs/sweep.md).
Result<std::vector<SweepRow>> sweepAndWrite(const Job& base, const SweepOptions& options,
                                            const OutputOptions& output,
                                            const RunSettings& settings,
                                            const SweepProgress& progress,
                                            const std::atomic<bool>& interrupted,
                                            MessageSink* notes = nullptr);

/// Every job file of `jobs` in the options' shard, each written as runAndWrite writes one into
/// output.outDir/<job name>/, with the manifest (docs/batch.md).
Result<std::vector<BatchRow>> batchAndWrite(const std::vector<BatchJob>& jobs,
                                            const BatchOptions& options,
                                            const OutputOptions& output,
                                            const RunSettings& settings,
                                            const BatchProgress& progress,
                                            const std::atomic<bool>& interrupted);

}  // namespace dform
