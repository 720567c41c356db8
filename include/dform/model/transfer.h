// SPDX-License-Identifier: GPL-3.0-or-later
// Carrying a solved shape from one triangulation of a flat piece to another (coarse to fine).
#pragma once

#include "dform/core/types.h"

namespace dform {

/// 3D positions for the flat vertices `points` (#P by 2, mm) by barycentric interpolation in
/// `source` (its flat mesh and 3D shape). A point outside the source's flat mesh (the fine seam
/// bulges past the coarse seam's chords) takes the barycentric coordinates of the nearest
/// triangle, clamped to it.
Points3 transferShape(const Piece& source, const Points2& points);

/// Starts a and b from the coarser solution: barycentric transfer, then each seam pair at the
/// mean of its two transferred positions so that the seam starts closed.
void startFromCoarser(const DForm& coarse, Piece& a, Piece& b);

}  // namespace dform
