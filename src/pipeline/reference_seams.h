// SPDX-License-Identifier: GPL-3.0-or-later
// The shapes a result's figures compare it with, made from its flat pieces: their exact D-Form
// (Alexandrov's convex body of the glued metric, src/exact) and, for an inverse result's round
// trip, the pieces zipped again. validate measures and judges; these are solved here and handed
// to it.
#pragma once

#include "dform/core/types.h"
#include "dform/validate/gate.h"
#include "dform/validate/metrics.h"

namespace dform {

/// The seam of the convex body that the flat pieces of `model` make when zipped (row k for seam
/// point k), or why there is none in the note: a piece joined along a hole (anti and demi D-Forms
/// glue no sphere), a glued metric that is not convex (naming the seam point and its angle sum:
/// no convex D-Form exists), a seam past exact::kMaxExactSeam, or an engine failure.
ReferenceSeam exactBodySeam(const DForm& model);

/// The seam the flat pieces of `model` take when zipped again, row k for seam point k: their
/// exact D-Form where it exists (`exactBody`, exactBodySeam(model)), otherwise the paper's
/// optimisation of the same meshes from its pillow start, coarse to fine as a forward run (a
/// non-convex metric: no convex body exists, and the sheet takes some other shape). The note says
/// which made it, or why neither could.
ReferenceSeam zippedAgainSeam(const DForm& model, const ReferenceSeam& exactBody);

/// The figures of `model`: computeMetrics against its exact body's seam.
Metrics measureModel(const DForm& model);

/// The figures of an inverse result `model` against its `target` curve, the exact body glued
/// once for both (the distance from it, and the round trip).
void measureInverse(const DForm& model, const Curve3& target, Metrics& metrics, CurveMatch& curve);

/// The gate on a model read back from files, measured here first (a run hands runGate the figures
/// it measured). With a `target` curve (one point per seam pair) the curve is matched too.
GateReport measureAndGate(const DForm& model, const GateLimits& limits, const Curve3* target);

/// How many models measureAndGate has measured in this process (tests count them).
long modelsMeasuredForGate();

}  // namespace dform
