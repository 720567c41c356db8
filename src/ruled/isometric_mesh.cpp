// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/ruled/isometric_mesh.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "dform/core/constants.h"
#include "dform/core/interrupt.h"
#include "dform/exact/exact_gluing.h"
#include "dform/ruled/ruled_surface.h"
#include "dform/solver/supernodal_cholesky.h"

namespace dform::ruled {
namespace {

// A step that lowers the length residual only after this many halvings is no progress; three
// such steps running stop the solve (the residual is then held by a vertex that cannot flatten).
constexpr int kStallHalvings = 6;
constexpr int kStallSteps = 3;
// A fold past this (radians) turns a triangle over its neighbour: the gate's `flipped` check
// fails such a sheet, and a card does not sit so.
constexpr double kLargestFold = 0.5 * kPi;
// Added to the diagonal of J J^T: keeps the factorisation defined where rows are dependent (a
// flat star, whose vertex may move off its plane to first order for free) without moving the
// step (the rows' scale is 1).
constexpr double kRegularisation = 1e-12;
// The length error each stage but the last of a continuation is solved to.
constexpr double kStageTolerance = 1e-6;

// An edge of either piece: its ends as 3D unknowns (shared across the seam) and in its piece.
struct MeshEdge {
  int piece = 0;
  int i = 0, j = 0;    // vertex rows of the piece
  int gi = 0, gj = 0;  // 3D unknowns
  double rest = 0;     // flat length at the start, mm: the residual's scale
};

struct Unknowns {
  int count3d = 0;
  std::vector<int> global[2];  // each piece's vertex -> its 3D unknown
  std::vector<int> free[2];    // each piece's vertex -> its flat unknown, -1 on the outline
  int countFlat = 0;
};

Unknowns numberUnknowns(const DForm& m) {
  const Piece* pieces[2] = {&m.a, &m.b};
  Unknowns u;
  u.global[0].resize(std::size_t(m.a.flat.rows()));
  for (std::size_t v = 0; v < u.global[0].size(); ++v) u.global[0][v] = int(v);
  u.count3d = int(m.a.flat.rows());
  u.global[1].assign(std::size_t(m.b.flat.rows()), -1);
  for (std::size_t k = 0; k < m.b.seam.size(); ++k)
    u.global[1][std::size_t(m.b.seam[k])] = m.a.seam[k];
  for (int& g : u.global[1])
    if (g < 0) g = u.count3d++;
  for (int p = 0; p < 2; ++p) {
    std::vector<bool> outline(std::size_t(pieces[p]->flat.rows()), false);
    for (int v : pieces[p]->seam) outline[std::size_t(v)] = true;
    for (const std::vector<int>& loop : pieces[p]->freeBoundaries)
      for (int v : loop) outline[std::size_t(v)] = true;
    u.free[p].assign(outline.size(), -1);
    for (std::size_t v = 0; v < outline.size(); ++v)
      if (!outline[v]) u.free[p][v] = u.countFlat++;
  }
  return u;
}

// Every edge once: a seam edge (between consecutive seam points) from piece A only, its two
// sides being one edge in 3D.
std::vector<MeshEdge> meshEdges(const DForm& m, const Unknowns& u) {
  const Piece* pieces[2] = {&m.a, &m.b};
  std::set<std::pair<int, int>> seamEdges;
  const int n = int(m.a.seam.size());
  for (int k = 0; k < n; ++k)
    seamEdges.insert(std::minmax(m.a.seam[std::size_t(k)], m.a.seam[std::size_t((k + 1) % n)]));
  std::vector<MeshEdge> edges;
  for (int p = 0; p < 2; ++p) {
    std::set<std::pair<int, int>> seen;
    const Faces& F = pieces[p]->F;
    for (int f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int i = F(f, c), j = F(f, (c + 1) % 3);
        if (!seen.insert(std::minmax(i, j)).second) continue;
        MeshEdge e{p, i, j, u.global[p][std::size_t(i)], u.global[p][std::size_t(j)], 0.0};
        if (p == 1 && seamEdges.count(std::minmax(e.gi, e.gj))) continue;
        e.rest = (pieces[p]->flat.row(i) - pieces[p]->flat.row(j)).norm();
        edges.push_back(e);
      }
  }
  return edges;
}

double signedArea(const Points2& V, int a, int b, int c) {
  const Eigen::Vector2d x = V.row(b) - V.row(a), y = V.row(c) - V.row(a);
  return 0.5 * (x.x() * y.y() - x.y() * y.x());
}

// An interior edge i-j of a piece and the corners k, l of its two triangles, as 3D unknowns.
struct Hinge {
  int i = 0, j = 0, k = 0, l = 0;
};

std::vector<Hinge> hingesOf(const DForm& m, const Unknowns& u) {
  std::vector<Hinge> hinges;
  for (int p = 0; p < 2; ++p) {
    const Faces& F = p == 0 ? m.a.F : m.b.F;
    std::map<std::pair<int, int>, int> opposite;
    for (int f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c) opposite[{F(f, c), F(f, (c + 1) % 3)}] = F(f, (c + 2) % 3);
    const std::vector<int>& g = u.global[p];
    for (const auto& [edge, k] : opposite) {
      const auto [i, j] = edge;
      const auto other = opposite.find({j, i});
      if (i > j || other == opposite.end()) continue;
      hinges.push_back(
          {g[std::size_t(i)], g[std::size_t(j)], g[std::size_t(k)], g[std::size_t(other->second)]});
    }
  }
  return hinges;
}

class Solver {
 public:
  Solver(DForm& m, const Unknowns& u, std::vector<MeshEdge> edges)
      : m_(m),
        u_(u),
        edges_(std::move(edges)),
        hinges_(hingesOf(m, u)),
        flat_{&m.a.flat, &m.b.flat} {
    X_.resize(u.count3d, 3);
    for (int p = 0; p < 2; ++p) {
      const Piece& piece = p == 0 ? m.a : m.b;
      for (Eigen::Index v = 0; v < piece.shape.rows(); ++v)
        X_.row(u.global[p][std::size_t(v)]) = piece.shape.row(v);
    }
    foldGuard_ = largestFold() <= kLargestFold;
    startSquared_.reserve(edges_.size());
    for (const MeshEdge& e : edges_)
      startSquared_.push_back((X_.row(e.gi) - X_.row(e.gj)).squaredNorm());
  }

  // The lengths aimed for: the start's 3D lengths blended into the flat ones, squared,
  // (1 - blend) l_start^2 + blend l_flat^2 (blend 1: the flat lengths themselves).
  void setBlend(double blend) { blend_ = blend; }

  // The largest |dihedral| over the interior edges.
  double largestFold() const {
    double largest = 0.0;
    for (const Hinge& h : hinges_) {
      const double theta = std::abs(dihedral(X_.row(h.i), X_.row(h.j), X_.row(h.k), X_.row(h.l)));
      if (!(theta <= largest)) largest = theta;  // a NaN is the largest
    }
    return largest;
  }

  // Edge k's squared length aimed for.
  double aimedSquared(std::size_t k) const {
    const MeshEdge& e = edges_[k];
    const double flat = (flat_[e.piece]->row(e.i) - flat_[e.piece]->row(e.j)).squaredNorm();
    return blend_ == 1.0 ? flat : (1.0 - blend_) * startSquared_[k] + blend_ * flat;
  }

  // Residual k: (|X_i - X_j|^2 - aimed^2) / (2 rest): the length error to first order.
  Eigen::VectorXd residual() const {
    Eigen::VectorXd r(Eigen::Index(edges_.size()));
    for (std::size_t k = 0; k < edges_.size(); ++k) {
      const MeshEdge& e = edges_[k];
      const double l3 = (X_.row(e.gi) - X_.row(e.gj)).squaredNorm();
      r[Eigen::Index(k)] = (l3 - aimedSquared(k)) / (2.0 * e.rest);
    }
    return r;
  }

  // The largest relative error of an edge's length against the length aimed for.
  double worstLengthError() const {
    double worst = 0.0;
    for (std::size_t k = 0; k < edges_.size(); ++k) {
      const MeshEdge& e = edges_[k];
      const double l3 = (X_.row(e.gi) - X_.row(e.gj)).norm();
      const double aimed = std::sqrt(aimedSquared(k));
      const double error = std::abs(l3 - aimed) / aimed;
      if (!(error <= worst)) worst = error;  // a NaN is the worst
    }
    return worst;
  }

  // One least-norm Gauss-Newton step, halved until the residual falls; the halvings taken, or
  // -1 where none lowers it.
  int step() {
    const Eigen::VectorXd r = residual();
    const int unknowns = 3 * u_.count3d + 2 * u_.countFlat;
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(edges_.size() * 10);
    for (std::size_t k = 0; k < edges_.size(); ++k) {
      const MeshEdge& e = edges_[k];
      const int row = int(k);
      const Eigen::Vector3d d = (X_.row(e.gi) - X_.row(e.gj)).transpose() / e.rest;
      for (int c = 0; c < 3; ++c) {
        entries.emplace_back(row, 3 * e.gi + c, d[c]);
        entries.emplace_back(row, 3 * e.gj + c, -d[c]);
      }
      const Eigen::Vector2d w =
          (flat_[e.piece]->row(e.i) - flat_[e.piece]->row(e.j)).transpose() / e.rest;
      const int fi = u_.free[e.piece][std::size_t(e.i)], fj = u_.free[e.piece][std::size_t(e.j)];
      for (int c = 0; c < 2; ++c) {
        if (fi >= 0) entries.emplace_back(row, 3 * u_.count3d + 2 * fi + c, -blend_ * w[c]);
        if (fj >= 0) entries.emplace_back(row, 3 * u_.count3d + 2 * fj + c, blend_ * w[c]);
      }
    }
    Eigen::SparseMatrix<double> J(Eigen::Index(edges_.size()), unknowns);
    J.setFromTriplets(entries.begin(), entries.end());
    const SupernodalCholesky::SparseLower normal =
        Eigen::SparseMatrix<double>(J * J.transpose()).triangularView<Eigen::Lower>();
    // Every step's normal matrix has the first one's pattern (the same edges and unknowns).
    if (!factor_) factor_ = std::make_unique<SupernodalCholesky>(normal);
    if (!factor_->factorize(normal, kRegularisation)) return -1;
    const Eigen::VectorXd delta = -(J.transpose() * factor_->solve(r));
    const double before = r.squaredNorm();
    const Eigen::MatrixX3d X = X_;
    const Points2 flat[2] = {*flat_[0], *flat_[1]};
    double t = 1.0;
    for (int halvings = 0; halvings < 30; ++halvings, t *= 0.5) {
      for (int g = 0; g < u_.count3d; ++g)
        X_.row(g) = X.row(g) + t * delta.segment<3>(3 * g).transpose();
      for (int p = 0; p < 2; ++p)
        for (std::size_t v = 0; v < u_.free[p].size(); ++v)
          if (const int f = u_.free[p][v]; f >= 0)
            flat_[p]->row(Eigen::Index(v)) =
                flat[p].row(Eigen::Index(v)) +
                t * delta.segment<2>(3 * u_.count3d + 2 * f).transpose();
      // From a start with no triangle folded over its neighbour, no step folds one over: the
      // least-norm step from a start far from the lengths (a finer mesh carried from an exact
      // coarse one, its edges across the folds short) can otherwise meet them with a fold.
      if (residual().squaredNorm() < before && (!foldGuard_ || largestFold() <= kLargestFold))
        return halvings;
    }
    X_ = X;
    *flat_[0] = flat[0];
    *flat_[1] = flat[1];
    return -1;
  }

  void writeShapes() {
    for (int p = 0; p < 2; ++p) {
      Piece& piece = p == 0 ? m_.a : m_.b;
      for (Eigen::Index v = 0; v < piece.shape.rows(); ++v)
        piece.shape.row(v) = X_.row(u_.global[p][std::size_t(v)]);
    }
  }

 private:
  DForm& m_;
  const Unknowns& u_;
  std::vector<MeshEdge> edges_;
  std::vector<Hinge> hinges_;
  std::vector<double> startSquared_;  // each edge's squared 3D length at the start
  double blend_ = 1.0;
  bool foldGuard_ = false;  // the start folds no triangle over: the steps keep it so
  Points2* flat_[2];
  Eigen::MatrixX3d X_;
  std::unique_ptr<SupernodalCholesky> factor_;  // analysed at the first step
};

// The bending energy over the interior edges of both pieces, with the flat areas as rest, and the
// largest fold among them.
std::pair<double, double> bendingOver(const DForm& m) {
  double energy = 0.0, largest = 0.0;
  for (const Piece* piece : {&m.a, &m.b}) {
    std::map<std::pair<int, int>, int> opposite;
    for (int f = 0; f < piece->F.rows(); ++f)
      for (int c = 0; c < 3; ++c)
        opposite[{piece->F(f, c), piece->F(f, (c + 1) % 3)}] = piece->F(f, (c + 2) % 3);
    for (const auto& [edge, k] : opposite) {
      const auto [i, j] = edge;
      const auto other = opposite.find({j, i});
      if (i > j || other == opposite.end()) continue;
      const int l = other->second;
      const double length = (piece->flat.row(i) - piece->flat.row(j)).norm();
      const double areas =
          std::abs(signedArea(piece->flat, i, j, k)) + std::abs(signedArea(piece->flat, j, i, l));
      const double theta = dihedral(piece->shape.row(i), piece->shape.row(j), piece->shape.row(k),
                                    piece->shape.row(l));
      energy += 3.0 * length * length / areas * theta * theta;
      largest = std::max(largest, std::abs(theta));
    }
  }
  return {energy, largest};
}

}  // namespace

Result<IsometricMesh> isometricMesh(const DForm& start, const IsometricMeshOptions& options) {
  if (start.a.seam.size() != start.b.seam.size() || start.a.seam.size() < 3)
    return Status(ErrorCode::Internal, "the two pieces' seams differ in length");
  IsometricMesh out;
  out.model = start;
  DForm& m = out.model;
  // Equal chords on both sides of the seam: the metric glues only then.
  exact::SeamPolygons seam;
  const Eigen::Index n = Eigen::Index(m.a.seam.size());
  seam.a.resize(n, 2);
  seam.b.resize(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) {
    seam.a.row(k) = m.a.flat.row(m.a.seam[std::size_t(k)]);
    seam.b.row(k) = m.b.flat.row(m.b.seam[std::size_t(k)]);
  }
  out.chordMoveMm = exact::equalizeChords(seam);
  for (Eigen::Index k = 0; k < n; ++k) {
    m.a.flat.row(m.a.seam[std::size_t(k)]) = seam.a.row(k);
    m.b.flat.row(m.b.seam[std::size_t(k)]) = seam.b.row(k);
  }
  const Unknowns unknowns = numberUnknowns(m);
  out.interiorVertices = unknowns.countFlat;
  Solver solver(m, unknowns, meshEdges(m, unknowns));
  const int stages = std::max(1, options.stages);
  for (int stage = 1; stage <= stages; ++stage) {
    solver.setBlend(double(stage) / stages);
    const double tolerance = stage == stages ? options.tolerance : kStageTolerance;
    int stalled = 0, steps = 0;
    while (solver.worstLengthError() > tolerance) {
      if (steps == options.maxSteps)
        return Status(ErrorCode::SolveFailed, "the edge lengths were not met in " +
                                                  std::to_string(options.maxSteps) +
                                                  " steps (largest error " +
                                                  std::to_string(solver.worstLengthError()) + ")");
      throwIfInterrupted("the solve");
      const int halvings = solver.step();
      ++steps;
      stalled = halvings < 0 || halvings >= kStallHalvings ? stalled + 1 : 0;
      if (halvings < 0 || stalled == kStallSteps)
        return Status(ErrorCode::SolveFailed,
                      "the edge lengths stop at a relative error of " +
                          std::to_string(solver.worstLengthError()) +
                          " (a vertex that cannot lie flat among its neighbours)");
    }
    out.steps += steps;
  }
  out.lengthError = solver.worstLengthError();
  solver.writeShapes();
  for (int p = 0; p < 2; ++p) {
    const Piece& before = p == 0 ? start.a : start.b;
    const Piece& after = p == 0 ? m.a : m.b;
    for (int f = 0; f < after.F.rows(); ++f)
      if (!(signedArea(after.flat, after.F(f, 0), after.F(f, 1), after.F(f, 2)) *
                signedArea(before.flat, before.F(f, 0), before.F(f, 1), before.F(f, 2)) >
            0.0))
        return Status(ErrorCode::SolveFailed, std::string("a flat triangle of piece ") +
                                                  (p == 0 ? "A" : "B") + " turned over");
    out.largestFlatMoveMm =
        std::max(out.largestFlatMoveMm, (after.flat - before.flat).rowwise().norm().maxCoeff());
  }
  std::tie(out.bendingEnergy, out.largestFold) = bendingOver(m);
  if (!(out.largestFold <= kLargestFold))
    return Status(ErrorCode::SolveFailed,
                  "the lengths are met with a triangle folded over its neighbour (a fold of " +
                      std::to_string(int(std::lround(out.largestFold / kDegree))) + " degrees)");
  return out;
}

}  // namespace dform::ruled
