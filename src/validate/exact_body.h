// The physical D-Form of a result's flat pieces: Alexandrov's convex body of their glued metric
// (src/exact), against which a result's shape is measured.
#pragma once

#include <string>

#include "core/status.h"
#include "core/types.h"

namespace dform {

/// The 3D seam of the convex body that the flat pieces of `model` make when zipped (row k for
/// seam point k), or a Status saying why there is none: a piece joined along a hole (anti and
/// demi D-Forms glue no sphere), a glued metric that is not convex (naming the seam point and
/// its angle sum: no convex D-Form exists), a seam past exact::kMaxExactSeam, or an engine failure.
Result<Points3> exactBodySeam(const DForm& model);

/// The 3D seam the flat pieces of `model` take when zipped again, row k for seam point k: their
/// exact D-Form where it exists, otherwise the paper's optimisation of the same meshes from its
/// pillow start, coarse to fine as a forward run (a non-convex metric: no convex body exists, and
/// the sheet takes some other shape). `how` says which made it and why.
Result<Points3> zippedAgainSeam(const DForm& model, std::string& how);

}  // namespace dform
