// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/allocator.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace dform {

void keepFreedMemory() {
#if defined(__GLIBC__)
  // Blocks up to 256 MB come from the heap rather than mmap, and the heap is trimmed only when
  // 1 GB lies free at its top.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace dform
