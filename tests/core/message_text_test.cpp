// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/message_text.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace dform {
namespace {

TEST(MessageText, ControlCharactersAreEscaped) {
  EXPECT_EQ(printable("cut\nout\x7f\t\r\x1b[31m"), "cut\\nout\\x7f\\t\\r\\x1b[31m");
  EXPECT_EQ(printable("plain text, UTF-8 \xc3\xa9"), "plain text, UTF-8 \xc3\xa9");
}

TEST(MessageText, LongTextIsCutAtACharacterBoundary) {
  EXPECT_EQ(printable(std::string(100, 'k'), 10), "kkkkkkkkkk...");
  // "é" is two bytes: a cut after 5 bytes would split the third one, so it comes before it.
  EXPECT_EQ(printable("\xc3\xa9\xc3\xa9\xc3\xa9", 5), "\xc3\xa9\xc3\xa9...");
}

TEST(MessageText, AMessageIsOneLineWithLongTokensCut) {
  const std::string digits(10'000'000, '7');
  const std::string shown = printableMessage("x\n\x1b[31m.svg: '" + digits + "' is too large");
  EXPECT_EQ(shown.find('\n'), std::string::npos);
  EXPECT_EQ(shown.find('\x1b'), std::string::npos);
  EXPECT_EQ(shown.rfind("x\\n\\x1b[31m.svg: '", 0), 0u) << shown;
  // The number is cut to kMaxTokenBytes with "...", the words around it are kept.
  EXPECT_EQ(shown,
            "x\\n\\x1b[31m.svg: '" + digits.substr(0, kMaxTokenBytes - 1) + "... is too large");
}

TEST(MessageText, ParserReasonDropsTheTag) {
  EXPECT_EQ(
      parserReason("[json.exception.parse_error.101] parse error at line 1: last read: '\x01'"),
      "parse error at line 1: last read: '\\x01'");
  EXPECT_EQ(parserReason(std::string(1000, 'x')).size(), 203u);
}

TEST(MessageText, JsonValuesAreShownShortAndFlat) {
  using nlohmann::json;
  EXPECT_EQ(describeJsonValue(json(2.5)), "2.5");
  EXPECT_EQ(describeJsonValue(json("a\x01")), "\"a\\u0001\"");
  EXPECT_EQ(describeJsonValue(json("\xff")), "\"\xef\xbf\xbd\"")
      << "invalid UTF-8 replaced, not thrown";
  json deep = json::array();
  for (int i = 0; i < 100000; ++i) deep = json::array({std::move(deep)});
  EXPECT_EQ(describeJsonValue(deep), "an array") << "never printed, so never recursed into";
  EXPECT_EQ(describeJsonValue(json::object()), "an object");
}

}  // namespace
}  // namespace dform
