// SPDX-License-Identifier: GPL-3.0-or-later
// Choosing the rulings: which chords of the pieces are the surface's edges. Flips of a chord
// (the other diagonal of its two triangles) change the choice; each step below is deterministic
// (candidates in a fixed order, ties by index).
#pragma once

#include <string>
#include <vector>

#include "dform/ruled/ruled_solve.h"
#include "dform/ruled/ruled_surface.h"

namespace dform::ruled {

/// Flips until no chord joins two vertices another edge joins (a chord of both pieces, or one
/// beside a seam chord): such a surface has two lengths for one distance. False when a doubled
/// chord cannot be flipped.
bool removeDoubleEdges(RuledSurface& surface);

/// With the 3D positions held, flips the chord folded most backwards (negative dihedral) while
/// one can be flipped, in pieces whose `use` entry is true: the convex triangulation of the
/// positions where there is one (for points of a convex body, its faces). Returns the flips.
int flipToConvexHeld(RuledSurface& surface, const std::array<bool, 2>& use = {true, true});

/// The change of the bending energy if the chord of halfedge h of piece p were flipped with the
/// positions held: its own hinge and the four sides of its quadrilateral, whose faces change
/// (the new chord's length then differs from its flat one; the estimate a flip search ranks by).
double flipBendingChange(const RuledSurface& surface, int piece, int h);

/// How a flip search runs: its budget of flips and candidates, and the solve after each flip.
struct FlipSearchOptions {
  int maxFlips = 2000;  ///< the most flips made before the search stops
  /// Candidates tried per step, best estimate first (the estimate is the energy with the
  /// positions held; each tried candidate is solved again).
  int candidatesPerStep = 8;
  SolveOptions solve;  ///< the solve after each flip tried
};

/// How a flip search went.
struct FlipSearchSummary {
  int flips = 0;            ///< flips made
  int tried = 0;            ///< candidate flips solved again
  bool stationary = false;  ///< no flip lowers the objective
  std::string message;      ///< why it stopped
};

/// Lawson's flips to convexity on a closed surface: the chord folded most backwards is flipped
/// and the lengths met again (Levenberg-Marquardt), until no chord is folded backwards or none
/// that is can be flipped.
FlipSearchSummary flipToConvex(RuledSurface& surface, const FlipSearchOptions& options = {});

/// Flips that lower the bending energy at met lengths: each step tries the chords whose flip
/// lowers the held energy most, meets the lengths and minimises the bending again, and keeps the
/// first that ends lower; until none does.
FlipSearchSummary flipToLessBending(RuledSurface& surface, const FlipSearchOptions& options = {});

/// Continuation from the lengths the surface's current positions give its edges to their flat
/// lengths: each step meets interpolated lengths by Newton steps from the last state. Where a
/// chord's dihedral crosses zero on the way and `flipAtZero` is set, it is flipped (if it can
/// be) and the new chord continues from its length then. False when the path cannot be followed
/// (`t` tells how far it came).
bool followLengths(RuledSurface& surface, bool flipAtZero, double& t, int& flips);

}  // namespace dform::ruled
