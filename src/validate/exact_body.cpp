#include "validate/exact_body.h"

#include "exact/exact_gluing.h"

namespace dform {

Result<Points3> exactBodySeam(const DForm& model) {
  const std::size_t n = model.a.seam.size();
  if (!model.a.freeBoundaries.empty() || !model.b.freeBoundaries.empty())
    return Status(ErrorCode::InputInvalid,
                  "a piece is zipped along a hole (anti or demi D-Form): its pieces glue no sphere");
  if (n > std::size_t(kMaxExactSeam))
    return Status(ErrorCode::InputInvalid, "the seam has " + std::to_string(n) + " points, more than the " +
                                               std::to_string(kMaxExactSeam) + " glued exactly for a figure");
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
  Points3 out = exact::placeOnBody(glued.value(), 0, glued.value().seam.a);
  if (!out.allFinite()) return Status(ErrorCode::SolveFailed, "a seam point could not be placed on the exact body");
  return out;
}

}  // namespace dform
