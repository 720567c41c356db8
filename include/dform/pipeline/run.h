// SPDX-License-Identifier: GPL-3.0-or-later
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
#include "dform/pipeline/exit_code.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/job_file.h"
#include "dform/pipeline/settings.h"
#include "dform/pipeline/sweep.h"
#include "dform/validate/gate.h"
#include "dform/validate/metrics.h"

namespace dform {

/// The templates folder (export profiles, gate presets, the report page and the studio's page):
/// $DFORM_TEMPLATES, else `templates` beside the shared object that holds this library (the
/// Python module of a pip-installed package), else share/dform/templates under the running
/// program's prefix (an installed or moved dform), else, for a program or module in the build
/// folder, the source tree's templates/, else the one `cmake --install` put under the configured
/// prefix. A folder counts when it has gates/, profiles/ and report/. InputUnreadable when
/// $DFORM_TEMPLATES is set to anything else, or no folder is found.
Result<std::string> templatesDir();

/// The export profiles a run can name (templates/profiles/*.json), sorted; none without a
/// templates folder.
std::vector<std::string> exportProfileNames();

/// Where a run writes its result (how it writes it is the job's: Job::exporting).
struct OutputOptions {
  std::string outDir;  ///< the result folder, replaced as one transaction
};

/// A gate preset's name (templates/gates/NAME.json: Usage when there is none) or a gate file.
Result<GateLimits> loadGate(const std::string& nameOrPath);

/// A run's export settings made ready before anything is solved: the gate's limits (none: no
/// gate), the export's options completed (the templates folder, the profile read) and what is
/// released.
struct RunSettings {
  std::optional<GateLimits> limits;                ///< the gate's limits; none for the gate "none"
  std::shared_ptr<const ExportOptions> exporting;  ///< the export's options, profile read
  bool cuttingFiles = true;                        ///< ExportSettings::cuttingFiles
  bool exportAnyway = false;                       ///< ExportSettings::exportAnyway
};

/// Checks `settings` (each in its range, the export's options against each other) and reads its
/// gate and profile: Usage (or the gate's or profile's read error) naming the setting, before any
/// work is done.
Result<RunSettings> checkOutput(const ExportSettings& settings);

/// What a result written into its folder shows afterwards. `exported` is the export's error
/// when the result was saved without its cutting files.
struct WrittenResult {
  Metrics metrics;                  ///< the figures report.json records
  std::optional<CurveMatch> curve;  ///< inverse: how near the seam is to the curve; else none
  Timings timings;                  ///< how long each stage took, seconds
  std::optional<GateReport> gate;   ///< the gate's verdict and checks; none for the gate "none"
  Status exported = Status::ok();   ///< ok, or why the cutting files were not written
};

/// Solves `job`, gates it, lays out its pattern and writes the whole result into output.outDir
/// as one transaction (locked, staged, swapped in), as `settings` (checkOutput of the job's
/// exporting) say. hooks.interrupted stops it with the folder left as it was; an allocation that
/// fails past the solve is reported with a resolution.
Result<WrittenResult> runAndWrite(const Job& job, const OutputOptions& output,
                                  const RunSettings& settings, MessageSink& sink,
                                  const RunHooks& hooks);

/// A result made in memory (makeDForm, makePieces) written into output.outDir as runAndWrite
/// writes one; `job` (its settings, and names for its inputs) is what report.json records.
Result<WrittenResult> writeResult(const Job& job, const SolvedRun& run, const OutputOptions& output,
                                  const RunSettings& settings, MessageSink& sink);

/// `base` from every start of `options`, each written as runAndWrite writes one into
/// output.outDir/<start>/, with sweep.json and gallery.html (docs/sweep.md).
Result<std::vector<SweepRow>> sweepAndWrite(const Job& base, const SweepOptions& options,
                                            const OutputOptions& output,
                                            const RunSettings& settings,
                                            const SweepProgress& progress,
                                            const std::atomic<bool>& interrupted,
                                            MessageSink* notes = nullptr);

/// Every job file of `jobs` in the options' shard, each read, changed by `adjust` (the command
/// line's settings over the file's; may be empty), checked (checkOutput) and written as
/// runAndWrite writes one into output.outDir/<job name>/, with the manifest (docs/batch.md).
Result<std::vector<BatchRow>> batchAndWrite(const std::vector<BatchJob>& jobs,
                                            const BatchOptions& options,
                                            const OutputOptions& output,
                                            const std::function<Status(Job&)>& adjust,
                                            const BatchProgress& progress,
                                            const std::atomic<bool>& interrupted);

}  // namespace dform
