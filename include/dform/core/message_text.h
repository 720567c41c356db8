// SPDX-License-Identifier: GPL-3.0-or-later
// Text from a user's file in a Status message. Messages are one printable line (the CLI prints
// "dform: error: <file>: <problem>"), but a key, a token or a parser's excerpt can hold anything:
// control characters, a megabyte of text, bytes that are not UTF-8.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace dform {

/// `text` as valid UTF-8: every byte that is not part of a well-formed UTF-8 character shown as
/// the text \xNN (a Latin-1 file name "ell\xe9.svg"), so that JSON, Cairo and HTML take it.
std::string utf8Text(std::string_view text);

/// `text` with control characters escaped (\n, \t, \r, else \xNN: an escape sequence of a
/// terminal is shown as \x1b[...), bytes that are not UTF-8 as utf8Text shows them, cut after
/// `maxBytes` (at a UTF-8 character boundary) with
/// "..." when longer.
std::string printable(std::string_view text, std::size_t maxBytes = 60);

/// The longest token (a run without spaces: a path, a number) a printed message quotes whole.
/// A path is rarely longer; a 10-million-digit number is cut.
constexpr std::size_t kMaxTokenBytes = 300;

/// A whole message as the CLI prints it: one line (control characters escaped as printable()
/// does), each token longer than kMaxTokenBytes cut with "...". Paths and values in messages
/// come from the user and may hold anything.
std::string printableMessage(std::string_view message);

/// The reason in a parser exception's text ("[json.exception.parse_error.101] parse error at line
/// 1, column 2: ...") without its bracketed tag, printable and at most 200 bytes.
std::string parserReason(std::string_view what);

/// `text` for XML or HTML text and double-quoted attributes: & < > " as entities.
std::string escapeXml(std::string_view text);

/// A JSON value (nlohmann::json; a template so that core needs no JSON library) as a message
/// shows it: a scalar as JSON text, printable and short; an array or object by its type only,
/// since printing one would recurse as deep as the file nests.
template <typename Json>
std::string describeJsonValue(const Json& value) {
  if (!value.is_primitive()) return std::string("an ") + (value.is_array() ? "array" : "object");
  return printable(value.dump(-1, ' ', false, Json::error_handler_t::replace));
}

}  // namespace dform
