// SPDX-License-Identifier: GPL-3.0-or-later
// Whether a run fits the machine: its memory, estimated before any meshing, against what the
// machine can give. A run that does not fit stops at once with a message saying what would,
// instead of being killed by the system part way through.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "dform/core/status.h"

namespace dform {

/// Bytes of memory this process can still get: /proc/meminfo's MemAvailable, or where lower the
/// room left under its cgroup's memory.max or under its address-space limit (RLIMIT_AS,
/// `ulimit -v`). 0 when none can be read.
std::size_t availableMemoryBytes();

/// Peak memory of a solve of `vertices` vertices (both pieces), from measurements on this code
/// (resources.cpp; docs/benchmarks.md, "Scale"): about 36 KB per vertex where Levenberg-Marquardt
/// runs (up to kDirectSolveVertices: its factorisation), about 9 KB per vertex where the relaxation
/// alone does, plus `extraBytes` (the inverse's pre-D-Form tables) and 64 MB for the program
/// itself.
std::size_t estimatedPeakBytes(double vertices, double extraBytes = 0.0);

/// What a run is estimated to hold at its peak: vertices of both pieces and bytes beside them
/// (the inverse's pre-D-Form tables); both grow with the square of the resolution.
struct MemoryEstimate {
  double vertices = 0;    ///< both pieces' vertices together
  double extraBytes = 0;  ///< bytes held beside the meshes (the inverse's pre-D-Form tables)
};

/// A run's estimate at any resolution: the formula the run itself is checked with, so that the
/// resolution a refusal offers is the one the same check accepts.
using MemoryAtResolution = std::function<MemoryEstimate(int resolution)>;

/// Usage error when the estimate at `resolution` exceeds 80 % of the available memory (the rest
/// for the system and the files written), saying how much is needed, what a run may use, and the
/// highest resolution (down to 8) whose estimate stays within it: a run at that resolution, on
/// the same machine, passes this check. `what` names the run for the message.
Status checkMemory(const MemoryAtResolution& estimateAt, int resolution, const std::string& what);

/// Usage error for a run that ran out of memory although checkMemory let it start (a limit it
/// cannot see, another process taking memory meanwhile, a shape the estimate undershoots),
/// offering the highest resolution whose estimate adds half of what this run's adds to the
/// program's own memory and fits what checkMemory allows now (without an estimate, an empty
/// `estimateAt`: the resolution of half the vertices).
Status outOfMemory(const MemoryAtResolution& estimateAt, int resolution, const std::string& what);

}  // namespace dform
