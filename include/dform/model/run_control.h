// SPDX-License-Identifier: GPL-3.0-or-later
// What the forward and inverse runs share about running: timing, message formatting, the levels
// of a coarse-to-fine solve and when one is left to the relaxation alone, and the caller's hooks
// (progress, a request to stop).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

#include "dform/core/interrupt.h"
#include "dform/core/status.h"
#include "dform/model/local_global.h"
#include "dform/model/run_types.h"
#include "dform/solver/solver.h"

namespace dform::detail {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// printf-style formatting into a message; the compiler checks the arguments against the pattern.
[[gnu::format(printf, 1, 2)]] inline std::string format(const char* pattern, ...) {
  char text[256];
  std::va_list arguments;
  va_start(arguments, pattern);
  std::vsnprintf(text, sizeof text, pattern, arguments);
  va_end(arguments);
  return text;
}

/// Above this many vertices (both pieces) a problem is solved by the local-global relaxation
/// alone: there one factorisation of J^T J costs seconds and hundreds of MB (a forward level of
/// 19k vertices needs 14 s of CPU and 690 MB with Levenberg-Marquardt; 50k vertices 10 s and
/// 430 MB without), while the relaxation's steps scale almost linearly (docs/benchmarks.md,
/// "Scale").
constexpr int kDirectSolveVertices = 10000;

/// A level that starts from a coarser level's solution and is solved by the relaxation alone
/// stops once a plain step would lower the energy by less than 1e-3 of it: what it still does then
/// is smooth the shape, not fit it. Measured: forward at 97k vertices L_error 0.014 %, L_max 0.35 %
/// in 26 steps; the inverse saddle at 300 points L_max 0.16 % in 25 steps, against 0.06 % in 300
/// at 1e-4 (the bars are 0.5 % and 3 %).
constexpr double kRefinedRelaxationTolerance = 1e-3;

/// Applies the first rule to a problem of `vertices` vertices (the large levels of both runs
/// start from a coarser one, so the second applies as well).
inline void relaxOnlyIfLarge(long vertices, SolverOptions& solver, LocalGlobalOptions& relaxation) {
  if (vertices <= kDirectSolveVertices) return;
  solver.maxIterations = 0;
  relaxation.relativeTolerance = kRefinedRelaxationTolerance;
}

/// Coarse-to-fine solves (paper model): each level has a third of the next one's seam vertices,
/// down to kCoarsestSeam, and starts from the coarser solution carried over by barycentric
/// transfer. The coarse levels do the large shape change cheaply; the finest level converges from
/// there in a few steps.
constexpr int kCoarsestSeam = 24;
constexpr int kLevelRatio = 3;
/// A coarse level only has to start the next one well: at most this many LM iterations.
constexpr int kCoarseIterations = 30;

/// The seam resolutions of a solve, coarsest first and `resolution` last (only it when
/// coarseToFine is off).
inline std::vector<int> seamLevels(int resolution, bool coarseToFine) {
  std::vector<int> levels{resolution};
  while (coarseToFine && levels.back() / kLevelRatio >= kCoarsestSeam)
    levels.push_back(levels.back() / kLevelRatio);
  std::reverse(levels.begin(), levels.end());
  return levels;
}

/// Whether the caller asked the run to stop: its hooks' flag, or the process's (core/interrupt.h),
/// which the reads and the relaxation's factorisations poll where no hooks reach.
inline bool stopRequested(const RunHooks& hooks) {
  return (hooks.interrupted && hooks.interrupted->load()) || interruptRequested();
}

/// Routes the relaxation's and the solver's iterations to the run's hooks, and stops them (the
/// relaxation stops, the solver ends with UserAbort) when the caller asks the run to stop.
inline void connectHooks(LocalGlobalOptions& relaxation, SolverOptions& solver,
                         const RunHooks& hooks) {
  auto callback = [&hooks](const char* stage) {
    return [&hooks, stage](const IterationSummary& it) {
      if (hooks.onIteration) hooks.onIteration(stage, it);
      return !stopRequested(hooks);
    };
  };
  relaxation.callback = callback("relaxing");
  solver.callback = callback("solving");
}

}  // namespace dform::detail
