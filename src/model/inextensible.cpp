// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/inextensible.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "dform/solver/supernodal_cholesky.h"

namespace dform {

namespace {

using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

// The sheet's unknowns and the constant parts of its energy. Unknown vertex v has its 3D position
// at 3v .. 3v + 2 of x; A's vertices come first, then B's that are not on the seam.
struct Sheet {
  int vertices = 0;
  std::array<std::vector<int>, 2> unknownOf;  ///< per piece: its vertex -> unknown vertex
  std::vector<std::array<int, 2>> edges;      ///< unknown vertices of each stretched edge
  std::vector<double> restSquared, area;      ///< L_e^2 and a_e of each, unit sqrt(area)
  std::vector<Triplet> bendingHessian;        ///< the constant Hessian of E_bend, 3n by 3n
  Sparse bending;                             ///< the same as a matrix
  double unit = 1.0;                          ///< mm per unit length
};

double triangleArea(const Points2& p, int a, int b, int c) {
  const Eigen::Vector2d u = p.row(b) - p.row(a), v = p.row(c) - p.row(a);
  return 0.5 * std::abs(u.x() * v.y() - u.y() * v.x());
}

// Bergou et al.'s hinge stencil on the flat rest state: weights w of the edge's ends p0, p1 and
// the opposite vertices p2, p3 with sum w_i = 0 and sum w_i p_i = 0 (a flat or rigidly moved
// hinge has no energy) and w2 = -l / h2, w3 = -l / h3, so that |sum w_i x_i| = l theta for a
// hinge folded by a small angle theta.
std::array<double, 4> hingeWeights(const std::array<Eigen::Vector2d, 4>& p) {
  const Eigen::Vector2d e = p[1] - p[0];
  const double l = e.norm();
  const Eigen::Vector2d along = e / l;
  const Eigen::Vector2d across(-along.y(), along.x());
  std::array<double, 4> w{};
  double sum = 0, moment = 0;
  for (int k = 2; k < 4; ++k) {
    const double h = (p[k] - p[0]).dot(across);  // signed: the two opposite vertices lie apart
    w[k] = -l / std::abs(h);
    sum += w[k];
    moment += w[k] * (p[k] - p[0]).dot(along) / l;
  }
  w[1] = -moment;
  w[0] = -(sum + w[1]);
  return w;
}

void addPiece(const Piece& piece, int p, double unit, Sheet& sheet,
              std::vector<Triplet>& bendingScalar) {
  const Points2 flat = piece.flat / unit;
  std::set<std::pair<int, int>> creaseEdges;
  for (const std::vector<int>& line : piece.creases)
    for (std::size_t k = 0; k + 1 < line.size(); ++k)
      creaseEdges.insert(std::minmax(line[k], line[k + 1]));
  // Each edge's adjacent faces' opposite vertices and its share of their area.
  std::map<std::pair<int, int>, std::pair<std::vector<int>, double>> edgeFaces;
  for (Eigen::Index f = 0; f < piece.F.rows(); ++f) {
    const double a = triangleArea(flat, piece.F(f, 0), piece.F(f, 1), piece.F(f, 2));
    for (int c = 0; c < 3; ++c) {
      auto& entry = edgeFaces[std::minmax(piece.F(f, c), piece.F(f, (c + 1) % 3))];
      entry.first.push_back(piece.F(f, (c + 2) % 3));
      entry.second += a / 3.0;
    }
  }
  const std::vector<int>& to = sheet.unknownOf[p];
  for (const auto& [edge, faces] : edgeFaces) {
    sheet.edges.push_back({to[edge.first], to[edge.second]});
    sheet.restSquared.push_back((flat.row(edge.first) - flat.row(edge.second)).squaredNorm());
    sheet.area.push_back(faces.second);
    if (faces.first.size() != 2 || creaseEdges.count(edge)) continue;
    const std::array<int, 4> v{edge.first, edge.second, faces.first[0], faces.first[1]};
    std::array<Eigen::Vector2d, 4> rest;
    for (int k = 0; k < 4; ++k) rest[k] = flat.row(v[k]).transpose();
    const std::array<double, 4> w = hingeWeights(rest);
    double hingeArea = 0;
    for (int k = 2; k < 4; ++k) hingeArea += triangleArea(flat, v[0], v[1], v[k]);
    // E_hinge = 3 / (A0 + A1) |sum w_i x_i|^2; its Hessian 6 / (A0 + A1) w w^T per coordinate.
    const double c = 6.0 / hingeArea;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) bendingScalar.emplace_back(to[v[i]], to[v[j]], c * w[i] * w[j]);
  }
}

Sheet buildSheet(const DForm& start) {
  Sheet sheet;
  const Piece* pieces[2] = {&start.a, &start.b};
  double totalArea = 0;
  for (const Piece* piece : pieces)
    for (Eigen::Index f = 0; f < piece->F.rows(); ++f)
      totalArea += triangleArea(piece->flat, piece->F(f, 0), piece->F(f, 1), piece->F(f, 2));
  sheet.unit = std::sqrt(totalArea);
  sheet.unknownOf[0].resize(start.a.flat.rows());
  for (Eigen::Index v = 0; v < start.a.flat.rows(); ++v) sheet.unknownOf[0][v] = int(v);
  int next = int(start.a.flat.rows());
  sheet.unknownOf[1].assign(start.b.flat.rows(), -1);
  for (std::size_t i = 0; i < start.b.seam.size(); ++i)
    sheet.unknownOf[1][start.b.seam[i]] = start.a.seam[i];
  for (int& u : sheet.unknownOf[1])
    if (u < 0) u = next++;
  sheet.vertices = next;
  std::vector<Triplet> scalar;
  for (int p = 0; p < 2; ++p) addPiece(*pieces[p], p, sheet.unit, sheet, scalar);
  for (const Triplet& t : scalar)
    for (int c = 0; c < 3; ++c)
      sheet.bendingHessian.emplace_back(3 * t.row() + c, 3 * t.col() + c, t.value());
  sheet.bending.resize(3 * next, 3 * next);
  sheet.bending.setFromTriplets(sheet.bendingHessian.begin(), sheet.bendingHessian.end());
  return sheet;
}

struct Evaluation {
  double bending = 0, stretching = 0;
  Eigen::VectorXd bendingGradient, stretchingGradient;
  double energy() const { return bending + stretching; }
};

Eigen::Vector3d position(const Eigen::VectorXd& x, int v) { return x.segment<3>(3 * v); }

double strain(const Sheet& sheet, const Eigen::VectorXd& x, std::size_t e) {
  const Eigen::Vector3d d = position(x, sheet.edges[e][0]) - position(x, sheet.edges[e][1]);
  return (d.squaredNorm() - sheet.restSquared[e]) / (2.0 * sheet.restSquared[e]);
}

double energyAt(const Sheet& sheet, double k, const Eigen::VectorXd& x) {
  double stretching = 0;
  for (std::size_t e = 0; e < sheet.edges.size(); ++e)
    stretching += sheet.area[e] * std::pow(strain(sheet, x, e), 2);
  return 0.5 * x.dot(sheet.bending * x) + 0.5 * k * stretching;
}

Evaluation evaluate(const Sheet& sheet, double k, const Eigen::VectorXd& x) {
  Evaluation out;
  out.bendingGradient = sheet.bending * x;
  out.bending = 0.5 * x.dot(out.bendingGradient);
  out.stretchingGradient = Eigen::VectorXd::Zero(x.size());
  for (std::size_t e = 0; e < sheet.edges.size(); ++e) {
    const int i = sheet.edges[e][0], j = sheet.edges[e][1];
    const double eps = strain(sheet, x, e);
    out.stretching += 0.5 * k * sheet.area[e] * eps * eps;
    const Eigen::Vector3d g =
        k * sheet.area[e] * eps / sheet.restSquared[e] * (position(x, i) - position(x, j));
    out.stretchingGradient.segment<3>(3 * i) += g;
    out.stretchingGradient.segment<3>(3 * j) -= g;
  }
  return out;
}

double stationarity(const Evaluation& e) {
  const double scale = e.bendingGradient.norm() + e.stretchingGradient.norm();
  return scale > 0 ? (e.bendingGradient + e.stretchingGradient).norm() / scale : 0.0;
}

// The exact Hessian. Where the sheet is compressed (eps < 0) it may be indefinite: the caller
// shifts it until it factorises (a buckling direction is then taken as a gradient step).
Sparse hessian(const Sheet& sheet, double k, const Eigen::VectorXd& x) {
  std::vector<Triplet> t = sheet.bendingHessian;
  t.reserve(t.size() + 36 * sheet.edges.size());
  for (std::size_t e = 0; e < sheet.edges.size(); ++e) {
    const int v[2] = {sheet.edges[e][0], sheet.edges[e][1]};
    const double l2 = sheet.restSquared[e];
    const Eigen::Vector3d d = (position(x, v[0]) - position(x, v[1])) / l2;
    const double eps = strain(sheet, x, e);
    const Eigen::Matrix3d block =
        k * sheet.area[e] * (d * d.transpose() + eps / l2 * Eigen::Matrix3d::Identity());
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            t.emplace_back(3 * v[a] + r, 3 * v[b] + c, (a == b ? 1 : -1) * block(r, c));
  }
  Sparse h(3 * sheet.vertices, 3 * sheet.vertices);
  h.setFromTriplets(t.begin(), t.end());
  return h;
}

// The unknowns of `model`'s 3D shape (B's seam rows give way to A's).
Eigen::VectorXd startPositions(const Sheet& sheet, const DForm& model) {
  Eigen::VectorXd x(3 * sheet.vertices);
  const Piece* pieces[2] = {&model.b, &model.a};
  for (int p = 0; p < 2; ++p)
    for (Eigen::Index v = 0; v < pieces[p]->shape.rows(); ++v)
      x.segment<3>(3 * sheet.unknownOf[1 - p][v]) =
          pieces[p]->shape.row(v).transpose() / sheet.unit;
  return x;
}

}  // namespace

double sheetEnergy(const DForm& model, double stiffness) {
  const Sheet sheet = buildSheet(model);
  return energyAt(sheet, stiffness, startPositions(sheet, model));
}

InextensibleResult solveInextensible(const DForm& start, const InextensibleOptions& options) {
  const auto clock = std::chrono::steady_clock::now();
  const Sheet sheet = buildSheet(start);
  Eigen::VectorXd x = startPositions(sheet, start);

  InextensibleResult result;
  InextensibleSummary& summary = result.summary;
  Sparse lower = Sparse(hessian(sheet, options.stiffness, x).triangularView<Eigen::Lower>());
  SupernodalCholesky factor(lower, 3);
  for (int stage = 0; stage <= options.continuation; ++stage) {
    const double k = options.stiffness * std::pow(10.0, stage - options.continuation);
    const bool last = stage == options.continuation;
    // Stages before the last only carry the shape along; the last one is solved to the tolerance.
    const double tolerance = last ? options.tolerance : std::max(options.tolerance, 1e-4);
    double shift = 0;
    for (;;) {
      const Evaluation now = evaluate(sheet, k, x);
      summary.stationarity = stationarity(now);
      summary.bendingEnergy = now.bending;
      summary.stretchingEnergy = now.stretching;
      if (summary.stationarity <= tolerance) {
        summary.converged = last;
        break;
      }
      if (summary.steps >= options.maxSteps) {
        summary.message = "stopped after " + std::to_string(summary.steps) + " Newton steps";
        break;
      }
      ++summary.steps;
      lower = hessian(sheet, k, x).triangularView<Eigen::Lower>();
      // The rigid motions are the energy's null space: a shift far below the stiffness keeps the
      // factorisation positive definite without bending the step.
      const double floorShift = 1e-10 * lower.diagonal().cwiseAbs().maxCoeff();
      shift = std::max(shift, floorShift);
      for (++summary.factorisations; !factor.factorize(lower, shift); ++summary.factorisations)
        shift *= 10;
      const Eigen::VectorXd g = now.bendingGradient + now.stretchingGradient;
      const Eigen::VectorXd step = factor.solve(-g);
      const double slope = g.dot(step);
      double alpha = 1;
      const double e0 = now.energy();
      // Near the answer the step's gain -slope / 2 falls below the rounding of E itself: there the
      // full step is taken when it lowers the gradient, which is what is left to measure.
      if (-slope <= 1e-12 * std::abs(e0)) {
        const Evaluation next = evaluate(sheet, k, x + step);
        if ((next.bendingGradient + next.stretchingGradient).norm() >= g.norm()) {
          summary.message = "stationary to rounding";
          summary.converged = last;
          break;
        }
      } else {
        while (alpha > 1e-10 &&
               !(energyAt(sheet, k, x + alpha * step) <= e0 + 1e-4 * alpha * slope))
          alpha *= 0.5;
      }
      if (alpha <= 1e-10) {
        if (shift > 1e12 * floorShift) {
          summary.message = "no descent along the Newton step";
          break;
        }
        shift *= 100;
        continue;
      }
      x += alpha * step;
      shift = alpha == 1 ? shift / 10 : shift;
    }
    if (!summary.message.empty() && !summary.converged) break;
  }
  if (summary.converged && summary.message.empty())
    summary.message = "stationary to " + std::to_string(summary.stationarity) + " in " +
                      std::to_string(summary.steps) + " Newton steps";

  result.model = start;
  Piece* out[2] = {&result.model.a, &result.model.b};
  for (int p = 0; p < 2; ++p)
    for (Eigen::Index v = 0; v < out[p]->shape.rows(); ++v)
      out[p]->shape.row(v) = sheet.unit * position(x, sheet.unknownOf[p][v]).transpose();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
  return result;
}

}  // namespace dform
