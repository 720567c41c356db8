#include "dform/cli/terminal.h"

#include <unistd.h>

#include <cstdio>

#include "dform/core/message_text.h"

namespace dform::cli {

Terminal::Terminal(bool quiet) : quiet_(quiet), tty_(isatty(STDERR_FILENO) == 1) {}

MessageSink::Listener Terminal::listener() {
  return [this](const Message& m) {
    if (m.level == Level::Debug || (quiet_ && m.level == Level::Info)) return;
    clearProgress();
    const char* prefix = m.level == Level::Warning ? "dform: warning: "
                         : m.level == Level::Error ? "dform: error: "
                                                   : "";
    std::fprintf(stderr, "%s%s\n", prefix, printableMessage(m.text).c_str());
  };
}

void Terminal::progress(const std::string& stage, const IterationSummary& it) {
  if (quiet_ || !tty_) return;
  std::fprintf(stderr, "\r\033[K%s: iteration %d, cost %.6g, %.2f s", stage.c_str(), it.iteration,
               it.cost, it.cumulativeSeconds);
  std::fflush(stderr);
  progressShown_ = true;
}

void Terminal::status(const std::string& text) {
  if (quiet_ || !tty_) return;
  std::fprintf(stderr, "\r\033[K%s", text.c_str());
  std::fflush(stderr);
  progressShown_ = true;
}

void Terminal::clearProgress() {
  if (!progressShown_) return;
  std::fprintf(stderr, "\r\033[K");
  progressShown_ = false;
}

void Terminal::error(const std::string& message) {
  std::fprintf(stderr, "dform: error: %s\n", printableMessage(message).c_str());
}

}  // namespace dform::cli
