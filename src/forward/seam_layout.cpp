#include "seam_layout.h"

#include <algorithm>
#include <cmath>

#include "dform/core/polyline.h"
#include "dform/model/run_control.h"

namespace dform {

std::vector<double> seamFractions(int n, std::vector<double> corners) {
  std::vector<double> uniform(n);
  for (int k = 0; k < n; ++k) uniform[k] = double(k) / n;
  if (int(corners.size()) > n / 4) return uniform;
  std::sort(corners.begin(), corners.end());
  std::vector<double> breaks{0.0};
  const double merge = 0.5 / n;
  for (double c : corners)
    if (c - breaks.back() >= merge && 1.0 - c >= merge) breaks.push_back(c);
  const int m = int(breaks.size());
  std::vector<double> lengths(m);
  for (int j = 0; j < m; ++j) lengths[j] = (j + 1 < m ? breaks[j + 1] : 1.0) - breaks[j];
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

exact::SeamPolygons seamPolygons(const DrawnPiece pieces[2], const double startFraction[2],
                                 const int direction[2], const std::vector<double>& fractions) {
  const Eigen::Index n = Eigen::Index(fractions.size());
  exact::SeamPolygons polygons;
  Points2* sides[2] = {&polygons.a, &polygons.b};
  for (int p = 0; p < 2; ++p) {
    const LoopSamples seam =
        sampleLoop(pieces[p].joined, fractions, startFraction[p], direction[p]);
    sides[p]->resize(n, 2);
    for (Eigen::Index k = 0; k < n; ++k) sides[p]->row(k) = seam.rows.row(seam.order[k]);
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
}

}  // namespace forward_detail

}  // namespace dform
