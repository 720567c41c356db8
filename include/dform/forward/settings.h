// SPDX-License-Identifier: GPL-3.0-or-later
// A forward run's settings: one flat struct of the knobs a user sets (CLI flags, job files,
// Python keywords, the studio), each with its default. The solve (solveForward,
// solveMeshedCoarseToFine) reads its fields from the same struct.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "dform/core/constants.h"
#include "dform/model/inextensible.h"
#include "dform/model/local_global.h"
#include "dform/model/weights.h"
#include "dform/solver/solver.h"

namespace dform {

/// Where a piece's seam starts: an arc-length fraction from the outline's first point, or the
/// outline point nearest to a given point (mm, page frame, y up).
struct StartPoint {
  /// true: start at the outline point nearest to `point`; false: at `fraction`.
  bool nearestToPoint = false;
  double fraction = 0.0;  ///< arc-length fraction in [0, 1) from the outline's first point
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< mm, page frame, y up
};

/// Which boundary of a piece is zipped (paper section 6.4): its outline, as in a classic D-Form,
/// or its one hole. Two holes make an anti D-Form, an outline and a hole a demi D-Form; the other
/// boundary of an annulus-like piece stays free.
enum class JoinedBoundary { Outer, Inner };

/// Which model makes the 3D shape: the exact D-Form (Alexandrov's convex body of the glued
/// pieces, src/exact), the ruled engine (rigid flat triangles between the pieces' boundary points,
/// src/ruled, started from the paper model's shape), the paper's optimisation, or the general
/// engine (the paper's shape relaxed to a stationary point of a stiff sheet's bending and
/// stretching energy, model/inextensible.h); `Auto` takes the exact one wherever it applies (two
/// discs zipped along their outlines, no drawn creases, a convex glued metric), else the ruled
/// one where it finds a state that does not fold the sheet back on itself, else the paper's.
enum class ModelChoice { Auto, Exact, Ruled, Paper, General };

/// A model choice's name (job files, the command line, Python, the studio) and what it does.
struct ModelChoiceInfo {
  ModelChoice choice;  ///< the choice
  const char* name;    ///< its name ("auto", "exact", ...)
  const char* help;    ///< one line saying what it does, for --help and the docstrings
};

/// Every model choice in the order --help lists them: the settings table's choices of the model
/// (pipeline/settings.h). A new choice is a value of ModelChoice and its line here.
const std::vector<ModelChoiceInfo>& modelChoices();

/// A value of the join (which boundary of A, then of B, is zipped) as job files name it
/// ("outer,inner") and what it makes.
struct JoinChoiceInfo {
  std::string name;  ///< "outer,outer", "inner,inner", "outer,inner" or "inner,outer"
  JoinedBoundary a;  ///< piece A's zipped boundary
  JoinedBoundary b;  ///< piece B's zipped boundary
  const char* help;  ///< what the join makes (a classic, anti or demi D-Form)
};

/// Every join: the settings table's choices of the join.
const std::vector<JoinChoiceInfo>& joinChoices();

/// The range of ForwardSettings::interiorEdgeFactor: finer meshes cost more than they show, and
/// coarser ones leave the paper model too few triangles to bend.
constexpr double kMinInteriorEdgeFactor = 0.25, kMaxInteriorEdgeFactor = 8.0;

/// Everything a forward run needs besides the two pieces: the model, which boundaries are
/// zipped, the starting pair, the mesh and the solve.
struct ForwardSettings {
  ModelChoice model = ModelChoice::Auto;         ///< which model makes the 3D shape
  JoinedBoundary joinA = JoinedBoundary::Outer;  ///< piece A's zipped boundary
  JoinedBoundary joinB = JoinedBoundary::Outer;  ///< piece B's zipped boundary
  /// The starting pair (paper Definition 3), on the joined boundaries: A's point, then B's.
  StartPoint startA;
  StartPoint startB;                    ///< see startA
  int resolution = kDefaultResolution;  ///< seam vertices per piece
  bool flip = false;                    ///< zip B turned over (its mirror image) instead
  bool fitPerimeter = false;            ///< scale B uniformly to A's perimeter
  double perimeterTolerance = 0.005;    ///< largest |pA - pB| / max(pA, pB) accepted as equal
  double interiorEdgeFactor = 1.0;      ///< interior edge length / seam edge length, in
                                        ///< [kMinInteriorEdgeFactor, kMaxInteriorEdgeFactor]
  bool coarseToFine = true;             ///< start from solutions at 1/3, 1/9, ... of the resolution

  /// The paper's term weights (dimensionless; defaultWeights gives a job's starting ones).
  ForwardWeights weights;
  /// Local-global relaxation from the pillow guess before Levenberg-Marquardt (cheap steps that
  /// do most of the shape change); maxIterations = 0 starts LM from the pillow.
  LocalGlobalOptions relaxation;
  /// Levenberg-Marquardt polishes the relaxation's shape on the paper's exact objective, and stops
  /// once a step lowers it by less than 1e-3 of it: past that it only drifts along the sheet's
  /// soft bending modes (on the samples the figures agree to two digits with 1e-6, which takes
  /// 5-7 times longer on the non-convex pair and the anti and demi D-Forms).
  SolverOptions solver = [] {
    SolverOptions o;
    o.functionTolerance = 1e-3;
    return o;
  }();
  /// Continuation in the 3D smoothing weight (a factor, dimensionless): when w_3D is below
  /// continuationSmoothing, the relaxation runs at the stiffer
  /// min(continuationSmoothing, smoothingContinuation * w_3D) and Levenberg-Marquardt goes on from
  /// its shape at w_3D itself (relaxationSmoothing). The relaxation's steps crawl along the
  /// sheet's bending modes the more, the less it resists them, where LM's steps follow them in one
  /// or two factorisations. Values <= 1 turn it off; so does a solve by the relaxation alone.
  double smoothingContinuation = 6.0;
  /// The 3D smoothing weight the continuation stops at (dimensionless): the weight the job's kind
  /// of D-Form is tuned for; a forward run sets it from defaultWeights (0.01 for a classic
  /// D-Form, 0.001 for anti and demi D-Forms, forward/dform_from_shapes.h).
  double continuationSmoothing = ForwardWeights{}.smooth3d;
  /// Every drawn line (the seam, free boundaries, creases) keeps its flat position exactly, but
  /// for the seam's corners: there, the real D-Form creases (paper section 7) and the corner needs
  /// a little room, so only the boundary-fix term holds it, tightened by multiplier updates
  /// (augmented Lagrangian) in at most constraintRounds extra solves (a count) until each such
  /// vertex lies within outlineTolerance of its drawn position. 0 rounds keeps the paper's soft
  /// term there.
  int constraintRounds = 8;
  /// The seam corners' tolerance, relative to the perimeter (dimensionless): 0.12 mm on a 400 mm
  /// outline, about a laser's kerf.
  double outlineTolerance = 3e-4;
  InextensibleOptions inextensible;  ///< the general engine's (ModelChoice::General)
};

}  // namespace dform
