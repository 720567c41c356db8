#include "dform/model/term_table.h"

namespace dform {

std::unique_ptr<ResidualTerm> isometryTerm(const TermInputs& in) {
  return makeIsometryTerm(in.edges);
}

std::unique_ptr<ResidualTerm> smooth3dTerm(const TermInputs& in) {
  return makeSmoothnessTerm(in.layout, in.a, in.b, true);
}

std::unique_ptr<ResidualTerm> smooth2dTerm(const TermInputs& in) {
  return makeSmoothnessTerm(in.layout, in.a, in.b, false);
}

std::unique_ptr<ResidualTerm> boundaryFixTerm(const TermInputs& in) {
  const Points2 targetsA = in.a.flat(in.anchoredA, Eigen::all),
                targetsB = in.b.flat(in.anchoredB, Eigen::all);
  return makeFlatAnchorTerm(in.layout, in.anchoredA, targetsA, in.anchoredB, targetsB);
}

std::unique_ptr<ResidualTerm> seamTerm(const TermInputs& in) {
  return makeSeamSmoothnessTerm(in.layout, in.a.seam, in.b.seam);
}

const TermTable<ForwardWeights>& forwardTerms() {
  // Alignment makes no term: any positive weight closes the seam exactly (shared unknowns).
  static const TermTable<ForwardWeights> table = {
      {"isometry", &ForwardWeights::isometry, isometryTerm, false},
      {"alignment", &ForwardWeights::alignment, nullptr, false},
      {"boundary_fix", &ForwardWeights::boundaryFix, boundaryFixTerm, true},
      {"smooth_3d", &ForwardWeights::smooth3d, smooth3dTerm, true},
      {"smooth_2d", &ForwardWeights::smooth2d, smooth2dTerm, true},
      {"seam", &ForwardWeights::seam, seamTerm, true}};
  return table;
}

const TermTable<InverseWeights>& inverseTerms() {
  // Closeness makes no term: any positive weight holds the seam on the curve exactly.
  static const TermTable<InverseWeights> table = {
      {"isometry", &InverseWeights::isometry, isometryTerm, false},
      {"closeness", &InverseWeights::closeness, nullptr, false},
      {"smooth_3d", &InverseWeights::smooth3d, smooth3dTerm, true},
      {"smooth_2d", &InverseWeights::smooth2d, smooth2dTerm, true}};
  return table;
}

}  // namespace dform
