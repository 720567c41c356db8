// SPDX-License-Identifier: GPL-3.0-or-later
// The exact model's meshes put on the exact body: each flat vertex at its place on the body.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "dform/core/types.h"
#include "dform/exact/exact_gluing.h"

namespace dform {

/// Both pieces' vertices placed on the body (sets each piece's `shape`). `known[p]` holds, per
/// vertex of piece p, its place where the body tells it (cone points, points of followed folds);
/// `walls[p]` the piece's constrained polylines (followed folds, the closed seam), which cut it
/// into regions that each lie in one plane of the body. Each region is moved onto its plane by
/// its known vertices (least squares, Kabsch), a seam point placed in one piece then known in the
/// other (they are one point of the body), so that a region of one piece bounded by flat seam
/// points takes its plane from the other piece's region there. Vertices no region places (a
/// region whose known vertices lie in a line, or off one plane: it spans a fold too gentle to be
/// followed) are traced onto the body from a cone point (exact::placeOnBody). False when a vertex
/// cannot be placed.
bool placeBothOnFaces(const exact::ExactGluing& g, Piece* pieces[2],
                      std::vector<std::optional<Eigen::Vector3d>> known[2],
                      const std::vector<std::vector<int>> walls[2]);

/// Every mesh edge on the body is a chord of a path as long as the flat edge, so never longer
/// than it: the largest excess of an edge of `piece` over its flat length, relative (a misplaced
/// vertex shows as one).
double longestStretch(const Piece& piece);

}  // namespace dform
