// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/ruled/ruled_solve.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

#include "dform/core/pattern_ldlt.h"

namespace dform::ruled {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;
using SparseMatrix = Eigen::SparseMatrix<double>;

// A surface in the solve's units: lengths over the mean edge length, so that tolerances and
// regularisations are relative.
struct Scaled {
  std::vector<SurfaceEdge> edges;
  Eigen::VectorXd lengths;
  double scale = 1;
  Points3 Y;

  explicit Scaled(const RuledSurface& surface, const std::vector<double>* given = nullptr)
      : edges(surface.edges()) {
    lengths.resize(Eigen::Index(edges.size()));
    for (std::size_t e = 0; e < edges.size(); ++e)
      lengths[Eigen::Index(e)] = given ? (*given)[e] : edges[e].length;
    scale = lengths.mean();
    lengths /= scale;
    Y = surface.X / scale;
  }
  Eigen::Index unknowns() const { return 3 * Y.rows(); }
  Eigen::Index rows() const { return lengths.size(); }

  Eigen::VectorXd residual(const Points3& at) const {
    Eigen::VectorXd r(rows());
    for (Eigen::Index e = 0; e < rows(); ++e) {
      const SurfaceEdge& edge = edges[std::size_t(e)];
      r[e] = (at.row(edge.i) - at.row(edge.j)).norm() - lengths[e];
    }
    return r;
  }
  SparseMatrix jacobian(const Points3& at) const {
    Triplets entries;
    entries.reserve(std::size_t(6 * rows()));
    for (Eigen::Index e = 0; e < rows(); ++e) {
      const SurfaceEdge& edge = edges[std::size_t(e)];
      const Eigen::Vector3d d = at.row(edge.i) - at.row(edge.j);
      const Eigen::Vector3d u = d / d.norm();
      for (int a = 0; a < 3; ++a) {
        entries.emplace_back(e, 3 * edge.i + a, u[a]);
        entries.emplace_back(e, 3 * edge.j + a, -u[a]);
      }
    }
    SparseMatrix J(rows(), unknowns());
    J.setFromTriplets(entries.begin(), entries.end());
    return J;
  }
  // The bending energy, and its gradient and Gauss-Newton Hessian when asked.
  double bending(const Points3& at, Eigen::VectorXd* gradient = nullptr,
                 SparseMatrix* hessian = nullptr) const {
    double energy = 0.0;
    if (gradient) *gradient = Eigen::VectorXd::Zero(unknowns());
    Triplets entries;
    for (const SurfaceEdge& edge : edges) {
      if (edge.kind != EdgeKind::Chord) continue;
      Eigen::Matrix<double, 4, 3> g;
      const double theta = dihedral(at.row(edge.i), at.row(edge.j), at.row(edge.k), at.row(edge.l),
                                    gradient ? &g : nullptr);
      energy += edge.weight * theta * theta;
      if (!gradient) continue;
      const int v[4] = {edge.i, edge.j, edge.k, edge.l};
      for (int p = 0; p < 4; ++p) {
        gradient->segment<3>(3 * v[p]) += 2.0 * edge.weight * theta * g.row(p).transpose();
        if (hessian)
          for (int q = 0; q < 4; ++q)
            for (int a = 0; a < 3; ++a)
              for (int b = 0; b < 3; ++b)
                entries.emplace_back(3 * v[p] + a, 3 * v[q] + b,
                                     2.0 * edge.weight * g(p, a) * g(q, b));
      }
    }
    if (hessian) {
      hessian->resize(unknowns(), unknowns());
      hessian->setFromTriplets(entries.begin(), entries.end());
    }
    return energy;
  }
};

Points3 moved(const Points3& Y, const Eigen::VectorXd& step, double t) {
  Points3 out = Y;
  for (Eigen::Index v = 0; v < Y.rows(); ++v) out.row(v) += t * step.segment<3>(3 * v).transpose();
  return out;
}

// The least-squares multipliers lambda of g + J^T lambda = 0, and |g + J^T lambda| over |g| +
// `floor` (the stationarity: 0 at a constrained stationary point; `floor` is the gradient below
// which the energy's own rounding decides its direction, so that a flat sheet, whose gradient
// is rounding, counts as stationary).
double stationarity(const Eigen::VectorXd& g, const SparseMatrix& J, double floor,
                    PatternLDLT& ldlt, Eigen::VectorXd* multipliers = nullptr) {
  SparseMatrix JJt = J * J.transpose();
  // Flat hinges make J J^T singular; 1e-14 of its unit diagonal only picks one solution.
  for (Eigen::Index k = 0; k < JJt.rows(); ++k) JJt.coeffRef(k, k) += 1e-14;
  ldlt.factorize(JJt);
  const Eigen::VectorXd lambda = ldlt.solver().solve(-(J * g));
  if (multipliers) *multipliers = lambda;
  const double size = g.lpNorm<Eigen::Infinity>() + floor;
  if (!(size > 0.0)) return 0.0;
  return (g + J.transpose() * lambda).lpNorm<Eigen::Infinity>() / size;
}

// sum_e lambda_e d^2 r_e / dx^2 for r_e = |x_i - x_j| - l_e: (I - u u^T) / |x_i - x_j| in the
// blocks (i, i) and (j, j), minus it in (i, j) and (j, i).
void addConstraintCurvature(const Scaled& s, const Points3& Y, const Eigen::VectorXd& lambda,
                            Triplets& entries) {
  for (Eigen::Index e = 0; e < s.rows(); ++e) {
    const SurfaceEdge& edge = s.edges[std::size_t(e)];
    const Eigen::Vector3d d = Y.row(edge.i) - Y.row(edge.j);
    const double length = d.norm();
    const Eigen::Vector3d u = d / length;
    const Eigen::Matrix3d A =
        lambda[e] * (Eigen::Matrix3d::Identity() - u * u.transpose()) / length;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        entries.emplace_back(3 * edge.i + a, 3 * edge.i + b, A(a, b));
        entries.emplace_back(3 * edge.j + a, 3 * edge.j + b, A(a, b));
        entries.emplace_back(3 * edge.i + a, 3 * edge.j + b, -A(a, b));
        entries.emplace_back(3 * edge.j + a, 3 * edge.i + b, -A(a, b));
      }
  }
}

// Levenberg-Marquardt in the solve's units, factorising J J^T + mu I with `ldlt`; returns the
// iterations taken.
int levenbergMarquardt(const Scaled& s, Points3& Y, const SolveOptions& options, PatternLDLT& ldlt,
                       bool& converged, std::string& message) {
  Eigen::VectorXd r = s.residual(Y);
  double cost = 0.5 * r.squaredNorm();
  // Nielsen's damping update (Madsen, Nielsen and Tingleff, "Methods for non-linear least
  // squares problems", 2004), starting at 1e-3 of J J^T's diagonal (whose entries are 2: each row
  // of J holds two unit vectors).
  double mu = options.initialDamping, growth = 2.0;
  int iteration = 0;
  for (; iteration < options.maxIterations; ++iteration) {
    if (r.lpNorm<Eigen::Infinity>() <= options.lengthTolerance) {
      converged = true;
      return iteration;
    }
    const SparseMatrix J = s.jacobian(Y);
    SparseMatrix A = J * J.transpose();
    for (Eigen::Index k = 0; k < A.rows(); ++k) A.coeffRef(k, k) += mu;
    if (!ldlt.factorize(A)) {
      message = "the lengths' normal equations could not be factorised";
      return iteration;
    }
    const Eigen::VectorXd dx = -(J.transpose() * ldlt.solver().solve(r));
    const Points3 trial = moved(Y, dx, 1.0);
    const Eigen::VectorXd rTrial = s.residual(trial);
    const double costTrial = 0.5 * rTrial.squaredNorm();
    const double predicted = cost - 0.5 * (r + J * dx).squaredNorm();
    const double rho = predicted > 0.0 ? (cost - costTrial) / predicted : -1.0;
    if (rho > 0.0) {
      Y = trial;
      r = rTrial;
      cost = costTrial;
      mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      // Flat hinges make J J^T singular: mu stays above rounding of its unit diagonal.
      mu = std::max(mu, 1e-12);
      growth = 2.0;
    } else {
      mu *= growth;
      growth *= 2.0;
      // The damped step is then shorter than rounding of the positions allows to judge.
      if (mu > 1e16) {
        message = "the lengths cannot all be met from here (a least-squares state)";
        return iteration;
      }
    }
  }
  message = "the step limit was reached";
  return iteration;
}

}  // namespace

SolveSummary solveLengths(RuledSurface& surface, const SolveOptions& options,
                          const std::vector<double>* lengths) {
  SolveSummary summary;
  Scaled s(surface, lengths);
  Points3 Y = s.Y;
  PatternLDLT ldlt;
  summary.iterations = levenbergMarquardt(s, Y, options, ldlt, summary.converged, summary.message);
  surface.X = Y * s.scale;
  summary.maxLengthError = (s.residual(Y).array().abs() / s.lengths.array()).maxCoeff();
  summary.bendingEnergy = s.bending(Y);
  return summary;
}

SolveSummary minimiseBending(RuledSurface& surface, const SolveOptions& options,
                             const std::vector<double>* lengths) {
  SolveSummary summary;
  Scaled s(surface, lengths);
  Points3 Y = s.Y;
  const Eigen::Index n = s.unknowns(), m = s.rows();
  // The Lagrangian's Hessian: the energy's Gauss-Newton Hessian and the lengths' curvature
  // weighted by the multipliers (the sheet's isometric bending curves the set where the lengths
  // hold). delta is added where needed to make it positive on the steps that keep the lengths
  // (inertia correction: the KKT matrix then has exactly m negative pivots) and damps the step
  // like Levenberg-Marquardt's mu; gamma makes the KKT matrix quasi-definite where flat regions
  // make the lengths' Jacobian rank-deficient, and iterative refinement takes its relaxation of
  // the constraint rows out again.
  double delta = 0.0;
  const double gamma = 1e-10;
  Eigen::VectorXd g, lambda;
  SparseMatrix H;
  double energy = s.bending(Y, &g, &H);
  // A hinge folded by theta pulls with about 2 w theta (the solve's lengths are of order 1): the
  // gradient every hinge folded by 1e-8 rad would give. A residual force under 1e-9 of it (the
  // stationarity tolerance) is rounding of the forces, so a flat sheet counts as stationary.
  double gradientFloor = 0.0;
  for (const SurfaceEdge& e : s.edges) gradientFloor += 2e-8 * e.weight;
  SolveOptions restore = options;
  restore.maxIterations = 20;
  restore.initialDamping = 1e-10;
  // J J^T (the multipliers, the steps back onto the lengths) and the KKT matrix each keep one
  // pattern through the run.
  PatternLDLT lengthsLDLT, kkt;
  for (summary.iterations = 0; summary.iterations < options.maxIterations; ++summary.iterations) {
    const SparseMatrix J = s.jacobian(Y);
    summary.stationarity = stationarity(g, J, gradientFloor, lengthsLDLT, &lambda);
    // Stationary, or flat: every fold below 1e-10 rad leaves nothing to lower (the energy's
    // minimum, 0, to rounding of the angles).
    const bool flat = energy <= 1e-20 * gradientFloor / 2e-8;
    if ((summary.stationarity <= options.stationarityTolerance || flat) &&
        s.residual(Y).lpNorm<Eigen::Infinity>() <= options.lengthTolerance) {
      summary.converged = true;
      break;
    }
    Triplets base;
    for (int k = 0; k < H.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(H, k); it; ++it)
        base.emplace_back(it.row(), it.col(), it.value());
    addConstraintCurvature(s, Y, lambda, base);
    for (int k = 0; k < J.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(J, k); it; ++it) {
        base.emplace_back(n + it.row(), it.col(), it.value());
        base.emplace_back(it.col(), n + it.row(), it.value());
      }
    SparseMatrix exactRows(n + m, n + m);
    bool factorised = false;
    for (int attempt = 0; attempt < 40 && !factorised; ++attempt) {
      Triplets entries = base;
      for (Eigen::Index k = 0; k < n; ++k) entries.emplace_back(k, k, delta + 1e-12);
      exactRows.setFromTriplets(entries.begin(), entries.end());
      for (Eigen::Index e = 0; e < m; ++e) entries.emplace_back(n + e, n + e, -gamma);
      SparseMatrix K(n + m, n + m);
      K.setFromTriplets(entries.begin(), entries.end());
      factorised = kkt.factorize(K) && (kkt.solver().vectorD().array() < 0.0).count() == m;
      if (!factorised) delta = std::max(1e-8, 10.0 * delta);
    }
    if (!factorised) {
      summary.message = "the KKT system could not be factorised";
      break;
    }
    Eigen::VectorXd rhs(n + m);
    rhs << -g, -s.residual(Y);
    Eigen::VectorXd step = kkt.solver().solve(rhs);
    for (int refinement = 0; refinement < 3; ++refinement)
      step += kkt.solver().solve(rhs - exactRows * step);
    // The step along the constraints, then back onto them (the lengths are met to the
    // tolerance at every accepted state): a lower energy there is accepted.
    bool accepted = false;
    for (double t = 1.0; t > 1e-10 && !accepted; t *= 0.5) {
      Points3 trial = moved(Y, step.head(n), t);
      bool feasible = false;
      std::string unused;
      levenbergMarquardt(s, trial, restore, lengthsLDLT, feasible, unused);
      if (!feasible) continue;
      const double trialEnergy = s.bending(trial);
      if (trialEnergy < energy) {
        Y = trial;
        energy = s.bending(Y, &g, &H);
        accepted = true;
        delta = t == 1.0 ? delta / 3.0 : std::max(1e-8, 2.0 * delta);
      }
    }
    if (!accepted) {
      delta = std::max(1e-8, 10.0 * delta);
      if (delta > 1e8) {
        // No lower energy within rounding of the positions: stationary as far as it can tell.
        summary.message = "no step lowers the bending energy";
        break;
      }
    }
  }
  surface.X = Y * s.scale;
  summary.maxLengthError = (s.residual(Y).array().abs() / s.lengths.array()).maxCoeff();
  summary.bendingEnergy = energy;
  if (!summary.converged && summary.message.empty()) summary.message = "the step limit was reached";
  return summary;
}

}  // namespace dform::ruled
