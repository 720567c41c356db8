// SPDX-License-Identifier: GPL-3.0-or-later
#include "isometric_states.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "dform/core/constants.h"
#include "dform/core/interrupt.h"
#include "dform/exact/aligned_distance.h"
#include "dform/forward/settings.h"
#include "dform/model/run_control.h"
#include "dform/model/transfer.h"

namespace dform::forward_detail {

namespace {

// The stages of the continuation in the lengths tried where a start cannot be made exact at once.
constexpr int kContinuationStages = 4;

// A state's seam points, in seam order.
Points3 seamOf(const DForm& m) {
  Points3 out(Eigen::Index(m.a.seam.size()), 3);
  for (std::size_t k = 0; k < m.a.seam.size(); ++k)
    out.row(Eigen::Index(k)) = m.a.shape.row(m.a.seam[k]);
  return out;
}

// The distance between two states' seams, one of them mirrored or not (a mirror image is the
// same shape seen from its other side, with the same energy), over the seam's diagonal.
double seamDistance(const DForm& a, const DForm& b) {
  const Points3 P = seamOf(a), Q = seamOf(b);
  Points3 mirrored = Q;
  mirrored.col(2) *= -1.0;
  return std::min(exact::alignedDistance(P, Q).maxRel, exact::alignedDistance(P, mirrored).maxRel);
}

// The resolutions a state made at `from` passes through on its way to the finer `to`: each twice
// the one below, `to` last.
std::vector<int> ladder(int from, int to) {
  std::vector<int> levels{from};
  while (2 * levels.back() < to) levels.push_back(2 * levels.back());
  if (levels.back() != to) levels.push_back(to);
  return levels;
}

// Where the coarser state's vertices inside the pieces are kept in a finer mesh: the nearest
// finer vertex within this fraction of the finer mesh's mean edge moves onto each.
constexpr double kKeptVertexReach = 0.6;
// A kept vertex thins none of its triangles below this fraction of its area (nor turns one over).
constexpr double kKeptVertexThinnest = 0.1;

// A piece's vertices on its outline (seam and free boundaries).
std::vector<bool> onOutline(const Piece& piece) {
  std::vector<bool> outline(std::size_t(piece.flat.rows()), false);
  for (int v : piece.seam) outline[std::size_t(v)] = true;
  for (const std::vector<int>& loop : piece.freeBoundaries)
    for (int v : loop) outline[std::size_t(v)] = true;
  return outline;
}

double doubleArea(const Points2& V, const Faces& F, Eigen::Index f) {
  const Eigen::Vector2d x = V.row(F(f, 1)) - V.row(F(f, 0)), y = V.row(F(f, 2)) - V.row(F(f, 0));
  return x.x() * y.y() - x.y() * y.x();
}

// `fine`'s vertices inside the piece moved onto `coarse`'s (kKeptVertexReach, kKeptVertexThinnest),
// each coarse vertex in turn taking the nearest fine one not yet moved.
void keepVerticesOf(const Piece& coarse, Piece& fine) {
  const std::vector<bool> coarseOutline = onOutline(coarse), fineOutline = onOutline(fine);
  double edges = 0.0;
  for (Eigen::Index f = 0; f < fine.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      edges += (fine.flat.row(fine.F(f, c)) - fine.flat.row(fine.F(f, (c + 1) % 3))).norm();
  const double reach =
      kKeptVertexReach * edges / double(std::max<Eigen::Index>(1, 3 * fine.F.rows()));
  // The fine vertices inside the piece bucketed in cells of side `reach`: a vertex within reach
  // of a point lies in its cell or the eight around it.
  const Eigen::RowVector2d lo = fine.flat.colwise().minCoeff();
  auto cellOf = [&](const Eigen::RowVector2d& q) {
    return std::pair<long, long>{long(std::floor((q.x() - lo.x()) / reach)),
                                 long(std::floor((q.y() - lo.y()) / reach))};
  };
  std::map<std::pair<long, long>, std::vector<int>> cells;
  for (Eigen::Index v = 0; v < fine.flat.rows(); ++v)
    if (!fineOutline[std::size_t(v)]) cells[cellOf(fine.flat.row(v))].push_back(int(v));
  std::vector<std::vector<int>> triangles(std::size_t(fine.flat.rows()));
  for (Eigen::Index f = 0; f < fine.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) triangles[std::size_t(fine.F(f, c))].push_back(int(f));
  std::vector<bool> moved(std::size_t(fine.flat.rows()), false);
  for (Eigen::Index v = 0; v < coarse.flat.rows(); ++v) {
    if (coarseOutline[std::size_t(v)]) continue;
    const Eigen::RowVector2d target = coarse.flat.row(v);
    const auto [cx, cy] = cellOf(target);
    int nearest = -1;
    double distance = reach;
    for (long y = cy - 1; y <= cy + 1; ++y)
      for (long x = cx - 1; x <= cx + 1; ++x) {
        const auto cell = cells.find({x, y});
        if (cell == cells.end()) continue;
        for (int w : cell->second) {
          const double d = (fine.flat.row(w) - target).norm();
          if (!moved[std::size_t(w)] && (d < distance || (d == distance && w < nearest)))
            distance = d, nearest = w;
        }
      }
    if (nearest < 0) continue;
    const Eigen::RowVector2d was = fine.flat.row(nearest);
    std::vector<double> before;
    for (int f : triangles[std::size_t(nearest)])
      before.push_back(doubleArea(fine.flat, fine.F, f));
    fine.flat.row(nearest) = target;
    bool kept = true;
    for (std::size_t t = 0; t < before.size() && kept; ++t) {
      const double after = doubleArea(fine.flat, fine.F, triangles[std::size_t(nearest)][t]);
      kept =
          after * before[t] > 0.0 && std::abs(after) >= kKeptVertexThinnest * std::abs(before[t]);
    }
    if (kept)
      moved[std::size_t(nearest)] = true;
    else
      fine.flat.row(nearest) = was;
  }
}

// `below` (an exact state, or the paper model's shape, on a mesh of `belowFactor`) ready to be
// made exact at `resolution` on a mesh of interior edge `factor`: both pieces meshed there (with
// `below`'s vertices inside the pieces kept where asked: keepVerticesOf) and started from it.
// Where `below` is already at `resolution` on that mesh, `below` itself. A failure is added to
// `why`.
std::optional<DForm> startOnto(const DForm& below, double belowFactor, int resolution,
                               double factor, bool keepVertices, const IsometricLevels& levels,
                               std::string& why) {
  if (int(below.a.seam.size()) == resolution && factor == belowFactor) return below;
  Result<std::array<Piece, 2>> meshed = levels.mesh(resolution, factor);
  if (!meshed.isOk()) {
    why += (why.empty() ? "" : "; ") + meshed.status().message();
    return std::nullopt;
  }
  DForm start;
  start.a = std::move(meshed.value()[0]);
  start.b = std::move(meshed.value()[1]);
  if (keepVertices) {
    keepVerticesOf(below.a, start.a);
    keepVerticesOf(below.b, start.b);
  }
  startFromCoarser(below, start.a, start.b);
  return start;
}

// `start` (startOnto) made exact in `stages` stages. A failure is added to `why`.
std::optional<IsometricState> madeExact(const DForm& start, int resolution, double factor,
                                        bool keepVertices, int stages, std::string& why) {
  ruled::IsometricMeshOptions options;
  options.stages = stages;
  Result<ruled::IsometricMesh> made = ruled::isometricMesh(start, options);
  if (made.isOk()) return IsometricState{"", std::move(made).value(), factor, 0, 0.0};
  why += (why.empty() ? "" : "; ") +
         detail::format("%d seam points, interior edge %g%s, %d stage(s): ", resolution, factor,
                        keepVertices ? " keeping the coarser vertices" : "", stages) +
         made.status().message();
  return std::nullopt;
}

// `below` carried to `resolution` on a mesh of interior edge `factor` (startOnto) and made exact,
// first at once and then by a continuation in the lengths. A failure is added to `why`.
std::optional<IsometricState> carryOnto(const DForm& below, double belowFactor, int resolution,
                                        double factor, bool keepVertices,
                                        const IsometricLevels& levels, std::string& why) {
  const std::optional<DForm> start =
      startOnto(below, belowFactor, resolution, factor, keepVertices, levels, why);
  if (!start) return std::nullopt;
  for (int stages : {1, kContinuationStages})
    if (std::optional<IsometricState> state =
            madeExact(*start, resolution, factor, keepVertices, stages, why))
      return state;
  return std::nullopt;
}

// The way round a mesh that cannot be made exact: `below` carried onto twice the interior edge
// (`coarse`), and from there onto the given one again (`refined`, its steps counted from below).
struct ViaCoarser {
  std::optional<IsometricState> coarse, refined;
  bool stoppedAfterCoarse = false;  // the caller asked to stop once `coarse` was made
  std::string why;                  // the failures, in the order they came
};

ViaCoarser viaCoarser(const DForm& below, double belowFactor, int resolution,
                      double interiorEdgeFactor, const IsometricLevels& levels) {
  ViaCoarser out;
  const double coarser = std::min(kMaxInteriorEdgeFactor, 2.0 * interiorEdgeFactor);
  if (coarser == interiorEdgeFactor) return out;
  out.coarse = carryOnto(below, belowFactor, resolution, coarser, false, levels, out.why);
  if (!out.coarse) return out;
  if (levels.stop()) {
    out.stoppedAfterCoarse = true;
    return out;
  }
  out.refined = carryOnto(out.coarse->exact.model, coarser, resolution, interiorEdgeFactor, false,
                          levels, out.why);
  if (out.refined) out.refined->exact.steps += out.coarse->exact.steps;
  return out;
}

// `below` carried to `resolution` on the given interior edge. Where its start there cannot be
// made exact at once: by a continuation in the lengths, else on twice the interior edge and from
// there onto the given one again (viaCoarser: the seam points stay and only the pieces' insides
// are refined, a smaller step than from the level below; the non-convex answer at 800 seam
// points, and the demi sample's other state at 400, are made so). The continuation and the way
// round are made side by side (the non-convex pair zipped from B's start at 0.5 fails both
// attempts on the job's mesh at 100 seam points, 0.26 s, and is made via the coarser one in 0.08
// s), the first that holds taken in that order. Where both fail, on the given interior edge
// keeping `below`'s vertices inside the pieces: where the state below folds at a vertex inside a
// piece (folds meeting there, as in the non-convex sample's dent), the finer mesh then has a
// vertex at that place to fold at (the non-convex answer from 100 to 150 seam points, whose seam
// points are not 100's, is made so). Where only twice the interior edge holds a state, that
// state.
Result<IsometricState> carry(const DForm& below, double belowFactor, int resolution,
                             double interiorEdgeFactor, const IsometricLevels& levels) {
  std::string why;
  const std::optional<DForm> start =
      startOnto(below, belowFactor, resolution, interiorEdgeFactor, false, levels, why);
  if (start)
    if (std::optional<IsometricState> state =
            madeExact(*start, resolution, interiorEdgeFactor, false, 1, why))
      return std::move(*state);
  ViaCoarser via;
  {
    Beside<ViaCoarser> coarser(
        levels.sideBySide && start.has_value(),
        [&] { return viaCoarser(below, belowFactor, resolution, interiorEdgeFactor, levels); },
        levels.stop);
    if (start)
      if (std::optional<IsometricState> state =
              madeExact(*start, resolution, interiorEdgeFactor, false, kContinuationStages, why))
        return std::move(*state);
    via = coarser.get();
  }
  if (!via.why.empty()) why += (why.empty() ? "" : "; ") + via.why;
  if (via.refined) return std::move(*via.refined);
  if (via.stoppedAfterCoarse) return std::move(*via.coarse);
  if (levels.stop()) return Status(ErrorCode::Interrupted, "the run was stopped");
  if (std::optional<IsometricState> kept =
          carryOnto(below, belowFactor, resolution, interiorEdgeFactor, true, levels, why))
    return std::move(*kept);
  if (via.coarse) return std::move(*via.coarse);
  return Status(ErrorCode::SolveFailed, why);
}

// `start` (on a mesh of `startFactor`) carried through the resolutions `ladder`, made exact at
// each on meshes of `interiorEdgeFactor` (or twice it).
Result<IsometricState> carried(DForm start, double startFactor, const std::vector<int>& ladder,
                               double interiorEdgeFactor, const IsometricLevels& levels) {
  IsometricState state;
  int steps = 0;
  for (int n : ladder) {
    if (levels.stop()) return Status(ErrorCode::Interrupted, "the run was stopped");
    Result<IsometricState> level = carry(start, startFactor, n, interiorEdgeFactor, levels);
    if (!level.isOk()) return level.status();
    steps += level.value().exact.steps;
    start = level.value().exact.model;
    startFactor = level.value().interiorEdgeFactor;
    state = std::move(level).value();
  }
  state.steps = steps;
  return state;
}

// The state `levels.paperShape(from)` leads to at the ranking resolution.
Result<IsometricState> stateFrom(int from, int ranking, bool reportsProgress,
                                 double interiorEdgeFactor, const IsometricLevels& levels) {
  if (levels.stop()) return Status(ErrorCode::Interrupted, "the run was stopped");
  Result<DForm> paper = levels.paperShape(from, reportsProgress);
  if (!paper.isOk()) return paper.status();
  return carried(std::move(paper).value(), interiorEdgeFactor, ladder(from, ranking),
                 interiorEdgeFactor, levels);
}

}  // namespace

IsometricStates isometricStates(int resolution, double interiorEdgeFactor,
                                const IsometricLevels& levels, double sameState) {
  // Each start's state made at the ranking resolution, then carried to the job's. A job coarser
  // than a start resolution (the studio's previews, at 36 seam points) starts at its own instead:
  // a start finer than the job costs more than the job.
  const int ranking = std::min(kIsometricStartResolutions.back(), resolution);
  std::vector<int> starts;
  for (int n : kIsometricStartResolutions)
    if (std::find(starts.begin(), starts.end(), std::min(n, resolution)) == starts.end())
      starts.push_back(std::min(n, resolution));
  IsometricStates found;
  auto distinct = [&](const IsometricState& state) {
    return std::none_of(found.states.begin(), found.states.end(), [&](const IsometricState& o) {
      return seamDistance(o.exact.model, state.exact.model) <= sameState;
    });
  };
  // The starts do not depend on each other: every one but the last is made on a thread of its own
  // (Beside: it reports no progress) while this thread makes the last. Their states are then
  // taken in the starts' order, so the answer is the one a single thread gives.
  std::vector<std::unique_ptr<Beside<Result<IsometricState>>>> beside;
  for (std::size_t s = 0; s + 1 < starts.size(); ++s)
    beside.push_back(std::make_unique<Beside<Result<IsometricState>>>(
        levels.sideBySide,
        [&, from = starts[s]] {
          return stateFrom(from, ranking, false, interiorEdgeFactor, levels);
        },
        levels.stop));
  std::vector<std::optional<Result<IsometricState>>> made(starts.size());
  made.back() = stateFrom(starts.back(), ranking, true, interiorEdgeFactor, levels);
  for (std::size_t s = 0; s < beside.size(); ++s) made[s] = beside[s]->get();
  for (std::size_t s = 0; s < starts.size(); ++s) {
    const std::string name = detail::format("the paper model's shape at %d seam points", starts[s]);
    if (levels.stop()) return found;
    Result<IsometricState>& state = *made[s];
    if (!state.isOk()) {
      found.failures.emplace_back(name, state.status().message());
      continue;
    }
    state.value().start = name;
    state.value().rankingEnergy = state.value().exact.bendingEnergy;
    if (distinct(state.value())) found.states.push_back(std::move(state).value());
  }
  std::stable_sort(found.states.begin(), found.states.end(),
                   [](const IsometricState& a, const IsometricState& b) {
                     return a.rankingEnergy < b.rankingEnergy;
                   });
  if (resolution == ranking) return found;
  std::vector<IsometricState> atRanking = std::move(found.states);
  found.states.clear();
  for (IsometricState& state : atRanking) {
    if (levels.stop()) return found;
    std::vector<int> rest = ladder(ranking, resolution);
    rest.erase(rest.begin());  // the state is exact at the ranking resolution
    Result<IsometricState> carriedState =
        carried(state.exact.model, state.interiorEdgeFactor, rest, interiorEdgeFactor, levels);
    if (!carriedState.isOk()) {
      found.failures.emplace_back(state.start, carriedState.status().message());
      continue;
    }
    carriedState.value().start = state.start;
    carriedState.value().rankingEnergy = state.rankingEnergy;
    carriedState.value().steps += state.steps;
    if (distinct(carriedState.value())) found.states.push_back(std::move(carriedState).value());
  }
  return found;
}

}  // namespace dform::forward_detail
