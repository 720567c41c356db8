// Small helpers shared by the pipeline's runs (internal to src/pipeline).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "pipeline/forward_pipeline.h"

namespace dform::detail {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// printf-style formatting of up to three numbers into a message.
inline std::string format(const char* pattern, double a, double b = 0, double c = 0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

/// Routes the solver's iterations to the run's hooks; `interrupted` turns true when the caller
/// asked the run to stop (the solver then ends with UserAbort).
inline void connectHooks(SolverOptions& options, const RunHooks& hooks, bool& interrupted) {
  options.callback = [&hooks, &interrupted](const IterationSummary& it) {
    if (hooks.onIteration) hooks.onIteration(it);
    interrupted = hooks.interrupted && hooks.interrupted->load();
    return !interrupted;
  };
}

}  // namespace dform::detail
