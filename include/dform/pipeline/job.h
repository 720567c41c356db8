// SPDX-License-Identifier: GPL-3.0-or-later
// A job: what one run solves (a forward or an inverse job, each with its inputs and its settings)
// and how it writes its result (the pattern and previews, and the gate that judges them), as a
// job file records it (pipeline/job_file.h, docs/cli.md). Its settings are the rows of the
// settings table (pipeline/settings.h).
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "dform/export/exporter.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/inverse_pipeline.h"

namespace dform {

/// How a run writes its result: the cutting patterns' and previews' options, the gate that
/// judges the result, and what is released when it fails.
struct ExportSettings {
  /// The pattern and previews as the export takes them (export/exporter.h): the settings table
  /// sets its user-settable fields; a run fills in the rest (templates, the profile read, the
  /// body's folds, the curvature maps, the job's name).
  ExportOptions pattern;
  std::string gate = "default";  ///< a gate preset's name or a gate file; "none": no gate
  bool cuttingFiles = true;      ///< write the cutting patterns and previews at all
  bool exportAnyway = false;     ///< release them when the gate fails (marked FAILED GATE)
};

/// A forward or an inverse job and how its result is written. A job is a forward job unless made
/// from an InverseJob; a stage that needs the mode's own fields visits `run`.
struct Job {
  std::variant<ForwardJob, InverseJob> run;  ///< the mode's inputs and settings
  ExportSettings exporting;                  ///< how its result is gated, exported and released

  Job() = default;
  /// A forward job with the default export settings.
  Job(ForwardJob job) : run(std::move(job)) {}  // NOLINT: implicit, as a job file reads
  /// An inverse job with the default export settings.
  Job(InverseJob job) : run(std::move(job)) {}  // NOLINT: implicit, as a job file reads

  /// Whether `run` holds a ForwardJob.
  bool isForward() const { return std::holds_alternative<ForwardJob>(run); }
  /// The mode's name in job files and reports: "forward" or "inverse".
  const char* modeName() const { return isForward() ? "forward" : "inverse"; }
  /// The input files (piece A and B, or the curve), in the order a job file lists them.
  std::vector<std::string> inputs() const;
  /// Seam vertices per piece (forward) or points of the curve (inverse).
  int resolution() const;
};

/// A solved job of either mode: the forward D-Form or the inverse pieces, with their figures.
using SolvedRun = std::variant<ForwardRun, InverseRun>;

/// What every solved run has, whichever mode made it: the meshes, the model that made them and
/// why, the figures and the timings.
const DForm& solvedModel(const SolvedRun& run);
const ModelUsed& solvedModelUsed(const SolvedRun& run);
const Metrics& solvedMetrics(const SolvedRun& run);
const Timings& solvedTimings(const SolvedRun& run);
/// The inverse run's match with its curve; null for a forward run.
const CurveMatch* solvedCurveMatch(const SolvedRun& run);

}  // namespace dform
