// SPDX-License-Identifier: GPL-3.0-or-later
// Finding the triangle of a flat triangulation that holds a point: triangles bucketed in square
// cells of about one triangle each, so that a query looks at one cell.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dform/core/types.h"

namespace dform::ruled {

/// Finds the triangle of a flat mesh that holds a point (for mapping a piece's points onto the
/// ruled engine's triangulation).
class FaceLocator {
 public:
  /// `V` #V by 2 and `F` #F by 3 counter-clockwise triangles; both must outlive the locator.
  FaceLocator(const Points2& V, const Faces& F);

  /// The triangle whose barycentric coordinates of q have the largest smallest one (the one
  /// holding q, or nearest to holding it among those whose box covers q's cell), and those
  /// coordinates; -1 when no triangle's box covers the cell.
  int locate(const Eigen::Vector2d& q, Eigen::Vector3d& bary) const;

 private:
  int cellX(double x) const;
  int cellY(double y) const;

  const Points2& V_;
  const Faces& F_;
  Eigen::Vector2d lo_;
  double cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cells_;
};

}  // namespace dform::ruled
