// SPDX-License-Identifier: GPL-3.0-or-later
// The steps runs and saved results share (pipeline-internal): export options checked, a pattern
// laid out (its layout judged by the caller) and rendered, the result folder's names and its
// interruptible commit.
#pragma once

#include <atomic>
#include <set>
#include <string>

#include "dform/core/messages.h"
#include "dform/core/result_folder.h"
#include "dform/core/status.h"
#include "dform/export/exporter.h"
#include "dform/pipeline/job_file.h"
#include "dform/pipeline/run.h"
#include "dform/validate/gate.h"

namespace dform {

/// The export options of `settings` completed (the templates folder; the profile read now, when
/// cutting files are written, not after the solve) and checked against each other: Usage with a
/// one-line message naming the setting.
Result<ExportOptions> exportOptions(const ExportSettings& settings);

/// The body's folds (`used`) in the flat frames of `model`, to score
/// (ExportOptions::scoreFoldsDeg).
std::vector<FoldToScore> foldsToScore(const ModelUsed& used, const DForm& model);

/// `options` with the body's folds to score, and a warning through `sink` when the model that
/// made the result (`modelName`) knows none; `options` as it is when no folds are to be scored.
ExportOptions withFolds(ExportOptions options, std::vector<FoldToScore> folds,
                        const std::string& modelName, MessageSink& sink);

/// Lays out the cutting patterns of `model` once, not yet rendered; the glTF preview will carry
/// the curvature map the report shows.
Result<LaidOutExport> layOut(const DForm& model, ExportOptions options, const std::string& jobName);

/// Renders a laid-out pattern of `model` and its previews, not yet written, stamped FAILED GATE
/// (an overlay: nothing moves) when `failedGate`.
Result<PreparedExport> render(const DForm& model, const LaidOutExport& laidOut, bool failedGate);

/// A run's job name: its first input's file name.
std::string jobName(const Job& job);

/// The gate's fabrication check: the laid-out pattern fits the sheet and nothing on it overlaps.
CheckResult layoutCheck(const LayoutFindings& findings);

/// Says what a prepared export holds, before it is written (so that the report has it).
void noteExport(const PreparedExport& prepared, MessageSink& sink);

/// Writes `dir`/report.html, rendered in memory from report.json's text (`reportPath` names it
/// in errors) and, when `exported` is given, the pattern's and the assembly sheet's SVG.
Status writeReportPage(const std::string& dir, const std::string& reportJson,
                       const std::string& reportPath, const PreparedExport* exported,
                       const DForm& model);

/// Every file a run or an export writes into a result folder: the only files a folder that is
/// replaced as a whole may hold.
std::set<std::string> resultFileNames();

/// An interrupt that stops a command before its result is in place, naming the folder.
Status leftAsItWas(const std::string& dir, const std::string& what);

/// Swaps the staged result in with SIGINT and SIGTERM held back, so that a signal cannot cut
/// the swap short; one that came before it leaves the folder as it was. What the swap kept that
/// appeared in the folder meanwhile is a warning in `sink`.
Status commitUnlessInterrupted(ResultFolder& folder, const std::string& dir,
                               const std::atomic<bool>& interrupted, MessageSink* sink);

}  // namespace dform
