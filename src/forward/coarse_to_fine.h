// Zipping two meshed pieces as a forward run zips drawn ones: coarse to fine.
#pragma once

#include "core/types.h"
#include "forward/forward.h"

namespace dform {

/// Solves the forward problem for two meshed pieces (as solveForward, from the pillow) level by
/// level as a forward run does (detail::seamLevels, detail::levelOptions): the coarser levels
/// mesh every third seam point of the coarser level's... of the pieces' own flat seam polygons, so
/// that the finest level starts from a coarser solution and a large one is left to the relaxation.
/// Pieces with a free boundary (a hole zipped) are solved in one level. Solved in one level from
/// the pillow, an inverse run's 99k-vertex pieces took 6 minutes (2000 relaxation steps, then LM).
ForwardResult solveMeshedCoarseToFine(const Piece& a, const Piece& b, const ForwardOptions& options);

}  // namespace dform
