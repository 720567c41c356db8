// Job files: a run's inputs and options as JSON, so that a result can be reproduced exactly
// (`dform run job.json -o out/`). Schema: docs/cli.md.
#pragma once

#include <string>

#include "dform/core/status.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/inverse_pipeline.h"

namespace dform {

struct Job {
  enum class Mode { Forward, Inverse };
  Mode mode = Mode::Forward;
  ForwardJob forward;  ///< used when mode is Forward
  InverseJob inverse;  ///< used when mode is Inverse
};

/// Reads a job file. Input paths in it are relative to the job file's folder. InputUnreadable
/// when the file is missing or not JSON; InputInvalid naming the key for a missing, unknown or
/// mistyped key or a bad value.
Result<Job> readJobFile(const std::string& path);

/// The same from the text of the job file at `path`, read by the caller.
Result<Job> parseJobFileText(const std::string& text, const std::string& path);

/// The same from text; `source` names it in messages and `baseDir` resolves relative paths.
Result<Job> parseJobJson(const std::string& text, const std::string& source,
                         const std::string& baseDir);

/// The job as JSON text (absolute input paths), readable by parseJobJson: report.json records it
/// so that a run can be repeated.
std::string jobToJson(const Job& job);

/// Sets the weight of `job`'s mode named `name` (as job files spell it, forward/forward.h and
/// inverse/inverse_solve.h list them); false for a name the mode has no weight of.
bool setNamedWeight(Job& job, const std::string& name, double value);

}  // namespace dform
