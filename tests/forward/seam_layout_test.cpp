// SPDX-License-Identifier: GPL-3.0-or-later
#include "forward/seam_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "dform/core/constants.h"
#include "dform/core/polyline.h"

namespace dform {
namespace {

TEST(SeamLayout, WithoutCornersTheSeamIsUniform) {
  const std::vector<double> t = seamFractions(100, {});
  ASSERT_EQ(t.size(), 100u);
  for (int k = 0; k < 100; ++k) EXPECT_NEAR(t[k], k / 100.0, 1e-15);
}

TEST(SeamLayout, EveryCornerIsAVertexAndStretchesAreUniform) {
  const std::vector<double> corners = {0.125, 0.375, 0.625, 0.875, 0.3};
  const std::vector<double> t = seamFractions(100, corners);
  ASSERT_EQ(t.size(), 100u);
  EXPECT_EQ(t[0], 0.0);
  EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
  for (double c : corners)
    EXPECT_NE(std::find_if(t.begin(), t.end(), [&](double v) { return std::abs(v - c) < 1e-15; }),
              t.end())
        << c;
  // Spacing is constant between consecutive corners and close to the uniform 1/n.
  for (int k = 0; k + 1 < 100; ++k) EXPECT_NEAR(t[k + 1] - t[k], 0.01, 0.0026);
}

TEST(SeamLayout, CornersCloseToEachOtherAreBothVerticesUnlessTheyAreOne) {
  // 0.01 apart, a tenth of a seam edge: two vertices, a short chord between them.
  const std::vector<double> t = seamFractions(10, {0.5, 0.51});
  ASSERT_EQ(t.size(), 10u);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.5), 1);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.51), 1);
  EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
  // Closer than kSameCorner of a seam edge: one vertex, the first corner's.
  const std::vector<double> u = seamFractions(10, {0.5, 0.5 + 0.5 * kSameCorner / 10});
  EXPECT_EQ(std::count(u.begin(), u.end(), 0.5), 1);
  EXPECT_EQ(std::count(u.begin(), u.end(), 0.5 + 0.5 * kSameCorner / 10), 0);
  // With more than n / 2 corners the seam is uniform.
  std::vector<double> many;
  for (int i = 1; i < 60; ++i) many.push_back(i / 60.0);
  const std::vector<double> w = seamFractions(100, many);
  for (int k = 0; k < 100; ++k) EXPECT_NEAR(w[k], k / 100.0, 1e-15);
}

TEST(SeamLayout, ACornerWithinHalfAnEdgeOfTheStartIsTheFirstVertex) {
  // Behind the start (0.97 = -0.03, within 0.05 of it): the seam runs from -0.03 to 0.97, every
  // corner a vertex, none cut off by the last chord.
  const std::vector<double> t = seamFractions(10, {0.97, 0.5});
  ASSERT_EQ(t.size(), 10u);
  EXPECT_DOUBLE_EQ(t[0], 0.97 - 1.0);
  EXPECT_TRUE(std::is_sorted(t.begin(), t.end()));
  EXPECT_LT(t.back(), 0.97);
  EXPECT_EQ(std::count(t.begin(), t.end(), 0.5), 1);
  // Ahead of it: the seam runs from the corner; the nearer of two corners is taken.
  const std::vector<double> u = seamFractions(10, {0.04, 0.02, 0.6});
  EXPECT_DOUBLE_EQ(u[0], 0.02);
  EXPECT_EQ(std::count(u.begin(), u.end(), 0.04), 1);
  EXPECT_LT(u.back(), 1.02);
  // Half an edge or more away: the start stays the first vertex.
  EXPECT_EQ(seamFractions(10, {0.05, 0.6})[0], 0.0);
}

// A stadium: two straight sides `side` mm long joined by half circles of radius 20 mm, each of
// 64 segments, counter-clockwise from the start of its lower side.
Points2 stadium(double side) {
  const int arc = 64;
  Points2 P(2 * (arc + 1), 2);
  for (int half = 0; half < 2; ++half)
    for (int i = 0; i <= arc; ++i) {
      const double t = -0.5 * kPi + kPi * (half + double(i) / arc);
      const double x = (half == 0 ? side : 0.0) + 20.0 * std::cos(t);
      P.row(half * (arc + 1) + i) << x, 20.0 * std::sin(t);
    }
  return P;
}

// The ends of the straight sides of P (its segments longer than `longest`) as seam fractions,
// with whether a fraction lies on one of them.
struct Sides {
  std::vector<std::pair<double, double>> spans;  // begin, length
  std::vector<double> ends;
  bool on(double x) const {
    for (const auto& [begin, length] : spans)
      if (std::fmod(x - begin + 2.0, 1.0) <= length + 1e-12) return true;
    return false;
  }
};
Sides sidesOf(const Points2& P, double longest, double start, int direction) {
  const Eigen::VectorXd s = cumulativeArcLength(P);
  const double total = closedLength(P);
  Sides out;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Index j = (i + 1) % P.rows();
    const double length = (P.row(j) - P.row(i)).norm();
    if (length < longest) continue;
    auto at = [&](double c) { return std::fmod(direction * (c / total - start) + 2.0, 1.0); };
    const double a = at(s(i)), b = at(j == 0 ? 0.0 : s(j));
    out.spans.emplace_back(direction > 0 ? a : b, length / total);
    out.ends.push_back(a);
    out.ends.push_back(b);
  }
  return out;
}

bool listed(const std::vector<double>& corners, double x) {
  return std::any_of(corners.begin(), corners.end(),
                     [&](double c) { return std::abs(std::remainder(c - x, 1.0)) < 1e-12; });
}

// Both ends of every straight side two seam edges long are seam corners; where the two pieces'
// sides end within a seam edge of each other and overlap, one end is, on both sides (A's where
// both are); where a gap parts them, both are.
TEST(SeamLayout, StraightSidesEndAtSeamCornersOnceWhereThePiecesEndTogether) {
  ForwardSettings job;
  job.resolution = 40;
  const Points2 A = stadium(100.0);
  const double edge = closedLength(A) / job.resolution;
  for (const double startB : {0.0, 0.5, 0.3 / job.resolution, -0.2 / job.resolution}) {
    forward_detail::SeamLayout layout;
    layout.pieces[0].joined = A;
    layout.pieces[1].joined = A;
    SolvedDForm run;
    run.startFractionB = std::fmod(startB + 1.0, 1.0);
    forward_detail::layOutSeam(job, run, layout);
    const Sides a = sidesOf(A, 2.0 * edge, 0.0, 1),
                b = sidesOf(A, 2.0 * edge, run.startFractionB, -1);
    int overlapping = 0;
    ASSERT_EQ(a.ends.size(), 4u);
    ASSERT_EQ(b.ends.size(), 4u);
    for (const auto& [mine, theirs] : {std::pair{&a, &b}, std::pair{&b, &a}})
      for (double end : mine->ends) {
        double partner = -1.0;
        for (double other : theirs->ends)
          if (const double apart = std::abs(std::remainder(end - other, 1.0));
              apart > 0.0 && apart < 1.0 / job.resolution)
            partner = other;
        const std::string what =
            "start B " + std::to_string(startB) + ", end " + std::to_string(end);
        // Alone, or with a gap between the two sides (neither end on the other's side): taken.
        if (partner < 0.0 || !(theirs->on(end) || mine->on(partner))) {
          EXPECT_TRUE(listed(layout.seamCorners, end)) << what;
          continue;
        }
        ++overlapping;
        // Of the two, exactly one, on both pieces' sides: A's where both are.
        EXPECT_NE(listed(layout.seamCorners, end), listed(layout.seamCorners, partner)) << what;
        const bool both = theirs->on(end) && mine->on(partner);
        EXPECT_EQ(listed(layout.seamCorners, end), both ? mine == &a : theirs->on(end)) << what;
      }
    // Zipped 0.3 of an edge one way, the sides' ends meet across a gap at two places; 0.2 the
    // other way, they overlap there (each place counted from both ends).
    if (startB < 0.0) {
      EXPECT_EQ(overlapping, 4);
    }
    if (startB > 0.0 && startB < 0.5) {
      EXPECT_EQ(overlapping, 0);
    }
  }
}

}  // namespace
}  // namespace dform
