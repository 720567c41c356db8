// The CLI's subcommands, each returning the process exit code (README "Exit codes").
#pragma once

#include <atomic>
#include <optional>
#include <string>

#include "core/status.h"
#include "pipeline/job_file.h"
#include "sweep/batch.h"
#include "sweep/sweep.h"

namespace dform::cli {

/// The documented exit code of an error kind.
int exitCode(ErrorCode code);

/// What to do with a run's result.
struct OutputOptions {
  std::string outDir;
  bool exportFiles = true;       ///< write the cutting patterns and previews
  std::string profile = "laser"; ///< export profile name or file
  std::string sheet;             ///< "WxH" in mm (e.g. 600x400mm); empty: the exporter's default
  std::string page;              ///< --page A4|Letter|A3|Tabloid|WxHmm; empty: the profile's
  std::string scale;             ///< --scale 0.8 | 80% | fit; empty: true size
  std::optional<double> tabWidthMm;     ///< --tab-width (mm; 0 = no tabs); unset: the default
  std::string tabs;                     ///< --tabs a|b|alternate|none; empty: the profile's
  std::optional<double> tickSpacingMm;  ///< --tick-spacing (mm); unset: the default
  bool gltfText = false;                ///< --gltf: dform.gltf (text) instead of dform.glb
  bool title = true;                    ///< the title block on the sheets (--no-title: none)
  std::string gate = "default";  ///< gate name or file; "none" skips the gate
  bool exportAnyway = false;     ///< export even when the gate fails (files marked FAILED GATE)
  bool quiet = false;
};

/// The templates folder: $DFORM_TEMPLATES, else the source tree's templates/.
std::string templatesDir();

int runJob(const Job& job, const OutputOptions& output, const std::atomic<bool>& interrupted);
/// `dform sweep`: `base` from every start of `options`, each result written as `runJob` writes
/// one, into output.outDir/<start>/, with sweep.json and gallery.html (docs/sweep.md).
int runSweepCommand(const Job& base, const SweepOptions& options, const OutputOptions& output,
                    const std::atomic<bool>& interrupted);
/// `dform batch`: every job of `jobs` in the options' shard, each written as `dform run` writes
/// it, into output.outDir/<job name>/, with the manifest (docs/batch.md).
int runBatchCommand(const std::vector<BatchJob>& jobs, const BatchOptions& options,
                    const OutputOptions& output, const std::atomic<bool>& interrupted);
/// `dform batch --merge DIR`: the shards' manifests gathered into batch.json and gallery.html.
int mergeBatchCommand(const std::string& dir);
int exportSaved(const std::string& dir, const OutputOptions& output,
                const std::atomic<bool>& interrupted);
int validateSaved(const std::string& dir, const std::string& gate);
int listProfiles();

}  // namespace dform::cli
