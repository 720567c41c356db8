#include "core/message_text.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace dform {
namespace {

TEST(MessageText, ControlCharactersAreEscaped) {
  EXPECT_EQ(printable("cut\nout\x7f\t"), "cut\\x0aout\\x7f\\x09");
  EXPECT_EQ(printable("plain text, UTF-8 \xc3\xa9"), "plain text, UTF-8 \xc3\xa9");
}

TEST(MessageText, LongTextIsCutAtACharacterBoundary) {
  EXPECT_EQ(printable(std::string(100, 'k'), 10), "kkkkkkkkkk...");
  // "é" is two bytes: a cut after 5 bytes would split the third one, so it comes before it.
  EXPECT_EQ(printable("\xc3\xa9\xc3\xa9\xc3\xa9", 5), "\xc3\xa9\xc3\xa9...");
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
