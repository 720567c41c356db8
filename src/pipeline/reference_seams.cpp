// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference_seams.h"

#include <atomic>

#include "dform/exact/body_edges.h"
#include "dform/exact/exact_gluing.h"
#include "dform/forward/coarse_to_fine.h"

namespace dform {

namespace {

using Missing = ReferenceSeam::Missing;

ReferenceSeam missing(Missing why, std::string note) { return {Points3(), std::move(note), why}; }

std::atomic<long> measuredForGate{0};

}  // namespace

ReferenceSeam exactBodySeam(const DForm& model) {
  const std::size_t n = model.a.seam.size();
  if (!model.a.freeBoundaries.empty() || !model.b.freeBoundaries.empty())
    return missing(
        Missing::HoleZipped,
        "a piece is zipped along a hole (anti or demi D-Form): its pieces glue no sphere");
  if (n > std::size_t(exact::kMaxExactSeam))
    return missing(Missing::SeamTooLong,
                   "the seam has " + std::to_string(n) + " points, more than the " +
                       std::to_string(exact::kMaxExactSeam) + " glued exactly for a figure");
  exact::SeamPolygons seam;
  seam.a.resize(Eigen::Index(n), 2);
  seam.b.resize(Eigen::Index(n), 2);
  for (std::size_t k = 0; k < n; ++k) {
    seam.a.row(Eigen::Index(k)) = model.a.flat.row(model.a.seam[k]);
    seam.b.row(Eigen::Index(k)) = model.b.flat.row(model.b.seam[k]);
  }
  exact::equalizeChords(seam);
  Result<exact::ExactGluing> glued = exact::glue(seam);
  if (!glued.isOk())
    return missing(
        exact::seamAngles(seam).firstNonConvex >= 0 ? Missing::NotConvex : Missing::EngineFailed,
        glued.status().message());
  // The body true to the pieces' lengths, as the exact model makes it.
  Result<std::vector<exact::BodyEdge>> edges = exact::traceBodyEdges(glued.value());
  if (!edges.isOk()) return missing(Missing::EngineFailed, edges.status().message());
  exact::fitBodyToEdges(glued.value(), edges.value());
  Points3 out = exact::placeOnBody(glued.value(), 0, glued.value().seam.a);
  if (!out.allFinite())
    return missing(Missing::EngineFailed, "a seam point could not be placed on the exact body");
  return {out, "the exact D-Form of the pieces", Missing::None};
}

ReferenceSeam zippedAgainSeam(const DForm& model, const ReferenceSeam& exactBody) {
  if (exactBody.missing == Missing::None)
    return {exactBody.points, "zipped by " + exactBody.note, Missing::None};
  // A non-convex metric: the optimisation says what shape the sheet takes instead. Other reasons
  // (a hole zipped, a seam too long to glue) are not the round trip's to work around.
  if (exactBody.missing != Missing::NotConvex) return exactBody;
  const ForwardResult solved = solveMeshedCoarseToFine(model.a, model.b, ForwardSettings{});
  if (!solved.summary.usable())
    return missing(Missing::EngineFailed,
                   exactBody.note + "; and the optimisation failed: " + solved.summary.message);
  Points3 seam(Eigen::Index(model.a.seam.size()), 3);
  for (std::size_t k = 0; k < model.a.seam.size(); ++k)
    seam.row(Eigen::Index(k)) = solved.model.a.shape.row(solved.model.a.seam[k]);
  return {seam, "zipped by the paper's optimisation, since " + exactBody.note, Missing::None};
}

Metrics measureModel(const DForm& model) { return computeMetrics(model, exactBodySeam(model)); }

void measureInverse(const DForm& model, const Curve3& target, Metrics& metrics, CurveMatch& curve) {
  const ReferenceSeam body = exactBodySeam(model);
  metrics = computeMetrics(model, body);
  curve = computeCurveMatch(model, target, zippedAgainSeam(model, body));
}

long modelsMeasuredForGate() { return measuredForGate.load(); }

GateReport measureAndGate(const DForm& model, const GateLimits& limits, const Curve3* target) {
  ++measuredForGate;
  const std::size_t pairs = model.a.seam.size();
  if (!(target && std::size_t(target->points.rows()) == pairs && pairs > 0))
    return runGate(model, limits, measureModel(model), target, nullptr);
  Metrics metrics;
  CurveMatch curve;
  measureInverse(model, *target, metrics, curve);
  return runGate(model, limits, metrics, target, &curve);
}

}  // namespace dform
