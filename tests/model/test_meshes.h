// SPDX-License-Identifier: GPL-3.0-or-later
// Small two-piece inputs for the forward tests.
#pragma once

#include <cmath>

#include "dform/core/polyline.h"
#include "dform/core/types.h"
#include "dform/meshing/triangulate.h"

namespace dform::test {

/// An ellipse with semi-axes a, b as a dense counter-clockwise polygon.
inline Points2 ellipse(double a, double b, int points = 2000) {
  Points2 P(points, 2);
  for (int i = 0; i < points; ++i) {
    const double t = 2 * M_PI * i / points;
    P.row(i) << a * std::cos(t), b * std::sin(t);
  }
  return P;
}

/// A piece meshed from `outline` with n seam vertices starting at `start`; B pieces get the
/// clockwise seam order (0, n-1, ..., 1).
inline Piece meshedPiece(const Points2& outline, int n, bool pieceB, double start = 0.0) {
  const Points2 seam = resampleClosed(outline, n, start);
  TriangulateOptions options;
  options.targetEdgeLength = closedLength(seam) / n;
  const Result<FlatMesh> mesh = triangulateDomain(seam, {}, options);
  Piece p;
  p.name = pieceB ? "B" : "A";
  p.flat = mesh.value().V;
  p.F = mesh.value().F;
  for (int i = 0; i < n; ++i) p.seam.push_back(pieceB ? (n - i) % n : i);
  return p;
}

}  // namespace dform::test
