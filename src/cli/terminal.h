// SPDX-License-Identifier: GPL-3.0-or-later
// What the CLI shows on the terminal: messages, a one-line progress display, errors.
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include "dform/core/messages.h"
#include "dform/pipeline/forward_pipeline.h"

namespace dform::cli {

/// Prints messages and solver progress to stderr, the settings they mention named by their flags.
/// Progress (an updating line) only when stderr is a terminal and not quiet; info messages unless
/// quiet; warnings and errors always.
class Terminal {
 public:
  explicit Terminal(bool quiet);
  MessageSink::Listener listener();
  /// The level a coarse-to-fine solve begins: the progress line names it from then on, with the
  /// time the level's iteration cap would take at the rate it runs at (an upper bound).
  void level(const LevelStart& start);
  void progress(const std::string& stage, const IterationSummary& it);
  /// One updating line of any text (e.g. a sweep's jobs done and time left), on the same terms.
  void status(const std::string& text);
  void clearProgress();
  /// One line "dform: error: ..." on stderr, the settings it mentions named by their flags.
  static void error(const std::string& message);
  static void error(const Status& status);

 private:
  bool quiet_;
  bool tty_;
  bool progressShown_ = false;
  std::optional<LevelStart> level_;
  std::string stage_;  ///< the stage whose rate stageStart_ times
  std::chrono::steady_clock::time_point stageStart_;
  int stageFirstIteration_ = 0;
};

}  // namespace dform::cli
