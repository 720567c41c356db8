// SPDX-License-Identifier: GPL-3.0-or-later
// Every term of the objective against finite differences, and the helpers around them.
#include "dform/model/terms.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "dform/validate/metrics.h"
#include "solver/gradient_check.h"
#include "test_meshes.h"

namespace dform {
namespace {

struct TwoPieces {
  Piece a = test::meshedPiece(test::ellipse(1.2, 0.8), 16, false);
  Piece b = test::meshedPiece(test::ellipse(1.0, 0.97), 16, true);
  VariableLayout layout{int(a.flat.rows()), int(b.flat.rows())};
};

void expectExactJacobian(const ResidualTerm& term, const Eigen::VectorXd& x, const char* name) {
  const JacobianCheck check = checkJacobian(term, x);
  EXPECT_LT(check.maxRelativeError, 1e-6)
      << name << " row " << check.worstRow << " column " << check.worstColumn;
  EXPECT_TRUE(check.outsidePatternIsZero) << name;
}

TEST(Terms, EveryJacobianMatchesFiniteDifferences) {
  TwoPieces m;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  Eigen::VectorXd x(m.layout.numVariables());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = noise(rng);
  Points2 targetsA = Points2::Random(16, 2), targetsB = Points2::Random(16, 2);

  expectExactJacobian(*makeIsometryTerm(meshEdgePairs(m.layout, m.a.F, m.b.F)), x, "isometry");
  expectExactJacobian(*makeFlatAnchorTerm(m.layout, m.a.seam, targetsA, m.b.seam, targetsB), x,
                      "boundary fix");
  expectExactJacobian(*makeSmoothnessTerm(m.layout, m.a, m.b, true), x, "smooth 3D");
  expectExactJacobian(*makeSmoothnessTerm(m.layout, m.a, m.b, false), x, "smooth 2D");
  expectExactJacobian(*makeSeamSmoothnessTerm(m.layout, m.a.seam, m.b.seam), x, "seam");
}

TEST(Terms, PackAndUnpackAreInverse) {
  TwoPieces m;
  m.a.shape = Points3::Random(m.a.flat.rows(), 3);
  m.b.shape = Points3::Random(m.b.flat.rows(), 3);
  const Eigen::VectorXd x = packVariables(m.layout, m.a, m.b);
  Piece a = m.a, b = m.b;
  a.shape.setZero();
  b.flat.setZero();
  unpackVariables(m.layout, x, a, b);
  EXPECT_EQ(a.shape, m.a.shape);
  EXPECT_EQ(b.flat, m.b.flat);
  EXPECT_EQ(x.segment<3>(m.layout.x(1, 4)), m.b.shape.row(4).transpose());
}

TEST(Terms, SharedSeamIsOneSetOfUnknownsAndKeepsExactJacobians) {
  TwoPieces m;
  const VariableLayout shared(int(m.a.flat.rows()), int(m.b.flat.rows()), m.a.seam, m.b.seam);
  ASSERT_TRUE(shared.sharesSeam());
  for (std::size_t k = 0; k < m.a.seam.size(); ++k)
    EXPECT_EQ(shared.x(1, m.b.seam[k]), shared.x(0, m.a.seam[k]));
  EXPECT_EQ(shared.x(1, m.b.flat.rows() - 1),
            m.layout.x(1, m.b.flat.rows() - 1));                    // interior: its own
  EXPECT_EQ(shared.u(1, m.b.seam[3]), m.layout.u(1, m.b.seam[3]));  // flat positions stay per piece

  // Unpacked, both sides of the seam sit at A's positions: the seam is closed exactly.
  m.a.shape = Points3::Random(m.a.flat.rows(), 3);
  m.b.shape = Points3::Random(m.b.flat.rows(), 3);
  const Eigen::VectorXd x = packVariables(shared, m.a, m.b);
  Piece a = m.a, b = m.b;
  unpackVariables(shared, x, a, b);
  EXPECT_EQ(a.shape, m.a.shape);
  for (std::size_t k = 0; k < m.a.seam.size(); ++k)
    EXPECT_EQ(b.shape.row(m.b.seam[k]), m.a.shape.row(m.a.seam[k]));
  EXPECT_EQ(b.shape.row(b.flat.rows() - 1), m.b.shape.row(m.b.flat.rows() - 1));

  Eigen::VectorXd y = Eigen::VectorXd::Random(shared.numVariables());
  expectExactJacobian(*makeIsometryTerm(meshEdgePairs(shared, m.a.F, m.b.F)), y,
                      "isometry, shared");
  expectExactJacobian(*makeSmoothnessTerm(shared, m.a, m.b, true), y, "smooth 3D, shared");
  expectExactJacobian(*makeSeamSmoothnessTerm(shared, m.a.seam, m.b.seam), y, "seam, shared");
}

TEST(Terms, IsometryCurvatureAlongADirectionIsExact) {
  // The isometry residual is quadratic, so the generic central difference (h = 0.1) and the
  // exact override agree to rounding, whatever the point and direction.
  TwoPieces m;
  const auto term = makeIsometryTerm(meshEdgePairs(m.layout, m.a.F, m.b.F));
  const Eigen::VectorXd x = Eigen::VectorXd::Random(m.layout.numVariables());
  const Eigen::VectorXd v = Eigen::VectorXd::Random(m.layout.numVariables());
  std::vector<double> exact(term->numResiduals()), difference(term->numResiduals());
  term->secondDirectionalDerivative(x, v, exact.data());
  term->ResidualTerm::secondDirectionalDerivative(x, v, difference.data());
  double largest = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    EXPECT_NEAR(exact[i], difference[i], 1e-9 * (1.0 + std::abs(exact[i]))) << "edge " << i;
    largest = std::max(largest, std::abs(exact[i]));
  }
  EXPECT_GT(largest, 0.1);  // the check is not vacuous
}

TEST(Terms, MeshEdgesOfADiscSatisfyEuler) {
  TwoPieces m;
  const auto E = meshEdges(m.a.F);
  EXPECT_EQ(m.a.flat.rows() - E.rows() + m.a.F.rows(), 1);  // V - E + F = 1 for a disc
  for (Eigen::Index e = 0; e < E.rows(); ++e) EXPECT_LT(E(e, 0), E(e, 1));
}

TEST(Terms, CotangentWeightsOfKnownTriangles) {
  // Right isosceles triangle: the 45-degree corners give cot = 1 to the edges they face.
  Points2 V(3, 2);
  V << 0, 0, 1, 0, 0, 1;
  Faces F(1, 3);
  F << 0, 1, 2;
  const CotangentWeights w = cotangentWeights(V, F);
  auto weight = [&](int i, int j) {
    for (const auto& [k, value] : w.neighbours[i])
      if (k == j) return value;
    return -1.0;
  };
  EXPECT_NEAR(weight(1, 2), 0.0, 1e-15);  // faces the right angle
  EXPECT_NEAR(weight(0, 1), 0.5, 1e-15);  // faces a 45-degree angle: cot / 2
  EXPECT_NEAR(weight(0, 2), 0.5, 1e-15);
  // Equilateral: cot 60 / 2 for every edge.
  V << 0, 0, 1, 0, 0.5, std::sqrt(3.0) / 2;
  const CotangentWeights e = cotangentWeights(V, F);
  for (int i = 0; i < 3; ++i)
    for (const auto& [k, value] : e.neighbours[i]) EXPECT_NEAR(value, 0.5 / std::sqrt(3.0), 1e-12);
}

TEST(Terms, SmoothnessVanishesOnAffineMapsAndIsometryOnRigidMotions) {
  TwoPieces m;
  // Any affine image of the flat mesh is harmonic for the cotangent Laplacian of that mesh,
  // and a rotation keeps every edge length.
  Eigen::Matrix<double, 3, 2> affine;
  affine << 0.3, -1.1, 0.8, 0.4, -0.2, 0.9;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Piece a = m.a, b = m.b;
  a.shape = (a.flat * affine.transpose()).rowwise() + Eigen::RowVector3d(1, 2, 3);
  b.shape = b.flat * affine.transpose();
  Eigen::VectorXd x = packVariables(m.layout, a, b);
  std::vector<double> r(makeSmoothnessTerm(m.layout, m.a, m.b, true)->numResiduals());
  makeSmoothnessTerm(m.layout, m.a, m.b, true)->evaluate(x, r.data(), nullptr);
  for (double v : r) EXPECT_NEAR(v, 0.0, 1e-12);

  a.shape = Points3::Zero(a.flat.rows(), 3);
  a.shape.leftCols<2>() = a.flat;
  a.shape = a.shape * R.transpose();
  b.shape = Points3::Zero(b.flat.rows(), 3);
  b.shape.leftCols<2>() = b.flat;
  x = packVariables(m.layout, a, b);
  const auto iso = makeIsometryTerm(meshEdgePairs(m.layout, m.a.F, m.b.F));
  std::vector<double> ri(iso->numResiduals());
  iso->evaluate(x, ri.data(), nullptr);
  for (double v : ri) EXPECT_NEAR(v, 0.0, 1e-12);
}

TEST(Terms, RolledRectangleIsIsometricUpToTheChordEffect) {
  // A 2 x 1 rectangle rolled into a cylinder of radius R: x = (R sin(u/R), v, R (1 - cos(u/R))).
  // Every edge keeps its length up to the chord of its u-extent, a relative shortening of at
  // most (l / R)^2 / 24: L_error and L_max of the rolled piece, and the isometry residuals, stay
  // within that bound.
  Points2 rect(4, 2);
  rect << 0, 0, 2, 0, 2, 1, 0, 1;
  const Points2 boundary = resampleClosed(rect, 60);
  TriangulateOptions options;
  options.targetEdgeLength = 0.1;
  const Result<FlatMesh> mesh = triangulateDomain(boundary, {}, options);
  ASSERT_TRUE(mesh.isOk());
  const double R = 0.5;
  Piece rolled;
  rolled.flat = mesh.value().V;
  rolled.F = mesh.value().F;
  rolled.seam = mesh.value().boundary;
  rolled.shape.resize(rolled.flat.rows(), 3);
  for (Eigen::Index i = 0; i < rolled.flat.rows(); ++i) {
    const double u = rolled.flat(i, 0), v = rolled.flat(i, 1);
    rolled.shape.row(i) << R * std::sin(u / R), v, R * (1 - std::cos(u / R));
  }
  const auto E = meshEdges(rolled.F);
  double longest = 0;
  for (Eigen::Index e = 0; e < E.rows(); ++e)
    longest = std::max(longest, (rolled.flat.row(E(e, 0)) - rolled.flat.row(E(e, 1))).norm());
  const double bound = longest * longest / (R * R) / 24.0;
  const Metrics m = computeMetrics(DForm{rolled, rolled}, {});
  EXPECT_LE(m.lengthErrorMax, bound);
  EXPECT_LE(m.lengthError, bound);
  EXPECT_LT(m.lengthError, 2e-3);
  EXPECT_EQ(m.flipped3d, 0);
  // The same edges through the isometry term: |x|^2 - |u|^2 relative to |u|^2.
  const VariableLayout layout(int(rolled.flat.rows()), int(rolled.flat.rows()));
  const auto iso = makeIsometryTerm(meshEdgePairs(layout, rolled.F, rolled.F));
  std::vector<double> r(iso->numResiduals());
  iso->evaluate(packVariables(layout, rolled, rolled), r.data(), nullptr);
  for (Eigen::Index e = 0; e < E.rows(); ++e) {
    const double flat2 = (rolled.flat.row(E(e, 0)) - rolled.flat.row(E(e, 1))).squaredNorm();
    EXPECT_LE(std::abs(r[e]) / flat2, 2.0 * bound + 1e-12);
  }
}

}  // namespace
}  // namespace dform
