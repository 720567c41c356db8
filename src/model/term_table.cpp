// SPDX-License-Identifier: GPL-3.0-or-later
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
      {"isometry", &ForwardWeights::isometry, "edge lengths kept (paper Eq. 1)", isometryTerm,
       false},
      {"alignment", &ForwardWeights::alignment,
       "the seam closed (Eq. 2): any positive weight closes it exactly", nullptr, false},
      {"boundary_fix", &ForwardWeights::boundaryFix, "the seam corners held where drawn (Eq. 3)",
       boundaryFixTerm, true},
      {"smooth_3d", &ForwardWeights::smooth3d, "smoothness of the 3D shape (Eq. 4)", smooth3dTerm,
       true},
      {"smooth_2d", &ForwardWeights::smooth2d, "smoothness of the flat pieces (Eq. 4)",
       smooth2dTerm, true},
      {"seam", &ForwardWeights::seam, "smoothness of the seam (Eq. 5)", seamTerm, true}};
  return table;
}

const TermTable<InverseWeights>& inverseTerms() {
  // Closeness makes no term: any positive weight holds the seam on the curve exactly.
  static const TermTable<InverseWeights> table = {
      {"isometry", &InverseWeights::isometry, "edge lengths kept (paper Eq. 1)", isometryTerm,
       false},
      {"closeness", &InverseWeights::closeness,
       "the seam on the curve (Eq. 6): any positive weight holds it there exactly", nullptr, false},
      {"smooth_3d", &InverseWeights::smooth3d, "smoothness of the 3D shape (Eq. 4)", smooth3dTerm,
       true},
      {"smooth_2d", &InverseWeights::smooth2d, "smoothness of the flat pieces (Eq. 4)",
       smooth2dTerm, true}};
  return table;
}

}  // namespace dform
