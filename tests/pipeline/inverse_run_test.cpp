// SPDX-License-Identifier: GPL-3.0-or-later
// Inverse runs on the samples: the figures the issue asks for, and bad curves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>

#include "dform/core/polyline.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/inverse_pipeline.h"
#include "dform/validate/gate.h"
#include "pipeline/reference_seams.h"
#include "shipped_samples.h"

namespace dform {
namespace {

class InverseSamples : public ::testing::TestWithParam<const char*> {};

// L_error and L_max measured on each sample at resolution 60 (dform inverse CURVE --resolution 60,
// report.json's metrics, 2026-11-23). The paper's limits (0.5 %, 3 %) are above them. The on-hull
// curves are made by the exact model: there the figures measure how the pieces' meshes chord the
// polyhedral hull of 60 points (their triangles cross its edges), not a solve.
std::pair<double, double> measuredFigures(const std::string& curve) {
  static const std::map<std::string, std::pair<double, double>> figures = {
      {"tennis-ball.obj", {1.518e-3, 8.366e-3}},
      {"saddle.obj", {1.152e-3, 7.554e-3}},
      {"pushed-in.obj", {4.521e-4, 3.470e-3}},
      {"rotated.json", {1.507e-3, 8.382e-3}}};
  return figures.at(curve);
}

TEST_P(InverseSamples, ReachThePapersFigures) {
  InverseJob job;
  job.curve = test::inverseSample(GetParam());
  job.resolution = 60;
  MessageSink sink;
  const Result<InverseRun> result = runInverse(job, sink);
  ASSERT_TRUE(result.isOk()) << result.status().message();
  const InverseRun& run = result.value();
  EXPECT_LE(run.curveMatch.curveError, 1e-6);
  // Twice the measured figures, so that a weaker solve fails here.
  const auto [lError, lMax] = measuredFigures(GetParam());
  EXPECT_LE(run.metrics.lengthError, 2 * lError);
  EXPECT_LE(run.metrics.lengthErrorMax, 2 * lMax);
  EXPECT_EQ(run.metrics.flipped2d + run.metrics.flipped3d, 0);
  // On its hull a curve comes back exactly when its pieces are zipped again (within 1e-6 of the
  // diagonal); the pushed-in curve leaves its hull, and its pieces make no convex D-Form at all.
  if (run.pre.isHull) {
    EXPECT_EQ(run.modelUsed.name, "exact");
    EXPECT_LE(run.curveMatch.roundtripMaxRel, 1e-6);
  } else {
    // Its pieces' metric is not convex, so no convex D-Form exists: zipped again by the
    // optimisation they take another shape, and the figure says how far off the curve it is.
    EXPECT_EQ(run.modelUsed.name, "paper");
    const std::string& note = run.curveMatch.roundtripNote;
    EXPECT_NE(note.find("optimisation"), std::string::npos) << note;
    EXPECT_NE(note.find("not convex"), std::string::npos) << note;
    EXPECT_GT(run.curveMatch.roundtripRmsRel, 1e-4);
    // The round trip's distance varies along the curve: its largest is above its RMS.
    EXPECT_GT(run.curveMatch.roundtripMaxRel, 1.05 * run.curveMatch.roundtripRmsRel);
  }
  // Flat outlines: simple polygons whose perimeters match the length of the curve as read (not
  // only of its resampled polygon) within 0.1 %, even at 60 points.
  const double curveLength = run.curveLength;
  for (const Piece* p : {&run.model.a, &run.model.b}) {
    Points2 outline(p->seam.size(), 2);
    for (std::size_t k = 0; k < p->seam.size(); ++k) outline.row(k) = p->flat.row(p->seam[k]);
    EXPECT_FALSE(findSelfIntersection(outline).has_value()) << p->name;
    EXPECT_NEAR(closedLength(outline), curveLength, 1e-3 * curveLength) << p->name;
  }
}

INSTANTIATE_TEST_SUITE_P(Samples, InverseSamples,
                         ::testing::Values("tennis-ball.obj", "saddle.obj", "pushed-in.obj",
                                           "rotated.json"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;  // "pushed-in.obj" -> "pushed_in_obj"
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(InverseRun, ALongCurveIsSolvedCoarseToFineAndMeetsTheSameBars) {
  // 250 points: the pre-D-Form is built on 83 of them, the result refined to 250.
  InverseJob job;
  job.curve = test::inverseSample("saddle.obj");
  job.resolution = 250;
  MessageSink sink;
  const Result<InverseRun> result = runInverse(job, sink);
  ASSERT_TRUE(result.isOk()) << result.status().message();
  const InverseRun& run = result.value();
  EXPECT_EQ(run.model.a.seam.size(), 250u);
  EXPECT_EQ(run.target.points.rows(), 250);
  EXPECT_TRUE(std::any_of(sink.messages().begin(), sink.messages().end(), [](const Message& m) {
    return m.text.rfind("coarse level: piece A with ", 0) == 0;
  }));
  EXPECT_LE(run.curveMatch.curveError, 1e-6);
  EXPECT_LE(run.metrics.lengthError, 0.005);
  EXPECT_LE(run.metrics.lengthErrorMax, 0.03);
  EXPECT_EQ(run.metrics.flipped2d + run.metrics.flipped3d, 0);
  for (const Piece* p : {&run.model.a, &run.model.b}) {
    Points2 outline(p->seam.size(), 2);
    for (std::size_t k = 0; k < p->seam.size(); ++k) outline.row(k) = p->flat.row(p->seam[k]);
    EXPECT_FALSE(findSelfIntersection(outline).has_value()) << p->name;
    EXPECT_NEAR(closedLength(outline), run.curveLength, 1e-3 * run.curveLength) << p->name;
    // The seam lies on the finest level's curve points, to the rounding of the solver's unit.
    double off = 0.0;
    for (std::size_t k = 0; k < p->seam.size(); ++k)
      off =
          std::max(off, (p->shape.row(p->seam[k]) - run.target.points.row(Eigen::Index(k))).norm());
    EXPECT_LT(off, 1e-9) << p->name;
  }
}

TEST(InverseRun, ATooDeepDentIsNamedAsTheCauseOfTheFold) {
  // The pushed-in saddle (samples/inverse/generate.py) dented to 70 % of its radius: its filled
  // pre-D-Form cannot bend into a D-Form without folding (docs/inverse.md, Limits). The run says
  // so, naming the stretch inside the hull, and its figures show the fold for the gate.
  const auto dir =
      std::filesystem::temp_directory_path() / ("dform_inverse_dent_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "dent70.obj").string();
  {
    std::ofstream out(path);
    const int n = 400;
    for (int i = 0; i < n; ++i) {
      const double t = 2 * M_PI * i / n, d = std::abs(std::remainder(t - M_PI / 4, 2 * M_PI));
      const double w = d < M_PI / 5 ? std::pow(std::cos(0.5 * M_PI * d / (M_PI / 5)), 2) : 0.0;
      const double r = 80.0 * (1.0 - 0.7 * w);
      out << "v " << r * std::cos(t) << " " << r * std::sin(t) << " " << 40.0 * std::cos(2 * t)
          << "\n";
    }
    out << "l";
    for (int i = 1; i <= n; ++i) out << " " << i;
    out << " 1\n";
  }
  InverseJob job;
  job.curve = path;
  MessageSink sink;
  const Result<InverseRun> result = runInverse(job, sink);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(result.isOk()) << result.status().message();
  EXPECT_GT(result.value().metrics.flipped3d, 0);
  EXPECT_FALSE(result.value().pre.onHull);
  const auto named =
      std::find_if(sink.messages().begin(), sink.messages().end(), [](const Message& m) {
        return m.level == Level::Warning &&
               m.text.find("too deep to bend into a D-Form") != std::string::npos;
      });
  ASSERT_NE(named, sink.messages().end());
  EXPECT_NE(named->text.find("curve points 6-25"), std::string::npos) << named->text;
}

TEST(InverseRun, BadCurvesAreInputErrorsNamingTheFile) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("dform_inverse_bad_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"open.obj", "v 0 0 0\nv 10 0 1\nv 10 10 0\nv 0 10 1\nv -5 5 2\nl 1 2 3 4 5\n"},
      {"few.obj", "v 0 0 0\nv 10 0 1\nv 10 10 0\nl 1 2 3 1\n"},
      {"nan.json", R"({"points": [[0,0,0],[10,0,1],[10,10,"nan"],[0,10,1],[-5,5,2],[0,0,0]]})"},
      {"repeated.obj",
       "v 0 0 0\nv 10 0 1\nv 10 0 1\nv 10 10 0\nv 0 10 1\nv -5 5 2\nl 1 2 3 4 5 6 1\n"},
      {"crossing.obj", "v 0 0 0\nv 10 10 0\nv 10 0 0\nv 0 10 0\nv 5 5 0\nl 1 2 3 4 1\n"},
      {"planar.obj", "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv -5 5 0\nl 1 2 3 4 5 1\n"},
      {"faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n"},
      {"malformed.obj", "v 0 0 zero\nl 1 2\n"},
  };
  for (const auto& [name, text] : bad) {
    InverseJob job;
    job.curve = write(name, text);
    MessageSink sink;
    const Result<InverseRun> run = runInverse(job, sink);
    ASSERT_FALSE(run.isOk()) << name;
    const ErrorCode code = run.status().code();
    EXPECT_TRUE(code == ErrorCode::InputInvalid || code == ErrorCode::InputUnreadable) << name;
    EXPECT_NE(run.status().message().find(job.curve), std::string::npos) << run.status().message();
    EXPECT_EQ(run.status().message().find('\n'), std::string::npos) << run.status().message();
  }
  std::filesystem::remove_all(dir);
}

// The gate a run judges on the figures it measured (the exact body, the round trip computed once)
// is the gate measured again on the same model: the same checks, verdicts and values.
void expectSameGate(const GateReport& once, const GateReport& again) {
  ASSERT_EQ(once.checks.size(), again.checks.size());
  for (std::size_t k = 0; k < once.checks.size(); ++k) {
    const CheckResult &a = once.checks[k], &b = again.checks[k];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.verdict, b.verdict) << a.name;
    EXPECT_EQ(a.detail, b.detail) << a.name;
    if (!std::isnan(a.value) || !std::isnan(b.value)) {
      EXPECT_EQ(a.value, b.value) << a.name;
    }
  }
}

TEST(InverseRun, TheGateOnTheRunsFiguresIsTheGateMeasuredAgain) {
  MessageSink sink;
  InverseJob inverse;
  inverse.curve =
      test::inverseSample("pushed-in.obj");  // the paper model and a round trip by optimisation
  inverse.resolution = 40;
  const Result<InverseRun> ran = runInverse(inverse, sink);
  ASSERT_TRUE(ran.isOk()) << ran.status().message();
  const InverseRun& r = ran.value();
  ASSERT_FALSE(r.curveMatch.roundtripNote.empty());
  const GateReport again = measureAndGate(r.model, GateLimits{}, &r.target);
  ASSERT_TRUE(again.curve.has_value());
  EXPECT_EQ(again.curve->roundtripRmsRel, r.curveMatch.roundtripRmsRel);
  expectSameGate(runGate(r.model, GateLimits{}, r.metrics, &r.target, &r.curveMatch), again);

  ForwardJob forward;
  forward.pieceA = std::string(DFORM_SAMPLES_DIR) + "/forward/ellipses-a.svg";
  forward.pieceB = std::string(DFORM_SAMPLES_DIR) + "/forward/ellipses-b.svg";
  const Result<ForwardRun> solved = runForward(forward, sink);
  ASSERT_TRUE(solved.isOk()) << solved.status().message();
  const DForm& model = solved.value().model;
  expectSameGate(runGate(model, GateLimits{}, solved.value().metrics, nullptr, nullptr),
                 measureAndGate(model, GateLimits{}, nullptr));
}

}  // namespace
}  // namespace dform
