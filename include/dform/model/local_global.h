// SPDX-License-Identifier: GPL-3.0-or-later
// A fast approximate minimiser of the D-Form objective, used to start Levenberg-Marquardt close to
// its minimum: local-global iterations (projective dynamics, Bouaziz et al. 2014) with Anderson
// acceleration (Peng et al. 2018). The isometry term is replaced by its projective form: each
// edge's 3D and flat vectors are projected onto a common length, then one prefactorised linear
// solve moves all vertices. Every other term of the objective is quadratic and enters as it is.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "dform/solver/problem.h"
#include "dform/solver/solver.h"

namespace dform {

/// Edges whose 3D length should equal their flat length: offsets of the two ends' 3D positions
/// (3 values each) and flat positions (2 values each) in the unknown vector, and a weight.
struct EdgeLengthPairs {
  std::vector<std::array<int, 2>> x;  ///< each edge's ends: offsets of their 3D positions
  std::vector<std::array<int, 2>> u;  ///< each edge's ends: offsets of their flat positions
  std::vector<double> weight;         ///< each edge's weight in the energy
  /// Unknowns per vertex: offsets are vertex * stride + coordinate. No term may couple two
  /// different coordinates (the local-global step solves each coordinate on its own).
  int stride = 5;
};

/// How relaxLocalGlobal runs: its budget, when it stops, its acceleration and its callback.
struct LocalGlobalOptions {
  /// 0 switches the relaxation off. Its steps cost a few back-substitutions each, so it may run
  /// long: a large shape change (an anti D-Form's brims swinging out) is far cheaper here than in
  /// Levenberg-Marquardt, whose steps the change's curvature keeps short. Stopping below 1e-7
  /// runs it close to the minimum, so that Levenberg-Marquardt mostly polishes: stopped at 1e-6,
  /// the demi sample leaves LM 8 iterations and 5 factorisations (14 s) where 1e-7 leaves it 1
  /// and 1 (4 s).
  int maxIterations = 2000;
  /// Stop where a plain local-global step would lower the energy by less than this fraction of
  /// it. That gain is measured at the current point (the global step's own decrease, a lower
  /// bound on the whole step's), not read off the step taken: an accelerated step's decrease
  /// depends on how far Anderson's extrapolation happened to jump, and stopping on it would end
  /// runs wherever one jump fell short.
  double relativeTolerance = 1e-7;
  int andersonDepth = 6;  ///< past iterates used by Anderson acceleration (0: plain)
  /// Where an accelerated step is refused, the plain step is tried 2, 4, ... 2^k times as long
  /// while the energy keeps falling. On a slow drift along a soft mode (an anti D-Form's brims)
  /// Anderson's secants are nearly parallel and every extrapolation is refused; the drift is
  /// then covered up to 2^k times faster per linear solve, at one energy evaluation per try.
  int plainStepExtensions = 3;
  /// Called after every iteration (iteration, cost = energy, costChange, cumulativeSeconds set);
  /// return false to stop the relaxation (a Ctrl-C, say).
  std::function<bool(const IterationSummary&)> callback;
};

/// How the local-global relaxation went.
struct LocalGlobalSummary {
  int iterations = 0;        ///< local-global steps taken
  int andersonRejected = 0;  ///< accelerated steps that did not lower the energy and were refused
  double initialEnergy = 0;  ///< the edge-length energy at the start (solver units)
  double finalEnergy = 0;    ///< the energy where it stopped
  double seconds = 0;        ///< wall time, seconds
  bool stopped = false;      ///< the callback asked to stop

  /// Appends a later relaxation of the same problem (after a multiplier update, say).
  void append(const LocalGlobalSummary& later) {
    iterations += later.iterations;
    andersonRejected += later.andersonRejected;
    finalEnergy = later.finalEnergy;
    seconds += later.seconds;
    stopped = stopped || later.stopped;
  }
};

/// Coordinate blocks of at least this many vertices are factorised by dform's supernodal Cholesky
/// (solver/supernodal_cholesky.h), smaller ones by CHOLMOD's simplicial factor; both round the
/// same on every machine. The simplicial factor does scalar work: at 97k vertices its two
/// factorisations take 5.9 and 4.3 s, the supernodal one's 1.0 and 0.7 s (plus 1.4 s of analysis),
/// while on small meshes, whose supernodes are mostly single columns, the simplicial factor
/// solves 2.5 times faster. Measured crossover at about 10k vertices (docs/solver-design.md).
constexpr int kSupernodalRelaxationVertices = 10000;

/// Minimises sum_t w_t ||M_t x - b_t||^2 + sum_e w_e (|x_a - x_b| - |u_a - u_b|)^2 / 2 over x by
/// local-global steps. `quadratic` lists the weighted linear terms. The linear system (one
/// factorisation per coordinate group) is set up once, at construction; relax() reads the terms'
/// targets b_t afresh, so it may be called again after a multiplier update moved one, and reuses
/// the factorisations. The terms and edges must outlive the object.
class LocalGlobalRelaxation {
 public:
  /// `held` lists unknowns kept at their values in x0 (rows of the system replaced by x_i = x0_i);
  /// held unknowns of one coordinate group must belong to the same vertices (e.g. u and v both).
  /// Blocks of `supernodalFrom` vertices or more are factorised supernodally.
  LocalGlobalRelaxation(std::vector<std::pair<double, const LinearResidual*>> quadratic,
                        const EdgeLengthPairs& edges, const Eigen::VectorXd& x0,
                        const std::vector<int>& held = {},
                        int supernodalFrom = kSupernodalRelaxationVertices);
  ~LocalGlobalRelaxation();
  LocalGlobalRelaxation(const LocalGlobalRelaxation&) = delete;
  LocalGlobalRelaxation& operator=(const LocalGlobalRelaxation&) = delete;

  /// Relaxes x in place; summary.iterations is 0 when the system could not be factorised.
  LocalGlobalSummary relax(const LocalGlobalOptions& options, Eigen::VectorXd& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dform
