// SPDX-License-Identifier: GPL-3.0-or-later
#include "seam_layout.h"

#include <algorithm>
#include <cmath>

#include "dform/core/polyline.h"
#include "dform/model/run_control.h"

namespace dform {

std::vector<double> seamFractions(int n, std::vector<double> corners) {
  std::vector<double> uniform(n);
  for (int k = 0; k < n; ++k) uniform[k] = double(k) / n;
  if (int(corners.size()) > n / 2) return uniform;
  for (double& c : corners) c -= std::floor(c);
  // The first seam point: the start, or the corner nearest it within half a seam edge. The seam
  // pairs the two loops by arc length from the starting pair, so sampling that pairing from a
  // corner beside the start zips the same pieces the same way; sampled from the start instead,
  // a corner just behind it would be cut off by the last chord, and one just ahead would leave a
  // chord far shorter than the others.
  double first = 0.0, nearest = 0.5 / n;
  for (double c : corners)
    for (double at : {c, c - 1.0})
      if (std::abs(at) < nearest) first = at, nearest = std::abs(at);
  const double end = first + 1.0;
  for (double& c : corners)
    if (c < first) c += 1.0;
  std::sort(corners.begin(), corners.end());
  // Corners closer than kSameCorner of a seam edge are one.
  std::vector<double> breaks{first};
  for (double c : corners)
    if (c - breaks.back() > kSameCorner / n && end - c > kSameCorner / n) breaks.push_back(c);
  const int m = int(breaks.size());
  std::vector<double> lengths(m);
  for (int j = 0; j < m; ++j) lengths[j] = (j + 1 < m ? breaks[j + 1] : end) - breaks[j];
  // Largest-remainder apportionment with at least one vertex per stretch.
  std::vector<int> counts(m);
  int assigned = 0;
  for (int j = 0; j < m; ++j) assigned += counts[j] = std::max(1, int(lengths[j] * n));
  while (assigned != n) {
    int pick = -1;
    double bestGap = 0;
    for (int j = 0; j < m; ++j) {
      const double gap = lengths[j] * n - counts[j];  // > 0: the stretch wants more vertices
      const bool eligible = assigned < n || counts[j] > 1;
      if (eligible && (pick < 0 || (assigned < n ? gap > bestGap : gap < bestGap)))
        pick = j, bestGap = gap;
    }
    counts[pick] += assigned < n ? 1 : -1;
    assigned += assigned < n ? 1 : -1;
  }
  std::vector<double> fractions;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < counts[j]; ++i) fractions.push_back(breaks[j] + lengths[j] * i / counts[j]);
  return fractions;
}

namespace forward_detail {

using detail::format;

namespace {

// The point at arc-length fraction t of the closed polyline P.
Eigen::Vector2d pointAtFraction(const Points2& P, double t) {
  return resampleClosed(P, 1, t).row(0).transpose();
}

double resolveFraction(const Points2& P, const StartPoint& start) {
  return start.nearestToPoint ? nearestArcFraction(P, start.point) : start.fraction;
}

// Applies the row map f to every line of the piece.
template <typename F>
void mapPiece(DrawnPiece& piece, F f) {
  piece.joined = f(piece.joined);
  if (piece.freeOutline) piece.freeOutline = f(*piece.freeOutline);
  for (Points2& crease : piece.creases) crease = f(crease);
}

// Piece B turned over: mirrored in x, loops reordered counter-clockwise. `start` follows the
// mirror.
void mirror(DrawnPiece& piece, StartPoint& start) {
  const Eigen::Vector2d startPoint =
      start.nearestToPoint ? start.point : pointAtFraction(piece.joined, start.fraction);
  mapPiece(piece,
           [](const Points2& P) { return Points2(P * Eigen::Vector2d(-1.0, 1.0).asDiagonal()); });
  piece.joined = piece.joined.colwise().reverse().eval();
  if (piece.freeOutline) piece.freeOutline = piece.freeOutline->colwise().reverse().eval();
  start.nearestToPoint = true;
  start.point = Eigen::Vector2d(-startPoint.x(), startPoint.y());
}

// Loop fraction c as a fraction of the way from `start` in `direction`.
double fractionFrom(double c, double start, int direction) {
  return std::fmod(direction * (c - start) + 2.0, 1.0);
}

}  // namespace

std::string pieceLabel(const Shape2& shape, const char* name) {
  return shape.outer.source.empty() ? std::string("piece ") + name : shape.outer.source;
}

Result<DrawnPiece> drawnPiece(Shape2& shape, JoinedBoundary join, const std::string& name,
                              MessageSink& sink) {
  const std::string path = pieceLabel(shape, name.c_str());
  const std::size_t holes = shape.holes.size();
  // "piece A (a.svg)" for a file; "piece A" alone when the piece has no file to name.
  const std::string who =
      shape.outer.source.empty() ? path : "piece " + name + " (" + shape.outer.source + ")";
  std::string found = who + ": outline " + format("%.3f mm", closedLength(shape.outer.points));
  for (const Outline2& hole : shape.holes)
    found += format(", hole %.3f mm", closedLength(hole.points));
  if (!shape.creases.empty()) found += ", " + std::to_string(shape.creases.size()) + " crease(s)";
  DrawnPiece piece;
  piece.sha256 = shape.sha256;
  for (CreaseLine& crease : shape.creases) piece.creases.push_back(std::move(crease.points));
  if (join == JoinedBoundary::Outer) {
    if (holes != 0)
      return Status(ErrorCode::InputInvalid,
                    path + ": the outline has " + std::to_string(holes) +
                        " hole(s); a classic D-Form piece must be a disc without holes (to zip a "
                        "hole, as in anti and demi D-Forms, choose it with " +
                        mention(Setting::Join) + ", e.g. " + mention(Setting::Join) +
                        " inner,inner)");
    piece.joined = std::move(shape.outer.points);
    sink.info(found + "; joining its outline");
  } else {
    if (holes != 1)
      return Status(ErrorCode::InputInvalid,
                    path + ": " + mention(Setting::Join) +
                        " inner needs a piece with exactly one hole, and this one has " +
                        std::to_string(holes));
    piece.joined = std::move(shape.holes[0].points);
    piece.freeOutline = std::move(shape.outer.points);
    sink.info(found + "; joining its hole, its outline stays free");
  }
  return piece;
}

LoopSamples sampleLoop(const Points2& P, const std::vector<double>& fractions, double start,
                       int direction) {
  const int n = int(fractions.size());
  std::vector<double> at(n);
  LoopSamples samples;
  samples.order.resize(n);
  for (int k = 0; k < n; ++k) {
    const int row = direction > 0 ? k : (n - k) % n;
    at[row] = start + direction * fractions[k];
    samples.order[k] = row;
  }
  // Inscribed, the samples would fall short of the drawn length by the chord loss, more on a
  // curved outline than on a straight one, and the seam could then not be isometric to both.
  samples.rows = compensateChordLoss(resampleAtFractions(P, at));
  return samples;
}

namespace {

// Whether row k of the closed polygon P lies on the straight line through its neighbours, turning
// forwards: a sample on a straight side of the outline (exact::kFlatCurvature, as the exact engine
// judges a seam point straight).
bool straightAt(const Points2& P, Eigen::Index k) {
  const Eigen::Index n = P.rows();
  const Eigen::Vector2d in = P.row(k) - P.row((k + n - 1) % n);
  const Eigen::Vector2d out = P.row((k + 1) % n) - P.row(k);
  return in.dot(out) > 0.0 && std::abs(in.x() * out.y() - in.y() * out.x()) <=
                                  exact::kFlatCurvature * in.norm() * out.norm();
}

// The compensated samples `moved` of the inscribed ones, with every straight stretch kept on its
// line: the chord-loss compensation moves a sample where a straight side meets a curve out along
// its bisector, off the side's line, and the side's samples next to it would turn backwards (a
// glued metric that is not convex where both pieces are). So each straight stretch's samples and
// the two samples that end it are put back on its line, moved along it only; a sample that ends
// two straight stretches (where two sides meet) stays where it was sampled, on both.
Points2 keptOnStraightSides(const Points2& inscribed, Points2 moved) {
  const Eigen::Index n = inscribed.rows();
  std::vector<bool> onSide(static_cast<std::size_t>(n), false);
  for (Eigen::Index k = 0; k < n; ++k) onSide[std::size_t(k)] = straightAt(inscribed, k);
  auto side = [&](Eigen::Index k) { return bool(onSide[std::size_t((k % n + n) % n)]); };
  for (Eigen::Index lo = 0; lo < n; ++lo) {
    // Each straight stretch once, from its first sample lo (its end lo - 1 not straight).
    if (!side(lo) || side(lo - 1)) continue;
    Eigen::Index hi = lo;
    while (side(hi + 1) && hi - lo < n) ++hi;
    const Eigen::Index first = (lo - 1 + n) % n, last = (hi + 1) % n;
    const Eigen::Vector2d p0 = inscribed.row(first).transpose();
    const Eigen::Vector2d u = (inscribed.row(last).transpose() - p0).normalized();
    for (Eigen::Index j = lo - 1; j <= hi + 1; ++j) {
      const Eigen::Index row = (j % n + n) % n;
      // An end between two straight stretches stays where it was sampled, on both lines.
      if (!side(j) && side(j - 1) && side(j + 1)) {
        moved.row(row) = inscribed.row(row);
        continue;
      }
      moved.row(row) = (p0 + u * u.dot(moved.row(row).transpose() - p0)).transpose();
    }
  }
  return moved;
}

// The sine of the turn at row k of the closed polygon P (> 0: forwards).
double turnSine(const Points2& P, Eigen::Index k) {
  const Eigen::Index n = P.rows();
  const Eigen::Vector2d in = P.row(k) - P.row((k + n - 1) % n);
  const Eigen::Vector2d out = P.row((k + 1) % n) - P.row(k);
  return (in.x() * out.y() - in.y() * out.x()) / (in.norm() * out.norm());
}

// `moved` with every sample that turns forwards (or is straight) as inscribed turning so still:
// the compensation pushes each sample out by the curvature of the circle through it and its
// neighbours, and where the outline's curvature changes within a chord (a side meeting a curve,
// a tight rounded corner) a sample pushed out further than its neighbour turns that neighbour
// backwards. The neighbours' compensation is halved until it turns forwards again.
Points2 keptConvex(const Points2& inscribed, Points2 moved) {
  const Eigen::Index n = inscribed.rows();
  for (int round = 0; round < 64; ++round) {
    bool halved = false;
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!(turnSine(inscribed, k) >= -exact::kFlatCurvature &&
            turnSine(moved, k) < -exact::kFlatCurvature))
        continue;
      for (const Eigen::Index j : {(k + n - 1) % n, (k + 1) % n})
        moved.row(j) = inscribed.row(j) + 0.5 * (moved.row(j) - inscribed.row(j));
      halved = true;
    }
    if (!halved) break;
  }
  return moved;
}

}  // namespace

exact::SeamPolygons seamPolygons(const DrawnPiece pieces[2], const double startFraction[2],
                                 const int direction[2], const std::vector<double>& fractions) {
  const Eigen::Index n = Eigen::Index(fractions.size());
  exact::SeamPolygons polygons;
  Points2* sides[2] = {&polygons.a, &polygons.b};
  for (int p = 0; p < 2; ++p) {
    // Corners of the two pieces closer than kSameCorner of a seam edge share one seam point
    // (seamFractions); on each piece that point is put on the piece's own corner, so that no
    // corner is cut off by a chord that short, nor leaves a cone point that nearly flat there.
    std::vector<double> own = fractions;
    for (double c : cornerFractions(pieces[p].joined, kCornerTurnRadians)) {
      const double at = fractionFrom(c, startFraction[p], direction[p]);
      double* nearest = nullptr;
      double nearestAt = 0.0;
      for (double& f : own)
        for (const double wrap : {-1.0, 0.0, 1.0})
          if (!nearest || std::abs(f - (at + wrap)) < std::abs(*nearest - nearestAt))
            nearest = &f, nearestAt = at + wrap;
      if (std::abs(*nearest - nearestAt) <= kSameCorner / double(n)) *nearest = nearestAt;
    }
    const LoopSamples seam = sampleLoop(pieces[p].joined, own, startFraction[p], direction[p]);
    // The inscribed samples in the same (counter-clockwise) order as sampleLoop's rows.
    std::vector<double> at(fractions.size());
    for (std::size_t k = 0; k < at.size(); ++k)
      at[std::size_t(seam.order[k])] = startFraction[p] + direction[p] * own[k];
    const Points2 inscribed = resampleAtFractions(pieces[p].joined, at);
    const Points2 rows = keptConvex(inscribed, keptOnStraightSides(inscribed, seam.rows));
    sides[p]->resize(n, 2);
    for (Eigen::Index k = 0; k < n; ++k) sides[p]->row(k) = rows.row(seam.order[std::size_t(k)]);
  }
  return polygons;
}

Status matchPieces(const ForwardSettings& job, SeamLayout& layout, SolvedDForm& run,
                   MessageSink& sink) {
  DrawnPiece& A = layout.pieces[0];
  DrawnPiece& B = layout.pieces[1];
  run.perimeterA = closedLength(A.joined);
  run.perimeterB = closedLength(B.joined);
  const double mismatch =
      std::abs(run.perimeterA - run.perimeterB) / std::max(run.perimeterA, run.perimeterB);
  const bool classic = job.joinA == JoinedBoundary::Outer && job.joinB == JoinedBoundary::Outer;
  const std::string lengths = classic ? "the perimeters" : "the joined boundaries' lengths";
  if (mismatch > job.perimeterTolerance) {
    if (!job.fitPerimeter)
      return Status(
          ErrorCode::InputInvalid,
          layout.bothPaths() + ": " + lengths + " differ" +
              format(" (%.3f mm and %.3f mm, %.2f%%", run.perimeterA, run.perimeterB,
                     100.0 * mismatch) +
              format(" > %.2f%%); a D-Form needs equal lengths (", 100.0 * job.perimeterTolerance) +
              mention(Setting::FitPerimeter) + " scales piece B to match)");
  }
  if (job.fitPerimeter) {
    run.scaleB = run.perimeterA / run.perimeterB;
    const Eigen::RowVector2d centre = B.joined.colwise().mean();
    mapPiece(B, [&](const Points2& P) {
      return Points2(((P.rowwise() - centre) * run.scaleB).rowwise() + centre);
    });
    sink.info(format("piece B scaled by %.6f to match piece A's joined length (%.3f mm)",
                     run.scaleB, run.perimeterA));
  }
  StartPoint startB = job.startB;
  if (job.flip) {
    mirror(B, startB);
    sink.info("piece B is zipped turned over (" + mention(Setting::Flip) +
              "): its flat pattern is mirrored");
  }
  run.startFractionA = resolveFraction(A.joined, job.startA);
  run.startFractionB = resolveFraction(B.joined, startB);
  return Status::ok();
}

// The finest mesh's vertices, for the memory check: interior points on a hexagonal lattice of
// spacing h, 2 / (sqrt(3) h^2) per unit area, plus the boundary samples.
double finestVertices(const ForwardSettings& job, const SeamLayout& layout, double perimeterA) {
  const double h = job.interiorEdgeFactor * perimeterA / job.resolution;
  double area = 0.0;
  for (const DrawnPiece& piece : layout.pieces)
    area += piece.freeOutline
                ? std::abs(signedArea(*piece.freeOutline)) - std::abs(signedArea(piece.joined))
                : std::abs(signedArea(piece.joined));
  return 2.0 * area / (std::sqrt(3.0) * h * h) + 2.0 * job.resolution;
}

namespace {

// A segment of an outline is a straight side meeting a curve where it is this many times as long
// as a segment beside it (the curve drawn in shorter ones). A smooth curve drawn in segments of
// slowly varying length (a superellipse's, longest near its flattest points) has none.
constexpr double kSideOverCurve = 4.0;

// The straight sides of the closed polygon P at least `longest` long and meeting a curve (at
// least kSideOverCurve times as long as a segment beside them), as seam fractions (from `start`
// in `direction`): where each begins and how far it runs.
std::vector<std::pair<double, double>> straightSides(const Points2& P, double longest, double start,
                                                     int direction) {
  const Eigen::Index n = P.rows();
  const Eigen::VectorXd s = cumulativeArcLength(P);
  const double total = closedLength(P);
  std::vector<std::pair<double, double>> sides;
  auto segment = [&](Eigen::Index i) { return (P.row((i + 1) % n) - P.row(i % n)).norm(); };
  for (Eigen::Index i = 0; i < n && total > 0.0; ++i)
    if (const double length = segment(i);
        length >= longest &&
        length >= kSideOverCurve * std::min(segment(i + n - 1), segment(i + 1))) {
      const double a = fractionFrom(s(i) / total, start, direction),
                   b = fractionFrom((i + 1 < n ? s(i + 1) : 0.0) / total, start, direction);
      sides.emplace_back(direction > 0 ? a : b, length / total);
    }
  return sides;
}

// Whether seam fraction x lies on one of `sides`.
bool onSide(const std::vector<std::pair<double, double>>& sides, double x) {
  for (const auto& [begin, length] : sides)
    if (std::fmod(x - begin + 2.0, 1.0) <= length) return true;
  return false;
}

// The ends of the pieces' straight sides two seam edges long or longer that meet a curve, as
// seam corners (a rounded corner's tangent point). A seam point a little way
// into the curve lies a little off the side's line, and the body's edge from it along the side,
// where the other piece is straight too, runs micrometres beside the seam, folding as sharply as
// the seam does: no mesh follows it without triangles that thin, and none crosses it without
// stretching. With a seam point on each end the side is straight from end to end and that edge
// is the seam. Where the two pieces' sides end within a seam edge of each other and overlap,
// one end is taken (a second, that close, would make a chord that short): the one that lies on
// both sides, A's where both do. Where a gap parts them, both are.
void addStraightSideEnds(const ForwardSettings& job, SeamLayout& layout) {
  std::vector<std::pair<double, double>> sides[2];
  for (int p = 0; p < 2; ++p) {
    const Points2& joined = layout.pieces[p].joined;
    sides[p] = straightSides(joined, 2.0 * closedLength(joined) / std::max(1, job.resolution),
                             layout.startFraction[p], layout.direction[p]);
  }
  const double edge = 1.0 / std::max(1, job.resolution);
  for (int p = 0; p < 2; ++p)
    for (const auto& [begin, length] : sides[p])
      for (const double end : {begin, std::fmod(begin + length, 1.0)}) {
        bool yields = false;
        for (const auto& [otherBegin, otherLength] : sides[1 - p])
          for (const double other : {otherBegin, std::fmod(otherBegin + otherLength, 1.0)}) {
            const double apart = std::abs(std::remainder(end - other, 1.0));
            yields = yields || (apart > 0.0 && apart < edge && onSide(sides[p], other) &&
                                (!onSide(sides[1 - p], end) || p == 1));
          }
        if (!yields) layout.seamCorners.push_back(end);
      }
}

}  // namespace

// Each seam runs so that the zipped pieces are consistently oriented: A's the way A's triangles
// run along it (counter-clockwise round an outline, clockwise round a hole), B's the other way
// round from B's triangles (so B is turned over unless exactly one of the two joins a hole).
void layOutSeam(const ForwardSettings& job, const SolvedDForm& run, SeamLayout& layout) {
  layout.direction[0] = job.joinA == JoinedBoundary::Outer ? 1 : -1;
  layout.direction[1] = job.joinB == JoinedBoundary::Outer ? -1 : 1;
  layout.startFraction[0] = run.startFractionA;
  layout.startFraction[1] = run.startFractionB;
  for (int p = 0; p < 2; ++p) {
    const DrawnPiece& piece = layout.pieces[p];
    const double start = layout.startFraction[p];
    const int direction = layout.direction[p];
    double& freeStart = layout.freeStart[p];
    for (double c : cornerFractions(piece.joined, kCornerTurnRadians))
      layout.seamCorners.push_back(fractionFrom(c, start, direction));
    if (piece.freeOutline) {
      freeStart = nearestArcFraction(*piece.freeOutline, pointAtFraction(piece.joined, start));
      for (double c : cornerFractions(*piece.freeOutline, kCornerTurnRadians))
        layout.freeCorners[p].push_back(fractionFrom(c, freeStart, 1));
    }
    for (const Points2& crease : piece.creases)
      for (const Eigen::Index end : {Eigen::Index(0), crease.rows() - 1}) {
        const Eigen::Vector2d q = crease.row(end);
        const double onJoined = nearestArcFraction(piece.joined, q);
        if ((pointAtFraction(piece.joined, onJoined) - q).norm() < 1e-6)
          layout.seamCorners.push_back(fractionFrom(onJoined, start, direction));
        else if (piece.freeOutline)
          layout.freeCorners[p].push_back(
              fractionFrom(nearestArcFraction(*piece.freeOutline, q), freeStart, 1));
      }
  }
  addStraightSideEnds(job, layout);
}

}  // namespace forward_detail

}  // namespace dform
