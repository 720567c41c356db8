// SPDX-License-Identifier: GPL-3.0-or-later
// The general engine: the D-Form as a thin sheet that resists bending and, far more, stretching.
// Its 3D shape is a stationary point of
//
//   E(x) = E_bend(x) + k E_stretch(x),
//
// where E_bend is the quadratic bending energy of inextensible surfaces (Bergou, Wardetzky,
// Harmon, Zorin, Grinspun 2006) on each piece's flat rest state, summed over the interior edges
// of each piece that are not drawn creases (the seam and the creases are free hinges), and
// E_stretch = 1/2 sum_e a_e eps_e^2 with eps_e = (|x_i - x_j|^2 - L_e^2) / (2 L_e^2) the Green
// strain of every edge of both pieces against its drawn length L_e, a_e a third of the edge's
// adjacent flat area. Lengths are taken in the unit sqrt(area of both pieces), so k is
// scale-free: k = 12 / (t / unit)^2 for an isotropic sheet of thickness t, about 1e7 for 0.3 mm
// card on a 250 mm part. The flat pieces are the ones given (as cut); the seam is closed exactly
// (B's seam vertices are A's). Solved by Newton's method with a fixed sparsity pattern, each step
// one factorisation of the exact Hessian (dform's supernodal Cholesky: no BLAS, no threads),
// shifted by a multiple of the identity until it factorises where compression makes it
// indefinite, continuation in k from stiffness / 10^continuation to stiffness, and a
// backtracking line search on E. It stops on the relative first-order residual
// |grad E| / (|grad E_bend| + |k grad E_stretch|), which is scale-free.
#pragma once

#include <string>

#include "dform/core/types.h"

namespace dform {

/// How solveInextensible runs: the sheet's stiffness, its continuation and when it stops.
struct InextensibleOptions {
  double stiffness = 1e9;  ///< k: stretching over bending, unit sqrt(area) (see above)
  int continuation = 1;    ///< k starts at stiffness / 10^continuation, x10 per stage
  double tolerance =
      1e-9;  ///< relative stationarity |grad E| / (|grad E_bend| + |k grad E_stretch|) to stop on
  int maxSteps = 200;  ///< Newton steps over all stages
};

/// How solveInextensible's Newton solve went.
struct InextensibleSummary {
  bool converged = false;       ///< the last stage reached the tolerance
  int steps = 0;                ///< Newton steps over all stages
  int factorisations = 0;       ///< Cholesky factorisations tried, those that failed included
  double stationarity = 0;      ///< |grad E| / (|grad E_bend| + |k grad E_stretch|) at the answer
  double bendingEnergy = 0;     ///< E_bend at the answer (dimensionless)
  double stretchingEnergy = 0;  ///< k E_stretch at the answer (unit sqrt(area))
  double seconds = 0;           ///< wall time of the solve, seconds
  std::string message;          ///< why it stopped
};

/// The general engine's answer: the relaxed D-Form and how its solve went.
struct InextensibleResult {
  DForm model;                  ///< the start's flat pieces, their 3D shape solved (mm)
  InextensibleSummary summary;  ///< how the solve went
};

/// The sheet's energy E_bend + k E_stretch at `model`'s 3D shape (dimensionless; what
/// solveInextensible makes stationary).
double sheetEnergy(const DForm& model, double stiffness);

/// Relaxes `start` (both pieces' flat meshes and a 3D shape, a.seam[i] and b.seam[i] at the same
/// point) to a stationary point of the sheet's energy.
InextensibleResult solveInextensible(const DForm& start, const InextensibleOptions& options);

}  // namespace dform
