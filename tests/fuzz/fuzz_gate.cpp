// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzzes the gate-file reader. Limits it accepts must be usable: finite and non-negative.
#include <cmath>

#include "dform/validate/gate.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  using namespace dform;
  const Result<GateLimits> gate = fuzz::parseChecked(data, size, "gate.json", parseGateJson);
  if (!gate.isOk()) return 0;
  const GateLimits& g = gate.value();
  for (const double limit : {g.lengthError, g.lengthErrorMax, g.seamError, g.curveError,
                             g.seamGapMm, g.gaussMaxRad, g.seamLengthRel, g.hullDistanceRel})
    fuzz::require(std::isfinite(limit) && limit >= 0.0, "an accepted limit is unusable");
  fuzz::require(g.flipped >= 0 && g.degenerate >= 0, "an accepted count is negative");
  return 0;
}
