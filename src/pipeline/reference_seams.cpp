#include "pipeline/reference_seams.h"

#include <optional>

#include "exact/body_edges.h"
#include "exact/exact_gluing.h"
#include "forward/coarse_to_fine.h"

namespace dform {

namespace {

Result<Points3> exactSeam(const DForm& model) {
  const std::size_t n = model.a.seam.size();
  if (!model.a.freeBoundaries.empty() || !model.b.freeBoundaries.empty())
    return Status(ErrorCode::InputInvalid,
                  "a piece is zipped along a hole (anti or demi D-Form): its pieces glue no sphere");
  if (n > std::size_t(exact::kMaxExactSeam))
    return Status(ErrorCode::InputInvalid, "the seam has " + std::to_string(n) + " points, more than the " +
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
  if (!glued.isOk()) return glued.status();
  // The body true to the pieces' lengths, as the exact model makes it.
  Result<std::vector<exact::BodyEdge>> edges = exact::traceBodyEdges(glued.value());
  if (!edges.isOk()) return edges.status();
  exact::fitBodyToEdges(glued.value(), edges.value());
  Points3 out = exact::placeOnBody(glued.value(), 0, glued.value().seam.a);
  if (!out.allFinite()) return Status(ErrorCode::SolveFailed, "a seam point could not be placed on the exact body");
  return out;
}

ReferenceSeam reference(const Result<Points3>& seam, const std::string& how) {
  if (!seam.isOk()) return {Points3(), seam.status().message()};
  return {seam.value(), how};
}

}  // namespace

ReferenceSeam exactBodySeam(const DForm& model) { return reference(exactSeam(model), "the exact D-Form of the pieces"); }

ReferenceSeam zippedAgainSeam(const DForm& model) {
  Result<Points3> exact = exactSeam(model);
  if (exact.isOk()) return reference(exact, "zipped by the exact D-Form of the pieces");
  // A non-convex metric: the optimisation says what shape the sheet takes instead. Other reasons
  // (a hole zipped, a seam too long to glue) are not the round trip's to work around.
  if (exact.status().message().find("not convex") == std::string::npos) return reference(exact, "");
  const ForwardResult solved = solveMeshedCoarseToFine(model.a, model.b, ForwardOptions{});
  if (!solved.summary.usable())
    return {Points3(), exact.status().message() + "; and the optimisation failed: " + solved.summary.message};
  Points3 seam(Eigen::Index(model.a.seam.size()), 3);
  for (std::size_t k = 0; k < model.a.seam.size(); ++k)
    seam.row(Eigen::Index(k)) = solved.model.a.shape.row(solved.model.a.seam[k]);
  return {seam, "zipped by the paper's optimisation, since " + exact.status().message()};
}

Metrics measureModel(const DForm& model) { return computeMetrics(model, exactBodySeam(model)); }

CurveMatch measureCurveMatch(const DForm& model, const Curve3& target) {
  return computeCurveMatch(model, target, zippedAgainSeam(model));
}

GateReport measureAndGate(const DForm& model, const GateLimits& limits, const Curve3* target) {
  const std::size_t pairs = model.a.seam.size();
  std::optional<CurveMatch> curve;
  if (target && std::size_t(target->points.rows()) == pairs && pairs > 0) curve = measureCurveMatch(model, *target);
  return runGate(model, limits, measureModel(model), target, curve ? &*curve : nullptr);
}

}  // namespace dform
