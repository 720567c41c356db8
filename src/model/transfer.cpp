// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/transfer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "dform/core/interrupt.h"

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

// The source's triangles bucketed by bounding box in a uniform grid of about one triangle per
// cell, so that a point looks at the triangles of its own cell, then of growing rings of cells,
// instead of at all of them.
class TriangleGrid {
 public:
  explicit TriangleGrid(const Piece& source) : source_(source) {
    lo_ = source.flat.colwise().minCoeff().transpose();
    const Eigen::Vector2d extent = source.flat.colwise().maxCoeff().transpose() - lo_;
    const double cells = std::max<double>(1.0, double(source.F.rows()));
    cell_ = std::max(std::sqrt(extent.x() * extent.y() / cells), 1e-12 * (extent.norm() + 1.0));
    nx_ = std::max(1, int(std::ceil(extent.x() / cell_)));
    ny_ = std::max(1, int(std::ceil(extent.y() / cell_)));
    buckets_.resize(std::size_t(nx_) * std::size_t(ny_));
    for (Eigen::Index f = 0; f < source.F.rows(); ++f) {
      Eigen::Vector2d fLo = source.flat.row(source.F(f, 0)), fHi = fLo;
      for (int k = 1; k < 3; ++k) {
        fLo = fLo.cwiseMin(source.flat.row(source.F(f, k)).transpose());
        fHi = fHi.cwiseMax(source.flat.row(source.F(f, k)).transpose());
      }
      for (int y = cellY(fLo.y()); y <= cellY(fHi.y()); ++y)
        for (int x = cellX(fLo.x()); x <= cellX(fHi.x()); ++x)
          buckets_[index(x, y)].push_back(int(f));
    }
  }

  // The triangle whose smallest barycentric coordinate at q is largest (q's own triangle, or
  // else the nearest one) and those coordinates.
  std::pair<int, Eigen::Vector3d> locate(const Eigen::Vector2d& q) const {
    double best = -std::numeric_limits<double>::infinity();
    Eigen::Vector3d bestWeights(1, 0, 0);
    int bestFace = 0;
    auto consider = [&](int f) {
      const Eigen::Vector3d w = barycentric(q, source_.flat.row(source_.F(f, 0)).transpose(),
                                            source_.flat.row(source_.F(f, 1)).transpose(),
                                            source_.flat.row(source_.F(f, 2)).transpose());
      if (w.minCoeff() > best) best = w.minCoeff(), bestWeights = w, bestFace = f;
    };
    const int cx = cellX(q.x()), cy = cellY(q.y());
    // A point inside the mesh lies in a triangle bucketed in its own cell. A point outside it
    // (a fine seam bulging past the coarse one) takes the nearest triangle: the rings grow until
    // one holds any triangle, and one ring more covers every triangle that could be nearer.
    int found = -1;
    for (int ring = 0; ring <= std::max(nx_, ny_); ++ring) {
      for (int y = cy - ring; y <= cy + ring; ++y)
        for (int x = cx - ring; x <= cx + ring; ++x) {
          if (std::max(std::abs(x - cx), std::abs(y - cy)) != ring) continue;
          if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
          for (int f : buckets_[index(x, y)]) consider(f);
        }
      if (best >= 0.0) break;  // inside a triangle: no other can do better
      if (found < 0 && best > -std::numeric_limits<double>::infinity()) found = ring;
      if (found >= 0 && ring >= found + 1) break;
    }
    return {bestFace, bestWeights};
  }

 private:
  int cellX(double x) const {
    return std::clamp(int(std::floor((x - lo_.x()) / cell_)), 0, nx_ - 1);
  }
  int cellY(double y) const {
    return std::clamp(int(std::floor((y - lo_.y()) / cell_)), 0, ny_ - 1);
  }
  std::size_t index(int x, int y) const {
    return std::size_t(y) * std::size_t(nx_) + std::size_t(x);
  }

  const Piece& source_;
  Eigen::Vector2d lo_;
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> buckets_;
};

}  // namespace

Points3 transferShape(const Piece& source, const Points2& points) {
  const TriangleGrid grid(source);
  Points3 out(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (i % 4096 == 0) throwIfInterrupted("the solve");
    auto [face, weights] = grid.locate(points.row(i).transpose());
    if (weights.minCoeff() < 0) {  // clamp onto the triangle
      weights = weights.cwiseMax(0.0);
      weights /= weights.sum();
    }
    out.row(i).setZero();
    for (int k = 0; k < 3; ++k) out.row(i) += weights[k] * source.shape.row(source.F(face, k));
  }
  return out;
}

void startFromCoarser(const DForm& coarse, Piece& a, Piece& b) {
  a.shape = transferShape(coarse.a, a.flat);
  b.shape = transferShape(coarse.b, b.flat);
  for (std::size_t k = 0; k < a.seam.size(); ++k) {
    const Eigen::RowVector3d mid = 0.5 * (a.shape.row(a.seam[k]) + b.shape.row(b.seam[k]));
    a.shape.row(a.seam[k]) = b.shape.row(b.seam[k]) = mid;
  }
}

}  // namespace dform
