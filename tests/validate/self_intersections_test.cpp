// SPDX-License-Identifier: GPL-3.0-or-later
// Which pairs of triangles cross: sheets meeting at an angle, or lying on each other the same
// way up, cross; sheets lying face to face (facing opposite ways, within kFaceToFaceTolerance of
// the soup's size) touch.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>

#include "validate/cgal_checks.h"

namespace dform::detail {
namespace {

// A soup of triangles, each given by its three corners (x, y, z), vertices not shared.
struct Soup {
  Points3 V;
  Faces F;
};
Soup soup(std::initializer_list<std::initializer_list<double>> corners) {
  Soup s;
  s.V.resize(Eigen::Index(corners.size()), 3);
  Eigen::Index row = 0;
  for (const auto& c : corners) {
    Eigen::Index col = 0;
    for (double x : c) s.V(row, col++) = x;
    ++row;
  }
  s.F.resize(s.V.rows() / 3, 3);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) s.F.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  return s;
}

int crossings(const Soup& s, double scale = 1.0) {
  return findSelfIntersections(scale * s.V, s.F).pairs;
}

// A right triangle in z = 0 facing up, and a smaller one over its middle facing down with its
// corners at heights z0, z1, z2.
Soup faceDownOver(double z0, double z1, double z2) {
  return soup({{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {1, 1, z0}, {1, 8, z1}, {8, 1, z2}});
}

TEST(SelfIntersections, CoplanarTrianglesFacingOppositeWaysTouch) {
  const Soup s = faceDownOver(0, 0, 0);
  const SelfIntersections hits = findSelfIntersections(s.V, s.F);
  EXPECT_EQ(hits.pairs, 0);
  EXPECT_EQ(hits.faceToFace, 1);
}

TEST(SelfIntersections, CoplanarTrianglesFacingTheSameWayCross) {
  const Soup s = soup({{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {1, 1, 0}, {8, 1, 0}, {1, 8, 0}});
  EXPECT_EQ(crossings(s), 1);
  EXPECT_EQ(findSelfIntersections(s.V, s.F).faceToFace, 0);
}

TEST(SelfIntersections, SheetsMeetingAtAnAngleCross) {
  // Upright through the middle of the flat one.
  EXPECT_EQ(crossings(soup({{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {1, 1, -3}, {1, 1, 3}, {4, 4, 0}})),
            1);
  // Facing down, tilted by 2e-4 rad through the flat one: a fraction 1e-5 of the soup's size,
  // far beyond the tolerance.
  EXPECT_EQ(crossings(faceDownOver(1e-3, -1e-3, 0)), 1);
}

TEST(SelfIntersections, TheTouchingToleranceIsAFractionOfTheSoupsSize) {
  const double diagonal = std::sqrt(200.0), tolerance = kFaceToFaceTolerance * diagonal;
  for (double scale : {1e-3, 1.0, 1e3}) {
    // Within a tenth of the tolerance the tilted sheet lies on the flat one, ten times beyond it
    // crosses it, at every size.
    EXPECT_EQ(crossings(faceDownOver(0.1 * tolerance, -0.1 * tolerance, 0), scale), 0) << scale;
    EXPECT_EQ(crossings(faceDownOver(10 * tolerance, -10 * tolerance, 0), scale), 1) << scale;
  }
}

TEST(SelfIntersections, AFlatFoldTouchesAndTheSameWayUpOverlaps) {
  // Two triangles on the edge (0,0,0)-(10,0,0), the second folded by 180 degrees onto the first.
  Soup folded;
  folded.V.resize(4, 3);
  folded.V << 0, 0, 0, 10, 0, 0, 0, 10, 0, 2, 5, 0;
  folded.F.resize(2, 3);
  folded.F << 0, 1, 2, 1, 0, 3;  // the edge runs opposite ways: oriented consistently
  EXPECT_EQ(crossings(folded), 0);
  folded.F << 0, 1, 2, 0, 1, 3;  // both facing up
  EXPECT_EQ(crossings(folded), 1);
}

}  // namespace
}  // namespace dform::detail
