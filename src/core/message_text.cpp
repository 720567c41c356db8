// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/message_text.h"

#include <algorithm>
#include <cstdio>

namespace dform {

namespace {

// The length of the well-formed UTF-8 character at text[i] (1 to 4), or 0 when it is not one
// (a stray continuation byte, an overlong form, a surrogate, past U+10FFFF, cut short).
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const unsigned char c = static_cast<unsigned char>(text[i]);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned char low = 0x80, high = 0xBF;  // the range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) low = 0xA0;
    if (c == 0xED) high = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) low = 0x90;
    if (c == 0xF4) high = 0x8F;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const unsigned char b = static_cast<unsigned char>(text[i + k]);
    if (b < (k == 1 ? low : 0x80) || b > (k == 1 ? high : 0xBF)) return 0;
  }
  return n;
}

}  // namespace

std::string utf8Text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8Length(text, i);
    if (n > 0) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02x", static_cast<unsigned char>(text[i]));
      out += escape;
      ++i;
    }
  }
  return out;
}

std::string printable(std::string_view text, std::size_t maxBytes) {
  std::size_t end = text.size();
  if (end > maxBytes) {
    end = maxBytes;
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80)
      --end;  // continuation
  }
  std::string out;
  for (std::size_t i = 0; i < end; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c < 0x20 || c == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02x", c);
      out += escape;
    } else if (c < 0x80) {
      out += char(c);
    } else {
      const std::size_t n = std::min(utf8Length(text, i), end - i);
      out += utf8Text(text.substr(i, std::max<std::size_t>(n, 1)));
      i += std::max<std::size_t>(n, 1) - 1;
    }
  }
  return end < text.size() ? out + "..." : out;
}

std::string printableMessage(std::string_view message) {
  std::string out;
  std::size_t start = 0;
  while (start < message.size()) {
    const std::size_t space = std::min(message.find(' ', start), message.size());
    out += printable(message.substr(start, space - start), kMaxTokenBytes);
    if (space < message.size()) out += ' ';
    start = space + 1;
  }
  return out;
}

std::string parserReason(std::string_view what) {
  if (!what.empty() && what.front() == '[') {
    const std::size_t close = what.find("] ");
    if (close != std::string_view::npos) what.remove_prefix(close + 2);
  }
  return printable(what, 200);
}

std::string escapeXml(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace dform
