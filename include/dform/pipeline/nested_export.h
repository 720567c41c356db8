// SPDX-License-Identifier: GPL-3.0-or-later
// Several saved results exported together: their pieces (and copies) nested on as few sheets as
// hold them, for a laser shop's sheet (`dform export DIR... --nest -o OUT`).
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/pipeline/job.h"
#include "dform/pipeline/saved_result.h"

namespace dform {

/// The pieces of every result in `dirs`, each D-Form `copies` times, nested with the pattern
/// settings of `settings` (its sheet, or its profile's page) into how.outDir (required) as one
/// transaction. Each result is judged as `dform export` judges it (how.regate: again on its
/// meshes), and one that failed its gate, or a nest that does not lay out cleanly, is refused
/// (GateFailed) unless settings.exportAnyway, which stamps the nest FAILED GATE. The nest's name
/// (title, files) is how.outDir's folder name. Usage for no result, a copy count out of 1 to
/// 1000, no output folder, a setting out of range, or more than kMaxNestSheets sheets. Returns
/// the folder written.
Result<std::string> exportNest(const std::vector<std::string>& dirs, int copies,
                               const ExportSettings& settings, const SavedExport& how,
                               MessageSink& sink, const std::atomic<bool>& interrupted);

/// The most sheets a nest may take: its output folder holds pattern-sheet-1 to this.
constexpr int kMaxNestSheets = 1000;

}  // namespace dform
