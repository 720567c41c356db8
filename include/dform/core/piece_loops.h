// SPDX-License-Identifier: GPL-3.0-or-later
// The boundary loops of a piece: its seam and its free boundaries, and which of them is the outer
// outline. Whether the seam is the outer outline (a classic piece, the disc of a demi D-Form) or a
// hole (an anti D-Form's pieces, the annulus of a demi D-Form) follows from the flat geometry.
#pragma once

#include <vector>

#include "dform/core/types.h"

namespace dform {

/// The rows of `flat` listed by `loop`, in order (#loop by 2).
Points2 loopPoints(const Points2& flat, const std::vector<int>& loop);

/// Every boundary loop of the piece: the seam first, then its free boundaries in order.
std::vector<std::vector<int>> boundaryLoops(const Piece& piece);

/// Index into boundaryLoops(piece) of the outer outline: the loop enclosing the largest area in
/// the flat layout (the others are holes inside it). 0, the seam, for a classic piece.
int outerLoopIndex(const Piece& piece);

/// Whether the piece's seam is a hole's loop rather than its outer outline.
inline bool seamIsHole(const Piece& piece) { return outerLoopIndex(piece) != 0; }

/// Whether the piece is a D-Form variant: it has free boundaries or creases.
inline bool isVariant(const Piece& piece) {
  return !piece.freeBoundaries.empty() || !piece.creases.empty();
}

}  // namespace dform
