// What the CLI shows on the terminal: messages, a one-line progress display, errors.
#pragma once

#include <string>

#include "dform/core/messages.h"
#include "dform/pipeline/forward_pipeline.h"

namespace dform::cli {

/// Prints messages and solver progress to stderr. Progress (an updating line) only when stderr
/// is a terminal and not quiet; info messages unless quiet; warnings and errors always.
class Terminal {
 public:
  explicit Terminal(bool quiet);
  MessageSink::Listener listener();
  void progress(const std::string& stage, const IterationSummary& it);
  /// One updating line of any text (e.g. a sweep's jobs done and time left), on the same terms.
  void status(const std::string& text);
  void clearProgress();
  /// One line "dform: error: ..." on stderr.
  static void error(const std::string& message);

 private:
  bool quiet_;
  bool tty_;
  bool progressShown_ = false;
};

}  // namespace dform::cli
