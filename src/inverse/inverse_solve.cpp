#include "inverse/inverse_solve.h"

#include <cassert>

#include "core/polyline.h"
#include "forward/terms.h"

namespace dform {

InverseResult solveInverse(const DForm& start, const Points3& curve, const InverseOptions& options) {
  assert(start.a.seam.size() == start.b.seam.size() &&
         start.a.seam.size() == std::size_t(curve.rows()) && "one seam pair per curve point");
  InverseResult result;
  // Internal unit: the curve's mean edge length (paper 5.1).
  result.unitMm = closedLength(curve) / double(curve.rows());
  const double unit = result.unitMm;
  DForm scaled = start;
  scaleLengths(scaled, 1.0 / unit);
  const Points3 target = curve / unit;

  // Both sides of the seam are one curve in 3D: shared unknowns, as in forward modelling.
  const VariableLayout layout(int(scaled.a.flat.rows()), int(scaled.b.flat.rows()), scaled.a.seam,
                              scaled.b.seam);
  const InverseWeights& w = options.weights;
  EdgeLengthPairs edges = meshEdgePairs(layout, scaled.a.F, scaled.b.F);
  auto closeness = makeCurveClosenessTerm(layout, scaled.a.seam, scaled.b.seam, target);
  auto smooth3d = makeSmoothnessTerm(layout, scaled.a, scaled.b, true);
  auto smooth2d = makeSmoothnessTerm(layout, scaled.a, scaled.b, false);
  Eigen::VectorXd x = packVariables(layout, scaled.a, scaled.b);

  weightByFlatLength(edges, x, w.isometry);
  auto* closenessTerm = static_cast<LinearResidual*>(closeness.get());
  result.relaxation = relaxLocalGlobal(
      {{w.closeness, closenessTerm},
       {w.smooth3d, static_cast<const LinearResidual*>(smooth3d.get())},
       {w.smooth2d, static_cast<const LinearResidual*>(smooth2d.get())}},
      edges, options.relaxation, x);

  Problem problem(layout.numVariables());
  problem.addTerm("isometry", w.isometry, makeIsometryTerm(edges));
  problem.addTerm("closeness", w.closeness, std::move(closeness));
  problem.addTerm("smooth_3d", w.smooth3d, std::move(smooth3d));
  problem.addTerm("smooth_2d", w.smooth2d, std::move(smooth2d));
  if (options.solver.maxIterations == 0) {  // the relaxation is the result
    result.summary = summaryWithoutSteps(problem, x);
  } else {
    LeastSquaresSolver solver(problem, options.solver);
    result.summary = solver.solve(x);
    if (w.closeness > 0)
      result.curveClosingRounds = enforceByMultipliers(
          solver, {{closenessTerm, 3, options.curveTolerance * double(curve.rows())}},
          options.curveClosingRounds, x, result.summary);
  }

  result.model = scaled;
  unpackVariables(layout, x, result.model.a, result.model.b);
  scaleLengths(result.model, unit);
  return result;
}

}  // namespace dform
