// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/ruled/ruled_search.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

namespace dform::ruled {

namespace {

double dihedralOf(const RuledSurface& s, const SurfaceEdge& e) {
  return dihedral(s.X.row(e.i), s.X.row(e.j), s.X.row(e.k), s.X.row(e.l));
}

// Whether the flip of e's chord leaves the surface without a doubled edge.
bool flipKeepsSingle(const RuledSurface& s, const SurfaceEdge& e) {
  RuledSurface trial = s;
  trial.pieces[std::size_t(e.piece)].flip(e.halfedge);
  return !trial.hasDoubleEdge();
}

// The chord of a piece in `use` folded furthest backwards (its dihedral below -1e-9: folds
// flatter than rounding are no fold) whose flip is possible and leaves no doubled edge.
std::optional<SurfaceEdge> mostFoldedBack(const RuledSurface& s, const std::array<bool, 2>& use) {
  double worst = -1e-9;
  std::optional<SurfaceEdge> chosen;
  for (const SurfaceEdge& e : s.edges()) {
    if (e.kind != EdgeKind::Chord || !use[std::size_t(e.piece)]) continue;
    const double theta = dihedralOf(s, e);
    if (!(theta < worst) || !s.pieces[std::size_t(e.piece)].flippable(e.halfedge) ||
        !flipKeepsSingle(s, e))
      continue;
    worst = theta;
    chosen = e;
  }
  return chosen;
}

// An edge's identity across flips: its piece (seam chords and ties: -1) and ends.
std::tuple<int, int, int> identity(const SurfaceEdge& e) {
  const int piece = e.kind == EdgeKind::Chord || e.kind == EdgeKind::Crease ? e.piece : -1;
  return {piece, std::min(e.i, e.j), std::max(e.i, e.j)};
}

// The hinge energy 3 l^2 / (A_left + A_right) theta^2 of the edge from row a to row b of piece p,
// with c the corner left of it (in the face of area aLeft) and d the one right of it.
double hingeEnergy(const RuledSurface& s, int p, int a, int b, int c, int d, double aLeft,
                   double aRight) {
  const PieceTriangulation& T = s.pieces[std::size_t(p)];
  const std::vector<int>& v = s.vertexOf[std::size_t(p)];
  const double l = (T.flat().row(a) - T.flat().row(b)).norm();
  const double theta = dihedral(s.X.row(v[std::size_t(a)]), s.X.row(v[std::size_t(b)]),
                                s.X.row(v[std::size_t(c)]), s.X.row(v[std::size_t(d)]));
  return 3.0 * l * l / (aLeft + aRight) * theta * theta;
}

double triangleArea(const Points2& P, int a, int b, int c) {
  const Eigen::Vector2d u = P.row(b) - P.row(a), w = P.row(c) - P.row(a);
  return 0.5 * (u.x() * w.y() - u.y() * w.x());
}

}  // namespace

double flipBendingChange(const RuledSurface& s, int p, int h) {
  const PieceTriangulation& T = s.pieces[std::size_t(p)];
  const int t = T.twin(h);
  const int i = T.tail(h), j = T.head(h), k = T.opposite(h), l = T.opposite(t);
  const double a1 = T.area(h / 3), a2 = T.area(t / 3);
  const double n1 = triangleArea(T.flat(), l, k, i), n2 = triangleArea(T.flat(), k, l, j);
  double before = hingeEnergy(s, p, i, j, k, l, a1, a2);
  double after = hingeEnergy(s, p, l, k, i, j, n1, n2);
  // Each side: its halfedge in the quadrilateral, the face it is in now and after the flip.
  struct Side {
    int halfedge;
    int cornerBefore;
    double areaBefore;
    int cornerAfter;
    double areaAfter;
  };
  const Side sides[4] = {{T.next(h), i, a1, l, n2},
                         {T.prev(h), j, a1, l, n1},
                         {T.next(t), j, a2, k, n1},
                         {T.prev(t), i, a2, k, n2}};
  for (const Side& side : sides) {
    const int o = T.twin(side.halfedge);
    if (o < 0 || T.fixed(side.halfedge)) continue;  // the boundary and creases do not bend
    const int a = T.tail(side.halfedge), b = T.head(side.halfedge), d = T.opposite(o);
    const double outer = T.area(o / 3);
    before += hingeEnergy(s, p, a, b, side.cornerBefore, d, side.areaBefore, outer);
    after += hingeEnergy(s, p, a, b, side.cornerAfter, d, side.areaAfter, outer);
  }
  return after - before;
}

namespace {

// Every pair of surface vertices an edge joins, as a key.
std::set<std::pair<int, int>> edgeEnds(const std::vector<SurfaceEdge>& edges) {
  std::set<std::pair<int, int>> out;
  for (const SurfaceEdge& e : edges) out.insert(std::minmax(e.i, e.j));
  return out;
}

// The surface vertices the flip of h's chord in piece p would join.
std::pair<int, int> newChordEnds(const RuledSurface& s, int p, int h) {
  const PieceTriangulation& T = s.pieces[std::size_t(p)];
  const std::vector<int>& v = s.vertexOf[std::size_t(p)];
  return std::minmax(v[std::size_t(T.opposite(h))], v[std::size_t(T.opposite(T.twin(h)))]);
}

}  // namespace

bool removeDoubleEdges(RuledSurface& surface) {
  for (int guard = 0; guard < 100000; ++guard) {
    const std::vector<SurfaceEdge> edges = surface.edges();
    std::map<std::pair<int, int>, int> count;
    for (const SurfaceEdge& e : edges) ++count[std::minmax(e.i, e.j)];
    bool doubled = false, flipped = false;
    // B's copy first, then A's: a seam chord beside a chord can only lose the chord.
    for (int piece : {1, 0}) {
      for (const SurfaceEdge& e : edges) {
        if (e.kind != EdgeKind::Chord || e.piece != piece || count[std::minmax(e.i, e.j)] < 2)
          continue;
        doubled = true;
        if (!surface.pieces[std::size_t(piece)].flippable(e.halfedge)) continue;
        surface.pieces[std::size_t(piece)].flip(e.halfedge);
        flipped = true;
        break;
      }
      if (flipped) break;
    }
    if (!doubled) return true;
    if (!flipped) return false;
  }
  return false;
}

int flipToConvexHeld(RuledSurface& surface, const std::array<bool, 2>& use) {
  int flips = 0;
  for (; flips < 100000; ++flips) {
    const std::optional<SurfaceEdge> chosen = mostFoldedBack(surface, use);
    if (!chosen) break;
    surface.pieces[std::size_t(chosen->piece)].flip(chosen->halfedge);
  }
  return flips;
}

FlipSearchSummary flipToConvex(RuledSurface& surface, const FlipSearchOptions& options) {
  FlipSearchSummary summary;
  SolveOptions solve = options.solve;
  solve.maxIterations = std::min(solve.maxIterations, 8);
  for (; summary.flips < options.maxFlips; ++summary.flips) {
    const std::optional<SurfaceEdge> chosen = mostFoldedBack(surface, {true, true});
    if (!chosen) {
      summary.stationary = true;
      break;
    }
    surface.pieces[std::size_t(chosen->piece)].flip(chosen->halfedge);
    solveLengths(surface, solve);
  }
  const SolveSummary last = solveLengths(surface, options.solve);
  summary.message = last.converged ? "" : last.message;
  return summary;
}

FlipSearchSummary flipToLessBending(RuledSurface& surface, const FlipSearchOptions& options) {
  FlipSearchSummary summary;
  SolveOptions restore = options.solve;
  restore.maxIterations = 20;
  restore.initialDamping = 1e-8;
  SolveOptions bend = options.solve;
  bend.maxIterations = 8;
  double energy = bendingEnergy(surface, surface.edges());
  while (summary.flips < options.maxFlips) {
    const std::vector<SurfaceEdge> edges = surface.edges();
    const std::set<std::pair<int, int>> ends = edgeEnds(edges);
    std::vector<std::pair<double, std::size_t>> estimates;
    for (std::size_t c = 0; c < edges.size(); ++c) {
      const SurfaceEdge& e = edges[c];
      if (e.kind != EdgeKind::Chord ||
          !surface.pieces[std::size_t(e.piece)].flippable(e.halfedge) ||
          ends.count(newChordEnds(surface, e.piece, e.halfedge)))
        continue;
      const double change = flipBendingChange(surface, e.piece, e.halfedge);
      // Lower with the positions held by more than rounding of the energy.
      if (change < -1e-12 * energy) estimates.emplace_back(change, c);
    }
    std::sort(estimates.begin(), estimates.end());
    bool accepted = false;
    // First every candidate whose quadrilateral and the faces beside it no better candidate
    // touches, flipped together and solved once; where that does not lower the energy, one at a
    // time, best first.
    if (estimates.size() > 1) {
      RuledSurface trial = surface;
      std::set<std::pair<int, int>> used;  // (piece, face)
      int batch = 0;
      for (const auto& [change, c] : estimates) {
        const SurfaceEdge& e = edges[c];
        const PieceTriangulation& T = trial.pieces[std::size_t(e.piece)];
        std::vector<int> faces{e.halfedge / 3, T.twin(e.halfedge) / 3};
        for (int side : {T.next(e.halfedge), T.prev(e.halfedge), T.next(T.twin(e.halfedge)),
                         T.prev(T.twin(e.halfedge))})
          if (T.twin(side) >= 0) faces.push_back(T.twin(side) / 3);
        if (std::any_of(faces.begin(), faces.end(), [&](int f) {
              return used.count({e.piece, f}) > 0;
            }))
          continue;
        for (int f : faces) used.insert({e.piece, f});
        trial.pieces[std::size_t(e.piece)].flip(e.halfedge);
        ++batch;
      }
      if (batch > 1 && !trial.hasDoubleEdge() && solveLengths(trial, restore).converged) {
        summary.tried += batch;
        const SolveSummary bent = minimiseBending(trial, bend);
        if (bent.maxLengthError <= 1e-9 && bent.bendingEnergy < energy * (1 - 1e-9)) {
          surface = std::move(trial);
          energy = bent.bendingEnergy;
          summary.flips += batch;
          continue;
        }
      }
    }
    for (std::size_t k = 0; k < estimates.size() && int(k) < options.candidatesPerStep; ++k) {
      const SurfaceEdge& e = edges[estimates[k].second];
      RuledSurface trial = surface;
      trial.pieces[std::size_t(e.piece)].flip(e.halfedge);
      ++summary.tried;
      if (!solveLengths(trial, restore).converged) continue;
      const SolveSummary bent = minimiseBending(trial, bend);
      if (!(bent.maxLengthError <= 1e-9) || !(bent.bendingEnergy < energy * (1 - 1e-9))) continue;
      surface = std::move(trial);
      energy = bent.bendingEnergy;
      ++summary.flips;
      accepted = true;
      break;
    }
    if (!accepted) {
      summary.stationary = true;
      break;
    }
  }
  return summary;
}

bool followLengths(RuledSurface& surface, bool flipAtZero, double& t, int& flips) {
  // Each edge's length at t = 0 (where it was first met) and the t it started from.
  std::map<std::tuple<int, int, int>, std::pair<double, double>> from;
  auto record = [&](double at) {
    for (const SurfaceEdge& e : surface.edges())
      from.try_emplace(identity(e), (surface.X.row(e.i) - surface.X.row(e.j)).norm(), at);
  };
  auto lengthsAt = [&](const RuledSurface& s, double at) {
    std::vector<double> out;
    for (const SurfaceEdge& e : s.edges()) {
      const auto [d0, t0] = from.at(identity(e));
      out.push_back(d0 + (at - t0) / (1.0 - t0) * (e.length - d0));
    }
    return out;
  };
  record(0.0);
  SolveOptions step;
  step.maxIterations = 12;
  step.lengthTolerance = 1e-10;
  step.initialDamping = 1e-12;
  t = 0.0;
  flips = 0;
  double dt = 0.05;
  while (t < 1.0) {
    if (dt < 1e-7) return false;
    const double next = std::min(1.0, t + dt);
    RuledSurface trial = surface;
    const std::vector<double> L = lengthsAt(trial, next);
    if (!solveLengths(trial, step, &L).converged) {
      dt *= 0.5;
      continue;
    }
    const SurfaceEdge* crossing = nullptr;
    const std::vector<SurfaceEdge> before = surface.edges(), after = trial.edges();
    double deepest = 0.0;
    for (std::size_t e = 0; flipAtZero && e < before.size(); ++e) {
      if (before[e].kind != EdgeKind::Chord) continue;
      const double b = dihedralOf(trial, after[e]);
      if (dihedralOf(surface, before[e]) > 0.0 && b < deepest &&
          trial.pieces[std::size_t(after[e].piece)].flippable(after[e].halfedge) &&
          flipKeepsSingle(trial, after[e])) {
        deepest = b;
        crossing = &after[e];
      }
    }
    // A chord crosses zero in this step: step shorter to flip it near where it is flat.
    if (crossing && dt > 1e-5) {
      dt *= 0.5;
      continue;
    }
    if (crossing) {
      const auto ends2 = newChordEnds(trial, crossing->piece, crossing->halfedge);
      from.erase({crossing->piece, ends2.first, ends2.second});
      trial.pieces[std::size_t(crossing->piece)].flip(crossing->halfedge);
      ++flips;
    }
    surface = std::move(trial);
    t = next;
    if (crossing) record(t);
    dt = std::min(0.05, 1.5 * dt);
  }
  return true;
}

}  // namespace dform::ruled
