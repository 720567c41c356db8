// SPDX-License-Identifier: GPL-3.0-or-later
// The forward run end to end: two outline files in, a solved and measured D-Form out.
#pragma once

#include <string>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/forward/dform_from_shapes.h"
#include "dform/validate/metrics.h"

namespace dform {

/// A forward job: the settings and the two outline files (SVG or JSON points).
struct ForwardJob : ForwardSettings {
  std::string pieceA;  ///< piece A's outline file
  std::string pieceB;  ///< piece B's outline file
};

/// A forward run's result: the solved D-Form and its figures.
struct ForwardRun : SolvedDForm {
  Metrics metrics;  ///< the figures measured on the solved D-Form (report.json's "metrics")
};

/// Reads the two files, then makes and measures their D-Form as makeDForm does. Errors name the
/// file and the problem.
Result<ForwardRun> runForward(const ForwardJob& job, MessageSink& sink, const RunHooks& hooks = {});

/// The D-Form of two shapes in memory, checked as a run from files checks its job and files
/// (the settings table's checkSettings, then io's checkOutline: the same codes and messages, a
/// piece named by its outline's `source`, else "piece A" / "piece B"), solved as forward's
/// solveDForm does (the exact model or the paper's), and measured: measureDForm(solveDForm(...)).
Result<ForwardRun> makeDForm(Shape2 a, Shape2 b, const ForwardSettings& settings, MessageSink& sink,
                             const RunHooks& hooks = {});

/// makeDForm without the figures, for a front end that shows the shape before them (the studio):
/// checked and solved as makeDForm does; measureDForm gives its figures.
Result<SolvedDForm> shapeDForm(Shape2 a, Shape2 b, const ForwardSettings& settings,
                               MessageSink& sink, const RunHooks& hooks = {});

/// The figures makeDForm gives a solved D-Form, for a front end that shows the shape (shapeDForm)
/// before its figures; `settings` and `pieces` (the pieces' names) for the message when
/// measuring runs out of memory.
Result<Metrics> measureDForm(const SolvedDForm& solved, const ForwardSettings& settings,
                             const std::string& pieces);

}  // namespace dform
