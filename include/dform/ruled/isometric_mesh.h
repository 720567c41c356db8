// SPDX-License-Identifier: GPL-3.0-or-later
// A D-Form of rigid flat triangles whose vertices inside the pieces are unknowns in the flat as
// well as in 3D: a shape that stretches (the paper model's) made one that does not, for sheets
// where the boundary points alone cannot carry the fold (docs/ruled.md, "Vertices inside the
// pieces").
#pragma once

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform::ruled {

/// When isometricMesh stops: the edge-length error it aims for and its step budget.
struct IsometricMeshOptions {
  /// The largest relative edge-length error of the answer.
  double tolerance = 1e-12;
  /// Gauss-Newton steps at most (per stage).
  int maxSteps = 60;
  /// Stages of a continuation in the lengths: stage s of S aims for the start's 3D lengths
  /// blended into the flat ones by s / S (squared), each but the last solved to 1e-6. One stage
  /// aims for the flat lengths at once; more take smaller steps from a start far from them.
  int stages = 1;
};

/// What isometricMesh made: the exact shape and how far it moved from the start.
struct IsometricMesh {
  DForm model;                   ///< the answer: every edge as long in 3D as it is flat
  double lengthError = 0;        ///< largest relative edge-length error, over both pieces
  double chordMoveMm = 0;        ///< how far seam points moved along the outlines to equal chords
  int steps = 0;                 ///< Gauss-Newton steps taken
  int interiorVertices = 0;      ///< vertices whose flat places were unknowns
  double largestFlatMoveMm = 0;  ///< the farthest an interior vertex moved in its piece
  double bendingEnergy = 0;      ///< over interior edges: sum of 3 l^2 / (A1 + A2) theta^2
  double largestFold = 0;        ///< the largest |dihedral| of an interior edge, radians
};

/// `start` (a solved D-Form: both pieces meshed, seam partners in order, any stretch) made exact:
/// the seam points' 3D places, the free outlines' and every vertex inside a piece are unknowns in
/// 3D, and the vertices inside a piece in the flat too; the outline is the pattern and stays
/// (seam points move along it by the few micrometres that give both pieces equal chords). Each
/// step is the least-norm Gauss-Newton step on the edge lengths (so the answer is the exact
/// shape nearest the start), halved until the length residual falls. Fails (SolveFailed, naming
/// why) where the steps stop lowering the residual above `tolerance` (a vertex whose star cannot
/// lie flat among its neighbours), a flat triangle turns over, or a 3D one folds over its
/// neighbour (by more than 90 degrees).
Result<IsometricMesh> isometricMesh(const DForm& start, const IsometricMeshOptions& options = {});

}  // namespace dform::ruled
