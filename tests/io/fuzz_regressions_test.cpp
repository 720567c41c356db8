// SPDX-License-Identifier: GPL-3.0-or-later
// Inputs that once crashed the io fuzz targets (tests/fuzz/regressions/): each now gives a proper
// Status. What each one found is in docs/hardening.md.
#include "dform/io/curve_reader.h"
#include "dform/io/outline_reader.h"
#include "fuzz/regressions.h"

namespace dform {
namespace {

Status readOutlineText(const std::string& text, const std::string& source) {
  return parseOutline(text, source).status();
}

Status readCurveText(const std::string& text, const std::string& source) {
  return parseCurve(text, source).status();
}

TEST(FuzzRegressions, Svg) {
  EXPECT_TRUE(test::regressionsHold(
      "svg", {{"near-touch-depends-on-direction.svg", ErrorCode::Ok, ""}}, readOutlineText));
}

TEST(FuzzRegressions, OutlineJson) {
  EXPECT_TRUE(test::regressionsHold(
      "outline_json",
      {{"control-character-in-parse-error.json", ErrorCode::InputUnreadable, "not valid JSON"}},
      readOutlineText));
}

TEST(FuzzRegressions, CurveObj) {
  EXPECT_TRUE(test::regressionsHold(
      "curve_obj",
      {{"control-character-in-token.obj", ErrorCode::InputUnreadable, "is not a number"},
       {"index-past-int-in-message.obj", ErrorCode::InputUnreadable,
        "vertex index 2147483648 is out of range"}},
      readCurveText));
}

TEST(FuzzRegressions, CurveJson) {
  EXPECT_TRUE(test::regressionsHold(
      "curve_json",
      {{"control-character-in-parse-error.json", ErrorCode::InputUnreadable, "not valid JSON"}},
      readCurveText));
}

}  // namespace
}  // namespace dform
