#include "core/message_text.h"

#include <algorithm>
#include <cstdio>

namespace dform {

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
    } else {
      out += char(c);
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
