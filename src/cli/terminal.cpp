// SPDX-License-Identifier: GPL-3.0-or-later
#include "terminal.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "dform/core/message_text.h"
#include "json_summary.h"
#include "setting_options.h"

namespace dform::cli {

Terminal::Terminal(bool quiet) : quiet_(quiet), tty_(isatty(STDERR_FILENO) == 1) {}

MessageSink::Listener Terminal::listener() {
  return [this](const Message& m) {
    if (m.level == Level::Debug || (quiet_ && m.level == Level::Info)) return;
    clearProgress();
    const char* prefix = m.level == Level::Warning ? "dform: warning: "
                         : m.level == Level::Error ? "dform: error: "
                                                   : "";
    const std::string shown = printableMessage(inCommandLineTerms(m.text));
    std::fprintf(stderr, "%s%s\n", prefix, shown.c_str());
    if (m.level == Level::Error) json_summary::error(shown);
  };
}

void Terminal::level(const LevelStart& start) {
  level_ = start;
  stage_.clear();
}

void Terminal::progress(const std::string& stage, const IterationSummary& it) {
  if (quiet_ || !tty_) return;
  if (!level_) {
    std::fprintf(stderr, "\r\033[K%s: iteration %d, cost %.6g, %.2f s", stage.c_str(), it.iteration,
                 it.cost, it.cumulativeSeconds);
  } else {
    const auto now = std::chrono::steady_clock::now();
    if (stage != stage_) {  // a new stage of the level: its rate timed from this iteration on
      stage_ = stage;
      stageStart_ = now;
      stageFirstIteration_ = it.iteration;
    }
    const bool relaxing = stage == "relaxing";
    const int cap = relaxing ? level_->relaxationSteps : level_->solverIterations;
    char eta[32] = "ETA -";  // no rate before the stage's second iteration
    if (const int timed = it.iteration - stageFirstIteration_; timed > 0) {
      const double seconds = std::chrono::duration<double>(now - stageStart_).count();
      std::snprintf(eta, sizeof eta, "ETA %.0f s",
                    seconds / timed * std::max(cap - it.iteration, 0));
    }
    std::fprintf(stderr, "\r\033[Klevel %d/%d: %s %d/%d %s, cost %.6g, %s", level_->level,
                 level_->levels, stage.c_str(), it.iteration, cap,
                 relaxing ? "steps" : "iterations", it.cost, eta);
  }
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
  const std::string shown = printableMessage(inCommandLineTerms(message));
  std::fprintf(stderr, "dform: error: %s\n", shown.c_str());
  json_summary::error(shown);
}

void Terminal::error(const Status& status) {
  const std::string shown = printableMessage(inCommandLineTerms(status.text()));
  std::fprintf(stderr, "dform: error: %s\n", shown.c_str());
  json_summary::error(shown, &status);
}

}  // namespace dform::cli
