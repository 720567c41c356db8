// SPDX-License-Identifier: GPL-3.0-or-later
// How far one seam is from another of the same points once rigid motion is taken out: the
// measure of "the shape on the screen against the shape on the table".
#pragma once

#include <Eigen/Geometry>

#include "dform/core/types.h"

namespace dform::exact {

/// How far two point sets with the same rows lie apart after the best rigid fit, relative to the
/// reference's size.
struct AlignedDistance {
  double rmsRel = 0;  ///< root mean square distance / the reference's bounding-box diagonal
  double maxRel = 0;  ///< largest distance / the same diagonal
  /// The reference's bounding-box diagonal, mm: what rmsRel and maxRel are relative to.
  double diagonalMm = 0;
};

/// Row i of `moved` against row i of `reference` (#P by 3 each, mm) after the rigid motion
/// (rotation and translation, no reflection, no scale) that best fits the first onto the second in
/// the least-squares sense (Kabsch).
AlignedDistance alignedDistance(const Points3& reference, const Points3& moved);

/// That rigid motion: the rotation and translation taking row i of `from` closest to row i of
/// `to` in the least-squares sense.
Eigen::Affine3d rigidFit(const Points3& from, const Points3& to);

}  // namespace dform::exact
