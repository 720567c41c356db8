// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/forward/forward.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cassert>
#include <cmath>
#include <tuple>

#include "dform/core/polyline.h"
#include "dform/model/injectivity.h"
#include "dform/model/relax_then_solve.h"
#include "dform/model/term_table.h"
#include "dform/model/terms.h"

namespace dform {

namespace {

Points2 seamPoints(const Piece& p) { return p.flat(p.seam, Eigen::all); }

// Seam positions (k of a.seam[k] and b.seam[k]) whose flat vertices may move a little from where
// they were drawn: each corner of either seam outline (sampledCorners) and
// its two seam neighbours, unless a drawn crease ends at the corner. Where a corner meets a
// smooth partner the real D-Form creases (paper section 7): a drawn crease takes that fold;
// otherwise the corner needs room to form it, and pinned there, the triangles fold over instead
// (measured on the circle and the square: the corner and its two neighbours move most).
std::vector<bool> seamCornerRoom(const Piece& a, const Piece& b) {
  const int n = int(a.seam.size());
  std::vector<bool> corner(n, false), creaseEnd(n, false), room(n, false);
  for (const Piece* p : {&a, &b}) {
    const std::vector<bool> corners = sampledCorners(seamPoints(*p));
    for (int k = 0; k < n; ++k) corner[k] = corner[k] || corners[k];
    std::vector<int> position(p->flat.rows(), -1);
    for (int k = 0; k < n; ++k) position[p->seam[k]] = k;
    for (const std::vector<int>& crease : p->creases)
      for (int end : {crease.front(), crease.back()})
        if (position[end] >= 0) creaseEnd[position[end]] = true;
  }
  for (int k = 0; k < n; ++k)
    if (corner[k] && !creaseEnd[k])
      for (int j : {k - 1, k, k + 1}) room[(j + n) % n] = true;
  return room;
}

// The vertices of every line that is cut or folded: the seam, then the free boundaries and
// creases (each vertex once). Their flat positions are the pattern the designer drew.
std::vector<int> drawnVertices(const Piece& p) {
  std::vector<int> vertices = p.seam;
  std::vector<bool> taken(p.flat.rows(), false);
  for (int v : vertices) taken[v] = true;
  for (const auto* lines : {&p.freeBoundaries, &p.creases})
    for (const std::vector<int>& line : *lines)
      for (int v : line)
        if (!taken[v]) taken[v] = true, vertices.push_back(v);
  return vertices;
}

// Least-squares rotation R (2 by 2) taking the centred rows of Q onto those of P.
Eigen::Matrix2d procrustesRotation(const Points2& P, const Points2& Q) {
  double dot = 0.0, cross = 0.0;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    dot += Q(i, 0) * P(i, 0) + Q(i, 1) * P(i, 1);
    cross += Q(i, 0) * P(i, 1) - Q(i, 1) * P(i, 0);
  }
  const double angle = std::atan2(cross, dot);
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return R;
}

// Solves the Dirichlet problem L f = rhs at interior vertices with f fixed on the seam, using the
// piece's cotangent Laplacian. Returns #V by cols.
Eigen::MatrixXd solveDirichlet(const Piece& p, const Eigen::MatrixXd& seamValues,
                               const Eigen::MatrixXd& rhs) {
  const int n = int(p.flat.rows());
  std::vector<int> interiorIndex(n, -1);
  std::vector<bool> onSeam(n, false);
  for (int v : p.seam) onSeam[v] = true;
  int m = 0;
  for (int i = 0; i < n; ++i)
    if (!onSeam[i]) interiorIndex[i] = m++;
  Eigen::MatrixXd f(n, seamValues.cols());
  for (std::size_t k = 0; k < p.seam.size(); ++k) f.row(p.seam[k]) = seamValues.row(k);
  if (m == 0) return f;

  const CotangentWeights w = cotangentWeights(p.flat, p.F);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(m, seamValues.cols());
  for (int i = 0; i < n; ++i) {
    if (onSeam[i]) continue;
    const int r = interiorIndex[i];
    double diagonal = 0.0;
    for (const auto& [j, weight] : w.neighbours[i]) {
      diagonal += weight;
      if (onSeam[j])
        b.row(r) += weight * f.row(j);
      else
        entries.emplace_back(r, interiorIndex[j], -weight);
    }
    entries.emplace_back(r, r, diagonal);
    b.row(r) += rhs.row(i);
  }
  Eigen::SparseMatrix<double> L(m, m);
  L.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
  const Eigen::MatrixXd interior = solver.solve(b);
  for (int i = 0; i < n; ++i)
    if (!onSeam[i]) f.row(i) = interior.row(interiorIndex[i]);
  return f;
}

// Turning angle at each vertex of a closed polygon (positive where a counter-clockwise polygon
// is convex).
Eigen::VectorXd signedTurningAngles(const Points2& P) {
  const int n = int(P.rows());
  Eigen::VectorXd angle(n);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d in = P.row(k) - P.row((k + n - 1) % n);
    const Eigen::Vector2d out = P.row((k + 1) % n) - P.row(k);
    angle[k] = std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out));
  }
  return angle;
}

}  // namespace

DForm pillowInitialGuess(const Piece& a, const Piece& b) {
  assert(a.seam.size() == b.seam.size() && "the seams must pair one to one");
  // The seam outline: A's as drawn and B's best-aligned to it, averaged. B is turned over (its
  // x mirrored) when its seam runs round the other way from A's in the plane: a classic D-Form
  // (two outlines joined) or an anti D-Form (two holes); a demi D-Form's pieces keep their sides.
  Points2 PA = seamPoints(a), PB = seamPoints(b);
  const bool turnedOver = (signedArea(PA) > 0.0) != (signedArea(PB) > 0.0);
  const Eigen::Matrix2d mirror = Eigen::Vector2d(turnedOver ? -1.0 : 1.0, 1.0).asDiagonal();
  PB = PB * mirror;
  const Eigen::RowVector2d cA = PA.colwise().mean(), cB = PB.colwise().mean();
  PA.rowwise() -= cA;
  PB.rowwise() -= cB;
  const int n = int(PA.rows());
  const Eigen::Matrix2d R = procrustesRotation(PA, PB);
  const Points2 PBpaired = PB * R.transpose();
  const Points2 mid = 0.5 * (PA + PBpaired);
  // Each piece's rigid placement in the frame of `mid` (x as a row: x * linear + offset).
  const Eigen::Matrix2d linear[2] = {Eigen::Matrix2d::Identity(), mirror * R.transpose()};
  const Eigen::RowVector2d offset[2] = {-cA, -cB * R.transpose()};

  // Where one piece's outline turns more sharply than its partner's, that piece is locally the
  // narrower one and the other wraps over it, so the seam leaves the mid plane towards it. The
  // seam's height profile starts as the (smoothed) difference of the two outlines' turning angles;
  // its amplitude and sign are fitted below.
  Eigen::VectorXd lift = signedTurningAngles(PA) - signedTurningAngles(PBpaired);
  for (int pass = 0; pass < 4; ++pass) {
    Eigen::VectorXd smooth(n);
    for (int k = 0; k < n; ++k)
      smooth[k] = 0.25 * lift[(k + n - 1) % n] + 0.5 * lift[k] + 0.25 * lift[(k + 1) % n];
    lift = smooth;
  }
  const double liftScale = lift.cwiseAbs().maxCoeff();
  if (liftScale > 0) lift /= liftScale;

  DForm model{a, b};
  Piece* pieces[2] = {&model.a, &model.b};
  const double meanEdge = closedLength(mid) / double(n);
  Eigen::MatrixX2d xy[2];
  Eigen::VectorXd phi[2], seamHeight[2];
  for (int p = 0; p < 2; ++p) {
    const Piece& piece = *pieces[p];
    const int vertices = int(piece.flat.rows());
    // The rigid placement plus the harmonic extension of the seam's move onto `mid`: free
    // boundaries follow the piece instead of collapsing onto the seam (a harmonic map of the
    // whole piece would), and a disc piece gets the harmonic map of `mid` all the same, since
    // the cotangent Laplacian reproduces the rigid part exactly.
    const Points2 placed = (piece.flat * linear[p]).rowwise() + offset[p];
    Points2 move(n, 2);
    for (int k = 0; k < n; ++k) move.row(k) = mid.row(k) - placed.row(piece.seam[k]);
    xy[p] = placed + solveDirichlet(piece, move, Eigen::MatrixXd::Zero(vertices, 2));
    seamHeight[p] = solveDirichlet(piece, lift, Eigen::MatrixXd::Zero(vertices, 1)).col(0);
    // A bump: -Laplace(phi) = 1 with phi = 0 on the seam, scaled to a unit maximum.
    phi[p] = solveDirichlet(piece, Eigen::MatrixXd::Zero(n, 1),
                            Eigen::MatrixXd::Constant(vertices, 1, meanEdge * meanEdge))
                 .col(0);
    const double top = phi[p].cwiseAbs().maxCoeff();
    if (top > 0) phi[p] /= top;
  }

  // Per edge: squared flat length, squared xy length of the map, differences of the bump and of
  // the seam height. The 3D edge is (s dxy, alpha dlift +- h dphi).
  struct EdgeData {
    Eigen::VectorXd rest2, xy2, dphi, dlift;
  } edges[2];
  for (int p = 0; p < 2; ++p) {
    const auto E = meshEdges(pieces[p]->F);
    EdgeData& d = edges[p];
    d.rest2.resize(E.rows()), d.xy2.resize(E.rows()), d.dphi.resize(E.rows()),
        d.dlift.resize(E.rows());
    for (int e = 0; e < E.rows(); ++e) {
      const int i = E(e, 0), j = E(e, 1);
      d.rest2[e] = (pieces[p]->flat.row(i) - pieces[p]->flat.row(j)).squaredNorm();
      d.xy2[e] = (xy[p].row(i) - xy[p].row(j)).squaredNorm();
      d.dphi[e] = phi[p][i] - phi[p][j];
      d.dlift[e] = seamHeight[p][i] - seamHeight[p][j];
    }
  }
  // Isometry residual sum_e (|3D edge|^2 - |flat edge|^2)^2 of one piece.
  auto residual = [](const EdgeData& d, double s, double alpha, double h) {
    const Eigen::ArrayXd z = alpha * d.dlift.array() + h * d.dphi.array();
    return (s * s * d.xy2.array() + z * z - d.rest2.array()).square().sum();
  };
  // Both pieces are inflated by the same height h, A up and B down, so that the start is a
  // pillow and not one flat piece against one domed one (which a separate fit per piece can
  // prefer). The residual is a quartic in h with up to two minima: a grid finds the basin,
  // golden-section search refines it.
  auto pillowResidual = [&](double s, double alpha, double h) {
    return residual(edges[0], s, alpha, h) + residual(edges[1], s, alpha, -h);
  };
  const double hMax = closedLength(mid);
  auto bestHeight = [&](double s, double alpha) {
    constexpr int kGrid = 24;
    double bestH = 0.0, best = pillowResidual(s, alpha, 0.0);
    for (int g = 1; g <= kGrid; ++g) {
      const double h = hMax * double(g * g) / double(kGrid * kGrid);  // denser near 0
      const double value = pillowResidual(s, alpha, h);
      if (value < best) best = value, bestH = h;
    }
    const double step = hMax / double(kGrid);
    double lo = std::max(0.0, bestH - step), hi = bestH + step;
    const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 30; ++it) {
      const double m1 = hi - golden * (hi - lo), m2 = lo + golden * (hi - lo);
      if (pillowResidual(s, alpha, m1) < pillowResidual(s, alpha, m2))
        hi = m2;
      else
        lo = m1;
    }
    const double h = 0.5 * (lo + hi);
    const double value = pillowResidual(s, alpha, h);
    return value < best ? std::make_pair(value, h) : std::make_pair(best, bestH);
  };

  // The seam outline shrinks by s <= kMaxShrink: at s = 1 two similar pieces fit best lying
  // flat on each other, the trivial isometry (a flat double disc) the start must stay away from.
  constexpr double kMaxShrink = 0.85;
  double bestCost = std::numeric_limits<double>::infinity(), bestS = kMaxShrink, bestAlpha = 0.0;
  double bestH = 0.0;
  for (double alphaStep = -4; alphaStep <= 4; ++alphaStep) {
    const double alpha = alphaStep * 0.05 * hMax;
    for (double s = 0.40; s <= kMaxShrink + 1e-9; s += 0.03) {
      const auto [cost, h] = bestHeight(s, alpha);
      if (cost < bestCost) bestCost = cost, bestS = s, bestAlpha = alpha, bestH = h;
    }
  }
  for (int p = 0; p < 2; ++p) {
    Piece& piece = *pieces[p];
    const double sign = p == 0 ? 1.0 : -1.0;
    piece.shape.resize(piece.flat.rows(), 3);
    piece.shape.leftCols<2>() = bestS * xy[p];
    piece.shape.col(2) = bestAlpha * seamHeight[p] + sign * bestH * phi[p];
  }
  return model;
}

double relaxationSmoothing(double smooth3d, const ForwardSettings& settings) {
  const double stiffest = settings.continuationSmoothing;
  if (settings.smoothingContinuation <= 1.0 || settings.solver.maxIterations == 0 ||
      smooth3d >= stiffest)
    return smooth3d;
  return std::min(stiffest, settings.smoothingContinuation * smooth3d);
}

ForwardResult solveForward(const Piece& a, const Piece& b, const ForwardSettings& settings) {
  assert(a.seam.size() == b.seam.size() && a.seam.size() >= 3 && "seams must pair one to one");
  ForwardResult result;
  // Internal unit: the mean flat seam edge length, as in the paper (section 4.1).
  result.unitMm = closedLength(seamPoints(a)) / double(a.seam.size());
  const double unit = result.unitMm;

  const bool haveShapes = a.shape.rows() == a.flat.rows() && b.shape.rows() == b.flat.rows();
  DForm start = haveShapes ? DForm{a, b} : pillowInitialGuess(a, b);
  scaleLengths(start, 1.0 / unit);
  const ForwardWeights& w = settings.weights;
  // The seam is closed exactly (shared 3D unknowns) whenever the alignment term is on at all.
  const VariableLayout layout =
      w.alignment > 0 ? VariableLayout(int(a.flat.rows()), int(b.flat.rows()), a.seam, b.seam)
                      : VariableLayout(int(a.flat.rows()), int(b.flat.rows()));
  EdgeLengthPairs edges = meshEdgePairs(layout, a.F, b.F);
  // Drawn lines stay where they were drawn: held exactly, except at seam corners, which only the
  // boundary-fix term holds (to outlineTolerance, by multiplier rounds below).
  const std::vector<int> drawnA = drawnVertices(start.a), drawnB = drawnVertices(start.b);
  const std::vector<bool> room = seamCornerRoom(start.a, start.b);
  std::vector<int> movableA, movableB, held;
  for (const auto& [p, drawn, movable] :
       {std::tuple{0, &drawnA, &movableA}, std::tuple{1, &drawnB, &movableB}})
    for (std::size_t k = 0; k < drawn->size(); ++k) {
      const int v = (*drawn)[k];
      if (w.boundaryFix > 0 && !(k < room.size() && room[k])) {  // drawn lists start with the seam
        held.push_back(layout.u(p, v));
        held.push_back(layout.u(p, v) + 1);
      } else {
        movable->push_back(v);
      }
    }
  const TermTable<ForwardWeights>& table = forwardTerms();
  std::vector<std::unique_ptr<ResidualTerm>> terms =
      makeTerms(table, {layout, start.a, start.b, edges, std::move(movableA), std::move(movableB)});
  auto* anchorTerm =
      static_cast<LinearResidual*>(terms[rowOf(table, &ForwardWeights::boundaryFix)].get());
  Eigen::VectorXd x = packVariables(layout, start.a, start.b);

  weightByFlatLength(edges, x, w.isometry);
  ForwardWeights relaxationWeights = w;
  relaxationWeights.smooth3d = relaxationSmoothing(w.smooth3d, settings);
  const LocalGlobalRelaxation relaxation(linearTerms(table, terms, relaxationWeights), edges, x,
                                         held);
  // No Levenberg-Marquardt step folds a triangle over that stood upright before it
  // (model/injectivity.h). The relaxation is not guarded: its path to the shape may pass
  // through folds (guarded, it stalled on the anti and Squaricle samples).
  const FoldGuard guard(layout, start.a, start.b);

  Problem problem(layout.numVariables());
  addTerms(problem, table, terms, w);
  problem.holdConstant(held);
  problem.setBlockSize(VariableLayout::kPerVertex);
  // Hold the seam corners near the drawn ones: the boundary fix as a constraint. The tolerance is
  // relative to the perimeter, #seam in the unit of the mean seam edge.
  const double perimeter = double(a.seam.size());
  std::vector<Constraint> constraints;
  if (w.boundaryFix > 0 && anchorTerm->numResiduals() > 0)
    constraints.push_back({anchorTerm, 2, settings.outlineTolerance * perimeter});
  SolveSequenceSummary solved =
      relaxThenSolve(relaxation, settings.relaxation, problem, settings.solver, guard, constraints,
                     settings.constraintRounds, x);
  result.relaxation = std::move(solved.relaxation);
  result.summary = std::move(solved.summary);
  result.constraintRounds = solved.constraintRounds;
  result.model = start;
  unpackVariables(layout, x, result.model.a, result.model.b);
  scaleLengths(result.model, unit);
  return result;
}

}  // namespace dform
