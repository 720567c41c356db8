// SPDX-License-Identifier: GPL-3.0-or-later
// A D-Form made by the ruled engine (src/ruled), meshed as the other models' pieces are: each
// piece's mesh follows the surface's folded chords, and every vertex is placed on the flat
// triangle of the surface it lies in, so every mesh triangle is an isometric copy of its flat one.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/exact/exact_gluing.h"
#include "dform/model/run_types.h"
#include "dform/ruled/ruled_surface.h"

namespace dform {

/// What the ruled engine is built from: the two sides of the seam (as the exact engine glues
/// them, chords equal), each piece's free outline where it is zipped along a hole (its samples,
/// counter-clockwise), and each piece's drawn creases as straight lines between two of its
/// boundary samples (seam or free outline: their ends, mm).
struct RuledPieces {
  exact::SeamPolygons seam;  ///< the seam's two sides, chords equal (mm)
  /// Per piece (A, B): its free outline's samples, counter-clockwise (mm), where it is zipped
  /// along a hole; nullopt where it is zipped along its outline.
  std::array<std::optional<Points2>, 2> freeOutline;
  /// Per piece (A, B): each drawn crease as the straight line between its two ends (mm).
  std::array<std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>, 2> creases;
};

/// The surface of both pieces triangulated with their boundary samples only (constrained Delaunay
/// triangulations, every crease an edge that is never flipped), seam point k one vertex of both,
/// X zero. InputInvalid naming the crease when one does not join two samples.
Result<ruled::RuledSurface> ruledSurface(const RuledPieces& pieces, const std::string paths[2]);

/// Where a model's pieces (a result of the same seam and free outlines, the paper model's) put
/// each vertex of `surface`: their seam rows and free outline rows, in order.
Points3 ruledStartOf(const DForm& model, const ruled::RuledSurface& surface);

/// The pieces of a solved ruled surface meshed with interior edges about `targetEdge` mm: every
/// chord folded by at least 1e-5 rad and every drawn crease a line of the mesh (folds steeper
/// than the found-crease angle of a seam of n points also the piece's creases, listed in
/// `used.creases`; every followed fold in `used.folds`). Piece A's seam rows run in seam order
/// as the surface's; `paths` name the pieces in errors.
Result<DForm> ruledDForm(const ruled::RuledSurface& surface, double targetEdge,
                         const std::string paths[2], ModelUsed& used);

}  // namespace dform
