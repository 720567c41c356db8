// SPDX-License-Identifier: GPL-3.0-or-later
// Zipping two meshed pieces as a forward run zips drawn ones: coarse to fine.
#pragma once

#include "dform/core/types.h"
#include "dform/forward/forward.h"

namespace dform {

/// Solves the forward problem for two meshed pieces (as solveForward, from the pillow) level by
/// level as a forward run does (detail::seamLevels, detail::levelSettings): each coarser level
/// meshes a third of the seam points of the pieces' own flat seam polygons, so that the finest
/// level starts from a coarser solution, and a large level is left to the relaxation. Pieces with
/// a free boundary (a hole zipped) are solved in one level. Solved in one level, an inverse run's
/// 99k-vertex pieces need 355 s to zip again; coarse to fine, about 16 s.
ForwardResult solveMeshedCoarseToFine(const Piece& a, const Piece& b,
                                      const ForwardSettings& settings);

namespace detail {

/// One level's settings: a coarse level runs a few LM iterations (kCoarseIterations) and leaves the
/// seam corners to the boundary-fix term (no constraint rounds); a large level is left to the
/// relaxation (relaxOnlyIfLarge, model/run_control.h).
ForwardSettings levelSettings(ForwardSettings settings, bool finest, long vertices);

}  // namespace detail

}  // namespace dform
