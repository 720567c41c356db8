// SPDX-License-Identifier: GPL-3.0-or-later
// The ruled engine end to end on a surface of rigid flat triangles: from each start shape, the
// rulings chosen and the 3D positions solved, giving a state whose every edge is as long as it
// is flat; the distinct states sorted by bending energy.
#pragma once

#include <string>
#include <vector>

#include "dform/ruled/ruled_search.h"
#include "dform/ruled/ruled_solve.h"
#include "dform/ruled/ruled_surface.h"

namespace dform::ruled {

/// Seams longer than this are not made by the ruled engine: its unknowns are the boundary points,
/// and a flip search over a few thousand chords takes longer than the paper model.
constexpr int kMaxRuledSeam = 1000;

/// A start: where each surface vertex is (#V by 3, mm), with the name reports give it.
struct RuledStart {
  std::string name;  ///< its name in reports ("paper", "convex hull", ...)
  Points3 X;         ///< each surface vertex's 3D position, #V by 3, mm
};

/// How solveRuled runs: its solve, its flip search and when two states are one.
struct RuledOptions {
  SolveOptions solve;       ///< the solve of the lengths (and of the bending energy where free)
  FlipSearchOptions flips;  ///< the flip search after each start's solve
  /// Two states whose seams lie within this fraction of the seam's bounding-box diagonal of each
  /// other (after the best rigid motion) are one state.
  double sameState = 1e-6;
};

/// A solved state: the surface and how it was reached.
struct RuledState {
  RuledSurface surface;          ///< the solved surface: triangulations and 3D positions
  std::string start;             ///< the name of the start it came from
  double bendingEnergy = 0;      ///< sum over chords of 3 l^2 / (A1 + A2) theta^2
  double maxLengthError = 0;     ///< relative, over every edge
  double stationarity = 0;       ///< of the bending energy at met lengths (0 on a closed surface)
  double largestFold = 0;        ///< largestFold(surface)
  int flips = 0;                 ///< flips made after the start's triangulation
  bool flipsStationary = false;  ///< no flip lowers the objective (bending, or convexity)
};

/// What solveRuled found: its distinct states and the starts that gave none.
struct RuledResult {
  std::vector<RuledState> states;  ///< distinct, least bending first
  /// Per start that gave no state: its name and why.
  std::vector<std::pair<std::string, std::string>> failures;
};

/// Solves `blank` (its triangulations as the caller chose them, its X ignored) from each start.
/// A closed surface (no free outline): the lengths met by Levenberg-Marquardt and the chords
/// folded backwards flipped (Lawson) until none is. With free outlines: the lengths followed
/// from the start's to the flat ones, the bending energy minimised where they hold, and flips
/// that lower it made until none does.
RuledResult solveRuled(const RuledSurface& blank, const std::vector<RuledStart>& starts,
                       const RuledOptions& options = {});

/// The largest |dihedral| of an interior chord that is no drawn crease (drawn creases are meant to
/// fold; the seam is where the pieces meet), radians.
double largestFold(const RuledSurface& surface);

}  // namespace dform::ruled
