// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/meshing/convex_hull.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>

#include "dform/core/constants.h"

namespace dform {
namespace {

// Closed 2-manifold with outward faces, Euler characteristic 2; returns the enclosed volume.
double checkClosedOutward(const ConvexHull3& hull, const Points3& P) {
  const Eigen::RowVector3d centre = P.colwise().mean();
  std::map<std::pair<int, int>, int> directed;
  std::set<int> vertices;
  double volume = 0.0;
  for (Eigen::Index f = 0; f < hull.F.rows(); ++f) {
    const Eigen::RowVector3d a = P.row(hull.F(f, 0)), b = P.row(hull.F(f, 1)),
                             c = P.row(hull.F(f, 2));
    const Eigen::RowVector3d normal = (b - a).cross(c - a);
    EXPECT_GT(normal.dot((a + b + c) / 3.0 - centre), 0.0) << "face " << f << " faces inward";
    volume += normal.dot(a - centre) / 6.0;
    for (int k = 0; k < 3; ++k) {
      vertices.insert(hull.F(f, k));
      ++directed[{hull.F(f, k), hull.F(f, (k + 1) % 3)}];
      EXPECT_TRUE(hull.onHull[std::size_t(hull.F(f, k))]);
    }
  }
  for (const auto& [e, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << e.first << "-" << e.second << " used twice the same way";
    EXPECT_EQ(directed.count({e.second, e.first}), 1u)
        << "edge " << e.first << "-" << e.second << " has no opposite: hull not closed";
  }
  const long euler = long(vertices.size()) - long(directed.size() / 2) + long(hull.F.rows());
  EXPECT_EQ(euler, 2);
  EXPECT_EQ(hull.onHull.size(), std::size_t(P.rows()));
  EXPECT_EQ(hull.distanceToHull.size(), std::size_t(P.rows()));
  return volume;
}

TEST(ConvexHull3, CubeWithInteriorAndFacePoints) {
  std::vector<Eigen::RowVector3d> rows;
  for (int i = 0; i < 8; ++i) rows.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> inner(0.1, 0.9);
  for (int i = 0; i < 50; ++i) rows.emplace_back(inner(random), inner(random), inner(random));
  rows.emplace_back(0.5, 0.5, 1.0);  // on a face: not a vertex
  rows.emplace_back(1.0, 0.5, 0.5);
  rows.emplace_back(1.0, 1.0, 0.5);  // on an edge
  rows.emplace_back(1.0, 1.0, 1.0);  // a repeated corner
  Points3 P(Eigen::Index(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) P.row(Eigen::Index(i)) = rows[i];

  const Result<ConvexHull3> result = convexHull3(P);
  ASSERT_TRUE(result.isOk()) << result.status().message();
  const ConvexHull3& hull = result.value();
  EXPECT_EQ(hull.F.rows(), 12);  // coplanar squares come as two triangles each
  EXPECT_NEAR(checkClosedOutward(hull, P), 1.0, 1e-12);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const bool corner = i < 8 || i == P.rows() - 1;
    EXPECT_EQ(hull.onHull[std::size_t(i)], corner) << "point " << i;
    const double toSurface = std::min({P.row(i).minCoeff(), 1.0 - P.row(i).maxCoeff()});
    EXPECT_NEAR(hull.distanceToHull[std::size_t(i)], toSurface, 1e-12) << "point " << i;
  }
  for (Eigen::Index f = 0; f < hull.F.rows(); ++f) EXPECT_LT(hull.F.row(f).maxCoeff(), 8);
}

TEST(ConvexHull3, TennisBallCurveIsAllOnTheHull) {
  const int n = 400;
  Points3 P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * kPi * i / n;
    const Eigen::RowVector3d q(std::cos(t) + 0.5 * std::cos(3.0 * t),
                               std::sin(t) - 0.5 * std::sin(3.0 * t), 1.3 * std::sin(2.0 * t));
    P.row(i) = 50.0 * q.normalized();  // on a sphere of radius 50 mm
  }
  const Result<ConvexHull3> result = convexHull3(P);
  ASSERT_TRUE(result.isOk()) << result.status().message();
  const ConvexHull3& hull = result.value();
  checkClosedOutward(hull, P);
  for (int i = 0; i < n; ++i) {
    EXPECT_TRUE(hull.onHull[std::size_t(i)]) << "point " << i;
    EXPECT_EQ(hull.distanceToHull[std::size_t(i)], 0.0);
  }
  EXPECT_EQ(hull.F.rows(), 2 * n - 4);  // a triangulated sphere with every point a vertex
}

void expectPlanar(const Points3& P, const std::string& words) {
  const Result<ConvexHull3> result = convexHull3(P);
  ASSERT_FALSE(result.isOk());
  EXPECT_EQ(result.status().code(), ErrorCode::InputInvalid);
  EXPECT_NE(result.status().message().find(words), std::string::npos) << result.status().message();
}

TEST(ConvexHull3, PlanarAndDegenerateCurvesAreInvalid) {
  const int n = 100;
  Points3 flat(n, 3), tilted(n, 3), line(n, 3);
  const Eigen::Vector3d u = Eigen::Vector3d(1, 2, 3).normalized();
  const Eigen::Vector3d v = u.cross(Eigen::Vector3d(0.3, -1, 0.2)).normalized();
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * kPi * i / n;
    flat.row(i) << 30 * std::cos(t), 20 * std::sin(t), 5.0;
    // In a tilted plane: rounding leaves it a sliver, not exactly coplanar.
    tilted.row(i) =
        (Eigen::Vector3d(7, -3, 11) + 30 * std::cos(t) * u + 20 * std::sin(t) * v).transpose();
    line.row(i) = (double(i) * u).transpose();
  }
  expectPlanar(flat, "the curve is planar: its convex hull has no inside");
  expectPlanar(tilted, "the curve is planar");
  // The same, its angles rounded through long double: a sliver on which CGAL's quickhull with
  // inexact constructions failed an assertion (and wrote out of bounds where CGAL's checks are
  // off).
  Points3 sliver(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = double(2.0L * EIGEN_PI * i / n);
    sliver.row(i) =
        (Eigen::Vector3d(7, -3, 11) + 30 * std::cos(t) * u + 20 * std::sin(t) * v).transpose();
  }
  ASSERT_NE(sliver, tilted);
  expectPlanar(sliver, "the curve is planar");
  expectPlanar(line, "the curve is planar");
  expectPlanar(Points3::Zero(10, 3), "the curve is planar");
  expectPlanar(Points3::Identity(3, 3), "fewer than 4 points");
  Points3 broken = Points3::Identity(4, 3);
  broken(3, 2) = NAN;
  expectPlanar(broken, "non-finite");
}

}  // namespace
}  // namespace dform
