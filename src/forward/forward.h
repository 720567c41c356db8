// Forward modelling (paper section 4): two triangulated flat pieces in, the D-Form they make out.
#pragma once

#include "core/types.h"
#include "model/local_global.h"
#include "model/weights.h"
#include "solver/solver.h"

namespace dform {

struct ForwardOptions {
  ForwardWeights weights;
  /// Local-global relaxation from the pillow guess before Levenberg-Marquardt (cheap steps that
  /// do most of the shape change); maxIterations = 0 starts LM from the pillow.
  LocalGlobalOptions relaxation;
  /// Levenberg-Marquardt polishes the relaxation's shape on the paper's exact objective, and stops
  /// once a step lowers it by less than 1e-3 of it: past that it only drifts along the sheet's
  /// soft bending modes (measured on the samples: the figures agree to two digits with 1e-6, which
  /// takes 5-7 times longer on the non-convex pair and the anti and demi D-Forms; e.g. non-convex
  /// 0.53 s against 3.3 s of CPU, L_error 0.124 % against 0.122 %).
  SolverOptions solver = [] {
    SolverOptions o;
    o.functionTolerance = 1e-3;
    return o;
  }();
  /// Continuation in the 3D smoothing weight: when w_3D is below continuationSmoothing (the
  /// weight the job's kind of D-Form is tuned for: 0.01 for a classic one, 0.001 for anti and demi
  /// D-Forms, forward/dform_from_shapes.h), the relaxation runs at the stiffer
  /// min(continuationSmoothing, smoothingContinuation * w_3D) and Levenberg-Marquardt goes on from
  /// its shape at w_3D itself (relaxationSmoothing). The relaxation's steps crawl along the
  /// sheet's bending modes the more, the less it resists them (1031 steps at w_3D = 0.0003 on the
  /// ellipses at 1k vertices, 165 at 0.01), where LM's steps follow them in one or two
  /// factorisations. Values <= 1 turn it off; so does a solve by the relaxation alone.
  double smoothingContinuation = 6.0;
  double continuationSmoothing = ForwardWeights{}.smooth3d;
  /// Every drawn line (the seam, free boundaries, creases) keeps its flat position exactly, but
  /// for the seam's corners: there, the real D-Form creases (paper section 7) and the corner needs
  /// a little room, so only the boundary-fix term holds it, tightened by multiplier updates
  /// (augmented Lagrangian) in at most constraintRounds extra solves until each such vertex lies
  /// within outlineTolerance of its drawn position, relative to the perimeter: 0.12 mm on a 400 mm
  /// outline, about a laser's kerf. 0 rounds keeps the paper's soft term there.
  int constraintRounds = 8;
  double outlineTolerance = 3e-4;
};

struct ForwardResult {
  DForm model;                    ///< solved pieces in mm
  LocalGlobalSummary relaxation;  ///< the local-global start
  SolverSummary summary;          ///< how the LM solve went; costs are in the normalised unit
  int constraintRounds = 0;       ///< multiplier updates used to meet the constraints
  double unitMm = 1.0;            ///< the solver's length unit in mm (mean seam edge length)
};

/// The 3D smoothing weight the relaxation runs at for a solve at `smooth3d` (see
/// ForwardOptions::smoothingContinuation).
double relaxationSmoothing(double smooth3d, const ForwardOptions& options);

/// Pillow-shaped starting shape: both pieces mapped harmonically onto the average of their seam
/// outlines (A as drawn, B turned over) and inflated, A up and B down, by the heights that best
/// preserve their edge lengths. The seam starts planar and closed. Inputs and output in mm.
DForm pillowInitialGuess(const Piece& a, const Piece& b);

/// Solves the forward problem. `a` and `b` carry the flat meshes (flat, F) in mm and their seams
/// (a.seam counter-clockwise, b.seam clockwise, a.seam[i] meeting b.seam[i]). When both carry a
/// shape (one 3D row per flat vertex, for example a coarser solution transferred), the solve starts
/// from it; otherwise from pillowInitialGuess.
ForwardResult solveForward(const Piece& a, const Piece& b, const ForwardOptions& options);

}  // namespace dform
