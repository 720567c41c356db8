// SPDX-License-Identifier: GPL-3.0-or-later
#include "inverse/unfold.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>

#include "dform/core/polyline.h"
#include "dform/inverse/pre_dform.h"
#include "inverse_test_util.h"

namespace dform {
namespace {

using test::kPi;

// Rounding only: lengths are recomputed from coordinates ~1e2 mm with ~1e-16 relative error.
constexpr double kExact = 1e-12;

double relativeError(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}

// Every edge of F has the same length flat as in 3D, and every flat triangle is counter-clockwise.
void expectIsometric(const Points3& V, const Points2& flat, const Faces& F) {
  ASSERT_EQ(flat.rows(), V.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int u = F(f, c), v = F(f, (c + 1) % 3);
      EXPECT_LE(relativeError((flat.row(u) - flat.row(v)).norm(), (V.row(u) - V.row(v)).norm()),
                kExact)
          << "edge " << u << "-" << v;
    }
    const Eigen::Vector2d a = flat.row(F(f, 0)), b = flat.row(F(f, 1)), c = flat.row(F(f, 2));
    const double twiceArea = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    const double area3 =
        (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0))).norm();
    EXPECT_GT(twiceArea, 0.0) << "face " << f << " is not counter-clockwise";
    EXPECT_NEAR(twiceArea, area3, 1e-9 * area3) << "face " << f;
  }
}

class SampleInit : public ::testing::TestWithParam<const char*> {};

TEST_P(SampleInit, UnfoldRemeshAndMapBack) {
  const int n = 100;
  const Points3 C = test::sampleCurve(GetParam(), n);
  ASSERT_EQ(C.rows(), n);
  Result<InverseInit> result = initialiseInverse(C);
  ASSERT_TRUE(result.isOk()) << result.status().message();
  const InverseInit& init = result.value();
  const double length = closedLength(C);
  const double meanEdge = length / n;

  for (const FlatMesh* pre : {&init.preFlatA, &init.preFlatB}) {
    const bool isA = pre == &init.preFlatA;
    SCOPED_TRACE(isA ? "piece A" : "piece B");
    // The unfolding keeps every edge length and lays every triangle counter-clockwise.
    expectIsometric(C, pre->V, pre->F);
    // Its outline (curve order) is a simple polygon as long as the curve, counter-clockwise in
    // `boundary` order, which runs the curve forwards for A and backwards for B.
    EXPECT_FALSE(findSelfIntersection(pre->V).has_value());
    EXPECT_LE(relativeError(closedLength(pre->V), length), kExact);
    ASSERT_EQ(int(pre->boundary.size()), n);
    Points2 outline(n, 2);
    for (int j = 0; j < n; ++j) outline.row(j) = pre->V.row(pre->boundary[std::size_t(j)]);
    EXPECT_GT(signedArea(outline), 0.0);
    for (int j = 0; j < n; ++j) EXPECT_EQ(pre->boundary[std::size_t(j)], isA ? j : (n - j) % n);
    // Flat area = 3D area of the disc.
    double area3 = 0.0;
    for (Eigen::Index f = 0; f < pre->F.rows(); ++f)
      area3 += 0.5 * (C.row(pre->F(f, 1)) - C.row(pre->F(f, 0)))
                         .cross(C.row(pre->F(f, 2)) - C.row(pre->F(f, 0)))
                         .norm();
    EXPECT_NEAR(signedArea(outline), area3, 1e-9 * area3);
    // The barycentric map sends every old vertex exactly onto its curve point.
    const Points3 back = mapBarycentric(pre->V, C, pre->F, pre->V);
    for (int i = 0; i < n; ++i)
      EXPECT_TRUE(back.row(i) == C.row(i)) << "curve point " << i << " maps to " << back.row(i);
  }

  for (const Piece* piece : {&init.model.a, &init.model.b}) {
    const bool isA = piece == &init.model.a;
    const FlatMesh& pre = isA ? init.preFlatA : init.preFlatB;
    SCOPED_TRACE("remeshed piece " + piece->name);
    EXPECT_EQ(piece->name, isA ? "A" : "B");
    ASSERT_EQ(int(piece->seam.size()), n);
    ASSERT_EQ(piece->shape.rows(), piece->flat.rows());
    EXPECT_GT(piece->flat.rows(), n) << "remeshing adds interior vertices";
    // Seam vertices keep the unfolded curve points bit for bit and map exactly onto the curve.
    std::set<int> seamVertices(piece->seam.begin(), piece->seam.end());
    EXPECT_EQ(int(seamVertices.size()), n);
    for (int i = 0; i < n; ++i) {
      const int v = piece->seam[std::size_t(i)];
      EXPECT_LT(v, n);
      EXPECT_TRUE(piece->flat.row(v) == pre.V.row(i)) << "seam " << i;
      EXPECT_TRUE(piece->shape.row(v) == C.row(i)) << "seam " << i;
    }
    // A's seam runs counter-clockwise around its flat outline, B's clockwise.
    Points2 seamOutline(n, 2);
    for (int i = 0; i < n; ++i) seamOutline.row(i) = piece->flat.row(piece->seam[std::size_t(i)]);
    EXPECT_EQ(signedArea(seamOutline) > 0.0, isA);
    // Faces counter-clockwise flat; remeshed edges near the target length.
    double edgeSum = 0.0;
    int edges = 0;
    for (Eigen::Index f = 0; f < piece->F.rows(); ++f) {
      const Eigen::Vector2d a = piece->flat.row(piece->F(f, 0)),
                            b = piece->flat.row(piece->F(f, 1)),
                            c = piece->flat.row(piece->F(f, 2));
      EXPECT_GT((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x(), 0.0);
      edgeSum += (b - a).norm() + (c - b).norm() + (a - c).norm();
      edges += 3;
    }
    EXPECT_NEAR(edgeSum / edges, meanEdge, 0.25 * meanEdge);
    // Every new vertex lies on the pre-D-Form: mapping it again through its own flat position
    // gives the same 3D point, and no 3D edge is longer than its flat length (a bent sheet).
    const Points3 again = mapBarycentric(pre.V, C, pre.F, piece->flat);
    EXPECT_LE((again - piece->shape).cwiseAbs().maxCoeff(), kExact * length);
    for (Eigen::Index f = 0; f < piece->F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int u = piece->F(f, c), v = piece->F(f, (c + 1) % 3);
        EXPECT_LE((piece->shape.row(u) - piece->shape.row(v)).norm(),
                  (piece->flat.row(u) - piece->flat.row(v)).norm() * (1 + kExact));
      }
  }

  // Both pieces together close up and face outwards.
  double volume = 0.0;
  for (const Piece* piece : {&init.model.a, &init.model.b})
    for (Eigen::Index f = 0; f < piece->F.rows(); ++f) {
      const Eigen::RowVector3d a = piece->shape.row(piece->F(f, 0)),
                               b = piece->shape.row(piece->F(f, 1)),
                               c = piece->shape.row(piece->F(f, 2));
      volume += a.dot(b.cross(c)) / 6.0;
    }
  EXPECT_GT(volume, 0.0);
  EXPECT_EQ(init.preDFormF.rows(), 2 * n - 4);
}

INSTANTIATE_TEST_SUITE_P(Inverse, SampleInit,
                         ::testing::Values("tennis-ball.obj", "saddle.obj", "pushed-in.obj",
                                           "rotated.json"),
                         [](const auto& info) {
                           std::string name = info.param;
                           name = name.substr(0, name.find('.'));
                           name.erase(std::remove(name.begin(), name.end(), '-'), name.end());
                           return name;
                         });

TEST(Unfold, BarycentricMapIsExactAtVerticesAndLinearInside) {
  // A random bent triangulated strip: map vertices and random interior points.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int m = 30;
  Points2 flat(2 * m, 2);
  Points3 shape(2 * m, 3);
  Faces F(2 * (m - 1), 3);
  for (int k = 0; k < m; ++k) {
    flat.row(2 * k) << 7.3 * k + unit(random), unit(random);
    flat.row(2 * k + 1) << 7.3 * k + unit(random), 9.0 + unit(random);
    for (int s = 0; s < 2; ++s)
      shape.row(2 * k + s) << flat(2 * k + s, 0), flat(2 * k + s, 1) * std::cos(0.1 * k),
          13.0 * std::sin(0.3 * k + s);
    if (k + 1 < m) {
      F.row(2 * k) << 2 * k, 2 * k + 2, 2 * k + 1;
      F.row(2 * k + 1) << 2 * k + 1, 2 * k + 2, 2 * k + 3;
    }
  }
  const Points3 atVertices = mapBarycentric(flat, shape, F, flat);
  EXPECT_TRUE(atVertices == shape);
  Points2 query(F.rows(), 2);
  Points3 expected(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    double l1 = unit(random), l2 = unit(random);
    if (l1 + l2 > 1.0) l1 = 1.0 - l1, l2 = 1.0 - l2;
    query.row(f) =
        (1 - l1 - l2) * flat.row(F(f, 0)) + l1 * flat.row(F(f, 1)) + l2 * flat.row(F(f, 2));
    expected.row(f) =
        (1 - l1 - l2) * shape.row(F(f, 0)) + l1 * shape.row(F(f, 1)) + l2 * shape.row(F(f, 2));
  }
  EXPECT_LE((mapBarycentric(flat, shape, F, query) - expected).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(Unfold, FanOfMoreThanAFullTurnCannotBeCut) {
  // A fan of 8 triangles of 60 degrees each around vertex 0, bent in 3D (a wavy cone): a valid
  // disc whose unfolding turns 480 degrees and overlaps itself.
  const int k = 8;
  Points3 V(k + 2, 3);
  V.row(0) << 0, 0, 0;
  Faces F(k, 3);
  // Rim points 50 from the apex and 50 from each other (equilateral triangles), alternately up
  // and down by h at plan radius r and plan angle 45 degrees apart: (r sep)^2 + (2h)^2 = 50^2
  // with r^2 + h^2 = 50^2, sep = 2 sin(22.5 degrees).
  const double plan = 2.0 * kPi / k, radius = 50.0;
  const double sep = 2.0 * std::sin(plan / 2.0);
  const double r = std::sqrt(3.0 * radius * radius / (4.0 - sep * sep));
  const double h = std::sqrt(radius * radius - r * r);
  for (int i = 0; i <= k; ++i)
    V.row(i + 1) << r * std::cos(plan * i), r * std::sin(plan * i), (i % 2 ? h : -h);
  for (int i = 0; i < k; ++i) F.row(i) << 0, i + 1, i + 2;
  Result<Points2> flat = unfoldDisc(V, F);
  ASSERT_TRUE(flat.isOk()) << flat.status().message();
  expectIsometric(V, flat.value(), F);
  // The outline, in vertex order, crosses itself; checkSheet says so.
  const Status sheet = checkSheet(flat.value(), "B");
  ASSERT_FALSE(sheet.isOk());
  EXPECT_EQ(sheet.code(), ErrorCode::InputInvalid);
  EXPECT_EQ(sheet.message().rfind("piece B unfolds onto itself near curve points ", 0), 0u)
      << sheet.message();
  EXPECT_NE(sheet.message().find("cannot be cut from one sheet"), std::string::npos);
  // The first five triangles (300 degrees) unfold to a simple outline.
  Result<Points2> five = unfoldDisc(V.topRows(7), F.topRows(5));
  ASSERT_TRUE(five.isOk());
  EXPECT_TRUE(checkSheet(five.value(), "A").isOk());
}

TEST(Unfold, RejectsWhatIsNotADiscWithoutInteriorVertices) {
  // A closed tetrahedron, a disc with an interior vertex, inconsistent orientation.
  Points3 V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Faces tet(4, 3);
  tet << 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2;
  EXPECT_EQ(unfoldDisc(V, tet).status().code(), ErrorCode::InputInvalid);
  Faces inner(3, 3);  // vertex 3 inside triangle 0 1 2 seen from above
  Points3 W = V;
  W.row(3) << 0.3, 0.3, 0.2;
  inner << 0, 1, 3, 1, 2, 3, 2, 0, 3;
  EXPECT_EQ(unfoldDisc(W, inner).status().code(), ErrorCode::InputInvalid);
  Faces flipped(2, 3);
  flipped << 0, 1, 2, 1, 2, 3;
  EXPECT_EQ(unfoldDisc(V, flipped).status().code(), ErrorCode::InputInvalid);
}

}  // namespace
}  // namespace dform
