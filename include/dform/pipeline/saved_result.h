// SPDX-License-Identifier: GPL-3.0-or-later
// A saved result folder exported again or validated: both read the meshes and run the gate on
// them again instead of trusting report.json.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/pipeline/run.h"
#include "dform/validate/gate.h"

namespace dform {

/// Where `dform export` writes a saved result's cutting files, and whether it judges it again.
struct SavedExport {
  std::string outDir;  ///< a folder of their own; empty: the result folder itself
  /// Measure and judge the result again even where report.json's verdict still holds (its meshes
  /// unchanged, the same gate and dform).
  bool regate = false;
};

/// `dform export DIR`: the cutting files of the result in `dir` with the pattern settings of
/// `settings` (its gate is the one the result recorded), into `dir` itself (its other files
/// kept) or into how.outDir when given, as one transaction. The gate's verdict is report.json's
/// where it still holds, unless how.regate. A result that fails its gate, or whose pattern does
/// not lay out cleanly, is exported only with settings.exportAnyway (marked FAILED GATE), else
/// GateFailed. Returns the folder the files went into.
Result<std::string> exportSavedResult(const std::string& dir, const ExportSettings& settings,
                                      const SavedExport& how, MessageSink& sink,
                                      const std::atomic<bool>& interrupted);

/// What `dform validate DIR` found: the gate run on the meshes, and report.json compared with
/// the figures measured again.
struct SavedCheck {
  std::string gateName;  ///< the gate run: a preset's name or a gate file
  bool judged = true;    ///< false for the gate "none": the checks measured, their verdicts moot
  GateReport gate;       ///< the gate's checks on the meshes
  /// report.json missing or unreadable (InputUnreadable) or malformed; ok when it was compared.
  Status report = Status::ok();
  std::vector<std::string> differences;  ///< report.json's entries that disagree with the meshes
};

/// Validates the result in `dir` against the gate `gateName` (a preset or a file; "none":
/// measured with the default gate's checks, not judged).
Result<SavedCheck> validateSavedResult(const std::string& dir, const std::string& gateName);

}  // namespace dform
