// SPDX-License-Identifier: GPL-3.0-or-later
// Inputs that once crashed the gate-file fuzz target (tests/fuzz/regressions/gate/): each now
// gives a proper Status. What each one found is in docs/hardening.md.
#include "dform/validate/gate.h"
#include "fuzz/regressions.h"

namespace dform {
namespace {

TEST(FuzzRegressions, GateFile) {
  EXPECT_TRUE(test::regressionsHold(
      "gate",
      {{"control-character-in-parse-error.json", ErrorCode::InputUnreadable, "not JSON"},
       {"number-overflow.json", ErrorCode::InputUnreadable, "number overflow"}},
      [](const std::string& text, const std::string& source) {
        return parseGateJson(text, source).status();
      }));
}

}  // namespace
}  // namespace dform
