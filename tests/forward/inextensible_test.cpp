// SPDX-License-Identifier: GPL-3.0-or-later
// The general engine's sheet: its energy against closed forms, and its answer stationary by
// central differences of that energy (independent of the engine's own gradient).
#include "dform/model/inextensible.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "dform/forward/forward.h"
#include "model/test_meshes.h"

namespace dform {
namespace {

// A square of side `side` mm split along its diagonal 0-2, as piece A, and its mirror image as
// piece B; all four corners are seam points, B's vertex i meeting A's vertex i. The 3D shape is
// the flat square with corner 3 turned by `theta` about the diagonal (both pieces alike).
DForm foldedSquares(double side, double theta) {
  DForm d;
  d.a.flat = Points2(4, 2);
  d.a.flat << 0, 0, side, 0, side, side, 0, side;
  d.a.F = Faces(2, 3);
  d.a.F << 0, 1, 2, 0, 2, 3;
  d.a.seam = {0, 1, 2, 3};
  d.b = d.a;
  d.b.flat.col(0) *= -1.0;
  d.b.F << 0, 2, 1, 0, 3, 2;  // counter-clockwise again after the mirror
  d.a.shape = Points3::Zero(4, 3);
  d.a.shape.leftCols(2) = d.a.flat;
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 1, 0).normalized();
  const Eigen::Vector3d corner(0, side, 0);
  const Eigen::Vector3d foot = corner.dot(axis) * axis, arm = corner - foot;
  d.a.shape.row(3) = (foot + std::cos(theta) * arm + std::sin(theta) * axis.cross(arm)).transpose();
  d.b.shape = d.a.shape;
  return d;
}

TEST(Inextensible, AFoldedHingeCostsThreeTimesItsEdgeSquaredTimesTheFoldOverItsArea) {
  // Bergou et al.: a hinge of edge l between triangles of area A0, A1 folded by theta has
  // |sum w_i x_i|^2 = 4 l^2 sin^2(theta / 2) and energy 3 |.|^2 / (A0 + A1). Here l^2 / (A0 + A1)
  // = 2 in each piece (scale-free), so E_bend = 2 pieces * 3 * 4 * 2 sin^2(theta / 2); the fold
  // keeps every edge's length, so no stretching, whatever k.
  for (double side : {1.0, 37.0})
    for (double theta : {0.0, 0.3, 1.2}) {
      const double expected = 48.0 * std::pow(std::sin(theta / 2), 2);
      EXPECT_NEAR(sheetEnergy(foldedSquares(side, theta), 1e9), expected, 1e-9 * (1 + expected))
          << "side " << side << ", theta " << theta;
    }
}

TEST(Inextensible, AUniformStretchCostsHalfTheStiffnessTimesTheGreenStrainSquared) {
  // Scaled by 1 + s in 3D, a flat sheet does not bend (the stencil is exact on planes) and every
  // edge has Green strain ((1 + s)^2 - 1) / 2; the edge weights share out the area, which is 1
  // in the energy's unit, so E = k / 2 eps^2.
  for (double s : {1e-3, 0.05}) {
    DForm d = foldedSquares(20.0, 0.0);
    d.a.shape *= 1 + s;
    d.b.shape *= 1 + s;
    const double eps = (std::pow(1 + s, 2) - 1) / 2;
    EXPECT_NEAR(sheetEnergy(d, 1e6), 0.5e6 * eps * eps, 1e-9 * 0.5e6 * eps * eps) << "s " << s;
  }
}

TEST(Inextensible, CountsEveryFactorisationTriedFailedOnesIncluded) {
  // A flat sheet stretched by 5 % is under tension at every Newton step (they approach its rest
  // size from above), so its Hessian factorises at the first try every time. Compressed by 5 %
  // instead, the Hessian across its edges is negative (the sheet could buckle out of its plane):
  // the first step needs a larger shift, and every try counts. (Three steps each: a flat sheet
  // has no bending force to measure its stationarity against.)
  for (double s : {0.05, -0.05}) {
    DForm d = foldedSquares(20.0, 0.0);
    d.a.shape *= 1 + s;
    d.b.shape *= 1 + s;
    InextensibleOptions options;
    options.stiffness = 1e6;
    options.maxSteps = 3;
    const InextensibleSummary summary = solveInextensible(d, options).summary;
    ASSERT_EQ(summary.steps, 3) << "s " << s << ": " << summary.message;
    if (s > 0)
      EXPECT_EQ(summary.factorisations, summary.steps);
    else
      EXPECT_GT(summary.factorisations, summary.steps);
  }
}

// The directional derivative of the sheet's energy at `model` along per-vertex unit directions
// (seeded), by central differences.
double energySlope(const DForm& model, double k, unsigned seed, double h) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  DForm plus = model, minus = model;
  for (Eigen::Index v = 0; v < model.a.shape.rows(); ++v) {
    const Eigen::RowVector3d d =
        Eigen::RowVector3d(normal(random), normal(random), normal(random)).normalized();
    plus.a.shape.row(v) += h * d;
    minus.a.shape.row(v) -= h * d;
  }
  // B's seam points are A's; its other vertices move as well.
  std::vector<bool> onSeam(model.b.shape.rows(), false);
  for (std::size_t i = 0; i < model.b.seam.size(); ++i) {
    onSeam[model.b.seam[i]] = true;
    plus.b.shape.row(model.b.seam[i]) = plus.a.shape.row(model.a.seam[i]);
    minus.b.shape.row(model.b.seam[i]) = minus.a.shape.row(model.a.seam[i]);
  }
  for (Eigen::Index v = 0; v < model.b.shape.rows(); ++v) {
    if (onSeam[v]) continue;
    const Eigen::RowVector3d d =
        Eigen::RowVector3d(normal(random), normal(random), normal(random)).normalized();
    plus.b.shape.row(v) += h * d;
    minus.b.shape.row(v) -= h * d;
  }
  return (sheetEnergy(plus, k) - sheetEnergy(minus, k)) / (2 * h);
}

TEST(Inextensible, TheAnswerIsStationaryByCentralDifferencesOfTheEnergy) {
  // Two ellipses of equal perimeter zipped from the pillow: the energy's slope along random
  // directions is measured from energy values alone, at the start and at the answer.
  const int n = 30;
  const Piece a = test::meshedPiece(test::ellipse(60, 35), n, false);
  const Piece b0 = test::meshedPiece(test::ellipse(35, 60), n, true);
  Piece b = b0;
  b.flat *= closedLength(test::ellipse(60, 35)) / closedLength(test::ellipse(35, 60));
  const DForm start = pillowInitialGuess(a, b);
  InextensibleOptions options;
  options.stiffness = 1e5;
  const InextensibleResult solved = solveInextensible(start, options);
  ASSERT_TRUE(solved.summary.converged) << solved.summary.message;
  EXPECT_LE(solved.summary.stationarity, options.tolerance);
  const double h = 1e-5;  // mm, on a ~100 mm sheet: truncation ~h^2, rounding ~1e-16 E / h
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const double before = energySlope(start, options.stiffness, seed, h);
    const double after = energySlope(solved.model, options.stiffness, seed, h);
    EXPECT_LE(std::abs(after), 1e-6 * std::abs(before))
        << "seed " << seed << ": " << before << " -> " << after;
  }
}

}  // namespace
}  // namespace dform
