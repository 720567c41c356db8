// SPDX-License-Identifier: GPL-3.0-or-later
// Job files: a run's inputs and settings as JSON, so that a result can be reproduced exactly
// (`dform run job.json -o out/`). Each setting is read and written through its row of the
// settings table (pipeline/settings.h); schema: docs/cli.md.
#pragma once

#include <string>

#include "dform/core/status.h"
#include "dform/pipeline/job.h"

namespace dform {

/// Reads a job file. Input paths in it are relative to the job file's folder. InputUnreadable
/// when the file is missing or not JSON; InputInvalid naming the key for a missing, unknown or
/// mistyped key or a bad value.
Result<Job> readJobFile(const std::string& path);

/// The same from the text of the job file at `path`, read by the caller.
Result<Job> parseJobFileText(const std::string& text, const std::string& path);

/// The same from text; `source` names it in messages and `baseDir` resolves relative paths.
Result<Job> parseJobJson(const std::string& text, const std::string& source,
                         const std::string& baseDir);

/// The job as JSON text (absolute input paths), readable by parseJobJson: every setting of the
/// job's mode (an optional one only when set), so that it reads back equal. report.json records
/// it so that a run can be repeated.
std::string jobToJson(const Job& job);

}  // namespace dform
