// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/piece_loops.h"

#include <cmath>

#include "dform/core/polyline.h"

namespace dform {

Points2 loopPoints(const Points2& flat, const std::vector<int>& loop) {
  Points2 P(Eigen::Index(loop.size()), 2);
  for (size_t i = 0; i < loop.size(); ++i) P.row(Eigen::Index(i)) = flat.row(loop[i]);
  return P;
}

std::vector<std::vector<int>> boundaryLoops(const Piece& piece) {
  std::vector<std::vector<int>> loops{piece.seam};
  loops.insert(loops.end(), piece.freeBoundaries.begin(), piece.freeBoundaries.end());
  return loops;
}

int outerLoopIndex(const Piece& piece) {
  int outer = 0;
  double largest = std::abs(signedArea(loopPoints(piece.flat, piece.seam)));
  for (size_t k = 0; k < piece.freeBoundaries.size(); ++k) {
    const double area = std::abs(signedArea(loopPoints(piece.flat, piece.freeBoundaries[k])));
    if (area > largest) {
      largest = area;
      outer = int(k) + 1;
    }
  }
  return outer;
}

}  // namespace dform
