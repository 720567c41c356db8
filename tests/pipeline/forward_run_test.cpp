// SPDX-License-Identifier: GPL-3.0-or-later
// Forward runs on the samples: the figures the issue asks for, and the run's options.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <new>
#include <regex>
#include <string>
#include <vector>

#include "dform/core/polyline.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/validate/gate.h"
#include "pipeline/reference_seams.h"
#include "shipped_samples.h"

namespace dform {
namespace {

ForwardRun runOk(const ForwardJob& job) {
  MessageSink sink;
  Result<ForwardRun> run = runForward(job, sink);
  EXPECT_TRUE(run.isOk()) << run.status().message();
  return run.isOk() ? std::move(run).value() : ForwardRun{};
}

ForwardJob job(const std::string& a, const std::string& b, int resolution = 60,
               double startB = 0.0) {
  ForwardJob j;
  j.pieceA = test::forwardSample(a);
  j.pieceB = test::forwardSample(b);
  j.resolution = resolution;
  j.startB.fraction = startB;
  return j;
}

void expectPapersFigures(const ForwardRun& run, const std::string& what) {
  const Metrics& m = run.metrics;
  EXPECT_LE(m.lengthError, 0.005) << what;
  EXPECT_LE(m.lengthErrorMax, 0.03) << what;
  EXPECT_LE(m.seamError, 1e-6) << what;
  EXPECT_EQ(m.flipped2d + m.flipped3d, 0) << what;
  // A D-Form, not a flat double disc: its depth is a good part of its width.
  const double depth =
      std::max(run.model.a.shape.col(2).maxCoeff(), run.model.b.shape.col(2).maxCoeff()) -
      std::min(run.model.a.shape.col(2).minCoeff(), run.model.b.shape.col(2).minCoeff());
  const double width =
      (run.model.a.shape.colwise().maxCoeff() - run.model.a.shape.colwise().minCoeff()).maxCoeff();
  EXPECT_GT(depth, 0.15 * width) << what;
}

// A sample pair at resolution 60 and the figures measured on it (dform forward A B
// --resolution 60 --start-b F, report.json's metrics, 2026-11-23).
struct Case {
  const char* a;
  const char* b;
  double startB;
  double lError, lMax, gaussMax;  ///< measured
};

class SampleRuns : public ::testing::TestWithParam<Case> {};

TEST_P(SampleRuns, ReachThePapersFigures) {
  const Case c = GetParam();
  // The paper's model, whose objective these figures pin (the exact one: exact_run_test.cpp).
  ForwardJob paper = job(c.a, c.b, 60, c.startB);
  paper.model = ModelChoice::Paper;
  const ForwardRun run = runOk(paper);
  expectPapersFigures(run, std::string(c.a) + " + " + c.b);
  // The paper's limits are far above these samples' figures: held to twice what was measured,
  // so that a weaker solve fails here. And L_error no lower than half of it: Table 1's 3D
  // smoothness term (w = 0.01) costs isometry (without it L_error falls 5 to 9 times on these
  // pairs), so a much lower figure means the objective is no longer the paper's.
  const Metrics& m = run.metrics;
  EXPECT_LE(m.lengthError, 2 * c.lError);
  EXPECT_GE(m.lengthError, 0.5 * c.lError);
  EXPECT_LE(m.lengthErrorMax, 2 * c.lMax);
  EXPECT_LE(m.gaussMax, 2 * c.gaussMax);
  // Seams pair one to one and the flat outlines keep their drawn perimeters (chords of n = 60).
  EXPECT_EQ(run.model.a.seam.size(), 60u);
  EXPECT_NEAR(run.metrics.seamLengthAMm, run.perimeterA, 2e-3 * run.perimeterA);
  EXPECT_NEAR(run.metrics.seamLengthBMm, run.perimeterB, 2e-3 * run.perimeterB);
  EXPECT_GT(run.timings.total, 0.0);
  EXPECT_GE(run.timings.total, run.timings.solve);
}

INSTANTIATE_TEST_SUITE_P(
    Samples, SampleRuns,
    ::testing::Values(Case{"ellipses-a.svg", "ellipses-b.svg", 0.0, 3.605e-4, 2.010e-3, 5.931e-3},
                      Case{"ellipses-a.svg", "ellipses-b.svg", 0.25, 3.864e-4, 2.382e-3, 5.853e-3},
                      Case{"ellipses-a.svg", "ellipses-a.svg", 0.25, 3.892e-4, 2.391e-3, 5.454e-3},
                      Case{"circle.svg", "square.svg", 0.0, 2.021e-3, 1.649e-2, 2.838e-2},
                      Case{"circle.svg", "square.svg", 0.125, 2.084e-3, 1.674e-2, 2.634e-2},
                      Case{"nonconvex-a.svg", "nonconvex-b.svg", 0.0, 2.010e-3, 1.331e-2, 3.857e-2},
                      Case{"nonconvex-a.svg", "nonconvex-b.svg", 0.3, 2.036e-3, 1.370e-2,
                           3.399e-2}),
    [](const ::testing::TestParamInfo<Case>& info) {
      // "circle_square_at_125": the two files and B's starting fraction in 1/1000.
      std::string name = std::filesystem::path(info.param.a).stem().string() + "_" +
                         std::filesystem::path(info.param.b).stem().string() + "_at_" +
                         std::to_string(int(info.param.startB * 1000));
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

TEST(ForwardRun, ConvexPairLiesOnItsSeamsHull) {
  const ForwardRun run = runOk(job("ellipses-a.svg", "ellipses-b.svg"));
  const GateReport gate = measureAndGate(run.model, GateLimits{}, nullptr);
  const CheckResult* hull = gate.find("hull_distance_rel");
  ASSERT_NE(hull, nullptr);
  EXPECT_EQ(hull->verdict, CheckResult::Verdict::Pass) << hull->detail;
  EXPECT_LT(hull->value, 0.01) << hull->detail;
}

// A closed polygon as a JSON outline file in the test's scratch folder (mm).
std::string polygonFile(const std::string& name, const std::vector<Eigen::Vector2d>& corners) {
  const auto path =
      std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()) + ".json");
  std::ofstream out(path);
  out << "{\"points\": [";
  for (size_t i = 0; i < corners.size(); ++i)
    out << (i ? ", " : "") << "[" << corners[i].x() << ", " << corners[i].y() << "]";
  out << "]}";
  return path.string();
}

// A regular polygon of `sides` sides and perimeter `perimeter` mm, one corner at the top.
std::vector<Eigen::Vector2d> regularPolygon(int sides, double perimeter) {
  const double radius = perimeter / sides / (2 * std::sin(M_PI / sides));
  std::vector<Eigen::Vector2d> corners;
  for (int i = 0; i < sides; ++i) {
    const double t = M_PI / 2 + 2 * M_PI * i / sides;
    corners.emplace_back(150 + radius * std::cos(t), 150 + radius * std::sin(t));
  }
  return corners;
}

// The hull check of a convex pair, with both flat seams judged convex (never "not convex").
CheckResult hullOfConvexPair(const ForwardJob& j) {
  const ForwardRun run = runOk(j);
  const CheckResult hull =
      *measureAndGate(run.model, GateLimits{}, nullptr).find("hull_distance_rel");
  EXPECT_EQ(hull.detail.find("not convex"), std::string::npos) << hull.detail;
  return hull;
}

TEST(ForwardRun, CornersMeetingSmoothPointsMustCreaseSoTheHullIsNotJudged) {
  // Circle and square (paper Fig. 14): each square corner meets a smooth point of the circle,
  // where the real D-Form creases (the Squaricle); the paper's crease-free model bends over the
  // creases and is not its seam's hull. The check says why, with the distance it measured. (The
  // exact model creases there by itself: exact_run_test.cpp.)
  ForwardJob squaricle = job("circle.svg", "square.svg", 60, 0.125);
  squaricle.model = ModelChoice::Paper;
  const CheckResult square = hullOfConvexPair(squaricle);
  EXPECT_EQ(square.verdict, CheckResult::Verdict::NotRun);
  EXPECT_NE(square.detail.find("piece B's corners at seam pairs "), std::string::npos)
      << square.detail;
  EXPECT_NE(square.detail.find("meet smooth points of piece A"), std::string::npos)
      << square.detail;
  EXPECT_NE(square.detail.find("largest distance to the seam's convex hull"), std::string::npos)
      << square.detail;

  // A regular pentagon of the circle's 800 mm: five corners, each named.
  ForwardJob pentagon = job("circle.svg", "circle.svg", 60);
  pentagon.model = ModelChoice::Paper;
  pentagon.pieceA = polygonFile("pentagon", regularPolygon(5, 800));
  const CheckResult five = hullOfConvexPair(pentagon);
  std::filesystem::remove(pentagon.pieceA);
  EXPECT_EQ(five.verdict, CheckResult::Verdict::NotRun);
  EXPECT_NE(five.detail.find("piece A's corners at seam pairs 0, 12, 24, 36, 48 meet smooth "
                             "points of piece B"),
            std::string::npos)
      << five.detail;
}

TEST(ForwardRun, PolygonsWhoseCornersMeetAreJudged) {
  // A square and a 75-degree rhombus with the same 200 mm sides, zipped corner to corner: no
  // corner meets a smooth point, so the check runs on the polygon pair.
  // (The paper model's shape: the exact model glues this pair too, and its body creases both
  // pieces, where the check does not run.)
  ForwardJob polygons = job("square.svg", "square.svg", 60);
  polygons.model = ModelChoice::Paper;
  const double c = std::cos(M_PI * 75 / 180) * 200, s = std::sin(M_PI * 75 / 180) * 200;
  polygons.pieceB = polygonFile("rhombus", {{0, 0}, {200, 0}, {200 + c, s}, {c, s}});
  const CheckResult hull = hullOfConvexPair(polygons);
  std::filesystem::remove(polygons.pieceB);
  EXPECT_NE(hull.verdict, CheckResult::Verdict::NotRun) << hull.detail;
  EXPECT_TRUE(std::isfinite(hull.value)) << hull.detail;
}

TEST(ForwardRun, SquareCornersStayOnTheCutPattern) {
  // The starting pair mid-side puts the corners between uniform seam vertices; the layout keeps
  // them as vertices, so the flat square is not chamfered.
  const ForwardRun run = runOk(job("circle.svg", "square.svg", 60, 0.125));
  const Piece& b = run.model.b;
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(50, 50), Eigen::Vector2d(250, 50),
                                        Eigen::Vector2d(250, 250), Eigen::Vector2d(50, 250)}) {
    double nearest = 1e9;
    for (int v : b.seam) nearest = std::min(nearest, (b.flat.row(v).transpose() - corner).norm());
    EXPECT_LT(nearest, 0.3) << corner.transpose();
  }
}

TEST(ForwardRun, StartNearAPointAndFlip) {
  ForwardJob near = job("circle.svg", "square.svg");
  near.startB.nearestToPoint = true;
  near.startB.point = {150, 50};  // the middle of the square's bottom side
  const ForwardRun run = runOk(near);
  // Counter-clockwise from the rect's first point, its top-left corner: down the left side
  // (0.25) and half along the bottom (0.125).
  EXPECT_NEAR(run.startFractionB, 0.375, 1e-3);
  const Eigen::RowVector2d first = run.model.b.flat.row(run.model.b.seam[0]);
  EXPECT_LT((first - Eigen::RowVector2d(150, 50)).norm(), 0.3);

  ForwardJob flipped = job("ellipses-a.svg", "ellipses-b.svg");
  flipped.flip = true;
  const ForwardRun f = runOk(flipped);
  expectPapersFigures(f, "flipped");
  // B is used turned over: its flat pattern is the mirror image, still counter-clockwise.
  EXPECT_LT(f.model.b.flat.col(0).maxCoeff(), 0.0);
  EXPECT_GT(signedArea(f.model.b.flat(Eigen::all, std::vector<int>{0, 1}).topRows(60)), 0.0);
}

TEST(ForwardRun, UnequalPerimetersStopOrFit) {
  ForwardJob unequal = job("circle.svg", "ellipses-a.svg", 40);
  MessageSink sink;
  const Result<ForwardRun> refused = runForward(unequal, sink);
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.status().code(), ErrorCode::InputInvalid);
  EXPECT_NE(refused.status().message().find("mm"), std::string::npos);
  unequal.fitPerimeter = true;
  const ForwardRun fitted = runOk(unequal);
  EXPECT_NEAR(fitted.scaleB, fitted.perimeterA / fitted.perimeterB, 1e-12);
  EXPECT_NEAR(fitted.metrics.seamLengthAMm, fitted.metrics.seamLengthBMm, 1e-3 * fitted.perimeterA);
}

TEST(ForwardRun, RunsAreReproducible) {
  const ForwardRun one = runOk(job("nonconvex-a.svg", "nonconvex-b.svg", 40));
  const ForwardRun two = runOk(job("nonconvex-a.svg", "nonconvex-b.svg", 40));
  EXPECT_EQ(one.metrics.lengthError, two.metrics.lengthError);
  EXPECT_EQ(one.model.a.shape, two.model.a.shape);
}

TEST(ForwardRun, BadJobsAreUsageErrors) {
  MessageSink sink;
  ForwardJob bad = job("circle.svg", "square.svg", 4);
  EXPECT_EQ(runForward(bad, sink).status().code(), ErrorCode::Usage);
  bad = job("circle.svg", "square.svg");
  bad.startA.fraction = 1.0;
  EXPECT_EQ(runForward(bad, sink).status().code(), ErrorCode::Usage);
  bad = job("circle.svg", "square.svg");
  bad.weights.isometry = -1;
  EXPECT_EQ(runForward(bad, sink).status().code(), ErrorCode::Usage);
}

// --interior-edge meshes the interiors coarser than the seam: about 1/F^2 of the interior
// vertices away from the body's folds (which the exact model meshes along at every factor, so the
// whole interior shrinks less: 0.46 at F = 2 on this pair), the same seam, and under the exact
// model the same seam in 3D (its shape is the seam's). Outside [0.25, 8] the job is refused
// naming the option.
TEST(ForwardRun, TheInteriorEdgeFactorCoarsensTheInteriorOnly) {
  const ForwardRun fine = runOk(job("ellipses-a.svg", "ellipses-b.svg", 60));
  ForwardJob coarseJob = job("ellipses-a.svg", "ellipses-b.svg", 60);
  coarseJob.interiorEdgeFactor = 2.0;
  const ForwardRun coarse = runOk(coarseJob);
  ASSERT_EQ(fine.modelUsed.name, "exact");
  ASSERT_EQ(coarse.modelUsed.name, "exact");
  ASSERT_EQ(coarse.model.a.seam.size(), fine.model.a.seam.size());
  const double interiorFine = double(fine.model.a.flat.rows()) - 60,
               interiorCoarse = double(coarse.model.a.flat.rows()) - 60;
  EXPECT_GT(interiorCoarse / interiorFine, 0.15);
  EXPECT_LT(interiorCoarse / interiorFine, 0.55);
  for (size_t i = 0; i < fine.model.a.seam.size(); ++i)
    EXPECT_LT((coarse.model.a.shape.row(coarse.model.a.seam[i]) -
               fine.model.a.shape.row(fine.model.a.seam[i]))
                  .norm(),
              1e-9)
        << "seam vertex " << i;
  MessageSink sink;
  for (double factor : {0.2, 9.0, std::nan("")}) {
    coarseJob.interiorEdgeFactor = factor;
    const Status refused = runForward(coarseJob, sink).status();
    EXPECT_EQ(refused.code(), ErrorCode::Usage) << factor;
    EXPECT_EQ(refused.setting(), Setting::InteriorEdge) << refused.message();
    EXPECT_EQ(refused.message().rfind("interior_edge must be a number between 0.25 and 8", 0), 0)
        << refused.message();
  }
}

TEST(ForwardRun, InterruptionStopsTheSolve) {
  std::atomic<bool> stop{false};
  RunHooks hooks;
  hooks.interrupted = &stop;
  // Asked for during the relaxation's first step: nothing runs after it, neither more
  // relaxation, nor Levenberg-Marquardt, nor the multiplier rounds.
  std::vector<std::string> stages;
  hooks.onIteration = [&](const char* stage, const IterationSummary&) {
    stages.push_back(stage);
    stop = true;
  };
  MessageSink sink;
  ForwardJob paper = job("ellipses-a.svg", "ellipses-b.svg", 40);
  paper.model = ModelChoice::Paper;
  const Result<ForwardRun> run = runForward(paper, sink, hooks);
  ASSERT_FALSE(run.isOk());
  EXPECT_EQ(run.status().code(), ErrorCode::Interrupted);
  EXPECT_EQ(run.status().message(), "interrupted during the solve");
  EXPECT_EQ(stages, std::vector<std::string>{"relaxing"});
  // Asked for before: the run stops before meshing a piece (seconds each on a fine mesh).
  stages.clear();
  const Result<ForwardRun> early = runForward(paper, sink, hooks);
  EXPECT_EQ(early.status().message(), "interrupted during the meshing");
  EXPECT_TRUE(stages.empty());
  // The exact engine has no iterations to report, and its result is not kept either.
  const Result<ForwardRun> exact =
      runForward(job("ellipses-a.svg", "ellipses-b.svg", 40), sink, hooks);
  ASSERT_FALSE(exact.isOk());
  EXPECT_EQ(exact.status().code(), ErrorCode::Interrupted);
  EXPECT_TRUE(stages.empty());
}

// A failed allocation during the run (here thrown where the solver reports an iteration) is a
// usage error offering a lower resolution, not an internal error.
TEST(ForwardRun, AFailedAllocationOffersALowerResolution) {
  RunHooks hooks;
  hooks.onIteration = [](const char*, const IterationSummary&) { throw std::bad_alloc(); };
  MessageSink sink;
  ForwardJob paper = job("ellipses-a.svg", "ellipses-b.svg", 60);
  paper.model = ModelChoice::Paper;
  const Result<ForwardRun> run = runForward(paper, sink, hooks);
  EXPECT_EQ(run.status().code(), ErrorCode::Usage);
  const std::string message = run.status().message();
  EXPECT_EQ(message.rfind(paper.pieceA + " and " + paper.pieceB +
                              ": the run at resolution 60 ran out of memory",
                          0),
            0u)
      << message;
  std::smatch offered;
  ASSERT_TRUE(
      std::regex_search(message, offered, std::regex("a resolution of ([0-9]+) or less fits")));
  EXPECT_LT(std::stoi(offered[1]), 60);
}

}  // namespace
}  // namespace dform
