#include "exact/aligned_distance.h"

#include <Eigen/Dense>
#include <cassert>

namespace dform::exact {

AlignedDistance alignedDistance(const Points3& reference, const Points3& moved) {
  assert(reference.rows() == moved.rows() && reference.rows() > 0);
  const Eigen::RowVector3d cr = reference.colwise().mean(), cm = moved.colwise().mean();
  const Points3 R0 = reference.rowwise() - cr, M0 = moved.rowwise() - cm;
  const Eigen::Matrix3d H = M0.transpose() * R0;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Eigen::Matrix3d rotation = svd.matrixV() * D * svd.matrixU().transpose();
  const Eigen::VectorXd distance = (M0 * rotation.transpose() - R0).rowwise().norm();
  AlignedDistance out;
  out.diagonalMm = (reference.colwise().maxCoeff() - reference.colwise().minCoeff()).norm();
  out.rmsRel = std::sqrt(distance.squaredNorm() / double(distance.size())) / out.diagonalMm;
  out.maxRel = distance.maxCoeff() / out.diagonalMm;
  return out;
}

}  // namespace dform::exact
