// SPDX-License-Identifier: GPL-3.0-or-later
// Process-wide allocator settings for dform's executables (never called by library code).
#pragma once

namespace dform {

/// Keeps freed memory in the process instead of returning it to the system after every large
/// solve buffer: the solver allocates and frees multi-megabyte vectors and CHOLMOD workspaces on
/// every iteration, and with glibc's defaults each comes back as fresh pages whose first touch
/// is a page fault (measured: ~15 % of a 1k-vertex forward solve). No effect outside glibc.
void keepFreedMemory();

}  // namespace dform
