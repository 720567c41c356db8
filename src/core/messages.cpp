// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/messages.h"

namespace dform {

const char* levelName(Level level) {
  switch (level) {
    case Level::Debug: return "debug";
    case Level::Info: return "info";
    case Level::Warning: return "warning";
    case Level::Error: return "error";
  }
  return "unknown";
}

void MessageSink::emit(Level level, std::string text) {
  messages_.push_back({level, std::move(text)});
  if (listener_) listener_(messages_.back());
}

}  // namespace dform
