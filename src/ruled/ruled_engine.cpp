// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/ruled/ruled_engine.h"

#include <algorithm>
#include <cmath>

#include "dform/exact/aligned_distance.h"

namespace dform::ruled {

namespace {

bool closed(const RuledSurface& s) { return s.freeRows[0].empty() && s.freeRows[1].empty(); }

// The seam's points of a state, in seam order.
Points3 seamOf(const RuledSurface& s) {
  const std::vector<int>& rows = s.seamRows[0];
  Points3 out(Eigen::Index(rows.size()), 3);
  for (std::size_t k = 0; k < rows.size(); ++k)
    out.row(Eigen::Index(k)) = s.X.row(s.vertexOf[0][std::size_t(rows[k])]);
  return out;
}

// The distance between two states' seams, one of them mirrored or not: a mirror image of a state
// is the same shape seen from its other side, with the same energy.
double seamDistance(const RuledSurface& a, const RuledSurface& b) {
  const Points3 P = seamOf(a), Q = seamOf(b);
  Points3 mirrored = Q;
  mirrored.col(2) *= -1.0;
  return std::min(exact::alignedDistance(P, Q).maxRel, exact::alignedDistance(P, mirrored).maxRel);
}

// One start through the search; false with `why` when it gives no state.
bool solveFrom(RuledSurface& s, const RuledOptions& options, RuledState& state, std::string& why) {
  if (!removeDoubleEdges(s)) {
    why = "a chord of both pieces joins the same two seam points and cannot be flipped";
    return false;
  }
  if (closed(s)) {
    // The convex triangulation of the start where it has one: for a start near a convex body,
    // that body's faces, from which Newton converges.
    flipToConvexHeld(s);
    const SolveSummary first = solveLengths(s, options.solve);
    if (!first.converged) {
      why = "the lengths cannot all be met from the start's convex triangulation (largest error " +
            std::to_string(100.0 * first.maxLengthError) + " %)";
      return false;
    }
    const FlipSearchSummary lawson = flipToConvex(s, options.flips);
    const SolveSummary met = solveLengths(s, options.solve);
    if (!met.converged) {
      why = "the lengths cannot all be met (largest error " +
            std::to_string(100.0 * met.maxLengthError) + " %)";
      return false;
    }
    state.flips = lawson.flips;
    state.flipsStationary = lawson.stationary;
    state.stationarity = 0.0;
  } else {
    double t = 0.0;
    int pathFlips = 0;
    if (!followLengths(s, false, t, pathFlips)) {
      why = "the lengths could not be followed from the start's to the flat ones (stopped at " +
            std::to_string(t) + " of the way)";
      return false;
    }
    minimiseBending(s, options.solve);
    const FlipSearchSummary flips = flipToLessBending(s, options.flips);
    const SolveSummary bent = minimiseBending(s, options.solve);
    if (!(bent.maxLengthError <= 1e-9)) {
      why = "the lengths were lost while the bending energy was minimised";
      return false;
    }
    state.flips = flips.flips;
    state.flipsStationary = flips.stationary;
    state.stationarity = bent.stationarity;
  }
  const std::vector<SurfaceEdge> edges = s.edges();
  state.bendingEnergy = bendingEnergy(s, edges);
  state.maxLengthError = maxLengthError(s, edges);
  state.largestFold = largestFold(s);
  state.surface = s;
  return true;
}

}  // namespace

double largestFold(const RuledSurface& surface) {
  double largest = 0.0;
  for (const SurfaceEdge& e : surface.edges())
    if (e.kind == EdgeKind::Chord)
      largest = std::max(largest, std::abs(dihedral(surface.X.row(e.i), surface.X.row(e.j),
                                                    surface.X.row(e.k), surface.X.row(e.l))));
  return largest;
}

RuledResult solveRuled(const RuledSurface& blank, const std::vector<RuledStart>& starts,
                       const RuledOptions& options) {
  RuledResult result;
  for (const RuledStart& start : starts) {
    RuledSurface s = blank;
    s.X = start.X;
    RuledState state;
    state.start = start.name;
    std::string why;
    if (!solveFrom(s, options, state, why)) {
      result.failures.emplace_back(start.name, why);
      continue;
    }
    const bool known =
        std::any_of(result.states.begin(), result.states.end(), [&](const RuledState& o) {
          return seamDistance(o.surface, state.surface) <= options.sameState;
        });
    if (!known) result.states.push_back(std::move(state));
  }
  std::stable_sort(
      result.states.begin(), result.states.end(),
      [](const RuledState& a, const RuledState& b) { return a.bendingEnergy < b.bendingEnergy; });
  return result;
}

}  // namespace dform::ruled
