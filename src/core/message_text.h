// Text from a user's file in a Status message. Messages are one printable line (the CLI prints
// "dform: error: <file>: <problem>"), but a key, a token or a parser's excerpt can hold anything:
// control characters, a megabyte of text, bytes that are not UTF-8.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace dform {

/// `text` with control characters written as \xNN escapes, cut after `maxBytes` (at a UTF-8
/// character boundary) with "..." when longer.
std::string printable(std::string_view text, std::size_t maxBytes = 60);

/// The reason in a parser exception's text ("[json.exception.parse_error.101] parse error at line
/// 1, column 2: ...") without its bracketed tag, printable and at most 200 bytes.
std::string parserReason(std::string_view what);

/// A JSON value (nlohmann::json; a template so that core needs no JSON library) as a message
/// shows it: a scalar as JSON text, printable and short; an array or object by its type only,
/// since printing one would recurse as deep as the file nests.
template <typename Json>
std::string describeJsonValue(const Json& value) {
  if (!value.is_primitive()) return std::string("an ") + (value.is_array() ? "array" : "object");
  return printable(value.dump(-1, ' ', false, Json::error_handler_t::replace));
}

}  // namespace dform
