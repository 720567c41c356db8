// SPDX-License-Identifier: GPL-3.0-or-later
// The bench's accuracy mode: how close the paper model comes to the exact D-Form of the same seam
// points, and in what solve time, as the 3D smoothing weight falls, against the goal of 5e-5 of
// the seam's bounding-box diagonal in at most 0.3 s on the ~1k-vertex ellipses.
#pragma once

#include <string>

/// Solves the ellipse pair with the paper model `repeats` times at each 3D smoothing weight of the
/// sweep, prints the Markdown table (solve time: the median) and, when plotPath is not empty,
/// writes the SVG plot of distance against solve time there. `smoke`: one weight on a 30-point
/// seam, so that ctest keeps the mode working. Returns the process exit code.
int runAccuracy(int repeats, const std::string& plotPath, bool smoke);
