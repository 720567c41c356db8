// Where the seam vertices go along the two outlines.
#pragma once

#include <vector>

namespace dform {

/// Arc-length fractions (from the starting pair, along the seam) of the n seam vertices: uniform,
/// except that every corner of either outline (`corners`, seam fractions) becomes a vertex, so that
/// no corner of the cut pattern is chamfered off. The stretch between two consecutive corners gets
/// a share of the n vertices in proportion to its length, spaced uniformly; both pieces use the
/// same fractions, so paired seam edges keep equal flat lengths. Corners closer than half a seam
/// edge to an earlier one are merged into it; with more than n / 4 corners the seam is uniform.
std::vector<double> seamFractions(int n, std::vector<double> corners);

}  // namespace dform
