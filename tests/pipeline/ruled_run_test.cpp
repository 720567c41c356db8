// Forward runs on the ruled engine: the exact body reached from the paper model's shape on convex
// pairs (the referee), drawn creases, anti D-Forms, what auto leaves to the paper model and why,
// and the same answer every run.
#include <gtest/gtest.h>

#include <cmath>

#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/job_file.h"

namespace dform {
namespace {

std::string sample(const std::string& name) {
  return std::string(DFORM_SAMPLES_DIR) + "/forward/" + name;
}

Result<ForwardRun> run(const ForwardJob& job) {
  MessageSink sink;
  return runForward(job, sink);
}

ForwardJob sampleJob(const std::string& name) {
  Result<Job> job = readJobFile(sample(name));
  EXPECT_TRUE(job.isOk()) << job.status().message();
  return std::get<ForwardJob>(job.value().run);
}

TEST(RuledRun, ReachesTheExactBodyFromThePaperModelsShapeOnConvexPairs) {
  // On a convex glued metric the body is unique (Alexandrov): from the paper model's stretched
  // shape the ruled engine must land on it, its seam within 1e-9 of the diagonal.
  for (const auto& [a, b] :
       {std::pair{"ellipses-a.svg", "ellipses-b.svg"}, std::pair{"circle.svg", "square.svg"}}) {
    ForwardJob j;
    j.pieceA = sample(a);
    j.pieceB = sample(b);
    j.model = ModelChoice::Ruled;
    j.resolution = 60;
    Result<ForwardRun> r = run(j);
    ASSERT_TRUE(r.isOk()) << a << ": " << r.status().message();
    const ForwardRun& ruled = r.value();
    EXPECT_EQ(ruled.modelUsed.name, "ruled");
    ASSERT_EQ(ruled.modelUsed.states.size(), 1u) << a << ": a convex metric has one body";
    EXPECT_LE(ruled.metrics.exactDistanceMaxRel, 1e-9) << a;
    EXPECT_LE(ruled.metrics.lengthErrorMax, 1e-8) << a;
    EXPECT_LE(ruled.modelUsed.lengthError, 1e-12) << a;
    EXPECT_TRUE(ruled.modelUsed.flipsStationary) << a;
    EXPECT_EQ(ruled.metrics.flipped2d + ruled.metrics.flipped3d, 0) << a;
  }
}

TEST(RuledRun, TheCreasedSquaricleIsItsExactBodyFoldedAlongTheDrawnCreases) {
  // Auto: the exact model refuses drawn creases; the ruled engine keeps them as edges that fold
  // freely, and the creases lie on the body's folds, so its answer is the exact body.
  Result<ForwardRun> r = run(sampleJob("squaricle.json"));
  ASSERT_TRUE(r.isOk()) << r.status().message();
  const ForwardRun& run = r.value();
  EXPECT_EQ(run.modelUsed.name, "ruled") << run.modelUsed.reason;
  EXPECT_LE(run.metrics.exactDistanceMaxRel, 1e-9);
  EXPECT_LE(run.metrics.lengthErrorMax, 1e-8);
  EXPECT_EQ(run.model.a.creases.size(), 4u);
}

TEST(RuledRun, AutoLeavesANegativelyCurvedSeamPointToThePaperModelSayingWhy) {
  Result<ForwardRun> r = run(sampleJob("nonconvex-shifted.json"));
  ASSERT_TRUE(r.isOk()) << r.status().message();
  EXPECT_EQ(r.value().modelUsed.name, "paper");
  const std::string& reason = r.value().modelUsed.reason;
  EXPECT_NE(reason.find("the ruled engine is not tried"), std::string::npos) << reason;
  EXPECT_NE(reason.find("negative curvature (point"), std::string::npos) << reason;
}

TEST(RuledRun, AskedForOnANonConvexPairItSaysWhyItFoundNoState) {
  ForwardJob j = sampleJob("nonconvex-shifted.json");
  j.model = ModelChoice::Ruled;
  j.resolution = 40;
  Result<ForwardRun> r = run(j);
  ASSERT_FALSE(r.isOk());
  EXPECT_EQ(r.status().code(), ErrorCode::SolveFailed);
  EXPECT_NE(r.status().message().find("the ruled model: the ruled engine found no state"),
            std::string::npos)
      << r.status().message();
}

TEST(RuledRun, GivesTheSameShapeEveryRun) {
  ForwardJob j = sampleJob("squaricle.json");
  j.resolution = 60;
  Result<ForwardRun> first = run(j), second = run(j);
  ASSERT_TRUE(first.isOk() && second.isOk());
  ASSERT_EQ(first.value().modelUsed.name, "ruled");
  EXPECT_TRUE(first.value().model.a.shape == second.value().model.a.shape);
  EXPECT_TRUE(first.value().model.b.shape == second.value().model.b.shape);
}

TEST(RuledRun, AntiSampleMeetsEveryLengthAtAStationaryLeastBendingState) {
  Result<ForwardRun> r = run(sampleJob("anti.json"));
  ASSERT_TRUE(r.isOk()) << r.status().message();
  const ForwardRun& anti = r.value();
  ASSERT_EQ(anti.modelUsed.name, "ruled") << anti.modelUsed.reason;
  EXPECT_LE(anti.metrics.lengthErrorMax, 1e-8);
  EXPECT_LE(anti.modelUsed.stationarity, 1e-9);
  EXPECT_TRUE(anti.modelUsed.flipsStationary);
  ASSERT_FALSE(anti.modelUsed.states.empty());
  // The answer is the least bending state found, and the states are listed least bending first.
  EXPECT_EQ(anti.modelUsed.states.front().bendingEnergy, anti.modelUsed.bendingEnergy);
  for (std::size_t s = 1; s < anti.modelUsed.states.size(); ++s)
    EXPECT_LE(anti.modelUsed.states[s - 1].bendingEnergy, anti.modelUsed.states[s].bendingEnergy);
  EXPECT_EQ(anti.metrics.flipped2d + anti.metrics.flipped3d, 0);
  // The card sits two ways: the paper model's shape on the run's start mesh and on a coarser one
  // lead to two states, bending 28.29 and 30.60; both are listed, named by their start.
  ASSERT_EQ(anti.modelUsed.states.size(), 2u);
  EXPECT_NEAR(anti.modelUsed.states[0].bendingEnergy, 28.29, 0.01);
  EXPECT_NEAR(anti.modelUsed.states[1].bendingEnergy, 30.60, 0.01);
  EXPECT_EQ(anti.modelUsed.states[0].start, "the paper model's shape");
  EXPECT_EQ(anti.modelUsed.states[1].start, "the paper model's shape on a coarse mesh");
}

}  // namespace
}  // namespace dform
