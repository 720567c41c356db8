// SPDX-License-Identifier: GPL-3.0-or-later
// The convex hull of a seam: a closed triangle mesh facing outward whatever the points' order,
// where many points lie on its faces and some are given twice; nothing for coplanar points.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <vector>

#include "validate/cgal_checks.h"

namespace dform::detail {
namespace {

// A 2 x 3 x 4 box: its corners, a grid of points on every face, the points of a D-Form's two
// seams that coincide (every point twice), shuffled.
Points3 boxWithFacePoints(unsigned seed) {
  std::vector<Eigen::Vector3d> points;
  const Eigen::Vector3d size(2.0, 3.0, 4.0);
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {0.0, 1.0})
      for (int i = 0; i <= 6; ++i)
        for (int j = 0; j <= 6; ++j) {
          Eigen::Vector3d p;
          p[axis] = side;
          p[(axis + 1) % 3] = i / 6.0;
          p[(axis + 2) % 3] = j / 6.0;
          points.push_back(p.cwiseProduct(size));
        }
  const std::size_t once = points.size();
  for (std::size_t i = 0; i < once; ++i) points.push_back(points[i]);
  std::shuffle(points.begin(), points.end(), std::mt19937(seed));
  Points3 P(Eigen::Index(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) P.row(Eigen::Index(i)) = points[i].transpose();
  return P;
}

TEST(ConvexHull, ABoxWithPointsOnItsFacesIsClosedAndFacesOutward) {
  for (unsigned seed = 0; seed < 20; ++seed) {
    const Points3 P = boxWithFacePoints(seed);
    const std::optional<HullMesh> hull = convexHull(P);
    ASSERT_TRUE(hull.has_value()) << seed;
    // A closed sphere of triangles: F = 2V - 4, every edge in two faces, opposite ways.
    EXPECT_EQ(hull->F.rows(), 2 * hull->V.rows() - 4) << seed;
    std::vector<std::pair<int, int>> edges;
    for (Eigen::Index f = 0; f < hull->F.rows(); ++f)
      for (int c = 0; c < 3; ++c) edges.emplace_back(hull->F(f, c), hull->F(f, (c + 1) % 3));
    std::sort(edges.begin(), edges.end());
    EXPECT_EQ(std::adjacent_find(edges.begin(), edges.end()), edges.end()) << seed;
    for (const auto& [i, j] : edges)
      EXPECT_TRUE(std::binary_search(edges.begin(), edges.end(), std::make_pair(j, i))) << seed;
    // Every face with area faces away from the box's centre, and every point lies on its inner
    // side; the faces' areas add up to the box's.
    const Eigen::Vector3d centre(1.0, 1.5, 2.0);
    double area = 0.0;
    for (Eigen::Index f = 0; f < hull->F.rows(); ++f) {
      const Eigen::Vector3d a = hull->V.row(hull->F(f, 0)), b = hull->V.row(hull->F(f, 1)),
                            c = hull->V.row(hull->F(f, 2));
      const Eigen::Vector3d normal = (b - a).cross(c - a);
      area += 0.5 * normal.norm();
      if (normal.norm() < 1e-12) continue;
      EXPECT_GT(normal.dot(a - centre), 0.0) << seed << ": face " << f;
      for (Eigen::Index i = 0; i < P.rows(); ++i)
        EXPECT_LE(normal.normalized().dot(P.row(i).transpose() - a), 1e-12) << seed;
    }
    EXPECT_NEAR(area, 2.0 * (2 * 3 + 3 * 4 + 2 * 4), 1e-12) << seed;
  }
}

TEST(ConvexHull, CoplanarOrTooFewPointsHaveNone) {
  Points3 square(5, 3);
  square << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 0;
  EXPECT_FALSE(convexHull(square).has_value());
  EXPECT_FALSE(convexHull(square.topRows(3)).has_value());
  Points3 tetrahedron(4, 3);
  tetrahedron << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  ASSERT_TRUE(convexHull(tetrahedron).has_value());
  EXPECT_EQ(convexHull(tetrahedron)->F.rows(), 4);
}

}  // namespace
}  // namespace dform::detail
