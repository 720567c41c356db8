// SPDX-License-Identifier: GPL-3.0-or-later
// The mirror symmetries of an outline, for snapping a start to where an axis crosses it.
#pragma once

#include <vector>

#include "dform/core/types.h"

namespace dform::studio {

/// The arc-length fractions (ascending, from the first point) of the closed outline P where its
/// mirror axes cross it. An axis is a line through the outline's area centroid whose mirror
/// image of the outline lies within 0.1 % of the outline's size (the largest distance from the
/// centroid, twice) of the outline, sampled at 120 points evenly by arc length; axes are sought
/// every half degree (on 48 points) and refined. None for an outline with no mirror symmetry, nor
/// for one with more than 12 axes (a circle's: every point of it is on one).
std::vector<double> symmetryFractions(const Points2& P);

}  // namespace dform::studio
