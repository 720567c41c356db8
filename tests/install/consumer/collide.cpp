// SPDX-License-Identifier: GPL-3.0-or-later
// Uses this project's core/types.h and dform's headers in one translation unit.
#include <dform/core/types.h>
#include <dform/pipeline/run.h>

#include "core/types.h"

int main() {
  const consumer::Point corner{3, 4};
  const dform::Job job;
  const dform::DForm made;
  return corner.x + corner.y == 7 && job.isForward() && made.a.shape.rows() == 0 ? 0 : 1;
}
