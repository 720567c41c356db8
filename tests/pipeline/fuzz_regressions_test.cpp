// SPDX-License-Identifier: GPL-3.0-or-later
// Inputs that once crashed the job-file fuzz target (tests/fuzz/regressions/job/): each now gives
// a proper Status. What each one found is in docs/hardening.md.
#include "dform/pipeline/job_file.h"
#include "fuzz/regressions.h"

namespace dform {
namespace {

TEST(FuzzRegressions, JobFile) {
  EXPECT_TRUE(test::regressionsHold(
      "job",
      {{"del-character-in-parse-error.json", ErrorCode::InputUnreadable, "not valid JSON"},
       {"number-overflow.json", ErrorCode::InputUnreadable, "number overflow"}},
      [](const std::string& text, const std::string& source) {
        return parseJobJson(text, source, "/base").status();
      }));
}

}  // namespace
}  // namespace dform
