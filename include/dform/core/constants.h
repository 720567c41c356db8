// SPDX-License-Identifier: GPL-3.0-or-later
// Constants that more than one module uses: pi and the seam resolution a run takes unless told.
#pragma once

namespace dform {

/// pi to double precision (M_PI is POSIX, not C++).
constexpr double kPi = 3.14159265358979323846;

/// One degree in radians.
constexpr double kDegree = kPi / 180.0;

/// Seam vertices per piece (forward) or points of the curve (inverse) when a job gives none: fine
/// enough that the figures agree to two digits with a finer seam on the samples, and solved in
/// seconds (docs/benchmarks.md).
constexpr int kDefaultResolution = 100;

/// The resolutions a run takes: from the coarsest mesh the solve still makes sense on to the
/// finest the solver is tested at (the memory check may refuse a finer one on a smaller machine).
constexpr int kMinResolution = 8, kMaxResolution = 20000;

}  // namespace dform
