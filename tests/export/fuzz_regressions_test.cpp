// SPDX-License-Identifier: GPL-3.0-or-later
// Inputs that once crashed the export-profile fuzz target (tests/fuzz/regressions/profile/): each
// now gives a proper Status. What each one found is in docs/hardening.md.
#include "dform/export/exporter.h"
#include "fuzz/regressions.h"

namespace dform {
namespace {

TEST(FuzzRegressions, ProfileFile) {
  EXPECT_TRUE(test::regressionsHold(
      "profile",
      {{"control-character-in-unknown-field.json", ErrorCode::InputInvalid, "unknown field"}},
      [](const std::string& text, const std::string& source) {
        return parseProfileJson(text, source).status();
      }));
}

}  // namespace
}  // namespace dform
