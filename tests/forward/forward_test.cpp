// SPDX-License-Identifier: GPL-3.0-or-later
// Forward modelling end to end on small inputs: the start, the local-global stage, the solve.
#include "dform/forward/forward.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "dform/exact/aligned_distance.h"
#include "dform/forward/coarse_to_fine.h"
#include "dform/model/injectivity.h"
#include "dform/model/term_table.h"
#include "dform/model/terms.h"
#include "dform/model/transfer.h"
#include "dform/validate/gate.h"
#include "dform/validate/metrics.h"
#include "model/test_meshes.h"
#include "pipeline/reference_seams.h"

namespace dform {
namespace {

// Two ellipses of (nearly) equal perimeter, 40 seam vertices: a few hundred vertices in all.
struct EllipsePair {
  EllipsePair(double startB = 0.0) {
    const Points2 A = test::ellipse(120, 70), B = test::ellipse(110, 82.305579);
    a = test::meshedPiece(A, 40, false);
    b = test::meshedPiece(B, 40, true, startB);
  }
  Piece a, b;
};

TEST(Forward, MeshedPiecesZipCoarseToFineToTheOneLevelShape) {
  // 90 seam points: a coarse level of 30 starts the finest one. Both solves end on the same shape
  // of the same objective; the finest level started from the coarse one needs fewer relaxation
  // steps (a coarse level that failed to mesh, or paired the wrong points, would start it from
  // the pillow or from a wrong shape).
  const Points2 A = test::ellipse(120, 70), B = test::ellipse(110, 82.305579);
  const Piece a = test::meshedPiece(A, 90, false), b = test::meshedPiece(B, 90, true);
  ForwardSettings o;
  o.solver.functionTolerance = 1e-10;
  const ForwardResult oneLevel = solveForward(a, b, o);
  const ForwardResult levels = solveMeshedCoarseToFine(a, b, o);
  ASSERT_TRUE(oneLevel.summary.usable() && levels.summary.usable());
  EXPECT_LT(levels.relaxation.iterations, oneLevel.relaxation.iterations / 2)
      << levels.relaxation.iterations << " against " << oneLevel.relaxation.iterations;
  ASSERT_EQ(levels.model.a.shape.rows(), a.flat.rows());
  auto seam = [](const Piece& p) {
    Points3 s(Eigen::Index(p.seam.size()), 3);
    for (std::size_t k = 0; k < p.seam.size(); ++k) s.row(Eigen::Index(k)) = p.shape.row(p.seam[k]);
    return s;
  };
  const exact::AlignedDistance d =
      exact::alignedDistance(seam(oneLevel.model.a), seam(levels.model.a));
  EXPECT_LT(d.maxRel, 1e-4);
}

TEST(Forward, PillowStartIsClosedAndInflated) {
  EllipsePair p;
  const DForm start = pillowInitialGuess(p.a, p.b);
  for (std::size_t k = 0; k < p.a.seam.size(); ++k)
    EXPECT_LT((start.a.shape.row(p.a.seam[k]) - start.b.shape.row(p.b.seam[k])).norm(), 1e-9);
  // A's interior above the seam, B's below.
  EXPECT_GT(start.a.shape.col(2).maxCoeff(), 1.0);
  EXPECT_LT(start.b.shape.col(2).minCoeff(), -1.0);
  EXPECT_EQ(computeMetrics(start, {}).flipped3d, 0);
}

TEST(Forward, SolvesTwoEllipsesToThePapersFigures) {
  EllipsePair p;
  const ForwardResult r = solveForward(p.a, p.b, ForwardSettings{});
  ASSERT_TRUE(r.summary.usable()) << r.summary.message;
  const Metrics m = computeMetrics(r.model, {});
  EXPECT_LE(m.lengthError, 0.005);
  EXPECT_LE(m.lengthErrorMax, 0.03);
  EXPECT_LE(m.seamError, 1e-6);
  EXPECT_EQ(m.flipped2d + m.flipped3d, 0);
  EXPECT_EQ(m.degenerate2d + m.degenerate3d, 0);
  // The flat outlines stay where they were drawn (within the outline tolerance).
  const double perimeter = closedLength(test::ellipse(120, 70));
  for (std::size_t k = 0; k < p.a.seam.size(); ++k)
    EXPECT_LT((r.model.a.flat.row(p.a.seam[k]) - p.a.flat.row(p.a.seam[k])).norm(),
              3e-4 * perimeter);
  // Not a flat double disc: the shape has depth comparable to its size.
  const double depth = r.model.a.shape.col(2).maxCoeff() - r.model.b.shape.col(2).minCoeff();
  EXPECT_GT(depth, 30.0);
  // Two convex outlines make the convex hull of their seam (Demaine and Price): every vertex
  // lies within 1 % of the seam's bounding-box diagonal of that hull.
  const GateReport gate = measureAndGate(r.model, GateLimits{}, nullptr);
  const CheckResult* hull = gate.find("hull_distance_rel");
  ASSERT_NE(hull, nullptr);
  EXPECT_EQ(hull->verdict, CheckResult::Verdict::Pass) << hull->detail;
  EXPECT_LT(hull->value, 0.01);
}

TEST(Forward, ADifferentStartingPairMakesADifferentDFormOfTheSameQuality) {
  EllipsePair p0(0.0), p1(0.25);
  const ForwardResult r0 = solveForward(p0.a, p0.b, ForwardSettings{});
  const ForwardResult r1 = solveForward(p1.a, p1.b, ForwardSettings{});
  const Metrics m1 = computeMetrics(r1.model, {});
  EXPECT_LE(m1.lengthError, 0.005);
  EXPECT_LE(m1.lengthErrorMax, 0.03);
  EXPECT_LE(m1.seamError, 1e-6);
  // Compare rotation-free sizes: the spread of the 3D seam around its centroid.
  auto extent = [](const Piece& a) {
    Points3 S(a.seam.size(), 3);
    for (std::size_t k = 0; k < a.seam.size(); ++k) S.row(k) = a.shape.row(a.seam[k]);
    const Points3 C = S.rowwise() - S.colwise().mean();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C.transpose() * C);
    return eig.eigenvalues();
  };
  EXPECT_GT((extent(r0.model.a) - extent(r1.model.a)).norm(), 0.05 * extent(r0.model.a).norm());
}

TEST(Forward, IdenticalEllipsesAQuarterTurnApartMakeTheClassicDForm) {
  // Zipped with the same start, the pair would close flat; a quarter turn on, the pillow start
  // must leave the flat state (the seam lift) for the solve to find the D-Form.
  const Points2 E = test::ellipse(120, 70);
  const Piece a = test::meshedPiece(E, 40, false), b = test::meshedPiece(E, 40, true, 0.25);
  const ForwardResult r = solveForward(a, b, ForwardSettings{});
  const Metrics m = computeMetrics(r.model, {});
  EXPECT_LE(m.lengthError, 0.005);
  EXPECT_LE(m.lengthErrorMax, 0.03);
  EXPECT_EQ(m.flipped3d, 0);
  const double depth = r.model.a.shape.col(2).maxCoeff() - r.model.b.shape.col(2).minCoeff();
  EXPECT_GT(depth, 40.0);
}

TEST(Forward, LocalGlobalNeverRaisesItsEnergy) {
  EllipsePair p;
  ForwardSettings plain, none;
  none.relaxation.maxIterations = 0;
  none.solver.maxIterations = 0;
  none.constraintRounds = 0;
  plain.solver.maxIterations = 0;
  plain.constraintRounds = 0;
  const ForwardResult relaxed = solveForward(p.a, p.b, plain);
  EXPECT_GT(relaxed.relaxation.iterations, 0);
  EXPECT_LE(relaxed.relaxation.finalEnergy, relaxed.relaxation.initialEnergy);
  // The relaxation alone brings the paper's objective down from the pillow start.
  const ForwardResult start = solveForward(p.a, p.b, none);
  EXPECT_LT(relaxed.summary.initialCost, 0.5 * start.summary.initialCost);
}

TEST(Forward, TheRelaxationNeverRaisesItsEnergyFromStepToStep) {
  EllipsePair p;
  ForwardSettings o;
  o.solver.maxIterations = 0;
  o.constraintRounds = 0;
  std::vector<double> energies;
  o.relaxation.callback = [&](const IterationSummary& it) {
    energies.push_back(it.cost);
    return true;
  };
  const ForwardResult r = solveForward(p.a, p.b, o);
  ASSERT_EQ(int(energies.size()), r.relaxation.iterations);
  double previous = r.relaxation.initialEnergy;
  for (double e : energies) {
    EXPECT_LE(e, previous);
    previous = e;
  }
  EXPECT_EQ(previous, r.relaxation.finalEnergy);
}

// The ellipse pair's relaxation from the pillow with the drawn outlines held, as the solve sets
// it up but in millimetres rather than the solver's unit (the mean seam edge): the terms balance
// otherwise and the relaxation has more to do (716 steps to a tolerance of 1e-6, against 150),
// enough to tell a good stop test and a working acceleration from bad ones.
struct EllipseRelaxation {
  EllipsePair p;
  DForm start = pillowInitialGuess(p.a, p.b);
  VariableLayout layout{int(p.a.flat.rows()), int(p.b.flat.rows()), p.a.seam, p.b.seam};
  EdgeLengthPairs edges = meshEdgePairs(layout, p.a.F, p.b.F);
  Eigen::VectorXd x0 = packVariables(layout, start.a, start.b);
  std::vector<std::unique_ptr<ResidualTerm>> terms;
  std::unique_ptr<LocalGlobalRelaxation> relaxation;
  explicit EllipseRelaxation(int supernodalFrom = kSupernodalRelaxationVertices) {
    weightByFlatLength(edges, x0, 1.0);
    terms = makeTerms(forwardTerms(), {layout, start.a, start.b, edges, p.a.seam, p.b.seam});
    std::vector<int> held;
    for (const auto& [piece, seam] : {std::pair{0, &p.a.seam}, std::pair{1, &p.b.seam}})
      for (int v : *seam) held.insert(held.end(), {layout.u(piece, v), layout.u(piece, v) + 1});
    relaxation = std::make_unique<LocalGlobalRelaxation>(
        linearTerms(forwardTerms(), terms, ForwardWeights{}), edges, x0, held, supernodalFrom);
  }
  LocalGlobalSummary relax(const LocalGlobalOptions& options, Eigen::VectorXd& x) const {
    return relaxation->relax(options, x);
  }
};

TEST(Forward, AndersonAcceleratesTheRelaxationAndKeepsMostOfItsSteps) {
  const EllipseRelaxation r;
  LocalGlobalOptions accelerated;
  accelerated.relativeTolerance = 1e-6;
  Eigen::VectorXd x = r.x0;
  const LocalGlobalSummary fast = r.relax(accelerated, x);
  ASSERT_LT(fast.iterations, accelerated.maxIterations);
  // Ten times as many plain steps end higher.
  LocalGlobalOptions plain = accelerated;
  plain.andersonDepth = 0;
  plain.maxIterations = 10 * fast.iterations;
  Eigen::VectorXd y = r.x0;
  const LocalGlobalSummary slow = r.relax(plain, y);
  EXPECT_EQ(slow.iterations, plain.maxIterations);
  EXPECT_GT(slow.finalEnergy, fast.finalEnergy);
  EXPECT_EQ(slow.andersonRejected, 0);
  // A refused accelerated step keeps Anderson's history. Cleared instead, it left one secant,
  // whose extrapolation was refused in turn: here 45 % of 1552 steps, against 25 % of 716.
  EXPECT_LT(3 * fast.andersonRejected, fast.iterations);
}

TEST(Forward, TheRelaxationStepsAlikeWithEitherFactor) {
  // Large meshes factorise the relaxation's blocks supernodally, small ones simplicially (the
  // ellipse pair's blocks have ~1.4k vertices). Forced to the supernodal factor, the same plain
  // steps reach the same point up to rounding, and the rounding differs: it was used.
  const EllipseRelaxation simplicial, supernodal(0);
  LocalGlobalOptions plain;
  plain.andersonDepth = 0;
  plain.maxIterations = 30;
  plain.relativeTolerance = 0.0;
  Eigen::VectorXd x = simplicial.x0, y = supernodal.x0;
  const LocalGlobalSummary a = simplicial.relax(plain, x), b = supernodal.relax(plain, y);
  ASSERT_EQ(a.iterations, 30);
  ASSERT_EQ(b.iterations, 30);
  EXPECT_GT((x - simplicial.x0).cwiseAbs().maxCoeff(), 1.0) << "the steps move the shape (mm)";
  // Up to rounding and a translation, which only the proximal term fixes (1e-8 of K's diagonal,
  // so rounding moves it by ~1e-6 mm): the edges agree.
  double edgeDifference = 0.0, longest = 0.0;
  for (std::size_t e = 0; e < simplicial.edges.x.size(); ++e) {
    const auto [i, j] = simplicial.edges.x[e];
    const auto [k, l] = simplicial.edges.u[e];
    edgeDifference = std::max(
        {edgeDifference,
         ((x.segment<3>(i) - x.segment<3>(j)) - (y.segment<3>(i) - y.segment<3>(j))).norm(),
         ((x.segment<2>(k) - x.segment<2>(l)) - (y.segment<2>(k) - y.segment<2>(l))).norm()});
    longest = std::max(longest, (x.segment<3>(i) - x.segment<3>(j)).norm());
  }
  EXPECT_LT(edgeDifference, 1e-10 * longest);
  EXPECT_NEAR(a.finalEnergy, b.finalEnergy, 1e-12 * a.finalEnergy);
  EXPECT_FALSE(x == y) << "the same rounding to the last bit: the supernodal factor was not used";
}

TEST(Forward, TheRelaxationStopsWhereAPlainStepGainsLittle) {
  // Stopped by its tolerance, the relaxation ends where one more plain step (no acceleration)
  // lowers the energy by little: the stop test measures that gain at the current point, not the
  // decrease of the step taken, which an accelerated step that jumped short makes small far from
  // the end (stopping on that, the run to 1e-5 ended where the next plain step gained 4e-5).
  const EllipseRelaxation r;
  for (double tolerance : {1e-4, 1e-5, 1e-6}) {
    LocalGlobalOptions o;
    o.relativeTolerance = tolerance;
    Eigen::VectorXd x = r.x0;
    const LocalGlobalSummary stopped = r.relax(o, x);
    ASSERT_LT(stopped.iterations, o.maxIterations);
    LocalGlobalOptions plainStep;
    plainStep.andersonDepth = 0;
    plainStep.maxIterations = 1;
    const LocalGlobalSummary next = r.relax(plainStep, x);
    EXPECT_EQ(next.initialEnergy, stopped.finalEnergy);
    const double gain = next.initialEnergy - next.finalEnergy;
    EXPECT_GE(gain, 0.0);
    // The test measures the global step's gain; the local step's comes on top (here up to as
    // much again).
    EXPECT_LT(gain, 3 * tolerance * next.initialEnergy) << tolerance;
  }
}

TEST(Forward, TheRelaxationRunsStifferBelowTheDefaultSmoothing) {
  ForwardSettings o;  // continuation 6
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.0005, o), 0.003);
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.0001, o), 0.0006);
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.004, o), 0.01) << "never stiffer than the default";
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.01, o), 0.01);
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.05, o), 0.05)
      << "a stiffer sheet relaxes at its own weight";
  ForwardSettings off = o;
  off.smoothingContinuation = 1.0;
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.0005, off), 0.0005);
  ForwardSettings relaxationOnly = o;  // nothing would continue from the relaxation's shape
  relaxationOnly.solver.maxIterations = 0;
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.0005, relaxationOnly), 0.0005);
  ForwardSettings hole = o;  // an anti or demi D-Form is tuned for 0.001
  hole.continuationSmoothing = 0.001;
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.001, hole), 0.001);
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.0001, hole), 0.0006);
  EXPECT_DOUBLE_EQ(relaxationSmoothing(0.0005, hole), 0.001);
}

TEST(Forward, AContinuationInTheSmoothingEndsOnTheDirectSolvesMinimum) {
  // At w_3D = 0.0005 the relaxation runs at 0.003 and LM continues at 0.0005. Both solves are
  // run to convergence: they must end on the same shape of the same objective, the continued
  // one after fewer relaxation steps.
  EllipsePair p;
  ForwardSettings continued;
  continued.weights.smooth3d = 0.0005;
  continued.solver.functionTolerance = 1e-12;
  continued.solver.gradientTolerance = 1e-9;
  continued.solver.maxIterations = 200;
  ForwardSettings direct = continued;
  direct.smoothingContinuation = 0.0;
  const ForwardResult c = solveForward(p.a, p.b, continued), d = solveForward(p.a, p.b, direct);
  ASSERT_TRUE(c.summary.usable() && d.summary.usable());
  EXPECT_NEAR(c.summary.finalCost, d.summary.finalCost, 1e-7 * d.summary.finalCost);
  double largest = 0;
  for (Eigen::Index i = 0; i < c.model.a.shape.rows(); ++i)
    largest = std::max(largest, (c.model.a.shape.row(i) - d.model.a.shape.row(i)).norm());
  EXPECT_LT(largest, 1e-3 * c.unitMm) << "mm";
  EXPECT_LT(c.relaxation.iterations, d.relaxation.iterations);
}

// An interior vertex of A (the one nearest the piece's centre) and a neighbour of it.
std::pair<int, int> centralVertexAndNeighbour(const Piece& a) {
  const Eigen::RowVector2d centre = a.flat.colwise().mean();
  int v = 0;
  for (int i = 1; i < a.flat.rows(); ++i)
    if ((a.flat.row(i) - centre).norm() < (a.flat.row(v) - centre).norm()) v = i;
  for (int f = 0; f < a.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (a.F(f, c) == v) return {v, a.F(f, (c + 1) % 3)};
  return {v, -1};
}

// The solved pair with A's central vertex dragged past its neighbour in 3D: the triangles
// between them turn over, so the shape has folds the gate counts.
DForm foldedEllipses(const DForm& solved) {
  DForm folded = solved;
  const auto [v, w] = centralVertexAndNeighbour(folded.a);
  folded.a.shape.row(v) += 1.8 * (folded.a.shape.row(w) - folded.a.shape.row(v));
  return folded;
}

TEST(Forward, FoldGuardCountsTheGatesFoldsAndRefusesOnlyNewOnes) {
  EllipsePair p;
  const ForwardResult r = solveForward(p.a, p.b, ForwardSettings{});
  const DForm folded = foldedEllipses(r.model);
  ASSERT_GT(computeMetrics(folded, {}).flipped3d, 0);
  const VariableLayout layout(int(p.a.flat.rows()), int(p.b.flat.rows()), p.a.seam, p.b.seam);
  const FoldGuard guard(layout, p.a, p.b);
  const Eigen::VectorXd clean = packVariables(layout, r.model.a, r.model.b);
  const Eigen::VectorXd bad = packVariables(layout, folded.a, folded.b);
  EXPECT_EQ(guard.count(clean), 0);
  EXPECT_GT(guard.count(bad), 0);
  EXPECT_TRUE(guard.addsFold(clean, bad));
  EXPECT_FALSE(guard.addsFold(bad, clean)) << "unfolding is always allowed";
  EXPECT_FALSE(guard.addsFold(bad, bad)) << "a fold already there is not a new one";
  // A flat triangle turned over counts as well: A's central vertex mirrored across a neighbour.
  DForm flipped = r.model;
  const auto [v, w] = centralVertexAndNeighbour(flipped.a);
  flipped.a.flat.row(v) += 2.0 * (flipped.a.flat.row(w) - flipped.a.flat.row(v));
  ASSERT_GT(computeMetrics(flipped, {}).flipped2d, 0);
  EXPECT_TRUE(guard.addsFold(clean, packVariables(layout, flipped.a, flipped.b)));
}

TEST(Forward, AFoldedStartEndsUnfolded) {
  EllipsePair p;
  const ForwardResult solved = solveForward(p.a, p.b, ForwardSettings{});
  const DForm folded = foldedEllipses(solved.model);
  ASSERT_GT(computeMetrics(folded, {}).flipped3d, 0);
  const ForwardResult r = solveForward(folded.a, folded.b, ForwardSettings{});
  ASSERT_TRUE(r.summary.usable()) << r.summary.message;
  const Metrics m = computeMetrics(r.model, {});
  EXPECT_EQ(m.flipped2d + m.flipped3d, 0);
  EXPECT_LE(m.lengthError, 0.005);
  EXPECT_LE(m.lengthErrorMax, 0.03);
}

TEST(Forward, TransferIsExactOnTheSameMeshAndStartsAFinerSolve) {
  EllipsePair coarse;
  const ForwardResult r = solveForward(coarse.a, coarse.b, ForwardSettings{});
  // The same mesh: barycentric transfer gives the vertices back.
  const Points3 same = transferShape(r.model.a, r.model.a.flat);
  EXPECT_LT((same - r.model.a.shape).cwiseAbs().maxCoeff(), 1e-9);
  // A finer mesh of the same outlines started from the coarse solution converges as well.
  Piece a = test::meshedPiece(test::ellipse(120, 70), 80, false);
  Piece b = test::meshedPiece(test::ellipse(110, 82.305579), 80, true);
  a.shape = transferShape(r.model.a, a.flat);
  b.shape = transferShape(r.model.b, b.flat);
  for (std::size_t k = 0; k < a.seam.size(); ++k)
    a.shape.row(a.seam[k]) = b.shape.row(b.seam[k]) =
        0.5 * (a.shape.row(a.seam[k]) + b.shape.row(b.seam[k]));
  const ForwardResult fine = solveForward(a, b, ForwardSettings{});
  const Metrics m = computeMetrics(fine.model, {});
  EXPECT_LE(m.lengthError, 0.005);
  EXPECT_LE(m.seamError, 1e-6);
  EXPECT_LE(fine.summary.factorisations, 3);
}

TEST(Forward, TransferInterpolatesInsideAndTakesTheNearestTriangleOutside) {
  // A piece whose 3D shape is a known linear map of its flat layout: any point inside must get
  // exactly that map (piecewise-linear interpolation reproduces linear functions), whichever
  // cells of the search grid it falls in.
  Piece source = test::meshedPiece(test::ellipse(120, 70), 40, false);
  Eigen::Matrix<double, 2, 3> map;
  map << 0.3, -1.2, 2.0, 0.7, 0.4, -0.5;
  source.shape = source.flat * map;
  source.shape.col(2).array() += 5.0;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> t(0.0, 2.0 * M_PI), r(0.0, 0.95);
  Points2 inside(2000, 2), outside(200, 2);
  for (Eigen::Index i = 0; i < inside.rows(); ++i) {
    const double angle = t(rng), radius = std::sqrt(r(rng));  // uniform in the ellipse
    inside.row(i) << 120 * radius * std::cos(angle), 70 * radius * std::sin(angle);
  }
  Points3 expected = inside * map;
  expected.col(2).array() += 5.0;
  EXPECT_LT((transferShape(source, inside) - expected).cwiseAbs().maxCoeff(), 1e-9);
  // Just outside (a finer seam bulging past the coarse one): clamped onto a boundary triangle
  // near the point, so within a triangle's size of the map's value there.
  for (Eigen::Index i = 0; i < outside.rows(); ++i) {
    const double angle = t(rng);
    outside.row(i) << 121.0 * std::cos(angle), 71.0 * std::sin(angle);
  }
  const Points3 clamped = transferShape(source, outside);
  Points3 onMap = outside * map;
  onMap.col(2).array() += 5.0;
  const double edge = 2.0 * M_PI * 100.0 / 40.0;  // about the mean seam edge
  EXPECT_LT((clamped - onMap).rowwise().norm().maxCoeff(), 3.0 * edge);
}

}  // namespace
}  // namespace dform
