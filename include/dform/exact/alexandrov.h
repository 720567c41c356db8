// SPDX-License-Identifier: GPL-3.0-or-later
// Alexandrov's theorem made constructive (Bobenko and Izmestiev, "Alexandrov's theorem, weighted
// Delaunay triangulations, and mixed volumes", 2008): a sphere with a convex flat-cone metric is
// the surface of one convex polyhedron. An apex inside is joined to every cone point by a radial
// edge of length r_i; each triangle of the weighted Delaunay triangulation of the metric (weights
// r_i^2) spans a tetrahedron with the apex. The curvature kappa_i = 2 pi - (sum of the dihedral
// angles at radial edge i) vanishes at every vertex exactly when the tetrahedra close up into the
// polyhedron; Newton steps on r (the Jacobian is the Hessian of the Hilbert-Einstein functional)
// with the triangulation kept weighted Delaunay by flips drive every kappa_i to zero.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

#include "dform/exact/intrinsic_triangulation.h"

namespace dform::exact {

/// Curvatures of the radial edges and their derivatives at radii r for the current triangulation.
struct RadialCurvatures {
  bool valid = false;     ///< every tetrahedron exists (the apex above every face)
  Eigen::VectorXd kappa;  ///< 2 pi - sum of dihedral angles at each radial edge (radians)
  Eigen::SparseMatrix<double> jacobian;  ///< d kappa_i / d r_j
  double minHeightSquared = 0;           ///< the smallest squared apex height over a face, mm^2
};

RadialCurvatures radialCurvatures(const IntrinsicTriangulation& tri, const Eigen::VectorXd& r);

/// Flips until the triangulation is weighted Delaunay for weights r_i^2 (the polyhedron convex at
/// every edge). False when an edge that must flip cannot (the radii are outside the domain).
bool makeRegular(IntrinsicTriangulation& tri, const Eigen::VectorXd& r);

/// When embedConvex stops: the curvature it aims for, the one it accepts, and its step budget.
struct AlexandrovOptions {
  /// Largest |kappa_i| accepted, radians. A curvature error kappa moves a vertex by about
  /// kappa times the body's size, so 1e-12 keeps the shape exact to ~1e-10 of its size.
  double curvatureTolerance = 1e-12;
  /// Where Newton stalls on rounding before curvatureTolerance (large seams: J is nearly
  /// singular at the solution), a result within this is accepted: 1e-9 rad moves a vertex by
  /// ~1e-9 of the body's size, 0.4 um on a 400 mm seam.
  double acceptedCurvature = 1e-9;
  int maxIterations = 200;  ///< Levenberg-Marquardt steps on the radii
};

/// What embedConvex reached: the radii, the 3D vertices and how well they fit the metric.
struct AlexandrovResult {
  /// Whether the curvatures reached AlexandrovOptions::acceptedCurvature.
  bool converged = false;
  std::string message;  ///< why not, when it did not converge
  /// Levenberg-Marquardt steps taken.
  int iterations = 0;
  double maxCurvature = 0;    ///< max |kappa_i| reached, radians
  Eigen::VectorXd radii;      ///< final r, mm
  Eigen::MatrixX3d vertices;  ///< each vertex in 3D, mm, the apex at the origin
  double maxEdgeError = 0;    ///< max | |V_i - V_j| - l_ij | / l_ij over the edges
};

/// Embeds the convex metric of `tri` (every cone angle below 2 pi) as a convex polyhedron; `tri`
/// ends as the polyhedron's triangulation (edges between coplanar faces included).
AlexandrovResult embedConvex(IntrinsicTriangulation& tri, const AlexandrovOptions& options = {});

}  // namespace dform::exact
