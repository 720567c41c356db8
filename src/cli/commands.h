// SPDX-License-Identifier: GPL-3.0-or-later
// The CLI's subcommands, each returning the process exit code (README "Exit codes").
#pragma once

#include <atomic>
#include <string>

#include "dform/pipeline/run.h"
#include "dform/pipeline/saved_result.h"
#include "dform/studio/studio.h"

namespace dform::cli {

/// How a command prints its outcome: `quiet`, nothing but errors; `json`, one JSON object on
/// stdout and nothing else there.
struct Printing {
  bool quiet = false;
  bool json = false;
};

/// `dform forward`, `inverse`, `run`: one job written into output.outDir, its figures and gate
/// printed (as text, or as one JSON object when printing.json; nothing when printing.quiet).
int runJob(const Job& job, const OutputOptions& output, const Printing& printing,
           const std::atomic<bool>& interrupted);
/// `dform sweep`: `base` from every start of `options`, each result written as `runJob` writes
/// one, into output.outDir/<start>/, with sweep.json and gallery.html (docs/sweep.md).
int runSweepCommand(const Job& base, const SweepOptions& options, const OutputOptions& output,
                    const Printing& printing, const std::atomic<bool>& interrupted);
/// `dform batch`: every job of `jobs` in the options' shard, `adjust`ed (the command line's
/// settings over each file's) and written as `dform run` writes it, into
/// output.outDir/<job name>/, with the manifest (docs/batch.md).
int runBatchCommand(const std::vector<BatchJob>& jobs, const BatchOptions& options,
                    const OutputOptions& output, const Printing& printing,
                    const std::function<Status(Job&)>& adjust,
                    const std::atomic<bool>& interrupted);
/// `dform batch --merge DIR`: the shards' manifests gathered into batch.json and gallery.html;
/// refused (exit 5) while a job of the list has not finished, unless `allowPartial`.
int mergeBatchCommand(const std::string& dir, bool allowPartial, bool quiet);
/// `dform export`: the result in `dir` exported again with `settings`' pattern, into how.outDir
/// when given, else into `dir`.
int exportSaved(const std::string& dir, const ExportSettings& settings, const SavedExport& how,
                bool quiet, const std::atomic<bool>& interrupted);
/// `dform export DIR... --nest`: the results' pieces nested into how.outDir.
int exportNested(const std::vector<std::string>& dirs, int copies, const ExportSettings& settings,
                 const SavedExport& how, bool quiet, const std::atomic<bool>& interrupted);
/// `dform validate`: the result in `dir` re-measured, against the gate `gate` or, for "none",
/// measured only (exit 0 unless the folder or its report is unreadable or wrong).
int validateSaved(const std::string& dir, const std::string& gate, const Printing& printing);
int listProfiles();
/// `dform studio`: serves the design page, prints its address (and opens it in the browser
/// when `openBrowser` and xdg-open is there) until `interrupted` is set (Ctrl-C, SIGTERM).
int runStudio(const StudioOptions& options, bool openBrowser, const std::atomic<bool>& interrupted);

}  // namespace dform::cli
