// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/exact/aligned_distance.h"

#include <Eigen/Dense>
#include <cassert>

namespace dform::exact {

Eigen::Affine3d rigidFit(const Points3& from, const Points3& to) {
  assert(from.rows() == to.rows() && from.rows() > 0);
  const Eigen::RowVector3d cf = from.colwise().mean(), ct = to.colwise().mean();
  const Eigen::Matrix3d H = (from.rowwise() - cf).transpose() * (to.rowwise() - ct);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  Eigen::Affine3d motion = Eigen::Affine3d::Identity();
  motion.linear() = svd.matrixV() * D * svd.matrixU().transpose();
  motion.translation() = ct.transpose() - motion.linear() * cf.transpose();
  return motion;
}

AlignedDistance alignedDistance(const Points3& reference, const Points3& moved) {
  const Eigen::Affine3d motion = rigidFit(moved, reference);
  const Points3 placed =
      (moved * motion.linear().transpose()).rowwise() + motion.translation().transpose();
  const Eigen::VectorXd distance = (placed - reference).rowwise().norm();
  AlignedDistance out;
  out.diagonalMm = (reference.colwise().maxCoeff() - reference.colwise().minCoeff()).norm();
  out.rmsRel = std::sqrt(distance.squaredNorm() / double(distance.size())) / out.diagonalMm;
  out.maxRel = distance.maxCoeff() / out.diagonalMm;
  return out;
}

}  // namespace dform::exact
