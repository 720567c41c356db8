// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/ruled/face_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dform::ruled {

namespace {

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

}  // namespace

FaceLocator::FaceLocator(const Points2& V, const Faces& F) : V_(V), F_(F) {
  lo_ = V.colwise().minCoeff().transpose();
  const Eigen::Vector2d size = V.colwise().maxCoeff().transpose() - lo_;
  // About one triangle per cell.
  cell_ = std::max(1e-12, std::sqrt(std::max(size.x() * size.y(), 1e-24) /
                                    double(std::max<Eigen::Index>(1, F.rows()))));
  nx_ = int(size.x() / cell_) + 1;
  ny_ = int(size.y() / cell_) + 1;
  cells_.resize(std::size_t(nx_) * std::size_t(ny_));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    Eigen::Vector2d lo = V.row(F(f, 0)), hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(V.row(F(f, c)).transpose());
      hi = hi.cwiseMax(V.row(F(f, c)).transpose());
    }
    for (int y = cellY(lo.y()); y <= cellY(hi.y()); ++y)
      for (int x = cellX(lo.x()); x <= cellX(hi.x()); ++x)
        cells_[std::size_t(y) * std::size_t(nx_) + std::size_t(x)].push_back(int(f));
  }
}

int FaceLocator::cellX(double x) const {
  return std::clamp(int(std::floor((x - lo_.x()) / cell_)), 0, nx_ - 1);
}

int FaceLocator::cellY(double y) const {
  return std::clamp(int(std::floor((y - lo_.y()) / cell_)), 0, ny_ - 1);
}

int FaceLocator::locate(const Eigen::Vector2d& q, Eigen::Vector3d& bary) const {
  int best = -1;
  double bestMin = -std::numeric_limits<double>::infinity();
  for (int f : cells_[std::size_t(cellY(q.y())) * std::size_t(nx_) + std::size_t(cellX(q.x()))]) {
    const Eigen::Vector2d a = V_.row(F_(f, 0)), b = V_.row(F_(f, 1)), c = V_.row(F_(f, 2));
    const double area = cross(b - a, c - a);
    const Eigen::Vector3d w(cross(b - q, c - q) / area, cross(c - q, a - q) / area,
                            cross(a - q, b - q) / area);
    if (w.minCoeff() > bestMin) {
      bestMin = w.minCoeff();
      best = f;
      bary = w;
    }
  }
  return best;
}

}  // namespace dform::ruled
