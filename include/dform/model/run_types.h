// SPDX-License-Identifier: GPL-3.0-or-later
// What a run of either kind reports besides its shape (the time each stage took, which model made
// it) and the hooks its caller passes in (progress, a request to stop).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "dform/solver/solver.h"

namespace dform {

/// Seconds spent in each stage.
struct Timings {
  double read = 0;   ///< reading the input files
  double mesh = 0;   ///< meshing the pieces
  double solve = 0;  ///< solving the shape
  double total = 0;  ///< the whole run, the above and what lies between
};

/// Folds of the exact D-Form through a piece that nobody drew: each is returned as one of the
/// piece's creases (Piece::creases) and listed here.
struct FoundCrease {
  int piece = 0;        ///< 0 for A, 1 for B
  int crease = 0;       ///< its index in that piece's creases
  double angleDeg = 0;  ///< its fold angle (0 = flat)
  double lengthMm = 0;  ///< its length in the flat piece, mm
};

/// A fold of the exact D-Form through a piece: a straight run of one of the body's edges between
/// two places on the piece's seam, with the angle between the two faces that meet along it.
/// Folds steeper than the found-crease angle are the piece's creases; gentler ones are listed too.
struct BodyFold {
  int piece = 0;           ///< 0 for A, 1 for B
  int from = 0;            ///< the mesh vertex (row of the piece's flat) at one end
  int to = 0;              ///< the mesh vertex at the other end
  int fromSeamPoint = -1;  ///< the seam point at `from`, -1 where it crosses a chord
  int toSeamPoint = -1;    ///< likewise at `to`
  int edgeFrom = 0;        ///< the seam point the body edge starts at (on the body)
  int edgeTo = 0;          ///< the seam point the body edge ends at
  double radians = 0;      ///< fold angle: between the two faces' normals (0 = flat)
  int crease = -1;         ///< its index in the piece's creases, -1 for a gentle fold
};

/// A state of the sheet the ruled engine found: the start it came from, its bending energy, the
/// energy the states are ordered by and its largest fold (of a chord that is no drawn crease).
struct RuledStateSummary {
  std::string start;          ///< the name of the start it came from
  double bendingEnergy = 0;   ///< its bending energy (dimensionless)
  double largestFoldDeg = 0;  ///< its largest fold of a chord that is no drawn crease, degrees
  /// The bending energy the states are ordered by, least first: bendingEnergy itself where the
  /// states are surfaces of boundary points; where they have vertices inside the pieces, their
  /// bending energy at the ranking resolution (docs/ruled.md)
  double rankingEnergy = 0;
};

/// Which model ran, and why the other did not.
struct ModelUsed {
  std::string name;         ///< "exact", "ruled", "paper" or "general"
  std::string reason;       ///< why this one: the exact model's conditions met, or which failed
  int conePoints = 0;       ///< exact: seam points that are vertices of the body
  int newtonSteps = 0;      ///< exact: steps of the deformation; general: Newton steps of the sheet
  double maxCurvature = 0;  ///< exact: largest |curvature| left at a cone point (radians)
  double chordMoveMm = 0;   ///< exact: the most a seam point moved to make paired chords equal
  bool doublyCovered = false;  ///< exact: the pieces fold flat onto each other
  /// exact, doubly covered: why ("congruent": the pieces are congruent to within the precision;
  /// "thin": the body glued came out too thin to be anything but flat; exact/exact_gluing.h)
  std::string pouch;
  double flatDeviationMm = 0;  ///< exact, doubly covered: farthest partner of B laid onto A, mm
  double thicknessMm = 0;      ///< exact, "thin": the glued body's thickness, mm
  double precisionMm = 0;      ///< exact: the precision the seam was glued to, mm
  /// general: relative first-order residual at the answer; ruled: of its bending energy where
  /// the lengths leave freedom (0 on a closed surface)
  double stationarity = 0;
  double stiffness = 0;  ///< general: stretching over bending stiffness (model/inextensible.h)
  std::vector<FoundCrease> creases;  ///< exact: the folds it found and made the pieces' creases
  /// exact and ruled: every fold through a piece (the paper model knows none)
  std::vector<BodyFold> folds;
  double bendingEnergy = 0;  ///< ruled: the answer's bending energy (dimensionless)
  double lengthError = 0;    ///< ruled: largest relative edge-length error of its surface
  int flips = 0;             ///< ruled: flips after the start's triangulation
  /// ruled: vertices inside the pieces whose flat places were unknowns too (0: the surface's
  /// vertices are the boundary points)
  int interiorVertices = 0;
  bool flipsStationary = false;           ///< ruled: no flip lowers its objective
  std::vector<RuledStateSummary> states;  ///< ruled: every distinct state, least bending first
};

/// A level of a coarse-to-fine solve begins: `level` of `levels` (from 1), with at most
/// `relaxationSteps` local-global steps and `solverIterations` Levenberg-Marquardt iterations.
struct LevelStart {
  int level = 1;             ///< this level, from 1 (coarsest)
  int levels = 1;            ///< how many levels the solve has
  int relaxationSteps = 0;   ///< the level's cap on local-global steps
  int solverIterations = 0;  ///< the level's cap on Levenberg-Marquardt iterations
};

/// Hooks for a caller that shows progress or can be interrupted.
struct RunHooks {
  /// Each level of the paper model's coarse-to-fine solve, forward or inverse, before its first
  /// iteration.
  std::function<void(const LevelStart&)> onLevel;
  /// Each iteration of a stage ("relaxing": local-global steps, "solving": Levenberg-Marquardt).
  std::function<void(const char* stage, const IterationSummary&)> onIteration;
  const std::atomic<bool>* interrupted = nullptr;  ///< checked between iterations
};

}  // namespace dform
