#include "forward/transfer.h"

#include <algorithm>
#include <limits>

namespace dform {

namespace {

// Barycentric coordinates of q in triangle (a, b, c); non-degenerate triangles assumed.
Eigen::Vector3d barycentric(const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d e0 = b - a, e1 = c - a, d = q - a;
  const double det = e0.x() * e1.y() - e0.y() * e1.x();
  const double s = (d.x() * e1.y() - d.y() * e1.x()) / det;
  const double t = (e0.x() * d.y() - e0.y() * d.x()) / det;
  return {1.0 - s - t, s, t};
}

}  // namespace

Points3 transferShape(const Piece& source, const Points2& points) {
  Points3 out(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector2d q = points.row(i).transpose();
    // The triangle whose smallest barycentric coordinate is largest contains q, or is nearest.
    double best = -std::numeric_limits<double>::infinity();
    Eigen::Vector3d bestWeights(1, 0, 0);
    int bestFace = 0;
    for (Eigen::Index f = 0; f < source.F.rows(); ++f) {
      const Eigen::Vector3d w = barycentric(q, source.flat.row(source.F(f, 0)).transpose(),
                                            source.flat.row(source.F(f, 1)).transpose(),
                                            source.flat.row(source.F(f, 2)).transpose());
      if (w.minCoeff() > best) {
        best = w.minCoeff();
        bestWeights = w;
        bestFace = int(f);
      }
    }
    if (best < 0) {  // clamp onto the triangle
      bestWeights = bestWeights.cwiseMax(0.0);
      bestWeights /= bestWeights.sum();
    }
    out.row(i).setZero();
    for (int k = 0; k < 3; ++k) out.row(i) += bestWeights[k] * source.shape.row(source.F(bestFace, k));
  }
  return out;
}

}  // namespace dform
