// SPDX-License-Identifier: GPL-3.0-or-later
// Helpers for the inverse-initialisation tests: sample seams and synthetic curves.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <string>

#include "dform/core/polyline.h"
#include "dform/core/types.h"
#include "dform/io/curve_reader.h"

namespace dform::test {

inline const double kPi = std::acos(-1.0);

/// A sample seam from samples/inverse/, read with io's readCurve and resampled uniformly to n
/// points.
inline Points3 sampleCurve(const std::string& name, int n) {
  const std::string path = std::string(DFORM_SAMPLES_DIR) + "/inverse/" + name;
  Result<Curve3> curve = readCurve(path);
  EXPECT_TRUE(curve.isOk()) << curve.status().message();
  if (!curve.isOk()) return Points3(0, 3);
  return resampleClosed(curve.value().points, n);
}

/// n points of the closed parametric curve f on [0, 2 pi), resampled uniformly by arc length.
inline Points3 parametricCurve(const std::function<Eigen::Vector3d(double)>& f, int n) {
  const int dense = 20 * n;
  Eigen::MatrixXd P(dense, 3);
  for (int k = 0; k < dense; ++k) P.row(k) = f(2.0 * kPi * k / dense).transpose();
  return resampleClosed(P, n);
}

/// Rows of C moved by a rotation about `axis` by `angle` and a translation.
inline Points3 rigidlyMoved(const Points3& C, const Eigen::Vector3d& axis, double angle,
                            const Eigen::Vector3d& shift) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  Points3 out = C * R.transpose();
  out.rowwise() += shift.transpose();
  return out;
}

}  // namespace dform::test
