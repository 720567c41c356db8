// SPDX-License-Identifier: GPL-3.0-or-later
// The ruled engine's pieces: the dihedral angle and its gradient, flips of a piece's
// triangulation, the held-positions estimate of a flip's bending change, the Levenberg-Marquardt
// and KKT solves on small surfaces.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>

#include "dform/ruled/ruled_engine.h"
#include "dform/ruled/ruled_search.h"
#include "dform/ruled/ruled_solve.h"
#include "dform/ruled/ruled_surface.h"

namespace dform::ruled {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Dihedral, GradientMatchesFiniteDifferences) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Vector3d x[4];
    for (Eigen::Vector3d& p : x)
      p = Eigen::Vector3d(uniform(random), uniform(random), uniform(random));
    // Keep the two triangles away from degenerate (each corner well off the hinge line).
    const Eigen::Vector3d e = (x[1] - x[0]).normalized();
    const double offK = ((x[2] - x[0]) - (x[2] - x[0]).dot(e) * e).norm();
    const double offL = ((x[3] - x[0]) - (x[3] - x[0]).dot(e) * e).norm();
    if (offK < 0.2 || offL < 0.2 || (x[1] - x[0]).norm() < 0.3) continue;
    Eigen::Matrix<double, 4, 3> g;
    const double theta = dihedral(x[0], x[1], x[2], x[3], &g);
    // Away from the cut of atan2 at +-pi, where a difference would wrap.
    if (std::abs(theta) > 3.0) continue;
    const double h = 1e-6;
    for (int v = 0; v < 4; ++v)
      for (int a = 0; a < 3; ++a) {
        Eigen::Vector3d plus[4] = {x[0], x[1], x[2], x[3]}, minus[4] = {x[0], x[1], x[2], x[3]};
        plus[v][a] += h;
        minus[v][a] -= h;
        const double fd = (dihedral(plus[0], plus[1], plus[2], plus[3]) -
                           dihedral(minus[0], minus[1], minus[2], minus[3])) /
                          (2 * h);
        EXPECT_NEAR(g(v, a), fd, 1e-6 * std::max(1.0, std::abs(fd)))
            << "trial " << trial << " vertex " << v << " axis " << a;
      }
  }
}

TEST(Dihedral, IsZeroFlatPositiveWhereConvexAndNegativeWhereFoldedBack) {
  // Hinge along x; the face (i, j, k) and (j, i, l) counter-clockwise seen from +z when flat.
  const Eigen::Vector3d i(0, 0, 0), j(1, 0, 0), k(0.5, 1, 0), l(0.5, -1, 0);
  EXPECT_NEAR(dihedral(i, j, k, l), 0.0, 1e-15);
  // Both outer corners dropped below the plane: a roof seen from +z, the normals' side, convex.
  const double drop = std::tan(0.3);
  const Eigen::Vector3d kDown(0.5, 1, -drop), lDown(0.5, -1, -drop);
  EXPECT_NEAR(dihedral(i, j, kDown, lDown), 0.6, 1e-12);
  const Eigen::Vector3d kUp(0.5, 1, drop), lUp(0.5, -1, drop);
  EXPECT_NEAR(dihedral(i, j, kUp, lUp), -0.6, 1e-12);
  // A regular tetrahedron with outward counter-clockwise faces: every edge folds by pi minus its
  // interior dihedral angle acos(1/3).
  const Eigen::Vector3d p[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  // Face (0, 1, 2) points away from p3 when counter-clockwise: check and pair it with (1, 0, 3).
  const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
  ASSERT_LT(n.dot(p[3] - p[0]), 0.0);
  EXPECT_NEAR(dihedral(p[0], p[1], p[2], p[3]), kPi - std::acos(1.0 / 3.0), 1e-12);
}

// A convex polygon of n points on an ellipse, fan-triangulated from point 0.
PieceTriangulation fan(int n) {
  Points2 P(n, 2);
  for (int k = 0; k < n; ++k)
    P.row(k) << 50.0 * std::cos(2 * kPi * k / n), 30.0 * std::sin(2 * kPi * k / n);
  Faces F(n - 2, 3);
  for (int k = 0; k < n - 2; ++k) F.row(k) << 0, k + 1, k + 2;
  return PieceTriangulation(P, F);
}

double totalArea(const PieceTriangulation& T) {
  double area = 0.0;
  for (int f = 0; f < T.faceCount(); ++f) area += T.area(f);
  return area;
}

TEST(PieceTriangulation, FlipsKeepEveryTriangleCounterClockwiseAndFlipBack) {
  PieceTriangulation T = fan(12);
  const double area = totalArea(T);
  int flips = 0;
  for (int h = 0; h < T.halfedgeCount(); ++h) {
    if (!T.flippable(h)) continue;
    const int i = T.tail(h), j = T.head(h);
    const int created = T.flip(h);
    ++flips;
    for (int f = 0; f < T.faceCount(); ++f) EXPECT_GT(T.area(f), 0.0);
    EXPECT_NEAR(totalArea(T), area, 1e-9 * area);
    // Every halfedge's twin runs back along it.
    for (int g = 0; g < T.halfedgeCount(); ++g)
      if (T.twin(g) >= 0) {
        EXPECT_EQ(T.twin(T.twin(g)), g);
        EXPECT_EQ(T.tail(T.twin(g)), T.head(g));
      }
    // The new edge flipped again is the old one.
    ASSERT_TRUE(T.flippable(created));
    const int back = T.flip(created);
    const std::pair<int, int> now = std::minmax(T.tail(back), T.head(back)),
                              old = std::minmax(i, j);
    EXPECT_EQ(now, old);
  }
  EXPECT_GT(flips, 5);
  // Fixed edges (creases) and the boundary are never flippable.
  PieceTriangulation creased(fan(12).flat(), fan(12).faces(), {{0, 5}});
  for (int h = 0; h < creased.halfedgeCount(); ++h) {
    if (std::pair<int, int>(std::minmax(creased.tail(h), creased.head(h))) == std::pair(0, 5)) {
      EXPECT_TRUE(creased.fixed(h));
      EXPECT_FALSE(creased.flippable(h));
    }
    if (creased.twin(h) < 0) {
      EXPECT_FALSE(creased.flippable(h));
    }
  }
}

// The faces F (rows of a piece's seam points) developed into the plane: each face laid beside
// one already laid, so that every face keeps the lengths X gives its edges.
Points2 develop(const Points3& X, const Faces& F) {
  Points2 P = Points2::Constant(X.rows(), 2, std::nan(""));
  std::vector<bool> laid(std::size_t(F.rows()), false);
  auto third = [&](int a, int b, int c) {  // c left of a -> b
    const Eigen::Vector2d pa = P.row(a), pb = P.row(b);
    const double ab = (pb - pa).norm(), ac = (X.row(c) - X.row(a)).norm(),
                 bc = (X.row(c) - X.row(b)).norm();
    const double x = (ab * ab + ac * ac - bc * bc) / (2 * ab);
    const Eigen::Vector2d u = (pb - pa) / ab, w(-u.y(), u.x());
    P.row(c) = (pa + x * u + std::sqrt(std::max(0.0, ac * ac - x * x)) * w).transpose();
  };
  P.row(F(0, 0)) << 0, 0;
  P.row(F(0, 1)) << (X.row(F(0, 1)) - X.row(F(0, 0))).norm(), 0;
  third(F(0, 0), F(0, 1), F(0, 2));
  laid[0] = true;
  for (bool again = true; again;) {
    again = false;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      if (laid[std::size_t(f)]) continue;
      for (int c = 0; c < 3; ++c) {
        const int a = F(f, c), b = F(f, (c + 1) % 3), d = F(f, (c + 2) % 3);
        if (std::isnan(P(a, 0)) || std::isnan(P(b, 0))) continue;
        if (std::isnan(P(d, 0))) third(a, b, d);
        laid[std::size_t(f)] = again = true;
        break;
      }
    }
  }
  return P;
}

// A closed surface that has a solution: a saddle-shaped 3D seam, piece A the fan of triangles
// from seam point 0, piece B the zigzag strip between the seam's two halves, each developed
// flat, so the seam's 3D points meet every length of both.
RuledSurface fanPair(int n) {
  Points3 X(n, 3);
  for (int k = 0; k < n; ++k) {
    const double t = 2 * kPi * k / n;
    X.row(k) << 50.0 * std::cos(t), 32.0 * std::sin(t), 10.0 * std::cos(2 * t);
  }
  Faces fanA(n - 2, 3);
  for (int m = 1; m + 1 < n; ++m) fanA.row(m - 1) << 0, m, m + 1;
  // B's faces run the other way round the seam: (k + 1, k, ...) where A's run (k, k + 1, ...).
  Faces zigzag(n - 2, 3);
  int lo = 1, hi = n - 1, f = 0;
  zigzag.row(f++) << 1, 0, n - 1;
  while (hi - lo > 1) {
    if (f % 2 == 1) {
      zigzag.row(f++) << lo + 1, lo, hi;
      ++lo;
    } else {
      zigzag.row(f++) << hi, hi - 1, lo;
      --hi;
    }
  }
  RuledSurface s;
  const Faces* faces[2] = {&fanA, &zigzag};
  for (int p = 0; p < 2; ++p) {
    s.pieces[std::size_t(p)] = PieceTriangulation(develop(X, *faces[p]), *faces[p]);
    for (int k = 0; k < n; ++k) {
      s.vertexOf[std::size_t(p)].push_back(k);
      s.seamRows[std::size_t(p)].push_back(k);
    }
  }
  s.X = X;
  return s;
}

TEST(SolveLengths, MeetsEveryLengthOnAClosedSurfaceAndStopsAtLeastSquaresWhereItCannot) {
  RuledSurface s = fanPair(16);
  for (int p = 0; p < 2; ++p)
    for (int f = 0; f < s.pieces[std::size_t(p)].faceCount(); ++f)
      ASSERT_GT(s.pieces[std::size_t(p)].area(f), 0.0) << "piece " << p << " face " << f;
  ASSERT_FALSE(s.hasDoubleEdge());
  ASSERT_LE(maxLengthError(s, s.edges()), 1e-12);
  const Points3 solution = s.X;
  // Moved off by up to 1 mm, Newton comes back to a state meeting every length.
  std::mt19937 random(5);
  std::normal_distribution<double> jitter(0.0, 0.3);
  for (Eigen::Index v = 0; v < s.X.rows(); ++v)
    s.X.row(v) += Eigen::RowVector3d(jitter(random), jitter(random), jitter(random));
  ASSERT_GT(maxLengthError(s, s.edges()), 1e-3);
  const SolveSummary met = solveLengths(s);
  ASSERT_TRUE(met.converged) << met.message;
  EXPECT_LE(maxLengthError(s, s.edges()), 1e-12);
  EXPECT_LE(met.maxLengthError, 1e-12);
  // A tie no position can meet (two seam points farther apart than the seam between them): a
  // least-squares state, reported as not converged.
  s.ties.push_back({0, 8, 1e4});
  const SolveSummary impossible = solveLengths(s);
  EXPECT_FALSE(impossible.converged);
  EXPECT_FALSE(impossible.message.empty());
}

TEST(FlipBendingChange, IsTheEnergyDifferenceWithThePositionsHeld) {
  RuledSurface s = fanPair(14);
  std::mt19937 random(3);
  std::normal_distribution<double> jitter(0.0, 2.0);
  for (Eigen::Index v = 0; v < s.X.rows(); ++v)
    s.X.row(v) += Eigen::RowVector3d(jitter(random), jitter(random), jitter(random));
  const double before = bendingEnergy(s, s.edges());
  int compared = 0;
  for (int p = 0; p < 2; ++p)
    for (int h = 0; h < s.pieces[std::size_t(p)].halfedgeCount(); ++h) {
      if (!s.pieces[std::size_t(p)].flippable(h) || s.pieces[std::size_t(p)].twin(h) < h) continue;
      RuledSurface flipped = s;
      flipped.pieces[std::size_t(p)].flip(h);
      const double after = bendingEnergy(flipped, flipped.edges());
      EXPECT_NEAR(flipBendingChange(s, p, h), after - before, 1e-9 * before);
      ++compared;
    }
  EXPECT_GT(compared, 10);
}

TEST(MinimiseBending, EndsStationaryWithEveryLengthMet) {
  // A strip: one piece, two free rows of points, its other piece a single triangle glued on
  // nothing but a seam of three points. The strip bends freely; its least bending is flat.
  RuledSurface s;
  const int n = 8;
  Points2 strip(2 * n, 2);
  for (int k = 0; k < n; ++k) {
    strip.row(k) << 10.0 * k, 0.0;
    strip.row(2 * n - 1 - k) << 10.0 * k, 12.0;
  }
  Faces F(2 * n - 2, 3);
  for (int k = 0; k + 1 < n; ++k) {
    F.row(2 * k) << k, k + 1, 2 * n - 1 - k;
    F.row(2 * k + 1) << k + 1, 2 * n - 2 - k, 2 * n - 1 - k;
  }
  s.pieces[0] = PieceTriangulation(strip, F);
  Points2 tri(3, 2);
  tri << 0, 0, 10, 0, 5, -8;
  Faces one(1, 3);
  one << 0, 2, 1;
  s.pieces[1] = PieceTriangulation(tri, one);
  for (int r = 0; r < 2 * n; ++r) s.vertexOf[0].push_back(r);
  s.vertexOf[1] = {0, 1, 2 * n};
  s.seamRows[0] = {0, 1};
  s.seamRows[1] = {0, 1};
  for (int r = 0; r < 2 * n; ++r) s.freeRows[0].push_back(r);
  s.freeRows[1] = {2};
  // Bent start: the strip rolled about the x axis.
  s.X.resize(2 * n + 1, 3);
  for (int r = 0; r < 2 * n; ++r) {
    const double y = strip(r, 1), angle = y / 20.0;
    s.X.row(r) << strip(r, 0), 20.0 * std::sin(angle), 20.0 * (1 - std::cos(angle)) + 0.1 * r;
  }
  s.X.row(2 * n) << 5, -8 * std::cos(0.2), -8 * std::sin(0.2);
  ASSERT_TRUE(solveLengths(s).converged);
  const double start = bendingEnergy(s, s.edges());
  ASSERT_GT(start, 1e-3);
  const SolveSummary bent = minimiseBending(s);
  // Converged on the flat strip (the energy's minimum, where the stationarity's ratio is one of
  // rounding errors and is not what stops the solve).
  EXPECT_TRUE(bent.converged) << bent.message;
  EXPECT_LE(bent.maxLengthError, 1e-12);
  EXPECT_LT(bent.bendingEnergy, 1e-16 * start);
}

}  // namespace
}  // namespace dform::ruled
