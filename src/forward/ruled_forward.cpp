// SPDX-License-Identifier: GPL-3.0-or-later
#include "ruled_forward.h"

#include <algorithm>
#include <cmath>

#include "dform/core/constants.h"
#include "dform/core/polyline.h"
#include "dform/model/ruled_model.h"
#include "dform/model/run_control.h"
#include "dform/ruled/ruled_engine.h"

namespace dform::forward_detail {

using detail::format;

namespace {

// A drawn crease as the straight line between its ends, if it is one: every point within 1e-6 of
// its length of that line (a curved crease is no chord of the piece).
bool straightCrease(const Points2& crease, Eigen::Vector2d& from, Eigen::Vector2d& to) {
  from = crease.row(0).transpose();
  to = crease.row(crease.rows() - 1).transpose();
  const Eigen::Vector2d u = (to - from).normalized();
  const double length = (to - from).norm();
  for (Eigen::Index k = 1; k + 1 < crease.rows(); ++k) {
    const Eigen::Vector2d d = crease.row(k).transpose() - from;
    if (std::abs(u.x() * d.y() - u.y() * d.x()) > 1e-6 * length) return false;
  }
  return true;
}

// The seam, the free outlines sampled as the paper model's finest level samples them, and the
// straight creases.
RuledPieces piecesOf(const ForwardSettings& job, const SeamLayout& layout, double perimeterA) {
  RuledPieces out;
  out.seam = seamPolygons(layout.pieces, layout.startFraction, layout.direction,
                          seamFractions(job.resolution, layout.seamCorners));
  exact::equalizeChords(out.seam);
  const double seamEdge = perimeterA / job.resolution;
  for (int p = 0; p < 2; ++p) {
    const DrawnPiece& piece = layout.pieces[p];
    if (piece.freeOutline) {
      const int m = std::max(3, int(std::lround(closedLength(*piece.freeOutline) / seamEdge)));
      out.freeOutline[std::size_t(p)] =
          sampleLoop(*piece.freeOutline, seamFractions(m, layout.freeCorners[p]),
                     layout.freeStart[p], 1)
              .rows;
    }
    for (const Points2& crease : piece.creases) {
      Eigen::Vector2d from, to;
      straightCrease(crease, from, to);
      out.creases[std::size_t(p)].emplace_back(from, to);
    }
  }
  return out;
}

// The starts: each shape, and where the sheet has a free brim its mirror image (a sheet with a
// brim may sit either way; a closed one has one convex state).
std::vector<ruled::RuledStart> startsOf(const std::vector<NamedShape>& shapes,
                                        const ruled::RuledSurface& blank) {
  const bool brim = !blank.freeRows[0].empty() || !blank.freeRows[1].empty();
  std::vector<ruled::RuledStart> starts;
  for (const NamedShape& shape : shapes) {
    starts.push_back({shape.name, ruledStartOf(shape.model, blank)});
    if (brim) {
      Points3 mirrored = starts.back().X;
      mirrored.col(2) *= -1.0;
      starts.push_back({shape.name + ", mirrored", std::move(mirrored)});
    }
  }
  return starts;
}

}  // namespace

std::string ruledModelRefusal(const ForwardSettings& job, const SeamLayout& layout, bool asked) {
  for (int p = 0; p < 2; ++p)
    for (const Points2& crease : layout.pieces[p].creases) {
      Eigen::Vector2d from, to;
      if (!straightCrease(crease, from, to))
        return "a drawn crease of " + layout.paths[p] +
               " is curved: the ruled engine folds along straight chords only";
    }
  if (job.resolution > ruled::kMaxRuledSeam)
    return "the seam has " + std::to_string(job.resolution) +
           " points, more than the ruled engine's " + std::to_string(ruled::kMaxRuledSeam);
  if (asked || (layout.pieces[0].freeOutline && layout.pieces[1].freeOutline)) return "";
  const auto [point, degrees] = negativelyCurvedSeamPoint(job, layout);
  if (point >= 0)
    return "a piece zipped along its outline meets a seam point of negative curvature (point " +
           std::to_string(point) +
           format(
               ", %.3f degrees): the ruled engine makes no state there without folding the "
               "sheet back",
               degrees);
  return "";
}

std::pair<int, double> negativelyCurvedSeamPoint(const ForwardSettings& job,
                                                 const SeamLayout& layout) {
  exact::SeamPolygons seam = seamPolygons(layout.pieces, layout.startFraction, layout.direction,
                                          seamFractions(job.resolution, layout.seamCorners));
  exact::equalizeChords(seam);
  const exact::SeamAngles angles = exact::seamAngles(seam);
  const int k = angles.firstNonConvex;
  return {k, k < 0 ? 0.0 : (angles.a[k] + angles.b[k]) / kDegree};
}

Status solveRuledModel(const ForwardSettings& job, const SeamLayout& layout, SolvedDForm& run,
                       const std::vector<NamedShape>& otherStarts, MessageSink& sink,
                       double largestFoldDeg) {
  const RuledPieces pieces = piecesOf(job, layout, run.perimeterA);
  Result<ruled::RuledSurface> blank = ruledSurface(pieces, layout.paths);
  if (!blank.isOk()) return blank.status();
  std::vector<NamedShape> shapes{{"the paper model's shape", run.model}};
  shapes.insert(shapes.end(), otherStarts.begin(), otherStarts.end());
  const ruled::RuledResult solved =
      ruled::solveRuled(blank.value(), startsOf(shapes, blank.value()));
  if (solved.states.empty()) {
    std::string why;
    for (const auto& [start, reason] : solved.failures)
      why += (why.empty() ? "" : "; ") + ("from " + start + ": " + reason);
    return Status(ErrorCode::SolveFailed, "the ruled engine found no state (" + why + ")");
  }
  const ruled::RuledState& best = solved.states.front();
  if (best.largestFold / kDegree > largestFoldDeg)
    return Status(ErrorCode::SolveFailed,
                  format("its least bending state folds a chord by %.1f degrees, the sheet back "
                         "on itself",
                         best.largestFold / kDegree));
  ModelUsed used;
  Result<DForm> meshed = ruledDForm(
      best.surface, job.interiorEdgeFactor * run.perimeterA / job.resolution, layout.paths, used);
  if (!meshed.isOk()) return meshed.status();
  used.name = "ruled";
  used.bendingEnergy = best.bendingEnergy;
  used.lengthError = best.maxLengthError;
  used.flips = best.flips;
  used.flipsStationary = best.flipsStationary;
  used.stationarity = best.stationarity;
  for (const ruled::RuledState& state : solved.states)
    used.states.push_back(
        {state.start, state.bendingEnergy, state.largestFold / kDegree, state.bendingEnergy});
  sink.info(format("ruled engine: %zu state(s); the answer, from ", solved.states.size()) +
            best.start +
            format(", has bending energy %.6g, edge lengths met to %.2g, %d flips",
                   best.bendingEnergy, best.maxLengthError, best.flips));
  for (std::size_t s = 1; s < solved.states.size(); ++s)
    sink.warning(
        "the sheet can also sit another way: from " + solved.states[s].start +
        format(", bending energy %.6g (report.json model.states)", solved.states[s].bendingEnergy));
  run.otherStates.clear();
  for (std::size_t s = 1; s < solved.states.size(); ++s) {
    ModelUsed unused;
    Result<DForm> other =
        ruledDForm(solved.states[s].surface,
                   job.interiorEdgeFactor * run.perimeterA / job.resolution, layout.paths, unused);
    run.otherStates.push_back(other.isOk() ? std::move(other).value() : DForm{});
  }
  run.model = std::move(meshed).value();
  run.modelUsed = std::move(used);
  return Status::ok();
}

}  // namespace dform::forward_detail
