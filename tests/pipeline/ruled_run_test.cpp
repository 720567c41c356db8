// SPDX-License-Identifier: GPL-3.0-or-later
// Forward runs on the ruled engine: the exact body reached from the paper model's shape on convex
// pairs (the referee), drawn creases, anti D-Forms, a seam point of negative curvature made exact
// with vertices inside the pieces, and the same answer every run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <thread>
#include <tuple>

#include "dform/exact/aligned_distance.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/job_file.h"
#include "dform/ruled/isometric_mesh.h"
#include "dform/validate/gate.h"
#include "forward/isometric_states.h"
#include "shipped_samples.h"

namespace dform {
namespace {

Result<ForwardRun> runRuled(const ForwardJob& job) {
  MessageSink sink;
  return runForward(job, sink);
}

ForwardJob sampleJob(const std::string& name) {
  Result<Job> job = readJobFile(test::forwardSample(name));
  EXPECT_TRUE(job.isOk()) << job.status().message();
  return std::get<ForwardJob>(job.value().run);
}

// A job of two shipped outlines.
ForwardJob pairJob(const std::string& a, const std::string& b, ModelChoice model, int resolution) {
  ForwardJob j;
  j.pieceA = test::forwardSample(a);
  j.pieceB = test::forwardSample(b);
  j.model = model;
  j.resolution = resolution;
  return j;
}

TEST(RuledRun, ReachesTheExactBodyFromThePaperModelsShapeOnConvexPairs) {
  // On a convex glued metric the body is unique (Alexandrov): from the paper model's stretched
  // shape the ruled engine must land on it, its seam within 1e-9 of the diagonal.
  for (const auto& [a, b] :
       {std::pair{"ellipses-a.svg", "ellipses-b.svg"}, std::pair{"circle.svg", "square.svg"}}) {
    Result<ForwardRun> r = runRuled(pairJob(a, b, ModelChoice::Ruled, 60));
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
  Result<ForwardRun> r = runRuled(sampleJob("squaricle.json"));
  ASSERT_TRUE(r.isOk()) << r.status().message();
  const ForwardRun& run = r.value();
  EXPECT_EQ(run.modelUsed.name, "ruled") << run.modelUsed.reason;
  EXPECT_LE(run.metrics.exactDistanceMaxRel, 1e-9);
  EXPECT_LE(run.metrics.lengthErrorMax, 1e-8);
  EXPECT_EQ(run.model.a.creases.size(), 4u);
}

// A seam point of negative curvature: the boundary points alone carry no state, so the paper
// model's shape is made exact with its vertices inside the pieces freed in the flat. The figures
// are the validator's, measured on the output; the gate passes and no triangle folds over.
TEST(RuledRun, ANegativelyCurvedSeamPointIsMadeExactWithVerticesInsideThePieces) {
  for (ModelChoice choice : {ModelChoice::Auto, ModelChoice::Ruled}) {
    ForwardJob j = sampleJob("nonconvex-shifted.json");
    j.model = choice;
    Result<ForwardRun> r = runRuled(j);
    ASSERT_TRUE(r.isOk()) << r.status().message();
    const ForwardRun& nonconvex = r.value();
    EXPECT_EQ(nonconvex.modelUsed.name, "ruled") << nonconvex.modelUsed.reason;
    EXPECT_GT(nonconvex.modelUsed.interiorVertices, 0);
    EXPECT_LE(nonconvex.metrics.lengthErrorMax, 1e-8);
    EXPECT_LE(nonconvex.modelUsed.lengthError, 1e-12);
    EXPECT_EQ(nonconvex.metrics.flipped2d + nonconvex.metrics.flipped3d, 0);
    const GateReport gate =
        runGate(nonconvex.model, GateLimits{}, nonconvex.metrics, nullptr, nullptr);
    EXPECT_TRUE(gate.passed());
    // Two states (docs/ruled.md), the answer first: the less bending at the ranking resolution.
    ASSERT_EQ(nonconvex.modelUsed.states.size(), 2u);
    EXPECT_EQ(nonconvex.modelUsed.states[0].bendingEnergy, nonconvex.modelUsed.bendingEnergy);
    EXPECT_LT(nonconvex.modelUsed.states[0].rankingEnergy,
              nonconvex.modelUsed.states[1].rankingEnergy);
    const std::string& reason = nonconvex.modelUsed.reason;
    EXPECT_NE(reason.find("vertices inside the pieces freed in the flat too, meets every edge "
                          "length"),
              std::string::npos)
        << reason;
    if (choice == ModelChoice::Auto) {
      EXPECT_NE(reason.find("negative curvature (point"), std::string::npos) << reason;
    }
  }
}

// The non-convex sample's states are made at the ranking resolution (100 seam points), ordered
// there and carried to the job's: at 200 seam points the same two states in the same order with
// the same ranking energies, and the answer's seam lies on the one at 100 (every other seam point
// of 200 is one of 100's: 1.3e-3 of the diagonal apart at most), not on the other state, in
// which the paper model at 200 seam points settles (3.8e-2 from the answer).
TEST(RuledRun, TheNonConvexSampleHasTheSameStatesAtEveryResolution) {
  ForwardJob coarse = sampleJob("nonconvex-shifted.json");
  ASSERT_EQ(coarse.resolution, 100);
  ForwardJob fine = coarse;
  fine.resolution = 200;
  Result<ForwardRun> r100 = runRuled(coarse), r200 = runRuled(fine);
  ASSERT_TRUE(r100.isOk() && r200.isOk());
  const ModelUsed& at100 = r100.value().modelUsed;
  const ModelUsed& at200 = r200.value().modelUsed;
  ASSERT_EQ(at100.states.size(), 2u);
  ASSERT_EQ(at200.states.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(at200.states[s].start, at100.states[s].start);
    EXPECT_EQ(at200.states[s].rankingEnergy, at100.states[s].rankingEnergy);
  }
  EXPECT_EQ(at100.states[0].rankingEnergy, at100.bendingEnergy);
  EXPECT_LE(r200.value().metrics.lengthErrorMax, 1e-8);
  const DForm& m100 = r100.value().model;
  const DForm& m200 = r200.value().model;
  ASSERT_EQ(m200.a.seam.size(), 2 * m100.a.seam.size());
  Points3 seam100(Eigen::Index(m100.a.seam.size()), 3), seam200(seam100.rows(), 3);
  for (Eigen::Index k = 0; k < seam100.rows(); ++k) {
    seam100.row(k) = m100.a.shape.row(m100.a.seam[std::size_t(k)]);
    seam200.row(k) = m200.a.shape.row(m200.a.seam[std::size_t(2 * k)]);
  }
  EXPECT_LE(exact::alignedDistance(seam100, seam200).maxRel, 5e-3);
}

// At 150 seam points, whose seam points are not 100's, the answer carried from 100 stalls at the
// dent in piece B (folds meeting at a vertex inside the piece) unless the finer mesh keeps the
// vertices of the state below: kept, the same two states as at 100 are found, in the same order,
// and the answer is the one at 100 (the old carry found one state, the other, from 50).
TEST(RuledRun, TheNonConvexSampleKeepsItsStatesAtAResolutionThatIsNotADoubling) {
  ForwardJob coarse = sampleJob("nonconvex-shifted.json");
  ForwardJob odd = coarse;
  odd.resolution = 150;
  Result<ForwardRun> r100 = runRuled(coarse), r150 = runRuled(odd);
  ASSERT_TRUE(r100.isOk() && r150.isOk());
  const ModelUsed& at100 = r100.value().modelUsed;
  const ModelUsed& at150 = r150.value().modelUsed;
  ASSERT_EQ(at150.states.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(at150.states[s].start, at100.states[s].start);
    EXPECT_EQ(at150.states[s].rankingEnergy, at100.states[s].rankingEnergy);
  }
  EXPECT_LE(r150.value().metrics.lengthErrorMax, 1e-8);
  EXPECT_EQ(r150.value().metrics.flipped2d + r150.value().metrics.flipped3d, 0);
}

// Where a level cannot be made exact on the job's mesh, it is made on twice the interior edge and
// carried onto the job's from there (the seam points stay and only the insides are refined), else
// on the job's mesh keeping the vertices of the state below, else on twice the interior edge.
// Meshes of the job's interior edge refused by a stand-in for the stall: once, the state is
// refined from twice the interior edge; twice, it keeps the vertices below; every time, it is the
// state on twice it. Each is exact.
TEST(IsometricStates, ALevelThatStallsIsMadeOnACoarserInteriorAndRefinedFromThere) {
  auto solved = [](int resolution, double interiorEdgeFactor) {
    ForwardJob job = pairJob("ellipses-a.svg", "ellipses-b.svg", ModelChoice::Paper, resolution);
    job.interiorEdgeFactor = interiorEdgeFactor;
    return runRuled(job);
  };
  using Asked = std::vector<std::pair<int, double>>;
  const Asked refining{{80, 1.0}, {80, 2.0}, {80, 1.0}},
      keeping{{80, 1.0}, {80, 2.0}, {80, 1.0}, {80, 1.0}};
  for (const auto& [refusals, expected, factor] :
       {std::tuple{1, refining, 1.0}, std::tuple{2, keeping, 1.0},
        std::tuple{1000, keeping, 2.0}}) {
    Asked asked;
    int refused = 0;
    std::mutex asking;  // the starts run side by side
    forward_detail::IsometricLevels levels;
    levels.paperShape = [&](int resolution, bool) -> Result<DForm> {
      Result<ForwardRun> r = solved(resolution, 1.0);
      if (!r.isOk()) return r.status();
      return r.value().model;
    };
    levels.mesh = [&](int resolution, double interiorEdgeFactor) -> Result<std::array<Piece, 2>> {
      const std::lock_guard<std::mutex> lock(asking);
      asked.emplace_back(resolution, interiorEdgeFactor);
      if (interiorEdgeFactor == 1.0 && refused++ < refusals)
        return Status(ErrorCode::SolveFailed, "refused by the test");
      Result<ForwardRun> r = solved(resolution, interiorEdgeFactor);
      if (!r.isOk()) return r.status();
      return std::array<Piece, 2>{r.value().model.a, r.value().model.b};
    };
    levels.stop = [] { return false; };
    // Starts at 50 and 80 seam points; the one from 50 is carried to 80, the one from 80 is
    // made exact on its own mesh. A convex metric: one state.
    const forward_detail::IsometricStates found = forward_detail::isometricStates(80, 1.0, levels);
    ASSERT_EQ(found.states.size(), 1u) << refusals;
    const forward_detail::IsometricState& state = found.states.front();
    EXPECT_EQ(state.start, "the paper model's shape at 50 seam points");
    EXPECT_EQ(asked, expected) << refusals;
    EXPECT_EQ(state.interiorEdgeFactor, factor) << refusals;
    const Result<ForwardRun> onThatMesh = solved(80, factor);
    ASSERT_TRUE(onThatMesh.isOk());
    EXPECT_EQ(state.exact.model.b.flat.rows(), onThatMesh.value().model.b.flat.rows());
    EXPECT_LE(state.exact.lengthError, 1e-12);
  }
}

// The starts are made side by side: every start but the last on a thread of its own, which
// reports no progress, the last on the caller's thread, reporting it; the states are listed as one
// thread would list them. Stopped, no start is made and nothing is found.
TEST(IsometricStates, TheStartsAreMadeSideBySideAndListedInOneOrder) {
  struct Call {
    int resolution;
    bool reportsProgress;
    std::thread::id thread;
  };
  std::vector<Call> calls;
  std::mutex calling;
  bool stopped = false;
  forward_detail::IsometricLevels levels;
  levels.paperShape = [&](int resolution, bool reportsProgress) -> Result<DForm> {
    {
      const std::lock_guard<std::mutex> lock(calling);
      calls.push_back({resolution, reportsProgress, std::this_thread::get_id()});
    }
    Result<ForwardRun> r =
        runRuled(pairJob("nonconvex-a.svg", "nonconvex-b.svg", ModelChoice::Paper, resolution));
    if (!r.isOk()) return r.status();
    return r.value().model;
  };
  levels.mesh = [](int, double) -> Result<std::array<Piece, 2>> {
    return Status(ErrorCode::SolveFailed, "not meshed by the test");
  };
  levels.stop = [&] { return stopped; };
  const forward_detail::IsometricStates found = forward_detail::isometricStates(60, 1.0, levels);
  ASSERT_EQ(calls.size(), 2u);
  std::sort(calls.begin(), calls.end(),
            [](const Call& a, const Call& b) { return a.resolution < b.resolution; });
  EXPECT_EQ(calls[0].resolution, 50);
  EXPECT_FALSE(calls[0].reportsProgress);
  EXPECT_NE(calls[0].thread, std::this_thread::get_id());
  EXPECT_EQ(calls[1].resolution, 60);
  EXPECT_TRUE(calls[1].reportsProgress);
  EXPECT_EQ(calls[1].thread, std::this_thread::get_id());
  // The start at 50 cannot be carried to 60 here (no mesh), so it is listed as a failure; the
  // one at 60 is made exact on its own mesh.
  ASSERT_EQ(found.failures.size(), 1u);
  EXPECT_EQ(found.failures[0].first, "the paper model's shape at 50 seam points");
  ASSERT_EQ(found.states.size(), 1u);
  EXPECT_EQ(found.states[0].start, "the paper model's shape at 60 seam points");
  EXPECT_LE(found.states[0].exact.lengthError, 1e-12);

  calls.clear();
  stopped = true;
  const forward_detail::IsometricStates none = forward_detail::isometricStates(60, 1.0, levels);
  EXPECT_TRUE(none.states.empty());
  EXPECT_TRUE(calls.empty());
}

// Where the job's mesh cannot be made exact at once, the continuation on it and the way round it
// (twice the interior edge, then back) are made side by side, the starts too; on one thread,
// one after another, the same states come, bit for bit, in the same order, with the same
// failures. The non-convex pair zipped from B's start at 0.5 is such a case at 100 seam points:
// the coarser mesh is made on a thread beside the caller's.
TEST(IsometricStates, SideBySideGivesWhatOneThreadGives) {
  auto job = [](int resolution, double interiorEdgeFactor, bool solve) {
    ForwardJob j = pairJob("nonconvex-a.svg", "nonconvex-b.svg", ModelChoice::Paper, resolution);
    j.startB.fraction = 0.5;
    j.interiorEdgeFactor = interiorEdgeFactor;
    if (!solve) j.relaxation.maxIterations = j.solver.maxIterations = 0;  // the mesh alone
    return j;
  };
  struct Asked {
    double interiorEdgeFactor;
    std::thread::id thread;
  };
  auto found = [&](bool sideBySide, std::vector<Asked>& asked) {
    std::mutex asking;  // the levels' functions are called from several threads
    forward_detail::IsometricLevels levels;
    levels.paperShape = [&](int resolution, bool) -> Result<DForm> {
      Result<ForwardRun> r = runRuled(job(resolution, 1.0, true));
      if (!r.isOk()) return r.status();
      return r.value().model;
    };
    levels.mesh = [&](int resolution, double interiorEdgeFactor) -> Result<std::array<Piece, 2>> {
      {
        const std::lock_guard<std::mutex> lock(asking);
        asked.push_back({interiorEdgeFactor, std::this_thread::get_id()});
      }
      Result<ForwardRun> r = runRuled(job(resolution, interiorEdgeFactor, false));
      if (!r.isOk()) return r.status();
      return std::array<Piece, 2>{r.value().model.a, r.value().model.b};
    };
    levels.stop = [] { return false; };
    levels.sideBySide = sideBySide;
    return forward_detail::isometricStates(100, 1.0, levels);
  };
  std::vector<Asked> besideAsked, oneAsked;
  const forward_detail::IsometricStates beside = found(true, besideAsked),
                                        one = found(false, oneAsked);
  auto coarserMeshThreads = [](const std::vector<Asked>& asked) {
    std::vector<std::thread::id> threads;
    for (const Asked& a : asked)
      if (a.interiorEdgeFactor == 2.0) threads.push_back(a.thread);
    return threads;
  };
  const std::vector<std::thread::id> besideThreads = coarserMeshThreads(besideAsked);
  ASSERT_EQ(besideThreads.size(), 1u) << "the start at 100 is made via the coarser mesh";
  EXPECT_NE(besideThreads[0], std::this_thread::get_id());
  EXPECT_EQ(coarserMeshThreads(oneAsked), std::vector<std::thread::id>{std::this_thread::get_id()});
  for (const Asked& a : oneAsked) EXPECT_EQ(a.thread, std::this_thread::get_id());

  ASSERT_EQ(beside.states.size(), 2u);
  ASSERT_EQ(one.states.size(), beside.states.size());
  EXPECT_EQ(one.failures, beside.failures);
  for (std::size_t s = 0; s < one.states.size(); ++s) {
    const forward_detail::IsometricState &a = beside.states[s], &b = one.states[s];
    EXPECT_EQ(a.start, b.start) << s;
    EXPECT_EQ(a.interiorEdgeFactor, b.interiorEdgeFactor) << s;
    EXPECT_EQ(a.steps, b.steps) << s;
    EXPECT_EQ(a.exact.bendingEnergy, b.exact.bendingEnergy) << s;
    EXPECT_EQ(a.exact.model.a.shape, b.exact.model.a.shape) << s;
    EXPECT_EQ(a.exact.model.b.shape, b.exact.model.b.shape) << s;
    EXPECT_EQ(a.exact.model.b.flat, b.exact.model.b.flat) << s;
  }
  EXPECT_EQ(one.states[1].start, "the paper model's shape at 100 seam points");
  EXPECT_EQ(one.states[1].interiorEdgeFactor, 1.0);
}

// Asked for where its boundary points find no state on a convex metric (the squaricle's pieces,
// creased, zipped from their starts at n = 30), the ruled model fails saying why: there the answer
// is the exact body, and a shape made exact from the paper model's would be another one.
TEST(RuledRun, AskedForWhereItFindsNoStateItSaysWhy) {
  Result<ForwardRun> r =
      runRuled(pairJob("squaricle-disc.svg", "squaricle-square.svg", ModelChoice::Ruled, 30));
  ASSERT_FALSE(r.isOk());
  EXPECT_EQ(r.status().code(), ErrorCode::SolveFailed);
  EXPECT_NE(r.status().message().find("the ruled model: the ruled engine found no state"),
            std::string::npos)
      << r.status().message();
}

// The paper model's shape of a pair made exact by ruled::isometricMesh, checked from outside:
// every edge of both pieces as long in 3D as flat (measured here), seam partners one point, the
// outline where it was but for the seam points' slide to equal chords, no flat triangle turned
// over, the same answer twice; too few steps is a failure that says so.
TEST(IsometricMesh, MeetsEveryEdgeLengthAndKeepsThePattern) {
  Result<ForwardRun> paper =
      runRuled(pairJob("ellipses-a.svg", "ellipses-b.svg", ModelChoice::Paper, 40));
  ASSERT_TRUE(paper.isOk()) << paper.status().message();
  const DForm& start = paper.value().model;
  ASSERT_GT(paper.value().metrics.lengthErrorMax, 1e-4);  // the paper model stretches
  Result<ruled::IsometricMesh> made = ruled::isometricMesh(start);
  ASSERT_TRUE(made.isOk()) << made.status().message();
  const DForm& m = made.value().model;
  for (const Piece* piece : {&m.a, &m.b})
    for (int f = 0; f < piece->F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int i = piece->F(f, c), k = piece->F(f, (c + 1) % 3);
        const double flat = (piece->flat.row(i) - piece->flat.row(k)).norm();
        const double bent = (piece->shape.row(i) - piece->shape.row(k)).norm();
        EXPECT_LE(std::abs(bent - flat), 1e-12 * flat) << piece->name << " edge " << i << "-" << k;
      }
  for (std::size_t k = 0; k < m.a.seam.size(); ++k)
    EXPECT_EQ(m.a.shape.row(m.a.seam[k]), m.b.shape.row(m.b.seam[k]));
  // The seam points slide along the outline by a small part of a seam edge (the sides' chords
  // differ by the two outlines' curvatures over an edge).
  double seamEdge = 0.0;
  for (std::size_t k = 0; k < start.a.seam.size(); ++k)
    seamEdge += (start.a.flat.row(start.a.seam[k]) -
                 start.a.flat.row(start.a.seam[(k + 1) % start.a.seam.size()]))
                    .norm() /
                double(start.a.seam.size());
  EXPECT_GT(made.value().chordMoveMm, 0.0);
  EXPECT_LE(made.value().chordMoveMm, 1e-3 * seamEdge);
  for (int p = 0; p < 2; ++p) {
    const Piece& before = p == 0 ? start.a : start.b;
    const Piece& after = p == 0 ? m.a : m.b;
    for (int v : after.seam)
      EXPECT_LE((after.flat.row(v) - before.flat.row(v)).norm(), made.value().chordMoveMm + 1e-12);
    for (int f = 0; f < after.F.rows(); ++f) {
      auto area = [&](const Points2& V) {
        const Eigen::Vector2d x = V.row(after.F(f, 1)) - V.row(after.F(f, 0)),
                              y = V.row(after.F(f, 2)) - V.row(after.F(f, 0));
        return x.x() * y.y() - x.y() * y.x();
      };
      EXPECT_GT(area(after.flat) * area(before.flat), 0.0) << after.name << " triangle " << f;
    }
  }
  EXPECT_EQ(made.value().interiorVertices,
            int(start.a.flat.rows() + start.b.flat.rows() - 2 * start.a.seam.size()));
  Result<ruled::IsometricMesh> again = ruled::isometricMesh(start);
  ASSERT_TRUE(again.isOk());
  EXPECT_TRUE(again.value().model.a.shape == m.a.shape && again.value().model.b.flat == m.b.flat);

  ruled::IsometricMeshOptions hurried;
  hurried.maxSteps = 1;
  Result<ruled::IsometricMesh> short_ = ruled::isometricMesh(start, hurried);
  ASSERT_FALSE(short_.isOk());
  EXPECT_EQ(short_.status().code(), ErrorCode::SolveFailed);
  EXPECT_NE(short_.status().message().find("not met in 1 steps"), std::string::npos)
      << short_.status().message();
  DForm unequal = start;
  unequal.b.seam.pop_back();
  EXPECT_FALSE(ruled::isometricMesh(unequal).isOk());
}

// A continuation in the lengths (stages aiming for the start's 3D lengths blended into the flat
// ones) ends where every edge has its flat length, by another path than the one-stage solve: a
// state of its own, as exact, after more steps.
TEST(IsometricMesh, AContinuationInTheLengthsEndsOnTheFlatLengths) {
  Result<ForwardRun> paper =
      runRuled(pairJob("ellipses-a.svg", "ellipses-b.svg", ModelChoice::Paper, 40));
  ASSERT_TRUE(paper.isOk()) << paper.status().message();
  const DForm& start = paper.value().model;
  ruled::IsometricMeshOptions staged;
  staged.stages = 4;
  Result<ruled::IsometricMesh> once = ruled::isometricMesh(start);
  Result<ruled::IsometricMesh> made = ruled::isometricMesh(start, staged);
  ASSERT_TRUE(once.isOk() && made.isOk()) << made.status().message();
  const DForm& m = made.value().model;
  for (const Piece* piece : {&m.a, &m.b})
    for (int f = 0; f < piece->F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int i = piece->F(f, c), k = piece->F(f, (c + 1) % 3);
        const double flat = (piece->flat.row(i) - piece->flat.row(k)).norm();
        const double bent = (piece->shape.row(i) - piece->shape.row(k)).norm();
        EXPECT_LE(std::abs(bent - flat), 1e-12 * flat) << piece->name << " edge " << i << "-" << k;
      }
  EXPECT_LE(made.value().lengthError, 1e-12);
  EXPECT_GT(made.value().steps, once.value().steps);
  EXPECT_GT((m.a.shape - once.value().model.a.shape).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(RuledRun, GivesTheSameShapeEveryRun) {
  ForwardJob j = sampleJob("squaricle.json");
  j.resolution = 60;
  Result<ForwardRun> first = runRuled(j), second = runRuled(j);
  ASSERT_TRUE(first.isOk() && second.isOk());
  ASSERT_EQ(first.value().modelUsed.name, "ruled");
  EXPECT_TRUE(first.value().model.a.shape == second.value().model.a.shape);
  EXPECT_TRUE(first.value().model.b.shape == second.value().model.b.shape);
}

TEST(RuledRun, AntiSampleMeetsEveryLengthAtAStationaryLeastBendingState) {
  Result<ForwardRun> r = runRuled(sampleJob("anti.json"));
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
