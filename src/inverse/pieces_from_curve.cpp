// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/inverse/pieces_from_curve.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <new>
#include <tuple>

#include "dform/core/polyline.h"
#include "dform/exact/aligned_distance.h"
#include "dform/meshing/triangulate.h"
#include "dform/model/exact_model.h"
#include "dform/model/resources.h"
#include "dform/model/run_control.h"
#include "dform/model/transfer.h"

namespace dform {

using detail::Clock;
using detail::format;
using detail::secondsSince;

std::string curveLabel(const Curve3& curve) {
  return curve.source.empty() ? "the curve" : curve.source;
}

namespace {

// The closed curve through the rows of P (#P by 2, point k at parameter k / #P) by periodic
// Catmull-Rom interpolation, at parameters j / m: a smooth boundary through the coarse seam
// vertices rather than their chords, which are shorter than the seam and straight where it bends.
Points2 catmullRom(const Points2& P, int m) {
  const int n = int(P.rows());
  Points2 out(m, 2);
  for (int j = 0; j < m; ++j) {
    const double t = double(j) * n / m;
    const int k = int(std::floor(t));
    const double u = t - k, u2 = u * u, u3 = u2 * u;
    const Eigen::RowVector2d p0 = P.row((k + n - 1) % n), p1 = P.row(k % n),
                             p2 = P.row((k + 1) % n), p3 = P.row((k + 2) % n);
    out.row(j) = 0.5 * ((2.0 * p1) + (p2 - p0) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2 +
                        (3.0 * p1 - p0 - 3.0 * p2 + p3) * u3);
  }
  return out;
}

// A finer level's piece from the coarser solution: its flat seam runs through the coarse flat
// seam (curve point j of m at parameter j / m: both levels sample the curve uniformly), meshed
// like the pre-D-Form pieces, and its 3D shape is carried over by barycentric transfer, with the
// seam on the finer curve. Seam convention as InverseInit's: A's seam counter-clockwise in rows
// 0..m-1, B's clockwise.
Result<Piece> refinePiece(const Piece& coarse, const Points3& curve, bool clockwiseSeam,
                          double edgeLength, const InverseInitOptions& init) {
  const int m = int(curve.rows());
  Points2 seam(Eigen::Index(coarse.seam.size()), 2);
  for (std::size_t k = 0; k < coarse.seam.size(); ++k)
    seam.row(Eigen::Index(k)) = coarse.flat.row(coarse.seam[k]);
  const Points2 fineSeam = catmullRom(seam, m);  // in seam order
  Points2 outline(m, 2);                         // counter-clockwise rows
  for (int row = 0; row < m; ++row)
    outline.row(row) = fineSeam.row(clockwiseSeam ? (m - row) % m : row);
  TriangulateOptions options;
  options.targetEdgeLength = edgeLength * init.edgeLengthFactor;
  options.minAngleDegrees = init.minAngleDegrees;
  Result<FlatMesh> mesh = triangulateDomain(outline, {}, options);
  if (!mesh.isOk()) return mesh.status();
  Piece piece;
  piece.name = coarse.name;
  piece.flat = std::move(mesh.value().V);
  piece.F = std::move(mesh.value().F);
  for (int k = 0; k < m; ++k) piece.seam.push_back(clockwiseSeam ? (m - k) % m : k);
  piece.shape = transferShape(coarse, piece.flat);
  for (int k = 0; k < m; ++k) piece.shape.row(piece.seam[std::size_t(k)]) = curve.row(k);
  return piece;
}

// The pieces of an on-hull curve: the pre-D-Form (the hull cut along the curve) unfolded, zipped
// by the exact engine and moved rigidly onto the curve.
Result<DForm> exactInverse(const InverseInit& init, const Points3& target, const std::string& name,
                           const InverseSettings& job, ModelUsed& used) {
  const Eigen::Index n = target.rows();
  exact::SeamPolygons polygons;
  polygons.a = init.preFlatA.V.topRows(n);
  polygons.b = init.preFlatB.V.topRows(n);
  const double edge = closedLength(target) / double(n);
  const std::string paths[2] = {name + " (piece A)", name + " (piece B)"};
  Result<DForm> made = exactDForm(polygons, edge * job.init.edgeLengthFactor, paths, used);
  if (!made.isOk()) return made.status();
  DForm model = std::move(made).value();
  // A fold of the body that crossed the seam would have become a seam vertex with no point of the
  // curve to pair with (on-hull curves have none: their chords are edges of the hull).
  if (Eigen::Index(model.a.seam.size()) != n)
    return Status(ErrorCode::SolveFailed,
                  "a fold of the exact D-Form crosses the seam between curve points");
  Points3 seam(n, 3);
  for (Eigen::Index k = 0; k < n; ++k)
    seam.row(k) = model.a.shape.row(model.a.seam[std::size_t(k)]);
  const Eigen::Affine3d onCurve = exact::rigidFit(seam, target);
  for (Piece* p : {&model.a, &model.b})
    p->shape =
        (p->shape * onCurve.linear().transpose()).rowwise() + onCurve.translation().transpose();
  used.name = "exact";
  used.reason =
      "the curve lies on its convex hull: the hull's two sides unfolded are the pieces, and zipped "
      "they make the hull again (Alexandrov)";
  return model;
}

// Coarse to fine, as in forward runs: the pre-D-Form's search is cubic in the curve's points and
// the relaxation smooths its facets slowly on a fine mesh, so a curve of more than
// kMaxPreDFormPoints is solved first at a third of its points (recursively), each finer level
// starting from the coarser solution.
constexpr int kMaxPreDFormPoints = 200;

// The levels' points, coarsest first.
std::vector<int> curveLevels(int resolution) {
  std::vector<int> levels{resolution};
  while (levels.back() > kMaxPreDFormPoints) levels.push_back(levels.back() / 3);
  std::reverse(levels.begin(), levels.end());
  return levels;
}

// Measured on the samples, a curve of n points gives pieces of 0.10 n^2 to 0.18 n^2 vertices
// together; the pre-D-Form's tables (cost, apex, normal, side per pair of points) hold 37 n^2
// bytes, n the coarsest level's points.
MemoryEstimate inverseMemory(int resolution) {
  const double n = resolution, coarsest = curveLevels(resolution).front();
  return {0.2 * n * n, 37.0 * coarsest * coarsest};
}

Result<SolvedPieces> solveCurve(const Curve3& curve, const InverseSettings& job, MessageSink& sink,
                                const RunHooks& hooks) {
  const auto start = Clock::now();
  SolvedPieces run;
  const std::string name = curveLabel(curve);
  const std::vector<int> levels = curveLevels(job.resolution);
  if (Status fits = checkMemory(inverseMemory, job.resolution, name + ": the run"); !fits.isOk())
    return fits;
  run.curveLength = closedLength(curve.points);
  run.target.source = curve.source;
  run.target.sha256 = curve.sha256;
  run.timings.read = secondsSince(start);
  sink.info(
      format("curve: %.0f points, length %.3f mm", double(curve.points.rows()), run.curveLength));

  InverseSettings hooked = job;
  detail::connectHooks(hooked.relaxation, hooked.solver, hooks);
  InverseResult solved;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const bool finest = level + 1 == levels.size();
    // Compensated for chord loss (core/polyline.h) so that the seam, and the flat outlines
    // isometric to it, keep the curve's length: inscribed, 100 points fall short of a
    // tennis-ball seam by 0.11 %.
    const Points3 target = compensateChordLoss(resampleClosed(curve.points, levels[level]));
    const auto meshStart = Clock::now();
    DForm startModel;
    if (level == 0) {
      Result<InverseInit> init = initialiseInverse(Curve3{target, curve.source, {}}, job.init);
      if (!init.isOk()) return init.status();
      run.pre = init.value().pre;
      sink.info("pre-D-Form: " + run.pre.summary);
      // On its hull the curve is the seam of the hull's two sides: unfolded, they are the pieces,
      // and zipped they make that hull again (Alexandrov), with nothing to optimise.
      if (finest && run.pre.isHull) {
        Result<DForm> exact = exactInverse(init.value(), target, name, job, run.modelUsed);
        run.timings.mesh += secondsSince(meshStart);
        if (exact.isOk()) {
          sink.info(
              "exact model: the pieces are the curve's convex hull cut along it and unfolded");
          run.model = std::move(exact).value();
          run.target.points = target;
          run.timings.total = secondsSince(start);
          return run;
        }
        sink.warning(name + ": the exact model failed (" + exact.status().message() +
                     "); optimising instead");
      }
      run.modelUsed.name = "paper";
      run.modelUsed.reason =
          !finest ? "the curve has more points than the exact inverse unfolds in one piece (" +
                        std::to_string(kMaxPreDFormPoints) + ")"
          : run.pre.isHull ? "the exact model failed"
                           : "the curve leaves its convex hull: the pieces are optimised from the "
                             "filled pre-D-Form, and zipped they take a convex shape (the round "
                             "trip says how far from the curve)";
      startModel = std::move(init.value().model);
    } else {
      const double edge = closedLength(target) / double(target.rows());
      for (auto [coarse, fine, clockwise] : {std::tuple{&solved.model.a, &startModel.a, false},
                                             std::tuple{&solved.model.b, &startModel.b, true}}) {
        // Meshing a fine level takes seconds per piece (2-3 s at resolution 1500).
        if (detail::stopRequested(hooks)) return interruptedDuring("the meshing");
        Result<Piece> piece = refinePiece(*coarse, target, clockwise, edge, job.init);
        if (piece.status().code() == ErrorCode::Interrupted)
          return piece.status();  // names no file
        if (!piece.isOk())
          return Status(piece.status().code(), name + ": " + piece.status().message());
        *fine = std::move(piece).value();
      }
    }
    run.timings.mesh += secondsSince(meshStart);
    const Level detail = finest ? Level::Info : Level::Debug;
    sink.emit(detail, (finest ? "meshed piece A with " : "coarse level: piece A with ") +
                          std::to_string(startModel.a.flat.rows()) + " vertices, piece B with " +
                          std::to_string(startModel.b.flat.rows()));

    if (detail::stopRequested(hooks)) return interruptedDuring("the meshing");
    const auto solveStart = Clock::now();
    InverseSettings levelSettings = hooked;
    detail::relaxOnlyIfLarge(startModel.a.flat.rows() + startModel.b.flat.rows(),
                             levelSettings.solver, levelSettings.relaxation);
    if (level > 0) levelSettings.relaxation.relativeTolerance = detail::kRefinedRelaxationTolerance;
    if (hooks.onLevel)
      hooks.onLevel({int(level) + 1, int(levels.size()), levelSettings.relaxation.maxIterations,
                     levelSettings.solver.maxIterations});
    solved = solveInverse(startModel, target, levelSettings);
    run.timings.solve += secondsSince(solveStart);
    if (detail::stopRequested(hooks)) return interruptedDuring("the solve");
    if (!solved.summary.usable())
      return Status(ErrorCode::SolveFailed,
                    name + ": the solver failed: " + solved.summary.message);
    sink.emit(Level::Debug, format("local-global start: %d iterations, energy %.4g -> %.4g",
                                   solved.relaxation.iterations, solved.relaxation.initialEnergy,
                                   solved.relaxation.finalEnergy));
    sink.emit(detail, "solve: " + solved.summary.briefReport());
    if (finest) run.target.points = target;
  }
  run.model = std::move(solved.model);
  run.relaxation = solved.relaxation;
  run.summary = std::move(solved.summary);
  run.timings.total = secondsSince(start);
  return run;
}

}  // namespace

Result<SolvedPieces> solvePieces(const Curve3& curve, const InverseSettings& settings,
                                 MessageSink& sink, const RunHooks& hooks) {
  try {
    return solveCurve(curve, settings, sink, hooks);
  } catch (const std::bad_alloc&) {
    return outOfMemory(inverseMemory, settings.resolution, curveLabel(curve) + ": the run");
  } catch (const Interrupted& stop) {
    return interruptedDuring(stop.stage());
  }
}

}  // namespace dform
