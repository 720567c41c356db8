// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/inverse/inverse_solve.h"

#include <cassert>

#include "dform/core/polyline.h"
#include "dform/model/relax_then_solve.h"
#include "dform/model/term_table.h"
#include "dform/model/terms.h"

namespace dform {

InverseResult solveInverse(const DForm& start, const Points3& curve,
                           const InverseSettings& settings) {
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
  const InverseWeights& w = settings.weights;
  EdgeLengthPairs edges = meshEdgePairs(layout, scaled.a.F, scaled.b.F);
  const TermTable<InverseWeights>& table = inverseTerms();
  // The flat boundaries are free: no vertex is anchored.
  std::vector<std::unique_ptr<ResidualTerm>> terms =
      makeTerms(table, {layout, scaled.a, scaled.b, edges, {}, {}});
  Eigen::VectorXd x = packVariables(layout, scaled.a, scaled.b);
  // The seam lies on the curve: the closeness term (Eq. 6) as an exact constraint, the limit of
  // its penalty (the paper's section 6.6 suggests it): its 3D unknowns are held at the curve.
  std::vector<int> held;
  if (w.closeness > 0)
    for (std::size_t k = 0; k < scaled.a.seam.size(); ++k)
      for (int c = 0; c < 3; ++c) {
        const int v = layout.x(0, scaled.a.seam[k]) + c;  // B's side shares it
        x[v] = target(Eigen::Index(k), c);
        held.push_back(v);
      }

  weightByFlatLength(edges, x, w.isometry);
  const LocalGlobalRelaxation relaxation(linearTerms(table, terms, w), edges, x, held);
  // No Levenberg-Marquardt step folds a triangle over (model/injectivity.h).
  const FoldGuard guard(layout, scaled.a, scaled.b);

  Problem problem(layout.numVariables());
  addTerms(problem, table, terms, w);
  problem.holdConstant(held);
  problem.setBlockSize(VariableLayout::kPerVertex);
  // The seam is held on the curve exactly: no constraint is left to multiplier rounds.
  SolveSequenceSummary solved =
      relaxThenSolve(relaxation, settings.relaxation, problem, settings.solver, guard, {}, 0, x);
  result.relaxation = std::move(solved.relaxation);
  result.summary = std::move(solved.summary);

  result.model = scaled;
  unpackVariables(layout, x, result.model.a, result.model.b);
  scaleLengths(result.model, unit);
  return result;
}

}  // namespace dform
