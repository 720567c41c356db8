#include "pipeline/forward_pipeline.h"

#include <algorithm>
#include <cmath>

#include "core/polyline.h"
#include "forward/transfer.h"
#include "io/outline_reader.h"
#include "meshing/triangulate.h"
#include "pipeline/run_util.h"
#include "pipeline/seam_layout.h"

namespace dform {

using detail::Clock;
using detail::format;
using detail::secondsSince;

namespace {

// The point at arc-length fraction t of the closed polyline P.
Eigen::Vector2d pointAtFraction(const Points2& P, double t) {
  return resampleClosed(P, 1, t).row(0).transpose();
}

// Piece B turned over: mirrored in x, reordered counter-clockwise. `start` follows the mirror.
void mirror(Points2& P, StartPoint& start) {
  const Eigen::Vector2d startPoint = start.nearestToPoint ? start.point : pointAtFraction(P, start.fraction);
  P.col(0) *= -1.0;
  P = P.colwise().reverse().eval();
  start.nearestToPoint = true;
  start.point = Eigen::Vector2d(-startPoint.x(), startPoint.y());
}

double resolveFraction(const Points2& P, const StartPoint& start) {
  return start.nearestToPoint ? nearestArcFraction(P, start.point) : start.fraction;
}

Result<Outline2> readDisc(const std::string& path) {
  Result<Shape2> shape = readShape(path);
  if (!shape.isOk()) return shape.status();
  if (!shape.value().holes.empty())
    return Status(ErrorCode::InputInvalid,
                  path + ": the outline has " + std::to_string(shape.value().holes.size()) +
                      " hole(s); a D-Form piece must be a disc without holes");
  return shape.value().outer;
}

// A piece meshed from its resampled seam (#n by 2, counter-clockwise). Piece A's seam runs
// counter-clockwise (0, 1, ..., n-1); piece B's clockwise (0, n-1, ..., 1) so that the pieces
// close into an outward-facing surface.
Result<Piece> meshPiece(const Points2& seam, bool clockwiseSeam, const std::string& name,
                        const std::string& source, double edgeLength) {
  TriangulateOptions options;
  options.targetEdgeLength = edgeLength;
  Result<FlatMesh> mesh = triangulateDomain(seam, {}, options);
  if (!mesh.isOk()) return Status(mesh.status().code(), source + ": " + mesh.status().message());
  Piece piece;
  piece.name = name;
  piece.flat = mesh.value().V;
  piece.F = mesh.value().F;
  const int n = int(seam.rows());
  for (int i = 0; i < n; ++i) piece.seam.push_back(clockwiseSeam ? (n - i) % n : i);
  return piece;
}

// Starts a and b from the coarser solution: barycentric transfer, then each seam pair at the mean
// of its two transferred positions so that the seam starts closed.
void startFromCoarser(const DForm& coarse, Piece& a, Piece& b) {
  a.shape = transferShape(coarse.a, a.flat);
  b.shape = transferShape(coarse.b, b.flat);
  for (std::size_t k = 0; k < a.seam.size(); ++k) {
    const Eigen::RowVector3d mid = 0.5 * (a.shape.row(a.seam[k]) + b.shape.row(b.seam[k]));
    a.shape.row(a.seam[k]) = b.shape.row(b.seam[k]) = mid;
  }
}

}  // namespace

Status validateForwardJob(const ForwardJob& job) {
  auto usage = [](const std::string& text) { return Status(ErrorCode::Usage, text); };
  if (job.resolution < 8 || job.resolution > 20000)
    return usage("resolution must be between 8 and 20000 seam vertices, got " +
                 std::to_string(job.resolution));
  for (const StartPoint* s : {&job.startA, &job.startB})
    if (!s->nearestToPoint && !(s->fraction >= 0.0 && s->fraction < 1.0))
      return usage("a start fraction must be in [0, 1)");
    else if (s->nearestToPoint && !s->point.allFinite())
      return usage("a start point must have finite coordinates");
  if (!(job.perimeterTolerance > 0.0 && job.perimeterTolerance < 1.0))
    return usage("the perimeter tolerance must be in (0, 1)");
  if (!(job.interiorEdgeFactor >= 0.25 && job.interiorEdgeFactor <= 8.0))
    return usage("the interior edge factor must be in [0.25, 8]");
  const ForwardWeights& w = job.solve.weights;
  for (double weight : {w.isometry, w.alignment, w.boundaryFix, w.smooth3d, w.smooth2d, w.seam})
    if (!(weight >= 0.0 && std::isfinite(weight))) return usage("weights must be finite and >= 0");
  std::string why;
  if (!job.solve.solver.isValid(&why)) return usage("solver options: " + why);
  return Status::ok();
}

Result<ForwardRun> runForward(const ForwardJob& job, MessageSink& sink, const RunHooks& hooks) {
  if (Status s = validateForwardJob(job); !s.isOk()) return s;
  const auto start = Clock::now();
  ForwardRun run;

  Result<Outline2> outlineA = readDisc(job.pieceA);
  if (!outlineA.isOk()) return outlineA.status();
  Result<Outline2> outlineB = readDisc(job.pieceB);
  if (!outlineB.isOk()) return outlineB.status();
  Points2 A = outlineA.value().points, B = outlineB.value().points;
  run.perimeterA = closedLength(A);
  run.perimeterB = closedLength(B);
  const double mismatch =
      std::abs(run.perimeterA - run.perimeterB) / std::max(run.perimeterA, run.perimeterB);
  if (mismatch > job.perimeterTolerance) {
    if (!job.fitPerimeter)
      return Status(ErrorCode::InputInvalid,
                    job.pieceA + " and " + job.pieceB + ": the perimeters differ" +
                        format(" (%.3f mm and %.3f mm, %.2f%%", run.perimeterA, run.perimeterB,
                               100.0 * mismatch) +
                        format(" > %.2f%%); a D-Form needs equal perimeters (--fit-perimeter "
                               "scales piece B to match)",
                               100.0 * job.perimeterTolerance));
  }
  if (job.fitPerimeter) {
    run.scaleB = run.perimeterA / run.perimeterB;
    const Eigen::RowVector2d centre = B.colwise().mean();
    B = ((B.rowwise() - centre) * run.scaleB).rowwise() + centre;
    sink.info(format("piece B scaled by %.6f to match piece A's perimeter (%.3f mm)", run.scaleB,
                     run.perimeterA));
  }
  StartPoint startB = job.startB;
  if (job.flip) {
    mirror(B, startB);
    sink.info("piece B is zipped turned over (--flip): its flat pattern is mirrored");
  }
  run.startFractionA = resolveFraction(A, job.startA);
  run.startFractionB = resolveFraction(B, startB);
  run.timings.read = secondsSince(start);

  // Coarse to fine: the job is solved first with a third of the seam vertices (recursively, down
  // to kCoarsestSeam), and each level starts from the coarser solution carried over by
  // barycentric transfer. The coarse levels do the large shape change cheaply; the finest level
  // then converges in a few Levenberg-Marquardt steps on one factorisation.
  constexpr int kCoarsestSeam = 24;
  constexpr int kLevelRatio = 3;
  constexpr int kCoarseIterations = 30;
  // A flattened smooth curve turns by a fraction of a degree per point; a drawn corner by much
  // more. 20 degrees separates the two for any outline a designer draws.
  const double kCornerTurn = 20.0 * M_PI / 180.0;
  std::vector<int> levels{job.resolution};
  while (job.coarseToFine && levels.back() / kLevelRatio >= kCoarsestSeam)
    levels.push_back(levels.back() / kLevelRatio);
  std::reverse(levels.begin(), levels.end());

  // Corners of both outlines as seam fractions from the starting pair.
  std::vector<double> seamCorners;
  for (double c : cornerFractions(A, kCornerTurn))
    seamCorners.push_back(std::fmod(c - run.startFractionA + 1.0, 1.0));
  for (double c : cornerFractions(B, kCornerTurn))
    seamCorners.push_back(std::fmod(run.startFractionB - c + 1.0, 1.0));

  ForwardOptions options = job.solve;
  bool interrupted = false;
  detail::connectHooks(options.solver, hooks, interrupted);
  ForwardResult solved;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const int n = levels[level];
    const bool finest = level + 1 == levels.size();
    const auto meshStart = Clock::now();
    // Seam vertex k sits at fraction startA + t_k on A (counter-clockwise) and startB - t_k on B
    // (clockwise); B's counter-clockwise row j is its seam vertex (n - j) % n.
    const std::vector<double> t = seamFractions(n, seamCorners);
    std::vector<double> onA(n), onB(n);
    for (int k = 0; k < n; ++k) {
      onA[k] = run.startFractionA + t[k];
      onB[(n - k) % n] = run.startFractionB - t[k];
    }
    const Points2 seamA = resampleAtFractions(A, onA);
    const Points2 seamB = resampleAtFractions(B, onB);
    const double seamEdge = run.perimeterA / n;
    Result<Piece> a = meshPiece(seamA, false, "A", job.pieceA, job.interiorEdgeFactor * seamEdge);
    if (!a.isOk()) return a.status();
    Result<Piece> b = meshPiece(seamB, true, "B", job.pieceB, job.interiorEdgeFactor * seamEdge);
    if (!b.isOk()) return b.status();
    if (level > 0) startFromCoarser(solved.model, a.value(), b.value());
    run.timings.mesh += secondsSince(meshStart);
    // The finest level is what the user asked for; coarser ones are details for the log.
    const Level detail = finest ? Level::Info : Level::Debug;
    sink.emit(detail, (finest ? "meshed piece A with " : "coarse level: piece A with ") +
                          std::to_string(a.value().flat.rows()) + " vertices and " +
                          std::to_string(a.value().F.rows()) + " triangles, piece B with " +
                          std::to_string(b.value().flat.rows()) + " and " +
                          std::to_string(b.value().F.rows()));

    const auto solveStart = Clock::now();
    // A coarse level only has to start the next one well: a few iterations, seam left to the
    // alignment weight.
    ForwardOptions levelOptions = options;
    if (!finest) {
      levelOptions.solver.maxIterations = std::min(options.solver.maxIterations, kCoarseIterations);
      levelOptions.constraintRounds = 0;
    }
    solved = solveForward(a.value(), b.value(), levelOptions);
    run.timings.solve += secondsSince(solveStart);
    if (interrupted) return Status(ErrorCode::Interrupted, "interrupted during the solve");
    if (!solved.summary.usable())
      return Status(ErrorCode::SolveFailed, "the solver failed: " + solved.summary.message);
    sink.emit(Level::Debug, format("local-global start: %.0f iterations, energy %.4g -> %.4g",
                                   solved.relaxation.iterations, solved.relaxation.initialEnergy,
                                   solved.relaxation.finalEnergy) +
                                format(" in %.3f s; level solved in %.3f s",
                                       solved.relaxation.seconds, secondsSince(solveStart)));
    sink.emit(detail, "solve: " + solved.summary.briefReport() + ", " +
                          std::to_string(solved.constraintRounds) + " constraint round(s)");
  }
  run.relaxation = solved.relaxation;
  run.constraintRounds = solved.constraintRounds;
  run.model = std::move(solved.model);
  run.summary = std::move(solved.summary);
  run.metrics = computeMetrics(run.model);
  run.timings.total = secondsSince(start);
  return run;
}

}  // namespace dform
