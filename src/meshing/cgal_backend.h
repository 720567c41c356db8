// SPDX-License-Identifier: GPL-3.0-or-later
// The CGAL side of the meshing module. cgal_meshing.cpp is the one translation unit that includes
// CGAL (slow to compile, leaks -frounding-math); the rest of the module calls it through this
// std/Eigen-only header. Not part of the public API.
#pragma once

#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform::meshing_detail {

/// A closed constraint loop made of the consecutive rows first .. first+count-1 of a point set.
struct Loop {
  int first = 0;
  int count = 0;
};

/// Constrained Delaunay triangulation of all rows of P (#P by 2) with every loop edge and every
/// edge of the open `chains` (row indices, consecutive pairs joined) as a constraint. Returns the
/// counter-clockwise triangles (indices into P) that lie inside an odd number of loops (chains
/// do not bound regions), or InputInvalid when points coincide or constraints cross or touch away
/// from a shared end (a constraint edge would be split), so every constraint edge is a triangle
/// edge in the result.
Result<Faces> constrainedDelaunay(const Points2& P, const std::vector<Loop>& loops,
                                  const std::vector<std::vector<int>>& chains = {});

}  // namespace dform::meshing_detail
