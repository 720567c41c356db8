// SPDX-License-Identifier: GPL-3.0-or-later
// Angles in a flat piece's plane, shared by the gluing and the tracing of the body's edges.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "dform/core/constants.h"

namespace dform::exact::plane {

inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// The angle from u to w turning counter-clockwise, in [0, 2 pi).
inline double ccwAngle(const Eigen::Vector2d& u, const Eigen::Vector2d& w) {
  const double t = std::atan2(cross(u, w), u.dot(w));
  return t < 0 ? t + 2.0 * kPi : t;
}

}  // namespace dform::exact::plane
