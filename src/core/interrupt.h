// The process's request to stop a run. Signals are process-wide, so the flag is too: the command
// line's SIGINT/SIGTERM handler sets it (an application embedding dform sets it to cancel a run),
// and the long loops and file reads of every stage poll it.
#pragma once

#include <atomic>

namespace dform {

/// The one flag of the process. Lock-free, so that a signal handler may set it.
std::atomic<bool>& interruptFlag();

/// Whether a stop has been requested (interruptFlag() is set).
inline bool interruptRequested() { return interruptFlag().load(std::memory_order_relaxed); }

}  // namespace dform
