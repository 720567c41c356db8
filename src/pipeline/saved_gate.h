// SPDX-License-Identifier: GPL-3.0-or-later
// What an export reads of a saved result besides its meshes (pipeline-internal): its job name, the
// body's folds and the target curve, and its gate's verdict (report.json's where it still holds,
// else measured again). `dform export DIR` and a nest of results share them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/export/exporter.h"
#include "dform/io/model_files.h"
#include "dform/validate/gate.h"

namespace dform {

/// A saved result's job name, from the job its report.json records; the folder's name when there
/// is no readable job.
std::string savedJobName(const std::string& dir);

/// The body's folds report.json records (model.folds, flat mm), for score lines and hinges;
/// entries that are not a piece, two points and an angle are passed over. `modelName` gets
/// model.name.
std::vector<FoldToScore> savedFolds(const std::string& dir, std::string& modelName);

/// An inverse result's target curve, when the folder holds one, checked against the seam.
Result<std::optional<Curve3>> readSavedTarget(const std::string& dir, const DForm& model);

/// A saved result's meshes, its target curve (an inverse result's) and the SHA-256 of each file as
/// read (report.json's `result_files` names the same).
struct SavedModel {
  DForm model;
  std::optional<Curve3> target;
  FileHashes files;
};

/// Reads the result in `dir`: readModel's and readSavedTarget's errors.
Result<SavedModel> readSaved(const std::string& dir);

/// A saved result's gate and verdict.
struct SavedGate {
  std::string gateName;  ///< the preset report.json names, else "default"
  GateReport gate;       ///< report.json's where it still holds, else measured now
  bool reused = false;   ///< the gate is report.json's
  bool failed = false;   ///< report.json records a failure, or the gate fails now
  std::string failing;   ///< the failing checks' names, comma-separated
};

/// Judges the result `saved` read from `dir`: report.json's gate where it still holds
/// (reusableGate) unless `regate`, else the gate measured again with the limits of the preset
/// report.json names (else the default ones); a message through `sink` says which.
Result<SavedGate> judgeSaved(const std::string& dir, const SavedModel& saved, bool regate,
                             MessageSink& sink);

/// The refusal of a result that failed its gate: GateFailed naming the folder, the gate and the
/// failing checks.
Status gateRefusal(const std::string& dir, const SavedGate& judged);

}  // namespace dform
