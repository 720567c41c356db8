// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/forward/dform_from_shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <new>
#include <numeric>
#include <optional>
#include <set>

#include "dform/core/constants.h"
#include "dform/core/polyline.h"
#include "dform/exact/exact_gluing.h"
#include "dform/forward/coarse_to_fine.h"
#include "dform/meshing/triangulate.h"
#include "dform/model/exact_model.h"
#include "dform/model/resources.h"
#include "dform/model/run_control.h"
#include "dform/model/transfer.h"
#include "dform/ruled/isometric_mesh.h"
#include "isometric_states.h"
#include "ruled_forward.h"
#include "seam_layout.h"

namespace dform {

using detail::Clock;
using detail::format;
using detail::secondsSince;
using namespace forward_detail;

namespace {

// The crease's ends as rows of the sampled boundary `fixed`, and its points in between, about
// `edge` apart. At the finest level its ends are sample points (see the corners passed to
// seamFractions); a coarse level takes the nearest ones.
InteriorLine creaseLine(const Points2& crease, const Points2& fixed, double edge) {
  auto nearestRow = [&](const Eigen::RowVector2d& q) {
    Eigen::Index row = 0;
    (fixed.rowwise() - q).rowwise().squaredNorm().minCoeff(&row);
    return int(row);
  };
  const int segments = std::max(1, int(std::lround(openLength(crease) / edge)));
  const Eigen::MatrixXd points = resampleOpen(crease, segments);
  return {nearestRow(crease.row(0)), nearestRow(crease.row(crease.rows() - 1)),
          points.middleRows(1, segments - 1)};
}

// Why the exact model cannot make this job, or "" when it can (the glued metric's convexity is
// checked when the seam is sampled).
std::string exactModelRefusal(const ForwardSettings& job, const DrawnPiece& A,
                              const DrawnPiece& B) {
  if (job.joinA != JoinedBoundary::Outer || job.joinB != JoinedBoundary::Outer)
    return "a piece is zipped along a hole (anti or demi D-Form): the glued pieces make no closed "
           "convex body";
  if (!A.creases.empty() || !B.creases.empty())
    return "creases are drawn: the exact D-Form folds only where the glued pieces make it fold";
  if (job.resolution > exact::kMaxExactSeam)
    return "the seam has " + std::to_string(job.resolution) +
           " points, more than the exact engine's " + std::to_string(exact::kMaxExactSeam);
  return "";
}

// The paper model's start on the exact D-Form of the same seam: every vertex placed on the body
// (seam vertices at its cone points). False when a vertex cannot be placed.
bool startOnExactBody(const exact::ExactGluing& g, Piece pieces[2]) {
  const Points3 seam = exact::placeOnBody(g, 0, g.seam.a);
  for (int p = 0; p < 2; ++p) {
    Points3 shape = exact::placeOnBody(g, p, pieces[p].flat);
    for (std::size_t k = 0; k < pieces[p].seam.size(); ++k)
      shape.row(pieces[p].seam[k]) = seam.row(Eigen::Index(k));
    if (!shape.allFinite()) return false;
    pieces[p].shape = std::move(shape);
  }
  return true;
}

}  // namespace

const std::vector<ModelChoiceInfo>& modelChoices() {
  static const std::vector<ModelChoiceInfo> choices = {
      {ModelChoice::Auto, "auto",
       "exact where the pieces make a convex body, else paper, then the ruled engine for drawn "
       "creases and anti D-Forms"},
      {ModelChoice::Exact, "exact", "Alexandrov's convex body of the glued pieces"},
      {ModelChoice::Ruled, "ruled",
       "rigid flat triangles between the pieces' boundary points, from the paper model's shape"},
      {ModelChoice::Paper, "paper", "the paper's optimisation"},
      {ModelChoice::General, "general", "a stiff sheet at a stationary point of its energy"}};
  return choices;
}

const char* modelChoiceName(ModelChoice model) {
  for (const ModelChoiceInfo& m : modelChoices())
    if (m.choice == model) return m.name;
  return "?";
}

bool parseModelChoice(const std::string& text, ModelChoice& model) {
  for (const ModelChoiceInfo& m : modelChoices())
    if (text == m.name) {
      model = m.choice;
      return true;
    }
  return false;
}

const char* joinedBoundaryName(JoinedBoundary boundary) {
  return boundary == JoinedBoundary::Outer ? "outer" : "inner";
}

const std::vector<JoinChoiceInfo>& joinChoices() {
  static const std::vector<JoinChoiceInfo> choices = [] {
    using J = JoinedBoundary;
    const std::pair<J, J> pairs[] = {
        {J::Outer, J::Outer}, {J::Inner, J::Inner}, {J::Outer, J::Inner}, {J::Inner, J::Outer}};
    const char* helps[] = {"a classic D-Form", "an anti D-Form", "a demi D-Form",
                           "a demi D-Form, B's outline zipped"};
    std::vector<JoinChoiceInfo> out;
    for (int k = 0; k < 4; ++k)
      out.push_back({std::string(joinedBoundaryName(pairs[k].first)) + "," +
                         joinedBoundaryName(pairs[k].second),
                     pairs[k].first, pairs[k].second, helps[k]});
    return out;
  }();
  return choices;
}

ForwardWeights defaultWeights(JoinedBoundary a, JoinedBoundary b) {
  ForwardWeights weights;
  if (a == JoinedBoundary::Inner || b == JoinedBoundary::Inner) weights.smooth3d = 0.001;
  return weights;
}

bool parseJoin(const std::string& text, JoinedBoundary& a, JoinedBoundary& b) {
  for (const JoinChoiceInfo& j : joinChoices())
    if (text == j.name) {
      a = j.a;
      b = j.b;
      return true;
    }
  return false;
}

namespace {

// The exact D-Form where it applies and was not declined: the finished run, or nothing with
// `refusal` saying why not (an error where the model setting asked for the exact one).
Result<std::optional<SolvedDForm>> tryExactModel(const ForwardSettings& job,
                                                 const SeamLayout& layout, SolvedDForm& run,
                                                 std::string& refusal, MessageSink& sink,
                                                 const RunHooks& hooks) {
  const std::string both = layout.bothPaths();
  refusal = exactModelRefusal(job, layout.pieces[0], layout.pieces[1]);
  if (job.model == ModelChoice::Paper || job.model == ModelChoice::General ||
      job.model == ModelChoice::Ruled)
    return std::optional<SolvedDForm>();
  if (!refusal.empty()) {
    if (job.model == ModelChoice::Exact)
      return Status(ErrorCode::InputInvalid,
                    both + ": " + mention(Setting::Model) + " exact: " + refusal);
    return std::optional<SolvedDForm>();
  }
  const auto solveStart = Clock::now();
  ModelUsed used;
  Result<DForm> exactModel =
      exactDForm(seamPolygons(layout.pieces, layout.startFraction, layout.direction,
                              seamFractions(job.resolution, layout.seamCorners)),
                 job.interiorEdgeFactor * run.perimeterA / job.resolution, layout.paths, used);
  run.timings.solve = secondsSince(solveStart);
  if (detail::stopRequested(hooks)) return interruptedDuring("the solve");
  if (!exactModel.isOk()) {
    refusal = exactModel.status().message();
    if (job.model == ModelChoice::Exact)
      return Status(exactModel.status().code(),
                    both + ": " + mention(Setting::Model) + " exact: " + refusal);
    if (exactModel.status().code() == ErrorCode::SolveFailed) {
      sink.warning("the exact model failed (" + refusal +
                   "); the paper model makes the shape instead");
      refusal = "it failed: " + refusal;
    }
    return std::optional<SolvedDForm>();
  }
  used.name = "exact";
  used.reason =
      used.pouch == "thin"
          ? format(
                "the body glued came out %.2g mm thick, too thin to be anything but flat: the "
                "pieces are congruent as far as their outlines are known (to %.2g mm) and "
                "zipped point to point, and fold flat onto each other",
                used.thicknessMm, used.precisionMm)
      : used.doublyCovered
          ? "the pieces are congruent and zipped point to point: they fold flat onto each other"
          : "two discs zipped along their outlines whose glued metric is convex (every seam "
            "point's "
            "angle sum at most 360 degrees): the D-Form is that metric's unique convex body";
  sink.info("exact model: " + std::to_string(used.conePoints) + " cone points, " +
            std::to_string(used.newtonSteps) + " Newton steps" +
            format(", curvature left %.2g rad, chords equalised by moving points at most %.2g mm",
                   used.maxCurvature, used.chordMoveMm));
  // Each crease once: the exact body may find one line in several pieces of the same fold.
  std::set<std::string> reported;
  for (const FoundCrease& c : used.creases) {
    const std::string line =
        std::string("the exact D-Form creases piece ") + (c.piece == 0 ? "A" : "B") +
        format(" along a line of %.1f mm folded by %.1f degrees", c.lengthMm, c.angleDeg);
    if (reported.insert(line).second) sink.info(line);
  }
  run.model = std::move(exactModel).value();
  run.modelUsed = std::move(used);
  return std::optional<SolvedDForm>(std::move(run));
}

// Both pieces meshed for a level of n seam vertices, seam rows listed in seam order.
Result<std::array<Piece, 2>> meshLevel(const ForwardSettings& job, const SeamLayout& layout, int n,
                                       double perimeterA, const RunHooks& hooks) {
  const std::vector<double> t = seamFractions(n, layout.seamCorners);
  const double seamEdge = perimeterA / n;
  std::array<Piece, 2> pieces;
  for (int p = 0; p < 2; ++p) {
    // Meshing a fine level takes seconds per piece.
    if (detail::stopRequested(hooks)) return interruptedDuring("the meshing");
    const DrawnPiece& piece = layout.pieces[p];
    const std::string& path = layout.paths[p];
    const LoopSamples seam =
        sampleLoop(piece.joined, t, layout.startFraction[p], layout.direction[p]);
    // The mesher's fixed points: the outline, then the hole. The joined boundary is the outline
    // of a disc and the hole of an annulus-like piece, whose outline is sampled about as
    // densely as the seam.
    Points2 outline = seam.rows;
    std::vector<Points2> holes;
    int seamFirstRow = 0;
    if (piece.freeOutline) {
      const int m = std::max(3, int(std::lround(closedLength(*piece.freeOutline) / seamEdge)));
      outline = sampleLoop(*piece.freeOutline, seamFractions(m, layout.freeCorners[p]),
                           layout.freeStart[p], 1)
                    .rows;
      holes.push_back(seam.rows);
      seamFirstRow = int(outline.rows());
    }
    Points2 fixed(outline.rows() + seam.rows.rows() * Eigen::Index(piece.freeOutline.has_value()),
                  2);
    fixed.topRows(outline.rows()) = outline;
    if (piece.freeOutline) fixed.bottomRows(seam.rows.rows()) = seam.rows;
    std::vector<InteriorLine> creases;
    for (const Points2& crease : piece.creases)
      creases.push_back(creaseLine(crease, fixed, seamEdge));

    TriangulateOptions meshOptions;
    meshOptions.targetEdgeLength = job.interiorEdgeFactor * seamEdge;
    Result<FlatMesh> mesh = triangulateDomain(outline, holes, meshOptions, creases);
    if (mesh.status().code() == ErrorCode::Interrupted) return mesh.status();  // names no file
    if (!mesh.isOk()) return Status(mesh.status().code(), path + ": " + mesh.status().message());
    Piece& out = pieces[p];
    out.name = p == 0 ? "A" : "B";
    out.flat = std::move(mesh.value().V);
    out.F = std::move(mesh.value().F);
    for (int row : seam.order) out.seam.push_back(seamFirstRow + row);
    if (piece.freeOutline) {
      out.freeBoundaries.emplace_back(seamFirstRow);
      std::iota(out.freeBoundaries[0].begin(), out.freeBoundaries[0].end(), 0);
    }
    out.creases = std::move(mesh.value().lines);
  }
  return pieces;
}

// The paper's optimisation, coarse to fine (detail::seamLevels): each level's pieces are meshed
// from the drawn outlines sampled at its resolution.
Status solvePaperModel(const ForwardSettings& job, const SeamLayout& layout, SolvedDForm& run,
                       MessageSink& sink, const RunHooks& hooks) {
  std::vector<int> levels = detail::seamLevels(job.resolution, job.coarseToFine);

  // Where creases are drawn on discs with a convex glued metric, the paper model starts on their
  // exact D-Form, which folds where the glued pieces fold: its solution differs from it only by
  // what the smoothing terms and the drawn creases ask, so the finest level alone converges in a
  // few steps and never passes through the folds that a pillow start leaves behind (the creased
  // Squaricle: 6 folded triangles in 13 s from the pillow, none in 0.6 s from the exact body).
  // Without creases the coarse-to-fine start is as good and faster (a finest level relaxed from
  // the exact body's ridges takes seconds at 7k vertices).
  const bool classic = job.joinA == JoinedBoundary::Outer && job.joinB == JoinedBoundary::Outer;
  const bool creased = !layout.pieces[0].creases.empty() || !layout.pieces[1].creases.empty();
  std::optional<exact::ExactGluing> exactStart;
  if (classic && creased && job.resolution <= exact::kMaxExactSeam) {
    exact::SeamPolygons polygons =
        seamPolygons(layout.pieces, layout.startFraction, layout.direction,
                     seamFractions(job.resolution, layout.seamCorners));
    exact::equalizeChords(polygons);
    Result<exact::ExactGluing> glued = exact::glue(polygons);
    if (glued.isOk() && !glued.value().doublyCovered) {
      exactStart = std::move(glued).value();
      levels = {job.resolution};
      sink.info("paper model: starting from the exact D-Form of the same seam");
    }
  }

  ForwardSettings hooked = job;
  hooked.continuationSmoothing = defaultWeights(job.joinA, job.joinB).smooth3d;
  detail::connectHooks(hooked.relaxation, hooked.solver, hooks);
  ForwardResult solved;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const bool finest = level + 1 == levels.size();
    const auto meshStart = Clock::now();
    Result<std::array<Piece, 2>> meshed =
        meshLevel(job, layout, levels[level], run.perimeterA, hooks);
    if (!meshed.isOk()) return meshed.status();
    Piece* pieces = meshed.value().data();
    if (level > 0) startFromCoarser(solved.model, pieces[0], pieces[1]);
    if (exactStart && finest && !startOnExactBody(*exactStart, pieces)) {
      for (Piece& piece : meshed.value()) piece.shape.resize(0, 3);
      sink.warning(
          "paper model: a vertex could not be placed on the exact D-Form; starting from the "
          "pillow");
    }
    run.timings.mesh += secondsSince(meshStart);
    // The finest level is what the user asked for; coarser ones are details for the log.
    const Level detail = finest ? Level::Info : Level::Debug;
    sink.emit(detail, (finest ? "meshed piece A with " : "coarse level: piece A with ") +
                          std::to_string(pieces[0].flat.rows()) + " vertices and " +
                          std::to_string(pieces[0].F.rows()) + " triangles, piece B with " +
                          std::to_string(pieces[1].flat.rows()) + " and " +
                          std::to_string(pieces[1].F.rows()));

    const auto solveStart = Clock::now();
    const ForwardSettings levelJob =
        detail::levelSettings(hooked, finest, pieces[0].flat.rows() + pieces[1].flat.rows());
    if (hooks.onLevel)
      hooks.onLevel({int(level) + 1, int(levels.size()), levelJob.relaxation.maxIterations,
                     levelJob.solver.maxIterations});
    solved = solveForward(pieces[0], pieces[1], levelJob);
    run.timings.solve += secondsSince(solveStart);
    if (detail::stopRequested(hooks)) return interruptedDuring("the solve");
    if (!solved.summary.usable())
      return Status(ErrorCode::SolveFailed, "the solver failed: " + solved.summary.message);
    sink.emit(Level::Debug, format("local-global start: %d iterations, energy %.4g -> %.4g",
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
  return Status::ok();
}

// Where the boundary points alone cannot carry the fold (a seam point of negative curvature), the
// states of the sheet made of rigid flat triangles whose vertices inside the pieces are unknowns
// in the flat as well (isometricStates): the paper model's shape at coarse resolutions made exact
// and carried up to the job's. The least bending state is the answer, the others are listed.
Status solveIsometricModel(const ForwardSettings& job, const SeamLayout& layout, SolvedDForm& run,
                           MessageSink& sink, const RunHooks& hooks) {
  IsometricLevels levels;
  RunHooks unreported;
  unreported.interrupted = hooks.interrupted;
  levels.paperShape = [&](int resolution, bool reportsProgress) -> Result<DForm> {
    ForwardSettings at = job;
    at.resolution = resolution;
    SolvedDForm start = run;
    MessageSink quiet;
    if (Status s = solvePaperModel(at, layout, start, quiet, reportsProgress ? hooks : unreported);
        !s.isOk())
      return s;
    return std::move(start.model);
  };
  levels.mesh = [&](int resolution, double interiorEdgeFactor) {
    ForwardSettings at = job;
    at.interiorEdgeFactor = interiorEdgeFactor;
    return meshLevel(at, layout, resolution, run.perimeterA, hooks);
  };
  levels.stop = [&hooks] { return detail::stopRequested(hooks); };
  const IsometricStates found = isometricStates(job.resolution, job.interiorEdgeFactor, levels);
  if (detail::stopRequested(hooks)) return interruptedDuring("the solve");
  if (found.states.empty()) {
    std::string why;
    for (const auto& [start, reason] : found.failures)
      why += (why.empty() ? "" : "; ") + ("from " + start + ": " + reason);
    return Status(ErrorCode::SolveFailed, why);
  }
  const IsometricState& best = found.states.front();
  const ruled::IsometricMesh& mesh = best.exact;
  const std::string paperReason = run.modelUsed.reason;
  run.model = mesh.model;
  ModelUsed& used = run.modelUsed;
  used.name = "ruled";
  used.reason = paperReason + format(
                                  "; the paper model's shape carried to a mesh of interior edge "
                                  "%g, its %d vertices inside the pieces freed in the flat too, "
                                  "meets every edge length",
                                  best.interiorEdgeFactor, mesh.interiorVertices);
  used.lengthError = mesh.lengthError;
  used.bendingEnergy = mesh.bendingEnergy;
  used.chordMoveMm = mesh.chordMoveMm;
  used.interiorVertices = mesh.interiorVertices;
  used.stationarity = std::numeric_limits<double>::quiet_NaN();  // the bending is not minimised
  used.flips = 0;
  used.flipsStationary = false;
  used.states.clear();
  run.otherStates.clear();
  for (const IsometricState& state : found.states) {
    used.states.push_back({state.start, state.exact.bendingEnergy,
                           state.exact.largestFold / kDegree, state.rankingEnergy});
    if (&state != &best) run.otherStates.push_back(state.exact.model);
  }
  sink.info(format("ruled engine: %zu state(s); the answer, from ", found.states.size()) +
            best.start +
            format(", made exact in %d steps on a mesh of interior edge %g (largest edge error "
                   "%.2g, vertices inside the pieces moved up to %.3g mm in the flat), bending "
                   "energy %.6g",
                   best.steps, best.interiorEdgeFactor, mesh.lengthError, mesh.largestFlatMoveMm,
                   mesh.bendingEnergy));
  for (std::size_t s = 1; s < found.states.size(); ++s)
    sink.warning("the sheet can also sit another way: from " + found.states[s].start +
                 format(", bending energy %.6g (report.json model.states)",
                        found.states[s].exact.bendingEnergy));
  for (const auto& [start, why] : found.failures)
    sink.info("ruled engine: from " + start + ", no state: " + why);
  return Status::ok();
}

// Auto's answer where the boundary points alone cannot carry the fold: the states with vertices
// inside the pieces, which start from coarse paper model shapes, so the job's own paper model is
// solved only where they fail (and its shape is then the answer, saying why).
Status solveIsometricOrPaper(const ForwardSettings& job, const SeamLayout& layout, SolvedDForm& run,
                             MessageSink& sink, const RunHooks& hooks) {
  const auto solveStart = Clock::now();
  Status s = solveIsometricModel(job, layout, run, sink, hooks);
  run.timings.solve += secondsSince(solveStart);
  if (s.isOk() || s.code() == ErrorCode::Interrupted) return s;
  sink.info("ruled engine, from the paper model's shapes: " + s.message() +
            "; the paper model's shape is kept");
  run.modelUsed.reason += "; from the paper model's shapes: " + s.message();
  return solvePaperModel(job, layout, run, sink, hooks);
}

// The run behind solveDForm and makeDForm (which turns a failed allocation into the resolution
// that fits); `estimateAt` is the formula the memory check held the run to.
Result<SolvedDForm> solveShapes(Shape2& shapeA, Shape2& shapeB, const ForwardSettings& job,
                                MessageSink& sink, const RunHooks& hooks,
                                MemoryAtResolution& estimateAt) {
  const auto start = Clock::now();
  SolvedDForm run;
  SeamLayout layout;
  layout.paths[0] = pieceLabel(shapeA, "A");
  layout.paths[1] = pieceLabel(shapeB, "B");
  Result<DrawnPiece> drawnA = drawnPiece(shapeA, job.joinA, "A", sink);
  if (!drawnA.isOk()) return drawnA.status();
  Result<DrawnPiece> drawnB = drawnPiece(shapeB, job.joinB, "B", sink);
  if (!drawnB.isOk()) return drawnB.status();
  layout.pieces[0] = std::move(drawnA).value();
  layout.pieces[1] = std::move(drawnB).value();
  run.sha256A = layout.pieces[0].sha256;
  run.sha256B = layout.pieces[1].sha256;
  if (Status s = matchPieces(job, layout, run, sink); !s.isOk()) return s;
  run.timings.read = secondsSince(start);

  estimateAt = [at = job, layout, perimeterA = run.perimeterA](int resolution) mutable {
    at.resolution = resolution;
    return MemoryEstimate{finestVertices(at, layout, perimeterA), 0.0};
  };
  if (Status fits = checkMemory(estimateAt, job.resolution, layout.bothPaths() + ": the run");
      !fits.isOk())
    return fits;
  layOutSeam(job, run, layout);

  // The exact D-Form wherever it applies; the paper's optimisation otherwise.
  std::string refusal;
  Result<std::optional<SolvedDForm>> exact = tryExactModel(job, layout, run, refusal, sink, hooks);
  if (!exact.isOk()) return exact.status();
  if (exact.value()) {
    exact.value()->timings.total = secondsSince(start);
    return std::move(*exact.value());
  }
  const bool general = job.model == ModelChoice::General;
  const bool ruledAsked = job.model == ModelChoice::Ruled;
  // The ruled engine starts from the paper model's shape: tried where asked, and by auto where
  // the exact model does not apply.
  const std::string ruledRefusal = ruledAsked || job.model == ModelChoice::Auto
                                       ? ruledModelRefusal(job, layout, ruledAsked)
                                       : "-";
  if (ruledAsked && !ruledRefusal.empty())
    return Status(ErrorCode::InputInvalid,
                  layout.bothPaths() + ": the ruled model: " + ruledRefusal);
  const bool ruled = ruledRefusal.empty();
  run.modelUsed.name = general ? "general" : "paper";
  run.modelUsed.reason = general || job.model == ModelChoice::Paper
                             ? std::string("asked for (") + settingKey(Setting::Model) + " " +
                                   modelChoiceName(job.model) + ")"
                             : "the exact model does not apply: " + refusal;
  if (job.model == ModelChoice::Auto && !ruled)
    run.modelUsed.reason +=
        "; the ruled engine's surface of boundary points is not tried: " + ruledRefusal;
  sink.info(run.modelUsed.name + " model" + (ruled ? " (the ruled engine's start): " : ": ") +
            run.modelUsed.reason);
  // Where the sheet has a free brim the ruled engine needs of its start only the boundary points'
  // places, so its paper model is solved on a coarser mesh than the job's (the ruled state is
  // meshed at the job's own). A closed sheet's flips to convex are taken on the start's own
  // positions, which the job's mesh gives more truly (circle + square from its mid side: the
  // exact body from the job's mesh, a state 1.9e-3 of the diagonal from it from the coarser one).
  const bool brim = layout.pieces[0].freeOutline || layout.pieces[1].freeOutline;
  if (job.model == ModelChoice::Auto && !ruled &&
      negativelyCurvedSeamPoint(job, layout).first >= 0) {
    if (Status s = solveIsometricOrPaper(job, layout, run, sink, hooks); !s.isOk()) return s;
    run.timings.total = secondsSince(start);
    return run;
  }
  ForwardSettings paperJob = job;
  if (ruled && brim)
    paperJob.interiorEdgeFactor = std::max(job.interiorEdgeFactor, kRuledStartInteriorEdge);
  if (Status s = solvePaperModel(paperJob, layout, run, sink, hooks); !s.isOk()) return s;
  if (general) {
    const auto solveStart = Clock::now();
    InextensibleResult sheet = solveInextensible(run.model, job.inextensible);
    run.timings.solve += secondsSince(solveStart);
    if (detail::stopRequested(hooks)) return interruptedDuring("the solve");
    run.model = std::move(sheet.model);
    run.modelUsed.stationarity = sheet.summary.stationarity;
    run.modelUsed.stiffness = job.inextensible.stiffness;
    run.modelUsed.newtonSteps = sheet.summary.steps;
    sink.info("general model: " + std::to_string(sheet.summary.steps) + " Newton steps" +
              format(", stationarity %.2g, bending energy %.4g, stretching energy %.4g",
                     sheet.summary.stationarity, sheet.summary.bendingEnergy,
                     sheet.summary.stretchingEnergy) +
              format(", %d factorisations in %.3f s", sheet.summary.factorisations,
                     sheet.summary.seconds));
    if (!sheet.summary.converged) sink.warning("general model: " + sheet.summary.message);
  }
  std::string ruledFailure;
  if (ruled) {
    const auto solveStart = Clock::now();
    const std::string paperReason = run.modelUsed.reason;
    // Auto takes no state that folds the sheet back on itself (a chord folded past 90 degrees).
    std::vector<NamedShape> otherStarts;
    if (brim) {
      SolvedDForm coarse = run;
      ForwardSettings coarseJob = job;
      coarseJob.interiorEdgeFactor =
          std::max(job.interiorEdgeFactor, kRuledSecondStartInteriorEdge);
      MessageSink coarseMessages;
      if (solvePaperModel(coarseJob, layout, coarse, coarseMessages, hooks).isOk())
        otherStarts.push_back(
            {"the paper model's shape on a coarse mesh", std::move(coarse.model)});
      if (detail::stopRequested(hooks)) return interruptedDuring("the solve");
    }
    Status s = solveRuledModel(job, layout, run, otherStarts, sink, ruledAsked ? 180.0 : 90.0);
    run.timings.solve += secondsSince(solveStart);
    if (s.isOk())
      run.modelUsed.reason = ruledAsked ? std::string("asked for (") + settingKey(Setting::Model) +
                                              " " + modelChoiceName(job.model) + ")"
                                        : paperReason + "; the ruled engine met every edge length";
    else {
      sink.info("ruled engine: " + s.message());
      run.modelUsed.reason = paperReason + "; the ruled engine: " + s.message();
      ruledFailure = s.message();
      // The paper model's answer on the job's own mesh.
      if (paperJob.interiorEdgeFactor != job.interiorEdgeFactor)
        if (Status p = solvePaperModel(job, layout, run, sink, hooks); !p.isOk()) return p;
    }
  }
  // A convex metric's answer is its exact body, which the boundary points carry: there a shape
  // made exact from the paper model's would be another shape (the creased squaricle at n = 40:
  // 2.3e-3 of the diagonal from its body).
  if (run.modelUsed.name == "paper" && ruledAsked &&
      negativelyCurvedSeamPoint(job, layout).first >= 0) {
    const auto solveStart = Clock::now();
    Status s = solveIsometricModel(job, layout, run, sink, hooks);
    run.timings.solve += secondsSince(solveStart);
    if (!s.isOk()) {
      ruledFailure += "; from the paper model's shapes: " + s.message();
      run.modelUsed.reason += "; from the paper model's shapes: " + s.message();
    }
  }
  if (ruledAsked && run.modelUsed.name != "ruled")
    return Status(ErrorCode::SolveFailed,
                  layout.bothPaths() + ": the ruled model: " + ruledFailure);
  run.timings.total = secondsSince(start);
  return run;
}

}  // namespace

Result<SolvedDForm> solveDForm(Shape2 a, Shape2 b, const ForwardSettings& settings,
                               MessageSink& sink, const RunHooks& hooks) {
  MemoryAtResolution estimateAt;
  try {
    return solveShapes(a, b, settings, sink, hooks, estimateAt);
  } catch (const std::bad_alloc&) {
    return outOfMemory(estimateAt, settings.resolution,
                       pieceLabel(a, "A") + " and " + pieceLabel(b, "B") + ": the run");
  } catch (const Interrupted& stop) {
    return interruptedDuring(stop.stage());
  }
}

}  // namespace dform
