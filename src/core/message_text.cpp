#include "core/message_text.h"

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
    if (c < 0x20 || c == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02x", c);
      out += escape;
    } else {
      out += char(c);
    }
  }
  return end < text.size() ? out + "..." : out;
}

std::string parserReason(std::string_view what) {
  if (!what.empty() && what.front() == '[') {
    const std::size_t close = what.find("] ");
    if (close != std::string_view::npos) what.remove_prefix(close + 2);
  }
  return printable(what, 200);
}

}  // namespace dform
