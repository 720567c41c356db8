// SPDX-License-Identifier: GPL-3.0-or-later
// report.json: what a run read, how it solved, and every figure (schema: docs/report.md).
#pragma once

#include <chrono>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/io/model_files.h"
#include "dform/pipeline/job_file.h"
#include "dform/validate/gate.h"

namespace dform {

/// The schema name and version written into every report.
constexpr const char* kReportSchema = "dform-report";
constexpr int kReportSchemaVersion = 2;

/// The command's stages around the pipeline's run, for report.json's timings (seconds).
struct CommandTimings {
  std::chrono::steady_clock::time_point start;             ///< when the command began
  double gate = std::numeric_limits<double>::quiet_NaN();  ///< running the gate; NaN: no gate
  double write = 0;  ///< writing the meshes (and an inverse run's target curve)
  /// laying out and rendering the cutting files in memory (they are written after report.json,
  /// so that the verdict is on record first); NaN: no export
  double exportFiles = std::numeric_limits<double>::quiet_NaN();
};

/// Writes `dir`/report.json (atomically) for a forward run and returns its text (for report.html).
/// `gate` may be null (no gate ran). Its timings add the command's stages, the making of
/// report.json itself, and the total from `command.start` to the moment report.json is made.
/// `resultFiles` are the SHA-256 of the meshes (and the target curve) written beside it, by name:
/// a saved result whose files still have them is the one the gate judged.
Result<std::string> writeForwardReport(const std::string& dir, const Job& job,
                                       const ForwardRun& run, const std::vector<Message>& messages,
                                       const GateReport* gate, const CommandTimings& command,
                                       const FileHashes& resultFiles);

/// The same for an inverse run; its metrics add D_error and curve_distance_max_mm.
Result<std::string> writeInverseReport(const std::string& dir, const Job& job,
                                       const InverseRun& run, const std::vector<Message>& messages,
                                       const GateReport* gate, const CommandTimings& command,
                                       const FileHashes& resultFiles);

/// The figures as report.json records them under "metrics" (NaN and infinity as null), with the
/// inverse's `curve` figures when given, as JSON text (for front ends that show them: the studio,
/// the Python module).
std::string metricsJsonText(const Metrics& metrics, const CurveMatch* curve);

/// Compares a saved result with what `dir`/report.json recorded: its mode (inverse when `curve`
/// is given, i.e. the folder holds a target curve), the mesh sizes of `model`, and every figure
/// of `metrics` and `curve` recomputed from the meshes (beyond 1e-9 relative; the OBJ files
/// round-trip exactly). Returns one line per entry that differs or is missing, empty when all
/// agree. InputUnreadable when report.json is missing, unreadable or not JSON.
Result<std::vector<std::string>> compareWithReport(const std::string& dir, const DForm& model,
                                                   const Metrics& metrics, const CurveMatch* curve);

/// The name of the gate `dir`/report.json recorded; InputInvalid when it records none.
Result<std::string> savedGateName(const std::string& dir);

/// The gate report `dir`/report.json recorded, when it still holds for the saved result: the same
/// dform version wrote it, `files` (the SHA-256 of the meshes and target curve as just read) are
/// those it records, and `limits` (the gate the result is judged by now) are the limits it
/// records. Its checks are the recorded ones but the pattern's layout (an export checks its own).
/// nullopt when any of that does not hold; InputUnreadable when report.json is unreadable.
Result<std::optional<GateReport>> reusableGate(const std::string& dir, const FileHashes& files,
                                               const GateLimits& limits);

/// The gate verdict `dir`/report.json recorded: passed or not, or nullopt when the run had no
/// gate. InputUnreadable when report.json is missing or not JSON, InputInvalid when its gate
/// has no verdict.
Result<std::optional<bool>> savedGateVerdict(const std::string& dir);

}  // namespace dform
