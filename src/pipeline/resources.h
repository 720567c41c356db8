// Whether a run fits the machine: its memory, estimated before any meshing, against what the
// machine can give. A run that does not fit stops at once with a message saying what would,
// instead of being killed by the system part way through.
#pragma once

#include <cstddef>
#include <string>

#include "core/status.h"

namespace dform {

/// Bytes of memory this process can still get: /proc/meminfo's MemAvailable, or where lower the
/// room left under its cgroup's memory.max or under its address-space limit (RLIMIT_AS,
/// `ulimit -v`). 0 when none can be read.
std::size_t availableMemoryBytes();

/// Peak memory of a solve of `vertices` vertices (both pieces), from measurements on this code
/// (docs/benchmarks.md, "Scale"): about 36 KB per vertex where Levenberg-Marquardt runs (up to
/// kDirectSolveVertices: its factorisation), about 9 KB per vertex where the relaxation alone
/// does, plus `extraBytes` (the inverse's pre-D-Form tables) and 64 MB for the program itself.
std::size_t estimatedPeakBytes(double vertices, double extraBytes = 0.0);

/// Usage error when the estimate exceeds 80 % of the available memory (the rest for the system
/// and the files written), saying how much is needed and which resolution would fit (the vertex
/// count grows with its square). `what` names the run for the message.
Status checkMemory(double vertices, double extraBytes, int resolution, const std::string& what);

}  // namespace dform
