// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzzes the job-file reader. A job it accepts must be valid and survive the trip through
// report.json unchanged (jobToJson, then read again), since that is how a run is repeated.
#include "dform/pipeline/job_file.h"
#include "dform/pipeline/settings.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  using namespace dform;
  const Result<Job> job = fuzz::parseChecked(
      data, size, "job.json", [](const std::string& text, const std::string& source) {
        return parseJobJson(text, source, "/base");
      });
  if (!job.isOk()) return 0;
  const Job& j = job.value();
  const Status valid = checkSettings(j);
  fuzz::require(valid.isOk(), "an accepted job is invalid", valid.message());
  const std::string saved = jobToJson(j);
  const Result<Job> again = parseJobJson(saved, "again.json", "/elsewhere");
  fuzz::require(again.isOk(), "a saved job does not read back", again.status().message());
  fuzz::require(jobToJson(again.value()) == saved, "a saved job reads back different", saved);
  return 0;
}
