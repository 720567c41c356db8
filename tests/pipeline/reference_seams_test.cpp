// SPDX-License-Identifier: GPL-3.0-or-later
// The references a result's figures are measured against (pipeline/reference_seams.h): the exact
// body where the glued metric is convex, and for each reason there is none, that reason as a
// value the round trip chooses its way by.
#include "pipeline/reference_seams.h"

#include <gtest/gtest.h>

#include "dform/exact/exact_gluing.h"
#include "dform/io/outline_reader.h"
#include "dform/pipeline/forward_pipeline.h"
#include "shipped_samples.h"

namespace dform {
namespace {

using Missing = ReferenceSeam::Missing;

DForm solvedPair(const std::string& a, const std::string& b, ModelChoice model) {
  Result<Shape2> shapeA = readOutline(test::samplePath(a)),
                 shapeB = readOutline(test::samplePath(b));
  EXPECT_TRUE(shapeA.isOk() && shapeB.isOk());
  ForwardSettings settings;
  settings.model = model;
  settings.resolution = 40;
  MessageSink sink;
  Result<SolvedDForm> solved = solveDForm(shapeA.value(), shapeB.value(), settings, sink);
  EXPECT_TRUE(solved.isOk()) << solved.status().message();
  return solved.value().model;
}

TEST(ReferenceSeams, AConvexMetricHasItsExactBodyZippedAgainAsItIs) {
  const DForm model =
      solvedPair("forward/ellipses-a.svg", "forward/ellipses-b.svg", ModelChoice::Exact);
  const ReferenceSeam body = exactBodySeam(model);
  EXPECT_EQ(body.missing, Missing::None) << body.note;
  ASSERT_EQ(std::size_t(body.points.rows()), model.a.seam.size());
  // The exact model's seam is the exact body's: the reference lies on it to rounding.
  double worst = 0;
  for (std::size_t k = 0; k < model.a.seam.size(); ++k)
    worst = std::max(
        worst, (body.points.row(Eigen::Index(k)) - model.a.shape.row(model.a.seam[k])).norm());
  EXPECT_LT(worst, 1e-6);
  const ReferenceSeam again = zippedAgainSeam(model, body);
  EXPECT_EQ(again.missing, Missing::None);
  EXPECT_EQ(again.points, body.points);
}

TEST(ReferenceSeams, ANonConvexMetricIsZippedAgainByTheOptimisation) {
  const DForm model =
      solvedPair("forward/nonconvex-a.svg", "forward/nonconvex-b.svg", ModelChoice::Paper);
  const ReferenceSeam body = exactBodySeam(model);
  EXPECT_EQ(body.missing, Missing::NotConvex) << body.note;
  EXPECT_EQ(body.points.rows(), 0);
  const ReferenceSeam again = zippedAgainSeam(model, body);
  EXPECT_EQ(again.missing, Missing::None) << again.note;
  EXPECT_EQ(std::size_t(again.points.rows()), model.a.seam.size());
  EXPECT_EQ(again.note.rfind("zipped by the paper's optimisation", 0), 0u) << again.note;
}

TEST(ReferenceSeams, AHoleZippedOrATooLongSeamHasNoReferenceAndNoRoundTrip) {
  DForm holed = solvedPair("forward/ellipses-a.svg", "forward/ellipses-b.svg", ModelChoice::Exact);
  holed.b.freeBoundaries.push_back({0, 1, 2});
  const ReferenceSeam body = exactBodySeam(holed);
  EXPECT_EQ(body.missing, Missing::HoleZipped) << body.note;
  const ReferenceSeam again = zippedAgainSeam(holed, body);
  EXPECT_EQ(again.missing, Missing::HoleZipped);
  EXPECT_EQ(again.points.rows(), 0);

  DForm longSeam;
  longSeam.a.seam.assign(std::size_t(exact::kMaxExactSeam) + 1, 0);
  longSeam.b.seam = longSeam.a.seam;
  EXPECT_EQ(exactBodySeam(longSeam).missing, Missing::SeamTooLong);
}

}  // namespace
}  // namespace dform
