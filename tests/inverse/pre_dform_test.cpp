// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/inverse/pre_dform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "dform/meshing/convex_hull.h"
#include "inverse_test_util.h"

namespace dform {
namespace {

using test::kPi;

// A disc of the pre-D-Form: n - 2 triangles on all n curve points, a manifold disc (Euler
// characteristic 1) whose boundary is the curve in order, run forwards (A) or backwards (B).
void checkDisc(const Faces& F, int n, bool forwards, const std::string& name) {
  SCOPED_TRACE("disc " + name);
  ASSERT_EQ(F.rows(), n - 2);
  std::map<std::pair<int, int>, int> directed;
  std::set<int> vertices;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      ASSERT_GE(F(f, c), 0);
      ASSERT_LT(F(f, c), n);
      vertices.insert(F(f, c));
      ++directed[{F(f, c), F(f, (c + 1) % 3)}];
    }
  EXPECT_EQ(int(vertices.size()), n) << "every curve point lies on the disc";
  std::set<std::pair<int, int>> undirected;
  for (const auto& [e, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << e.first << "-" << e.second << " twice the same way";
    undirected.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
  }
  EXPECT_EQ(int(vertices.size()) - int(undirected.size()) + int(F.rows()), 1)
      << "Euler characteristic";
  // Boundary edges (one face) are exactly the curve edges, in the disc's direction.
  int boundary = 0;
  for (const auto& [e, count] : directed) {
    if (directed.count({e.second, e.first})) continue;
    ++boundary;
    const int expectedNext = forwards ? (e.first + 1) % n : (e.first + n - 1) % n;
    EXPECT_EQ(e.second, expectedNext)
        << "boundary edge " << e.first << "-" << e.second << " is not a curve edge in order";
  }
  EXPECT_EQ(boundary, n);
}

// The whole pre-D-Form: two discs sharing only the curve, closed, outward (positive volume), no
// degenerate triangle.
void checkPreDForm(const Points3& C, const PreDForm& pre) {
  const int n = int(C.rows());
  checkDisc(pre.discA, n, true, "A");
  checkDisc(pre.discB, n, false, "B");
  std::map<std::pair<int, int>, int> directed;
  double volume = 0.0;
  const Eigen::RowVector3d centre = C.colwise().mean();
  const double diagonal = (C.colwise().maxCoeff() - C.colwise().minCoeff()).norm();
  for (const Faces* F : {&pre.discA, &pre.discB})
    for (Eigen::Index f = 0; f < F->rows(); ++f) {
      const Eigen::RowVector3d a = C.row((*F)(f, 0)), b = C.row((*F)(f, 1)), c = C.row((*F)(f, 2));
      const Eigen::RowVector3d normal = (b - a).cross(c - a);
      EXPECT_GT(normal.norm(), 1e-9 * diagonal * diagonal) << "degenerate triangle";
      volume += normal.dot(a - centre) / 6.0;
      for (int k = 0; k < 3; ++k) ++directed[{(*F)(f, k), (*F)(f, (k + 1) % 3)}];
    }
  for (const auto& [e, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << e.first << "-" << e.second
                        << " in both discs: they share more than the curve";
    EXPECT_EQ(directed.count({e.second, e.first}), 1u)
        << "open edge " << e.first << "-" << e.second;
  }
  EXPECT_GT(volume, 0.0) << "faces point inwards";
  EXPECT_EQ(pre.hullTriangles + pre.filledTriangles, 2 * n - 4);
  EXPECT_FALSE(pre.summary.empty());
}

Faces both(const PreDForm& pre) {
  Faces F(pre.discA.rows() + pre.discB.rows(), 3);
  F << pre.discA, pre.discB;
  return F;
}

// A bean bent over a saddle, tilted: no symmetry swaps its two discs.
Eigen::Vector3d beanCurve(double t) {
  const double r = 1.0 + 0.35 * std::cos(2 * t);
  return {100 * r * std::cos(t), 60 * r * std::sin(t), 30 * std::cos(2 * t) + 10 * std::sin(t)};
}

struct SampleCase {
  const char* file;
  bool onHull;
};

class Samples : public ::testing::TestWithParam<SampleCase> {};

TEST_P(Samples, PreDFormIsTwoDiscsOnTheCurve) {
  for (int n : {40, 100, 240}) {
    SCOPED_TRACE(std::string(GetParam().file) + " n=" + std::to_string(n));
    const Points3 C = test::sampleCurve(GetParam().file, n);
    ASSERT_EQ(C.rows(), n);
    Result<PreDForm> pre = buildPreDForm(C);
    ASSERT_TRUE(pre.isOk()) << pre.status().message();
    checkPreDForm(C, pre.value());
    EXPECT_EQ(pre.value().onHull, GetParam().onHull) << pre.value().summary;
    EXPECT_EQ(pre.value().insideVertices.empty(), GetParam().onHull);
    if (GetParam().onHull) {
      // The pre-D-Form is the convex hull, cut along the curve: every triangle's plane has all
      // curve points behind it (facets of coplanar points may be split either way).
      EXPECT_TRUE(pre.value().isHull) << pre.value().summary;
      EXPECT_EQ(pre.value().hullTriangles, 2 * n - 4);
      const Faces F = both(pre.value());
      const double diagonal = (C.colwise().maxCoeff() - C.colwise().minCoeff()).norm();
      for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const Eigen::RowVector3d a = C.row(F(f, 0));
        const Eigen::RowVector3d normal =
            (C.row(F(f, 1)) - a).cross(C.row(F(f, 2)) - a).normalized();
        EXPECT_LE(((C.rowwise() - a) * normal.transpose()).maxCoeff(), 1e-9 * diagonal)
            << "face " << f;
      }
    } else {
      EXPECT_FALSE(pre.value().isHull);
      EXPECT_GT(pre.value().filledTriangles, 0);
      EXPECT_NE(pre.value().summary.find("non-on-hull"), std::string::npos) << pre.value().summary;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Inverse, Samples,
                         ::testing::Values(SampleCase{"tennis-ball.obj", true},
                                           SampleCase{"saddle.obj", true},
                                           SampleCase{"pushed-in.obj", false},
                                           SampleCase{"rotated.json", true}),
                         [](const auto& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.find('.'));
                           name.erase(std::remove(name.begin(), name.end(), '-'), name.end());
                           return name;
                         });

TEST(PreDForm, PushedInStretchIsReportedInside) {
  const Points3 C = test::sampleCurve("pushed-in.obj", 100);
  Result<PreDForm> pre = buildPreDForm(C);
  ASSERT_TRUE(pre.isOk()) << pre.status().message();
  Result<ConvexHull3> hull = convexHull3(C);
  ASSERT_TRUE(hull.isOk());
  // Exactly the points that are not hull vertices, and they form one stretch around t = pi/4.
  std::vector<int> expected;
  for (int i = 0; i < 100; ++i)
    if (!hull.value().onHull[std::size_t(i)]) expected.push_back(i);
  EXPECT_EQ(pre.value().insideVertices, expected);
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(expected.back() - expected.front() + 1, int(expected.size())) << "one stretch";
  const double angle =
      std::atan2(C(expected[expected.size() / 2], 1), C(expected[expected.size() / 2], 0));
  EXPECT_NEAR(angle, kPi / 4, 0.15);
}

// Areas of disc A and disc B.
std::pair<double, double> discAreas(const Points3& C, const PreDForm& pre) {
  auto area = [&C](const Faces& F) {
    double sum = 0.0;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      sum += 0.5 * (C.row(F(f, 1)) - C.row(F(f, 0))).cross(C.row(F(f, 2)) - C.row(F(f, 0))).norm();
    return sum;
  };
  return {area(pre.discA), area(pre.discB)};
}

TEST(PreDForm, IndependentOfFrameAndScale) {
  const Points3 C = test::sampleCurve("tennis-ball.obj", 100);
  const Points3 D = test::sampleCurve("pushed-in.obj", 100);
  for (const Points3* curve : {&C, &D}) {
    Result<PreDForm> base = buildPreDForm(*curve);
    ASSERT_TRUE(base.isOk());
    const auto [baseA, baseB] = discAreas(*curve, base.value());
    const Points3 moved = test::rigidlyMoved(*curve, {0.3, -1.0, 0.7}, 2.1, {500.0, -250.0, 80.0});
    const double scale = 1e-3;
    const Points3 scaled = *curve * scale;
    for (const Points3* other : {&moved, &scaled}) {
      Result<PreDForm> pre = buildPreDForm(*other);
      ASSERT_TRUE(pre.isOk()) << pre.status().message();
      EXPECT_EQ(pre.value().onHull, base.value().onHull);
      EXPECT_EQ(pre.value().isHull, base.value().isHull);
      EXPECT_EQ(pre.value().insideVertices, base.value().insideVertices);
      EXPECT_EQ(pre.value().filledTriangles, base.value().filledTriangles);
      // Triangles may differ where a split is a tie (coplanar points, mirror-symmetric fills);
      // the surfaces may not.
      const double factor = other == &scaled ? scale * scale : 1.0;
      const auto [a, b] = discAreas(*other, pre.value());
      EXPECT_NEAR(a, baseA * factor, 1e-9 * baseA * factor);
      EXPECT_NEAR(b, baseB * factor, 1e-9 * baseB * factor);
    }
  }
}

TEST(PreDForm, ReversedCurveSwapsTheDiscs) {
  const int n = 100;
  const Points3 C = test::parametricCurve(beanCurve, n);
  Points3 R(n, 3);
  for (int i = 0; i < n; ++i) R.row(i) = C.row((n - i) % n);  // same points, run backwards
  Result<PreDForm> forward = buildPreDForm(C), backward = buildPreDForm(R);
  ASSERT_TRUE(forward.isOk() && backward.isOk());
  checkPreDForm(R, backward.value());
  // Reversed, the disc on the left becomes the disc on the right: B of one is A of the other.
  const auto [forwardA, forwardB] = discAreas(C, forward.value());
  const auto [backwardA, backwardB] = discAreas(R, backward.value());
  EXPECT_NEAR(backwardA, forwardB, 1e-9 * forwardB);
  EXPECT_NEAR(backwardB, forwardA, 1e-9 * forwardA);
  EXPECT_GT(std::abs(forwardA - forwardB), 1e-3 * forwardA) << "the test needs unequal discs";
}

TEST(PreDForm, HarderCurvesStillSplit) {
  using Curve = std::function<Eigen::Vector3d(double)>;
  // Smooth bump of height 1 and half-width w around `centre` (angles).
  const auto bump = [](double t, double centre, double w) {
    const double d = std::abs(std::remainder(t - centre, 2 * kPi));
    return d < w ? std::pow(std::cos(0.5 * kPi * d / w), 2) : 0.0;
  };
  // A tennis ball with a lobe pushed deep inside.
  const Curve dented = [&](double t) {
    const Eigen::Vector3d p(40 * std::cos(t) + 20 * std::cos(3 * t),
                            40 * std::sin(t) - 20 * std::sin(3 * t),
                            2 * std::sqrt(800.0) * std::sin(2 * t));
    return Eigen::Vector3d(p * (1.0 - 0.4 * bump(t, kPi / 4, 0.6)));
  };
  // The saddle pushed in by 70 %, or in two places.
  const Curve deepSaddle = [&](double t) {
    const double s = 80 * (1 - 0.7 * bump(t, kPi / 4, 0.9));
    return Eigen::Vector3d(s * std::cos(t), s * std::sin(t), 40 * std::cos(2 * t));
  };
  const Curve twoDents = [&](double t) {
    const double s = 80 - 30 * bump(t, kPi / 4, 0.6) - 30 * bump(t, 5 * kPi / 4, 0.6);
    return Eigen::Vector3d(s * std::cos(t), s * std::sin(t), 40 * std::cos(2 * t));
  };
  // A tennis seam on a peanut: the waist dips inside the hull.
  const Curve peanut = [](double t) {
    const Eigen::Vector3d u = Eigen::Vector3d(40 * std::cos(t) + 20 * std::cos(3 * t),
                                              40 * std::sin(t) - 20 * std::sin(3 * t),
                                              2 * std::sqrt(800.0) * std::sin(2 * t))
                                  .normalized();
    return Eigen::Vector3d(60 * (1 - 0.4 * (1 - u.z() * u.z())) * u);
  };
  // A crown with five waves (on-hull), also too coarse for every curve edge to be a hull edge.
  const Curve crown = [](double t) {
    return Eigen::Vector3d(90 * std::cos(t), 90 * std::sin(t), 35 * std::cos(5 * t));
  };
  // The boundary of a helical band of 1.3 turns: two helices joined by straight vertical ends
  // (collinear points that must not form a triangle).
  const Curve helixBand = [](double t) {
    const double s = t / (2 * kPi), turns = 1.3;
    const double angle = 2 * kPi * turns * (s < 0.5 ? 2 * s : 2 - 2 * s);
    return Eigen::Vector3d(60 * std::cos(angle), 60 * std::sin(angle),
                           20 * angle + (s < 0.5 ? 0.0 : 60.0));
  };
  const std::vector<std::tuple<const char*, Curve, int>> cases{
      {"dented", dented, 100},      {"deep saddle", deepSaddle, 200},
      {"two dents", twoDents, 200}, {"peanut", peanut, 100},
      {"crown", crown, 100},        {"coarse crown", crown, 24},
      {"bean", beanCurve, 120},     {"helix band", helixBand, 100}};
  for (const auto& [name, f, n] : cases) {
    SCOPED_TRACE(name);
    const Points3 C = test::parametricCurve(f, n);
    Result<InverseInit> init = initialiseInverse(C);
    ASSERT_TRUE(init.isOk()) << init.status().message();
    checkPreDForm(C, init.value().pre);
  }
}

TEST(PreDForm, BadCurvesAreRejectedWithTheirCause) {
  auto expectInvalid = [](const Points3& C, const std::string& words) {
    Result<PreDForm> pre = buildPreDForm(C);
    ASSERT_FALSE(pre.isOk());
    EXPECT_EQ(pre.status().code(), ErrorCode::InputInvalid);
    EXPECT_NE(pre.status().message().find(words), std::string::npos) << pre.status().message();
  };
  // Planar: a circle, also tilted and with rounding noise from the rotation.
  const Points3 circle = test::parametricCurve(
      [](double t) { return Eigen::Vector3d(50 * std::cos(t), 50 * std::sin(t), 0.0); }, 80);
  expectInvalid(circle, "the curve is planar");
  expectInvalid(test::rigidlyMoved(circle, {1, 1, 0}, 0.7, {3, 4, 5}), "the curve is planar");
  // A trefoil knot bounds no embedded disc, so no pre-D-Form can avoid crossing itself.
  const Points3 trefoil = test::parametricCurve(
      [](double t) {
        return Eigen::Vector3d(30 * (std::sin(t) + 2 * std::sin(2 * t)),
                               30 * (std::cos(t) - 2 * std::cos(2 * t)), -30 * std::sin(3 * t));
      },
      120);
  expectInvalid(trefoil, "cannot be split into two discs");
  expectInvalid(trefoil, "crosses itself");
  InverseInitOptions tangled;
  tangled.allowSelfIntersection = true;
  Result<PreDForm> anyway = buildPreDForm(trefoil, tangled);
  ASSERT_TRUE(anyway.isOk()) << anyway.status().message();
  checkPreDForm(trefoil, anyway.value());
  // Too few points, a non-finite coordinate, a repeated point, a curve touching itself.
  expectInvalid(Points3::Random(3, 3), "at least 4 points");
  Points3 bad = test::sampleCurve("saddle.obj", 40);
  bad(7, 1) = std::numeric_limits<double>::quiet_NaN();
  expectInvalid(bad, "non-finite");
  bad = test::sampleCurve("saddle.obj", 40);
  bad.row(8) = bad.row(7);
  expectInvalid(bad, "zero-length edge between points 8 and 9");
  bad = test::sampleCurve("saddle.obj", 40);
  bad.row(20) = bad.row(5);
  expectInvalid(bad, "points 6 and 21 coincide");
}

TEST(PreDForm, FileNamePrefixesErrors) {
  Curve3 curve;
  curve.points = test::parametricCurve(
      [](double t) { return Eigen::Vector3d(50 * std::cos(t), 50 * std::sin(t), 0.0); }, 40);
  curve.source = "flat.obj";
  Result<InverseInit> init = initialiseInverse(curve);
  ASSERT_FALSE(init.isOk());
  EXPECT_EQ(init.status().message().rfind("flat.obj: the curve is planar", 0), 0u)
      << init.status().message();
}

}  // namespace
}  // namespace dform
